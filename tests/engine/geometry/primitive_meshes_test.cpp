#include "engine/geometry/primitive_meshes.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace tumble::engine {
namespace {

using ::testing::HasSubstr;

// Checks, without engine code, that the mesh is a closed, consistently wound, welded surface:
// every directed edge appears exactly once and its reverse exactly once, no triangle is
// degenerate and no two vertices coincide.
void expect_closed_and_clean(const TriangleMesh& mesh) {
  const std::size_t vertex_count = mesh.positions.size();
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  std::size_t degenerate = 0;
  for (const auto& triangle : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      ASSERT_LT(triangle[k], vertex_count);
      ++directed[{triangle[k], triangle[(k + 1) % 3]}];
    }
    const Eigen::Vector3d& a = mesh.positions[triangle[0]];
    const Eigen::Vector3d& b = mesh.positions[triangle[1]];
    const Eigen::Vector3d& c = mesh.positions[triangle[2]];
    const double longest =
        std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    if (!((b - a).cross(c - a).norm() > 1e-9 * longest)) ++degenerate;
  }
  EXPECT_EQ(degenerate, 0u);
  std::size_t bad_edges = 0;
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    if (count != 1 || reverse == directed.end() || reverse->second != 1) ++bad_edges;
  }
  EXPECT_EQ(bad_edges, 0u);

  std::set<std::tuple<double, double, double>> distinct;
  for (const auto& p : mesh.positions) distinct.emplace(p.x(), p.y(), p.z());
  EXPECT_EQ(distinct.size(), vertex_count) << "unwelded vertices";
}

// Signed volume by the divergence theorem: tetrahedra from the bounding-box centre.
double signed_volume(const TriangleMesh& mesh) {
  Eigen::Vector3d low = mesh.positions.front();
  Eigen::Vector3d high = mesh.positions.front();
  for (const auto& p : mesh.positions) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const Eigen::Vector3d centre = 0.5 * (low + high);
  double six_volume = 0.0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.positions[t[0]] - centre;
    const Eigen::Vector3d b = mesh.positions[t[1]] - centre;
    const Eigen::Vector3d c = mesh.positions[t[2]] - centre;
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

// Area of a regular n-gon inscribed in the unit circle.
double unit_ngon_area(int n) {
  return 0.5 * n * std::sin(2.0 * std::numbers::pi / n);
}

double relative_error(double value, double exact) {
  return std::abs(value - exact) / exact;
}

TEST(BoxMesh, IsAClosedBoxOfExactVolume) {
  const TriangleMesh box = box_mesh({0.3, 0.5, 0.7});
  EXPECT_EQ(box.positions.size(), 8u);
  EXPECT_EQ(box.triangles.size(), 12u);
  expect_closed_and_clean(box);
  EXPECT_NEAR(signed_volume(box), 0.3 * 0.5 * 0.7, 1e-15);
  for (const auto& p : box.positions) {
    EXPECT_DOUBLE_EQ(std::abs(p.x()), 0.15);
    EXPECT_DOUBLE_EQ(std::abs(p.z()), 0.35);
  }
}

TEST(TetrahedronMesh, FacesOutwardWhateverTheCornerOrder) {
  const std::array<Eigen::Vector3d, 4> corners = {
      Eigen::Vector3d(0.1, 0.0, 0.0), Eigen::Vector3d(1.0, 0.2, 0.0),
      Eigen::Vector3d(0.3, 1.1, 0.1), Eigen::Vector3d(0.2, 0.3, 0.9)};
  const double exact =
      std::abs(
          (corners[1] - corners[0]).cross(corners[2] - corners[0]).dot(corners[3] - corners[0])) /
      6.0;
  std::array<int, 4> order = {0, 1, 2, 3};
  do {
    const TriangleMesh tet = tetrahedron_mesh(
        {corners[order[0]], corners[order[1]], corners[order[2]], corners[order[3]]});
    expect_closed_and_clean(tet);
    EXPECT_NEAR(signed_volume(tet), exact, 1e-14 * exact);
  } while (std::next_permutation(order.begin(), order.end()));
}

TEST(TetrahedronMesh, RejectsCoplanarCorners) {
  EXPECT_THAT(
      [] {
        tetrahedron_mesh({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
                          Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(1, 1, 0)});
      },
      ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("coplanar")));
}

