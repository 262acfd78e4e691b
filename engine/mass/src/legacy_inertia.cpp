// MuJoCo's legacy mesh inertia, recomputed from its description (MuJoCo 2.2.2's default,
// compiler exactmeshinertia="false": mjCMesh's processing of a mesh, then mjCGeom's volume):
//  1. c0 = the area-weighted mean of the triangles' centroids.
//  2. Each triangle spans a tetrahedron with c0, of volume |n . (centroid - c0)| area / 3 (n the
//     unit normal): the ABSOLUTE value, so a triangle facing c0 adds volume instead of taking
//     it away. The centre of mass is the mean of the tetrahedra's centroids weighted by those
//     volumes.
//  3. The vertices are moved so that centre is the origin, and step 2 is repeated with the
//     apex at the origin: volume V and second moment C about the centre (V/20 (D D^T + E E^T +
//     F F^T + s s^T) per tetrahedron, s = D + E + F, as mass_properties.hpp), with no
//     parallel-axis correction for this second sum's own centroid.
//  4. The body is the uniform box of equal inertia: half sizes b_i = sqrt(3 c_i / V) for the
//     principal values c_i of C (MuJoCo writes them from the moments e_i: sqrt(6 (e_j + e_k -
//     e_i) / V) / 2), so its volume 8 b_0 b_1 b_2 is the mass's volume and its inertia is
//     (mass / V) times that of step 3 at unit density.
// A box's volume is its own box's, so boxes are exact; any other shape is not (a sphere's box
// of equal inertia has 11% less volume, an L-prism's 13.9% more). MuJoCo keeps vertices in
// single precision and some of its sums see only float operands: the positions are rounded to
// float as read and again once moved to the centre, and the centroids, the edges and the
// vertex products of step 3 are summed in float, as MuJoCo's arithmetic does, so the numbers
// agree with its compiler to 1e-9 rather than 1e-7. Triangles under 1e-15 in twice their area
// count for nothing, as in MuJoCo.
#include "legacy_inertia.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>

#include "base/errors.hpp"
#include "engine/mass/mass_properties.hpp"

