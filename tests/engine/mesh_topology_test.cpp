// Welding and edge topology on hand-made meshes whose counts are known by inspection.
#include "engine/mesh_topology.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <tuple>

namespace tumble::engine {
namespace {

using Triangle = std::array<std::uint32_t, 3>;

/// Tetrahedron on (0,0,0), (1,0,0), (0,1,0), (0,0,1), wound outward, vertex indices + `base`.
std::vector<Triangle> tetrahedron_triangles(std::uint32_t base = 0) {
  return {{base + 0, base + 2, base + 1},
          {base + 0, base + 1, base + 3},
          {base + 0, base + 3, base + 2},
          {base + 1, base + 2, base + 3}};
}

std::vector<Eigen::Vector3d> tetrahedron_positions(const Eigen::Vector3d& offset) {
  return {offset, offset + Eigen::Vector3d::UnitX(), offset + Eigen::Vector3d::UnitY(),
          offset + Eigen::Vector3d::UnitZ()};
}

TriangleMesh tetrahedron() {
  return {tetrahedron_positions(Eigen::Vector3d::Zero()), tetrahedron_triangles()};
}

TEST(WeldByPosition, MergesEqualPositionsKeepingFirstOccurrenceOrder) {
  const Eigen::Vector3d a(1.0, 2.0, 3.0), b(-1.0, 0.5, 0.25), c(4.0, 4.0, 4.0);
  TriangleMesh mesh{{a, b, a, c, b, c}, {{0, 1, 3}, {2, 4, 5}, {5, 4, 2}}};
  EXPECT_EQ(weld_by_position(mesh), 3u);
  EXPECT_THAT(mesh.positions, ::testing::ElementsAre(a, b, c));
  EXPECT_THAT(mesh.triangles,
              ::testing::ElementsAre(Triangle{0, 1, 2}, Triangle{0, 1, 2}, Triangle{2, 1, 0}));
}

TEST(WeldByPosition, NegativeZeroEqualsPositiveZero) {
  TriangleMesh mesh{{{0.0, -0.0, 1.0}, {-0.0, 0.0, 1.0}, {1.0, 0.0, 0.0}, {0.0, 0.0, -0.0}},
                    {{0, 2, 1}, {1, 2, 3}}};
  EXPECT_EQ(weld_by_position(mesh), 1u);
  ASSERT_EQ(mesh.positions.size(), 3u);
  EXPECT_THAT(mesh.triangles, ::testing::ElementsAre(Triangle{0, 1, 0}, Triangle{0, 1, 2}));
}

TEST(WeldByPosition, NearlyEqualPositionsStayApart) {
  // Welding is exact: one ulp apart is a different vertex.
  const double x = 0.1;
  TriangleMesh mesh{{{x, 0.0, 0.0}, {std::nextafter(x, 1.0), 0.0, 0.0}, {0.0, 1.0, 0.0}},
                    {{0, 1, 2}}};
  EXPECT_EQ(weld_by_position(mesh), 0u);
  EXPECT_EQ(mesh.positions.size(), 3u);
}

TEST(WeldByPosition, MatchesNaiveWeldOnLargeSoup) {
  // Many duplicates of a few thousand distinct points, in random order: compare with a welding
  // done by a std::map (first occurrence numbering).
  std::mt19937_64 rng(42);
  std::uniform_int_distribution<int> coordinate(-20, 20);
  std::vector<Eigen::Vector3d> distinct;
  for (int i = 0; i < 3000; ++i) {
    distinct.emplace_back(coordinate(rng) * 0.1, coordinate(rng) * 0.1, coordinate(rng) * 0.1);
  }
  std::uniform_int_distribution<std::size_t> pick(0, distinct.size() - 1);
  TriangleMesh mesh;
  for (int i = 0; i < 60000; ++i) {
    // One position in five is the same point: a long run of equal positions (a fan's centre).
    Eigen::Vector3d p = i % 5 == 0 ? distinct[0] : distinct[pick(rng)];
    if (i % 7 == 0) {
      for (int axis = 0; axis < 3; ++axis) {
        if (p[axis] == 0.0) p[axis] = -0.0;  // the same position with a negative zero
      }
    }
    mesh.positions.push_back(p);
  }
  for (std::uint32_t i = 0; i + 2 < mesh.positions.size(); i += 3) {
    mesh.triangles.push_back({i, i + 1, i + 2});
  }

  std::map<std::tuple<double, double, double>, std::uint32_t> index_of;
  std::vector<Eigen::Vector3d> expected_positions;
  std::vector<std::uint32_t> expected_index;
  for (const Eigen::Vector3d& p : mesh.positions) {
    const auto key = std::make_tuple(p.x() + 0.0, p.y() + 0.0, p.z() + 0.0);  // -0 -> +0
    const auto [it, inserted] =
        index_of.try_emplace(key, static_cast<std::uint32_t>(expected_positions.size()));
    if (inserted) expected_positions.push_back(p);
    expected_index.push_back(it->second);
  }
  const TriangleMesh original = mesh;

  EXPECT_EQ(weld_by_position(mesh), original.positions.size() - expected_positions.size());
  ASSERT_EQ(mesh.positions.size(), expected_positions.size());
  for (std::size_t i = 0; i < expected_positions.size(); ++i) {
    ASSERT_EQ(mesh.positions[i], expected_positions[i]) << i;
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int corner = 0; corner < 3; ++corner) {
      ASSERT_EQ(mesh.triangles[t][corner], expected_index[original.triangles[t][corner]]);
    }
  }
}

TEST(RemoveDegenerateTriangles, RemovesOnlyRepeatedVertexTriangles) {
  TriangleMesh mesh{{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}},
                    {{0, 1, 3}, {0, 0, 1}, {1, 2, 1}, {3, 1, 3}, {0, 1, 2}, {2, 2, 2}}};
  EXPECT_EQ(remove_degenerate_triangles(mesh), 4u);
  // The collinear (zero-area) triangle 0-1-2 has three distinct vertices: it stays.
  EXPECT_THAT(mesh.triangles, ::testing::ElementsAre(Triangle{0, 1, 3}, Triangle{0, 1, 2}));
}