TEST(CylinderMesh, IsTheExactPrismAndConvergesQuadratically) {
  const double r = 0.2;
  const double h = 0.5;
  for (const int n : {3, 7, 64}) {
    const TriangleMesh cylinder = cylinder_mesh(r, h, n);
    expect_closed_and_clean(cylinder);
    EXPECT_EQ(cylinder.triangles.size(), 4u * n);
    EXPECT_NEAR(signed_volume(cylinder), unit_ngon_area(n) * r * r * h, 1e-14);
  }
  // Doubling the segments quarters the error of the volume (O(h^2)).
  const double exact = std::numbers::pi * r * r * h;
  const double coarse = relative_error(signed_volume(cylinder_mesh(r, h, 64)), exact);
  const double fine = relative_error(signed_volume(cylinder_mesh(r, h, 128)), exact);
  EXPECT_NEAR(coarse / fine, 4.0, 0.01);
  EXPECT_LT(fine, 5e-4);

  const TriangleMesh cylinder = cylinder_mesh(r, h, 16);
  for (const auto& p : cylinder.positions) EXPECT_NEAR(std::abs(p.z()), 0.5 * h, 1e-15);
}

TEST(ConeMesh, IsTheExactPyramidWithApexAtTheTop) {
  const double r = 0.1;
  const double h = 0.3;
  const TriangleMesh cone = cone_mesh(r, h, 48);
  expect_closed_and_clean(cone);
  EXPECT_EQ(cone.positions.size(), 50u);
  EXPECT_NEAR(signed_volume(cone), unit_ngon_area(48) * r * r * h / 3.0, 1e-15);
  double lowest = 1.0;
  double highest = -1.0;
  for (const auto& p : cone.positions) {
    lowest = std::min(lowest, p.z());
    highest = std::max(highest, p.z());
  }
  EXPECT_EQ(lowest, 0.0);
  EXPECT_EQ(highest, h);
  EXPECT_LT(relative_error(signed_volume(cone_mesh(r, h, 256)), std::numbers::pi * r * r * h / 3.0),
            2e-4);
}

TEST(UvSphereMesh, ConvergesToTheBallQuadratically) {
  const double r = 0.25;
  const double exact = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const TriangleMesh coarse = uv_sphere_mesh(r, 64, 32);
  const TriangleMesh fine = uv_sphere_mesh(r, 128, 64);
  expect_closed_and_clean(coarse);
  expect_closed_and_clean(fine);
  EXPECT_EQ(coarse.positions.size(), 64u * 31u + 2u);
  EXPECT_EQ(coarse.triangles.size(), 2u * 64u * 31u);
  const double coarse_error = relative_error(signed_volume(coarse), exact);
  const double fine_error = relative_error(signed_volume(fine), exact);
  EXPECT_LT(signed_volume(fine), exact);  // inscribed
  EXPECT_NEAR(coarse_error / fine_error, 4.0, 0.05);
  EXPECT_LT(fine_error, 1.5e-3);
  for (const auto& p : fine.positions) EXPECT_NEAR(p.norm(), r, 1e-15);
}

TEST(UvSphereMesh, SmallestSphereIsAClosedDoublePyramid) {
  const TriangleMesh sphere = uv_sphere_mesh(1.0, 3, 2);
  expect_closed_and_clean(sphere);
  EXPECT_EQ(sphere.triangles.size(), 6u);
  EXPECT_GT(signed_volume(sphere), 0.0);
}

TEST(EllipsoidMesh, IsTheStretchedSphere) {
  const Eigen::Vector3d radii(0.3, 0.2, 0.1);
  const TriangleMesh ellipsoid = ellipsoid_mesh(radii, 96, 48);
  expect_closed_and_clean(ellipsoid);
  const double unit = signed_volume(uv_sphere_mesh(1.0, 96, 48));
  EXPECT_NEAR(signed_volume(ellipsoid), unit * radii.prod(), 1e-14);
  EXPECT_LT(relative_error(signed_volume(ellipsoid), 4.0 / 3.0 * std::numbers::pi * radii.prod()),
            2e-3);
}

