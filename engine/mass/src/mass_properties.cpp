// Volume and surface integrals of triangle meshes, and the mass properties they give.
#include "engine/mass/mass_properties.hpp"

#include <cmath>
#include <stdexcept>

#include "engine/geometry/prefetch.hpp"

namespace tumble::engine {
namespace {

/// Running sums of a mesh integral: 6 unique entries of a symmetric second moment.
struct Sums {
  double measure = 0.0;
  double absolute = 0.0;
  double fx = 0.0, fy = 0.0, fz = 0.0;
  double xx = 0.0, yy = 0.0, zz = 0.0, xy = 0.0, xz = 0.0, yz = 0.0;

  /// Adds weight * (a a^T + b b^T + c c^T + s s^T) with s = a + b + c, and weight * s.
  void add(double weight, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
           const Eigen::Vector3d& c) {
    const Eigen::Vector3d s = a + b + c;
    fx += weight * s.x();
    fy += weight * s.y();
    fz += weight * s.z();
    xx += weight * (a.x() * a.x() + b.x() * b.x() + c.x() * c.x() + s.x() * s.x());
    yy += weight * (a.y() * a.y() + b.y() * b.y() + c.y() * c.y() + s.y() * s.y());
    zz += weight * (a.z() * a.z() + b.z() * b.z() + c.z() * c.z() + s.z() * s.z());
    xy += weight * (a.x() * a.y() + b.x() * b.y() + c.x() * c.y() + s.x() * s.y());
    xz += weight * (a.x() * a.z() + b.x() * b.z() + c.x() * c.z() + s.x() * s.z());
    yz += weight * (a.y() * a.z() + b.y() * b.z() + c.y() * c.z() + s.y() * s.z());
  }

  MomentIntegrals scaled(double measure_scale, double first_scale, double second_scale) const {
    MomentIntegrals out;
    out.measure = measure * measure_scale;
    out.absolute_measure = absolute * measure_scale;
    out.first = Eigen::Vector3d(fx, fy, fz) * first_scale;
    out.second << xx, xy, xz, xy, yy, yz, xz, yz, zz;
    out.second *= second_scale;
    return out;
  }
};

/// Hints the processor to fetch the corners of triangle `i`, if there is one (prefetch.hpp).
inline void prefetch_corners(const TriangleMesh& mesh, std::size_t i) {
  if (i >= mesh.triangles.size()) return;
  for (const std::uint32_t v : mesh.triangles[i]) detail::prefetch(mesh.positions.data() + v);
}

}  // namespace

MomentIntegrals solid_integrals(const TriangleMesh& mesh, const Eigen::Vector3d& reference) {
  // Each triangle with the reference point spans a tetrahedron of signed volume det/6, first
  // moment det/24 * s and second moment det/120 * (a a^T + b b^T + c c^T + s s^T).
  Sums sums;
  const Eigen::Vector3d* p = mesh.positions.data();
  const std::size_t count = mesh.triangles.size();
  for (std::size_t i = 0; i < count; ++i) {
    prefetch_corners(mesh, i + detail::kPrefetchDistance);
    const auto& t = mesh.triangles[i];
    const Eigen::Vector3d a = p[t[0]] - reference;
    const Eigen::Vector3d b = p[t[1]] - reference;
    const Eigen::Vector3d c = p[t[2]] - reference;
    const double det = a.dot(b.cross(c));
    sums.measure += det;
    sums.absolute += std::abs(det);
    sums.add(det, a, b, c);
  }
  return sums.scaled(1.0 / 6.0, 1.0 / 24.0, 1.0 / 120.0);
}

MomentIntegrals surface_integrals(const TriangleMesh& mesh, const Eigen::Vector3d& reference) {
  // A triangle of area A has first moment A s/3 and second moment A/12 (a a^T + b b^T + c c^T
  // + s s^T): the exact integrals of x and x x^T over its interior.
  Sums sums;
  const Eigen::Vector3d* p = mesh.positions.data();
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = p[t[0]] - reference;
    const Eigen::Vector3d b = p[t[1]] - reference;
    const Eigen::Vector3d c = p[t[2]] - reference;
    const double double_area = (b - a).cross(c - a).norm();
    sums.measure += double_area;
    sums.absolute += double_area;
    sums.add(double_area, a, b, c);
  }
  return sums.scaled(0.5, 1.0 / 6.0, 1.0 / 24.0);
}

Eigen::Matrix3d inertia_from_second_moment(const Eigen::Matrix3d& second_moment, double density) {
  return density * (second_moment.trace() * Eigen::Matrix3d::Identity() - second_moment);
}

MassProperties mass_properties(const MomentIntegrals& integrals, const Eigen::Vector3d& reference,
                               double density) {
  // Shift the second moment from the reference point to the centroid before forming the
  // inertia: C_centroid = C_reference - measure * d d^T.
  const Eigen::Vector3d offset = integrals.first / integrals.measure;
  const Eigen::Matrix3d centred =
      integrals.second - integrals.measure * (offset * offset.transpose());
  MassProperties out;
  out.mass = density * integrals.measure;
  out.center_of_mass = reference + offset;
  out.inertia = inertia_from_second_moment(centred, density);
  return out;
}

MassProperties MassProperties::translated(const Eigen::Vector3d& offset) const {
  MassProperties out = *this;
  out.center_of_mass += offset;
  return out;
}

MassProperties MassProperties::rotated(const Eigen::Matrix3d& rotation) const {
  MassProperties out = *this;
  out.center_of_mass = rotation * center_of_mass;
  out.inertia = rotation * inertia * rotation.transpose();
  return out;
}

Eigen::Matrix3d MassProperties::inertia_about(const Eigen::Vector3d& point) const {
  const Eigen::Vector3d d = center_of_mass - point;
  return inertia + mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
}

MassProperties combined(const std::vector<MassProperties>& parts) {
  if (parts.empty()) throw std::invalid_argument("combined: no parts");
  MassProperties out;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (const MassProperties& part : parts) {
    out.mass += part.mass;
    moment += part.mass * part.center_of_mass;
  }
  if (!(out.mass > 0.0)) throw std::invalid_argument("combined: total mass not positive");
  out.center_of_mass = moment / out.mass;
  for (const MassProperties& part : parts) out.inertia += part.inertia_about(out.center_of_mass);
  return out;
}

}  // namespace tumble::engine
