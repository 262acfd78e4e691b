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
// single precision: the positions are rounded to float as read and again once moved to the
// centre, as MuJoCo stores them, so the numbers agree with its compiler to about 1e-12 rather
// than 1e-7. Triangles under 1e-15 in twice their area count for nothing, as in MuJoCo.
#include "legacy_inertia.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include <Eigen/Eigenvalues>

#include "base/errors.hpp"
#include "engine/mass/mass_properties.hpp"

namespace tumble::engine::detail {
namespace {

/// Below this, twice a triangle's area counts as zero (MuJoCo's mjMINVAL).
constexpr double kLegacySmallestArea = 1e-15;

struct LegacyTriangle {
  double area = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< unit, or zero for a negligible one
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
};

LegacyTriangle legacy_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c) {
  LegacyTriangle t;
  t.centroid = (a + b + c) / 3.0;
  const Eigen::Vector3d cross = (b - a).cross(c - a);
  const double length = cross.norm();
  if (length < kLegacySmallestArea) return t;
  t.normal = cross / length;
  t.area = length / 2.0;
  return t;
}

Eigen::Vector3d single_precision(const Eigen::Vector3d& p) {
  return p.cast<float>().cast<double>();
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
Eigen::Vector3d legacy_centre(const TriangleMesh& mesh, const std::string& source) {
  double area = 0.0;
  Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
  for (const auto& t : mesh.triangles) {
    const LegacyTriangle face =
        legacy_triangle(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
    weighted += face.area * face.centroid;
    area += face.area;
  }
  if (!(area >= kLegacySmallestArea)) legacy_fail(source, "has zero surface area");
  const Eigen::Vector3d face_centre = weighted / area;
  double volume = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (const auto& t : mesh.triangles) {
    const LegacyTriangle face =
        legacy_triangle(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
    const double v = std::abs(face.normal.dot(face.centroid - face_centre) * face.area / 3.0);
    volume += v;
    moment += v * (face.centroid * 0.75 + face_centre * 0.25);
  }
  if (!(volume > 0.0)) legacy_fail(source, "spans no volume (all its faces lie in one plane)");
  return moment / volume;
}

/// Step 3 about the origin: the volume and the second moment of the absolute tetrahedra.
MomentIntegrals legacy_integrals(const TriangleMesh& centred) {
  MomentIntegrals integrals;
  for (const auto& t : centred.triangles) {
    const Eigen::Vector3d& d = centred.positions[t[0]];
    const Eigen::Vector3d& e = centred.positions[t[1]];
    const Eigen::Vector3d& f = centred.positions[t[2]];
    const LegacyTriangle face = legacy_triangle(d, e, f);
    const double v = std::abs(face.centroid.dot(face.normal) * face.area / 3.0);
    const Eigen::Vector3d s = d + e + f;
    integrals.measure += v;
    integrals.second +=
        v / 20.0 * (d * d.transpose() + e * e.transpose() + f * f.transpose() + s * s.transpose());
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
  TriangleMesh stored = mesh;
  for (Eigen::Vector3d& p : stored.positions) p = single_precision(p);
  const Eigen::Vector3d centre = legacy_centre(stored, report.source);
  for (Eigen::Vector3d& p : stored.positions) p = single_precision(p - centre);
  const MomentIntegrals integrals = legacy_integrals(stored);
  if (!(integrals.measure > 0.0)) {
    legacy_fail(report.source, "spans no volume (all its faces lie in one plane)");
  }
  report.method = InertiaMethod::legacy;
  report.volume = equal_inertia_box_volume(integrals, report.source);
  report.enclosed_volume = enclosed_volume;
  report.density = options.mass ? *options.mass / report.volume : options.density.value_or(1000.0);
  MassProperties& body = report.mass_properties;
  body.mass = report.density * report.volume;
  body.center_of_mass = centre;
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