TEST(AnalyzeTopology, ClosedTetrahedron) {
  const Topology topology = analyze_topology(tetrahedron());
  EXPECT_EQ(topology.boundary_edges, 0u);
  EXPECT_EQ(topology.inconsistent_edges, 0u);
  EXPECT_EQ(topology.non_manifold_edges, 0u);
  EXPECT_EQ(topology.parts, 1u);
  EXPECT_TRUE(topology.closed());
  EXPECT_THAT(topology.triangle_part, ::testing::ElementsAre(0u, 0u, 0u, 0u));
}

TEST(AnalyzeTopology, MissingFaceLeavesThreeBoundaryEdges) {
  TriangleMesh mesh = tetrahedron();
  mesh.triangles.pop_back();
  const Topology topology = analyze_topology(mesh);
  EXPECT_EQ(topology.boundary_edges, 3u);
  EXPECT_EQ(topology.inconsistent_edges, 0u);
  EXPECT_FALSE(topology.closed());
}

TEST(AnalyzeTopology, SingleTriangleAndOpenStrip) {
  TriangleMesh single{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}};
  EXPECT_EQ(analyze_topology(single).boundary_edges, 3u);

  // A square of two triangles: 4 boundary edges, the diagonal is shared properly.
  TriangleMesh square{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}}};
  const Topology topology = analyze_topology(square);
  EXPECT_EQ(topology.boundary_edges, 4u);
  EXPECT_EQ(topology.inconsistent_edges, 0u);
  EXPECT_EQ(topology.parts, 1u);
}

TEST(AnalyzeTopology, OneFlippedFaceMakesItsThreeEdgesInconsistent) {
  TriangleMesh mesh = tetrahedron();
  std::swap(mesh.triangles[3][1], mesh.triangles[3][2]);
  const Topology topology = analyze_topology(mesh);
  EXPECT_EQ(topology.inconsistent_edges, 3u);
  EXPECT_EQ(topology.boundary_edges, 0u);
  EXPECT_EQ(topology.non_manifold_edges, 0u);
  EXPECT_FALSE(topology.closed());
}

TEST(AnalyzeTopology, AllFacesFlippedIsStillConsistent) {
  TriangleMesh mesh = tetrahedron();
  for (Triangle& t : mesh.triangles) std::swap(t[0], t[1]);
  EXPECT_TRUE(analyze_topology(mesh).closed());
}

