// Back faces of closed meshes (MeshData::closed): skipped where front faces hide them, so the
// image stays that of drawing both sides, and drawn again where they can show (the camera
// inside the mesh's bounding sphere, the near plane cutting it); the arrows' unit shapes are
// closed and face out, as their flag says.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <tuple>
#include <utility>

#include "arrow_geometry.hpp"
#include "render/renderer.hpp"
#include "render_support.hpp"

namespace tumble::render {
namespace {

using testing::box_mesh;

/// The mesh's triangles, their corners welded within 1e-5 (the shapes' seams meet to a float
/// rounding), zero-area ones left out: each directed edge must be run once each way.
void expect_closed_and_outward(const MeshData& mesh, double expected_volume) {
  std::map<std::tuple<long, long, long>, int> ids;
  const auto id = [&](std::uint32_t index) {
    const Eigen::Vector3f& p = mesh.positions[index];
    const auto key = std::make_tuple(std::lround(p.x() * 1e5), std::lround(p.y() * 1e5),
                                     std::lround(p.z() * 1e5));
    return ids.emplace(key, static_cast<int>(ids.size())).first->second;
  };
  std::map<std::pair<int, int>, int> edges;  // uses of a -> b minus uses of b -> a
  double six_volume = 0.0;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const int a = id(mesh.indices[t]), b = id(mesh.indices[t + 1]), c = id(mesh.indices[t + 2]);
    if (a == b || b == c || c == a) continue;
    for (const auto& [from, to] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) {
      edges[{std::min(from, to), std::max(from, to)}] += from < to ? 1 : -1;
    }
    const Eigen::Vector3d p = mesh.positions[mesh.indices[t]].cast<double>();
    const Eigen::Vector3d q = mesh.positions[mesh.indices[t + 1]].cast<double>();
    const Eigen::Vector3d r = mesh.positions[mesh.indices[t + 2]].cast<double>();
    six_volume += p.dot(q.cross(r));
  }
  for (const auto& [edge, balance] : edges) {
    EXPECT_EQ(balance, 0) << "edge " << edge.first << "-" << edge.second;
  }
  EXPECT_NEAR(six_volume / 6.0, expected_volume, 1e-5 * expected_volume);
}

TEST(BackFaces, ArrowShapesAreClosedAndFaceOut) {
  constexpr int kSegments = 24;
  // The inscribed regular polygon's area: n/2 sin(2 pi / n); a prism of height 1, a pyramid.
  const double base = 0.5 * kSegments * std::sin(2.0 * std::numbers::pi / kSegments);
  const MeshData cylinder = detail::unit_cylinder(kSegments);
  const MeshData cone = detail::unit_cone(kSegments);
  EXPECT_TRUE(cylinder.closed);
  EXPECT_TRUE(cone.closed);
  expect_closed_and_outward(cylinder, base);
  expect_closed_and_outward(cone, base / 3.0);
}

/// One frame of `mesh` at `pose` seen from `eye`, drawn by a fresh renderer.
Image draw(const MeshData& mesh, const Eigen::Matrix4f& pose, const Eigen::Vector3f& eye,
           float near_plane = 0.05f) {
  Renderer renderer({160, 120});
  DrawList frame;
  frame.camera.eye = eye;
  frame.camera.target = Eigen::Vector3f::Zero();
  frame.camera.near_plane = near_plane;
  frame.meshes.push_back({renderer.upload(mesh), pose, {0.8f, 0.4f, 0.2f, 1.0f}});
  frame.arrows.push_back({{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.5f}, {0.2f, 0.8f, 0.3f, 1.0f}});
  return renderer.render(frame);
}

std::size_t differing_pixels(const Image& a, const Image& b) {
  std::size_t count = 0;
  for (std::size_t i = 0; i < a.rgba.size(); i += 4) {
    count +=
        a.rgba[i] != b.rgba[i] || a.rgba[i + 1] != b.rgba[i + 1] || a.rgba[i + 2] != b.rgba[i + 2];
  }
  return count;
}

MeshData box(bool closed) {
  MeshData mesh = box_mesh({0.5f, 0.4f, 0.3f});
  mesh.closed = closed;
  return mesh;
}

const Eigen::Matrix4f kTurned =
    Eigen::Affine3f(Eigen::AngleAxisf(0.7f, Eigen::Vector3f(0.3f, 0.5f, 0.8f).normalized()))
        .matrix();

TEST(BackFaces, ClosedMeshSeenFromOutsideLooksAsBothSidesDrawn) {
  const Eigen::Vector3f eye(3.0f, -4.0f, 2.5f);
  // Only silhouette pixels may differ, where a back face at the same depth won the tie.
  EXPECT_LE(differing_pixels(draw(box(true), kTurned, eye), draw(box(false), kTurned, eye)), 8u);
  // A mirroring pose turns the winding around: still the front faces that are kept.
  Eigen::Matrix4f mirrored = kTurned;
  mirrored.col(0) *= -1.0f;
  EXPECT_LE(differing_pixels(draw(box(true), mirrored, eye), draw(box(false), mirrored, eye)), 8u);
}

TEST(BackFaces, MarkedClosedAreSkippedAsAnInsideOutBoxShows) {
  // An inside-out box falsely marked closed loses its near faces: the far faces' insides show.
  MeshData inside_out = box(true);
  for (std::size_t t = 0; t < inside_out.indices.size(); t += 3) {
    std::swap(inside_out.indices[t + 1], inside_out.indices[t + 2]);
  }
  MeshData both_sides = inside_out;
  both_sides.closed = false;
  const Eigen::Vector3f eye(3.0f, -4.0f, 2.5f);
  EXPECT_GT(differing_pixels(draw(inside_out, kTurned, eye), draw(both_sides, kTurned, eye)), 200u);
}

TEST(BackFaces, DrawnWhereTheyCanShow) {
  const Eigen::Matrix4f identity = Eigen::Matrix4f::Identity();
  // The camera inside the box, and outside it with the near plane cutting it open: the same
  // image as both sides drawn, pixel for pixel.
  const Eigen::Vector3f inside(0.1f, -0.1f, 0.05f);
  EXPECT_EQ(differing_pixels(draw(box(true), identity, inside), draw(box(false), identity, inside)),
            0u);
  const Eigen::Vector3f near_it(0.0f, -1.2f, 0.0f);
  EXPECT_EQ(differing_pixels(draw(box(true), identity, near_it, 0.9f),
                             draw(box(false), identity, near_it, 0.9f)),
            0u);
  // That near plane does cut the box: without it the image differs.
  EXPECT_GT(differing_pixels(draw(box(false), identity, near_it, 0.9f),
                             draw(box(false), identity, near_it, 0.05f)),
            100u);
}

}  // namespace
}  // namespace tumble::render