namespace tumble::engine::detail {
namespace {

/// Below this, twice a triangle's area counts as zero (MuJoCo's mjMINVAL).
constexpr double kLegacySmallestArea = 1e-15;

using LegacyPoint = std::array<float, 3>;

/// The mesh's positions as MuJoCo keeps them: single precision.
std::vector<LegacyPoint> single_precision(const std::vector<Eigen::Vector3d>& positions) {
  std::vector<LegacyPoint> out;
  out.reserve(positions.size());
  for (const Eigen::Vector3d& p : positions) {
    out.push_back(
        {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
  }
  return out;
}

double legacy_dot(const std::array<double, 3>& u, const std::array<double, 3>& v) {
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

struct LegacyTriangle {
  double area = 0.0;
  std::array<double, 3> normal{};  ///< unit, or not normalised for a negligible triangle
  std::array<double, 3> centroid{};
};

/// Area, unit normal and centroid in MuJoCo's arithmetic: the centroid and the two edges are
/// summed in single precision (float operands), the cross product and its length in double.
LegacyTriangle legacy_triangle(const LegacyPoint& a, const LegacyPoint& b, const LegacyPoint& c) {
  LegacyTriangle t;
  std::array<double, 3> u{}, v{};
  for (std::size_t i = 0; i < 3; ++i) {
    const float sum = a[i] + b[i] + c[i];
    t.centroid[i] = sum / 3.0f;
    u[i] = b[i] - a[i];
    v[i] = c[i] - a[i];
  }
  t.normal = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  const double length = std::sqrt(legacy_dot(t.normal, t.normal));
  if (length < kLegacySmallestArea) return t;
  for (double& n : t.normal) n /= length;
  t.area = length / 2.0;
  return t;
}

std::string legacy_number(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

[[noreturn]] void legacy_fail(const std::string& source, const std::string& problem) {
  throw InputError(source + ": " + problem);
}

/// Steps 1 and 2: the centre of the absolute tetrahedra spanned from the face centroid.
std::array<double, 3> legacy_centre(const std::vector<LegacyPoint>& points,
                                    const TriangleMesh& mesh, const std::string& source) {
  double area = 0.0;
  std::array<double, 3> face_centre{};
  for (const auto& t : mesh.triangles) {
    const LegacyTriangle face = legacy_triangle(points[t[0]], points[t[1]], points[t[2]]);
    for (std::size_t j = 0; j < 3; ++j) face_centre[j] += face.area * face.centroid[j];
    area += face.area;
  }
  if (!(area >= kLegacySmallestArea)) legacy_fail(source, "has zero surface area");
  for (double& x : face_centre) x /= area;
  double volume = 0.0;
  std::array<double, 3> moment{};
  for (const auto& t : mesh.triangles) {
    const LegacyTriangle face = legacy_triangle(points[t[0]], points[t[1]], points[t[2]]);
    const std::array<double, 3> apex_to_face = {face.centroid[0] - face_centre[0],
                                                face.centroid[1] - face_centre[1],
                                                face.centroid[2] - face_centre[2]};
    const double v = std::abs(legacy_dot(apex_to_face, face.normal) * face.area / 3);
    volume += v;
    for (std::size_t j = 0; j < 3; ++j) {
      moment[j] += v * (face.centroid[j] * 3.0 / 4.0 + face_centre[j] / 4.0);
    }
  }
  if (!(volume > 0.0)) legacy_fail(source, "spans no volume (all its faces lie in one plane)");
  for (double& x : moment) x /= volume;
  return moment;
}

/// Step 3 about the origin: the volume and the second moment of the absolute tetrahedra. The
/// vertex products are summed in single precision, as MuJoCo's float operands make them.
MomentIntegrals legacy_integrals(const std::vector<LegacyPoint>& centred,
                                 const TriangleMesh& mesh) {
  MomentIntegrals integrals;
  for (const auto& t : mesh.triangles) {
    const LegacyPoint& d = centred[t[0]];
    const LegacyPoint& e = centred[t[1]];
    const LegacyPoint& f = centred[t[2]];
    const LegacyTriangle face = legacy_triangle(d, e, f);
    const double v = std::abs(legacy_dot(face.centroid, face.normal) * face.area / 3);
    integrals.measure += v;
    for (Eigen::Index r = 0; r < 3; ++r) {
      for (Eigen::Index c = r; c < 3; ++c) {
        const auto i = static_cast<std::size_t>(r), k = static_cast<std::size_t>(c);
        const float products = 2 * (d[i] * d[k] + e[i] * e[k] + f[i] * f[k]) + d[i] * e[k] +
                               d[k] * e[i] + d[i] * f[k] + d[k] * f[i] + e[i] * f[k] + e[k] * f[i];
        integrals.second(r, c) += v / 20 * products;
        integrals.second(c, r) = integrals.second(r, c);
      }
    }
  }
  integrals.absolute_measure = integrals.measure;
  return integrals;
}

/// Step 4: the volume of the uniform box whose second moments are those of `integrals`.
double equal_inertia_box_volume(const MomentIntegrals& integrals, const std::string& source) {
  const Eigen::Vector3d principal =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(integrals.second, Eigen::EigenvaluesOnly)
          .eigenvalues();
  if (!(principal.minCoeff() > 0.0)) {
    legacy_fail(source,
                "has no box of equal inertia (a principal second moment is not "
                "positive), which MuJoCo's legacy inertia needs");
  }
  double volume = 8.0;
  for (int axis = 0; axis < 3; ++axis) {
    volume *= std::sqrt(3.0 * principal[axis] / integrals.measure);
  }
  return volume;
}

}  // namespace

void legacy_properties(const TriangleMesh& mesh, const MassOptions& options,
                       std::optional<double> enclosed_volume, MeshReport& report) {
  std::vector<LegacyPoint> points = single_precision(mesh.positions);
  const std::array<double, 3> centre = legacy_centre(points, mesh, report.source);
  for (LegacyPoint& p : points) {
    for (std::size_t j = 0; j < 3; ++j) p[j] = static_cast<float>(p[j] - centre[j]);
  }
  const MomentIntegrals integrals = legacy_integrals(points, mesh);
  if (!(integrals.measure > 0.0)) {
    legacy_fail(report.source, "spans no volume (all its faces lie in one plane)");
  }
  report.method = InertiaMethod::legacy;
  report.volume = equal_inertia_box_volume(integrals, report.source);
  report.enclosed_volume = enclosed_volume;
  report.density = options.mass ? *options.mass / report.volume : options.density.value_or(1000.0);
  MassProperties& body = report.mass_properties;
  body.mass = report.density * report.volume;
  body.center_of_mass = Eigen::Vector3d(centre[0], centre[1], centre[2]);
  body.inertia = inertia_from_second_moment(integrals.second, body.mass / integrals.measure);
  std::string note =
      "legacy is MuJoCo 2.2.2's approximation (the box of equal inertia, from absolute "
      "tetrahedron volumes about the mesh's centre): ";
  if (!enclosed_volume) {
    note += "exact refuses this mesh, so it cannot be compared with the enclosed solid";
  } else {
    const double excess = (report.volume - *enclosed_volume) / *enclosed_volume;
    if (std::abs(excess) <= 1e-9) {
      note += "its volume equals the solid the mesh encloses (" + legacy_number(*enclosed_volume) +
              " m^3, the exact method's: a box)";
      report.warnings.push_back(note);
      return;
    }
    note += "its volume (" + legacy_number(report.volume) + " m^3) is " +
            legacy_number(100.0 * std::abs(excess)) + (excess < 0.0 ? "% less" : "% more") +
            " than the solid the mesh encloses (" + legacy_number(*enclosed_volume) +
            " m^3, the exact method's)";
  }
  report.warnings.push_back(note);
}

}  // namespace tumble::engine::detail