TEST(AnalyzeTopology, TwoTetrahedraSharingAnEdgeAreNonManifold) {
  // A second tetrahedron, the first turned half a turn about z, shares the edge 0-3: that edge
  // is used by four triangles, two in each direction.
  TriangleMesh mesh = tetrahedron();
  mesh.positions.push_back({-1.0, 0.0, 0.0});  // 4
  mesh.positions.push_back({0.0, -1.0, 0.0});  // 5
  // Tetrahedron (0, 4, 5, 3): vertices 1 and 2 mapped to 4 and 5, windings kept.
  mesh.triangles.push_back({0, 5, 4});
  mesh.triangles.push_back({0, 4, 3});
  mesh.triangles.push_back({0, 3, 5});
  mesh.triangles.push_back({4, 5, 3});
  const Topology topology = analyze_topology(mesh);
  EXPECT_EQ(topology.non_manifold_edges, 1u);
  EXPECT_EQ(topology.boundary_edges, 0u);
  EXPECT_EQ(topology.inconsistent_edges, 0u);
  EXPECT_TRUE(topology.closed());
  EXPECT_EQ(topology.parts, 1u);
}

TEST(AnalyzeTopology, ThreeTrianglesOnOneEdgeAreInconsistent) {
  // Three fins on the edge 0-1: directions 0->1, 1->0, 0->1 do not balance.
  TriangleMesh mesh{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, -1, -1}},
                    {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}};
  const Topology topology = analyze_topology(mesh);
  EXPECT_EQ(topology.inconsistent_edges, 1u);
  EXPECT_EQ(topology.boundary_edges, 6u);
}

TEST(AnalyzeTopology, PartsNumberedInOrderOfFirstTriangle) {
  // Three separate tetrahedra whose triangles are interleaved; the part of the first
  // triangle is 0, the next new part 1, and so on.
  TriangleMesh mesh;
  for (int k = 0; k < 3; ++k) {
    const auto positions = tetrahedron_positions(Eigen::Vector3d(3.0 * k, 0.0, 0.0));
    mesh.positions.insert(mesh.positions.end(), positions.begin(), positions.end());
  }
  const auto t0 = tetrahedron_triangles(0), t1 = tetrahedron_triangles(4),
             t2 = tetrahedron_triangles(8);
  mesh.triangles = {t2[0], t0[0], t2[1], t1[0], t0[1], t1[1],
                    t1[2], t0[2], t2[2], t0[3], t1[3], t2[3]};
  const Topology topology = analyze_topology(mesh);
  EXPECT_EQ(topology.parts, 3u);
  EXPECT_TRUE(topology.closed());
  EXPECT_THAT(topology.triangle_part,
              ::testing::ElementsAre(0u, 1u, 0u, 2u, 1u, 2u, 2u, 1u, 0u, 1u, 2u, 0u));
}

TEST(AnalyzeTopology, PartsJoinThroughASharedVertex) {
  // Two tetrahedra touching at one vertex form one part (and every edge is still manifold).
  TriangleMesh mesh = tetrahedron();
  mesh.positions.push_back({-1.0, 0.0, 0.0});
  mesh.positions.push_back({0.0, -1.0, 0.0});
  mesh.positions.push_back({0.0, 0.0, -1.0});
  // Tetrahedron (0, 4, 5, 6): the first reflected through the origin (point reflection
  // reverses orientation, so the winding is reversed too).
  mesh.triangles.push_back({0, 4, 5});
  mesh.triangles.push_back({0, 6, 4});
  mesh.triangles.push_back({0, 5, 6});
  mesh.triangles.push_back({4, 6, 5});
  const Topology topology = analyze_topology(mesh);
  EXPECT_EQ(topology.parts, 1u);
  EXPECT_TRUE(topology.closed());
  EXPECT_EQ(topology.non_manifold_edges, 0u);
}

TEST(AnalyzeTopology, UnweldedSoupIsAllBoundary) {
  // Without welding, each triangle's edges are its own: topology needs welded input.
  TriangleMesh soup;
  const TriangleMesh tet = tetrahedron();
  for (const Triangle& t : tet.triangles) {
    const auto base = static_cast<std::uint32_t>(soup.positions.size());
    for (const std::uint32_t v : t) soup.positions.push_back(tet.positions[v]);
    soup.triangles.push_back({base, base + 1, base + 2});
  }
  const Topology before = analyze_topology(soup);
  EXPECT_EQ(before.boundary_edges, 12u);
  EXPECT_EQ(before.parts, 4u);

  EXPECT_EQ(weld_by_position(soup), 8u);
  const Topology after = analyze_topology(soup);
  EXPECT_TRUE(after.closed());
  EXPECT_EQ(after.parts, 1u);
}

}  // namespace
}  // namespace tumble::engine