TEST(TorusMesh, IsTheExactRevolvedPolygonAndConverges) {
  const double big = 0.3;
  const double small = 0.05;
  const TriangleMesh torus = torus_mesh(big, small, 40, 12);
  expect_closed_and_clean(torus);
  EXPECT_EQ(torus.triangles.size(), 2u * 40u * 12u);
  // Pappus on polygons: an n-gon ring scales the revolved area by unit_ngon_area(n) / pi.
  EXPECT_NEAR(signed_volume(torus),
              2.0 * big * unit_ngon_area(40) * unit_ngon_area(12) * small * small, 1e-15);
  const double exact = 2.0 * std::numbers::pi * std::numbers::pi * big * small * small;
  EXPECT_LT(relative_error(signed_volume(torus_mesh(big, small, 256, 64)), exact), 2e-3);
}

TEST(RevolveProfile, MatchesTheSumOfFrustumsEitherDirection) {
  // A vase: point at the bottom, bulge, neck, flat lip with an overhang, closed top.
  const std::vector<Eigen::Vector2d> profile = {{0.0, 0.0},   {0.05, 0.01}, {0.08, 0.06},
                                                {0.03, 0.12}, {0.04, 0.13}, {0.06, 0.13},
                                                {0.06, 0.14}, {0.0, 0.14}};
  double exact = 0.0;  // solid of revolution, signed frustums along the profile
  for (std::size_t i = 0; i + 1 < profile.size(); ++i) {
    const double r1 = profile[i].x();
    const double r2 = profile[i + 1].x();
    exact += std::numbers::pi * (profile[i + 1].y() - profile[i].y()) *
             (r1 * r1 + r1 * r2 + r2 * r2) / 3.0;
  }
  const int n = 36;
  const TriangleMesh forward = revolve_profile(profile, n);
  const TriangleMesh backward = revolve_profile({profile.rbegin(), profile.rend()}, n);
  for (const TriangleMesh* mesh : {&forward, &backward}) {
    expect_closed_and_clean(*mesh);
    EXPECT_EQ(mesh->positions.size(), 6u * n + 2u);
    EXPECT_NEAR(signed_volume(*mesh), exact * unit_ngon_area(n) / std::numbers::pi, 1e-15);
  }
}

TEST(RevolveProfile, RejectsProfilesOffOrOnTheAxis) {
  EXPECT_THAT(
      [] {
        revolve_profile({{0.1, 0.0}, {0.2, 0.5}, {0.0, 1.0}}, 8);
      },
      ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("on the axis")));
  EXPECT_THAT(
      [] {
        revolve_profile({{0.0, 0.0}, {0.2, 0.5}, {0.0, 0.7}, {0.0, 1.0}}, 8);
      },
      ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("r > 0")));
  EXPECT_THAT(
      [] {
        revolve_profile({{0.0, 0.0}, {0.2, 0.5}, {0.0, 1.0}}, 2);
      },
      ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("segments")));
}

TEST(ExtrudePolygon, NonConvexOutlineGivesAreaTimesHeight) {
  // A comb: three teeth, with collinear points along the back and a teeth's side.
  std::vector<Eigen::Vector2d> outline = {
      {0.0, 0.0}, {0.1, 0.0}, {0.2, 0.0}, {0.3, 0.0}, {0.5, 0.0}, {0.5, 0.4},
      {0.4, 0.4}, {0.4, 0.1}, {0.3, 0.1}, {0.3, 0.4}, {0.2, 0.4}, {0.2, 0.1},
      {0.1, 0.1}, {0.1, 0.2}, {0.1, 0.3}, {0.1, 0.4}, {0.0, 0.4}};
  double twice_area = 0.0;
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const auto& a = outline[i];
    const auto& b = outline[(i + 1) % outline.size()];
    twice_area += a.x() * b.y() - a.y() * b.x();
  }
  const TriangleMesh prism = extrude_polygon(outline, -0.02, 0.03);
  expect_closed_and_clean(prism);
  EXPECT_EQ(prism.triangles.size(), 2u * (outline.size() - 2) + 2u * outline.size());
  EXPECT_NEAR(signed_volume(prism), 0.5 * twice_area * 0.05, 1e-15);

  // Clockwise outline and swapped planes give the same solid.
  const TriangleMesh mirrored = extrude_polygon({outline.rbegin(), outline.rend()}, 0.03, -0.02);
  expect_closed_and_clean(mirrored);
  EXPECT_NEAR(signed_volume(mirrored), 0.5 * twice_area * 0.05, 1e-15);
}

TEST(ExtrudePolygon, FinelySampledRoundOutline) {
  std::vector<Eigen::Vector2d> outline;
  const int n = 400;
  for (int k = 0; k < n; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / n;
    const double radius = 0.1 * (1.0 + 0.3 * std::cos(5.0 * angle));  // a five-petal flower
    outline.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
  }
  double twice_area = 0.0;
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const auto& a = outline[i];
    const auto& b = outline[(i + 1) % outline.size()];
    twice_area += a.x() * b.y() - a.y() * b.x();
  }
  const TriangleMesh prism = extrude_polygon(outline, 0.0, 0.01);
  expect_closed_and_clean(prism);
  EXPECT_NEAR(signed_volume(prism), 0.5 * twice_area * 0.01, 1e-16);
}

TEST(ExtrudePolygon, RejectsSelfIntersectingOrDegenerateOutlines) {
  EXPECT_THAT(
      [] {
        extrude_polygon({{0, 0}, {1, 1}, {1, 0}, {0, 1}}, 0.0, 1.0);
      },
      ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("encloses no area")));
  EXPECT_THAT(
      [] {
        extrude_polygon({{0, 0}, {1, 0}, {1, 1}}, 1.0, 1.0);
      },
      ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("distinct")));
  EXPECT_THAT(
      [] {
        extrude_polygon({{0, 0}, {4, 0}, {4, 2}, {1, -1}, {0, 2}}, 0.0, 1.0);
      },
      ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("not a simple polygon")));
}

TEST(IcosphereMesh, HasTheRightCountsAndConvergesFromInside) {
  const double r = 0.4;
  const double exact = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  double previous_error = 1.0;
  for (int level = 0; level <= 4; ++level) {
    const TriangleMesh sphere = icosphere_mesh(r, level);
    expect_closed_and_clean(sphere);
    EXPECT_EQ(sphere.triangles.size(), 20u << (2 * level));
    EXPECT_EQ(sphere.positions.size(), 10u * (1u << (2 * level)) + 2u);  // Euler: V = F/2 + 2
    for (const auto& p : sphere.positions) EXPECT_NEAR(p.norm(), r, 1e-15);
    const double volume = signed_volume(sphere);
    EXPECT_GT(volume, 0.0);
    EXPECT_LT(volume, exact);
    const double error = relative_error(volume, exact);
    if (level >= 2) {
      EXPECT_NEAR(previous_error / error, 4.0, 0.3);
    }
    previous_error = error;
  }
  EXPECT_LT(previous_error, 3e-3);
}

TEST(TransformMesh, MirrorKeepsTheMeshOutward) {
  TriangleMesh cone = cone_mesh(0.1, 0.2, 24);
  const double volume = signed_volume(cone);
  const Eigen::Matrix3d mirror = Eigen::Vector3d(1.0, -1.0, 1.0).asDiagonal();
  transform_mesh(cone, 2.0 * mirror, Eigen::Vector3d(5.0, 0.0, 0.0));
  expect_closed_and_clean(cone);
  EXPECT_NEAR(signed_volume(cone), 8.0 * volume, 1e-14);

  // A rotation composed with a point reflection (det = -1) too.
  TriangleMesh torus = torus_mesh(0.3, 0.1, 24, 12);
  const double torus_volume = signed_volume(torus);
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  transform_mesh(torus, -rotation, Eigen::Vector3d(0.1, 0.2, 0.3));
  expect_closed_and_clean(torus);
  EXPECT_NEAR(signed_volume(torus), torus_volume, 1e-14);
}

TEST(AppendMesh, DisjointPartsAddUp) {
  TriangleMesh both = box_mesh({1.0, 1.0, 1.0});
  TriangleMesh second = icosphere_mesh(0.5, 2);
  transform_mesh(second, Eigen::Matrix3d::Identity(), Eigen::Vector3d(3.0, 0.0, 0.0));
  append_mesh(both, second);
  expect_closed_and_clean(both);
  EXPECT_EQ(both.triangles.size(), 12u + 320u);
  EXPECT_NEAR(signed_volume(both), 1.0 + signed_volume(second), 1e-14);
}

}  // namespace
}  // namespace tumble::engine
