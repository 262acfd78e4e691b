// Welding and edge topology on hand-made meshes whose counts are known by inspection.
#include "engine/geometry/mesh_topology.hpp"

#include "engine/geometry/primitive_meshes.hpp"

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

TEST(RemoveUnreferencedVertices, KeepsUsedVerticesInOrderAndRenumbers) {
  // The tetrahedron's four vertices spread among unused ones: first, middle and last, or
  // only after some used ones.
  const TriangleMesh expected = tetrahedron();
  for (const std::vector<bool>& used :
       {std::vector<bool>{0, 1, 1, 0, 1, 1, 0}, std::vector<bool>{1, 1, 0, 1, 0, 0, 1}}) {
    TriangleMesh mesh;
    std::vector<std::uint32_t> moved;
    for (std::size_t i = 0; i < used.size(); ++i) {
      if (used[i]) {
        moved.push_back(static_cast<std::uint32_t>(i));
        mesh.positions.push_back(expected.positions[moved.size() - 1]);
      } else {
        mesh.positions.push_back(Eigen::Vector3d(9.0, 9.0, 9.0 + static_cast<double>(i)));
      }
    }
    mesh.triangles = expected.triangles;
    for (Triangle& t : mesh.triangles) {
      for (std::uint32_t& v : t) v = moved[v];
    }
    EXPECT_EQ(remove_unreferenced_vertices(mesh), 3u);
    EXPECT_EQ(mesh.positions, expected.positions);
    EXPECT_EQ(mesh.triangles, expected.triangles);
  }
  // A mesh that uses every vertex is left as it is.
  TriangleMesh mesh = tetrahedron();
  EXPECT_EQ(remove_unreferenced_vertices(mesh), 0u);
  EXPECT_EQ(mesh.positions, expected.positions);
  EXPECT_EQ(mesh.triangles, expected.triangles);
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

TEST(AnalyzeTopology, ThreeTrianglesOnOneEdgeAreNonManifoldNotInconsistent) {
  // Three fins on the edge 0-1: directions 0->1, 1->0, 0->1 do not balance. An edge of three
  // triangles is a non-manifold edge, whatever its directions; it used to be counted as
  // inconsistent winding.
  TriangleMesh mesh{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, -1, -1}},
                    {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}};
  const Topology topology = analyze_topology(mesh);
  EXPECT_EQ(topology.inconsistent_edges, 0u);
  EXPECT_EQ(topology.non_manifold_edges, 1u);
  EXPECT_EQ(topology.unpaired_non_manifold_edges, 1u);
  EXPECT_EQ(topology.boundary_edges, 6u);
  EXPECT_FALSE(topology.closed());
}

TEST(AnalyzeTopology, AStrayReversedCopyOfAFaceMakesThreeUnpairedNonManifoldEdges) {
  // No edge is open, yet each edge of the copied face is used twice one way and once the
  // other: three non-manifold edges that do not pair up, so the surface is not closed.
  TriangleMesh mesh = tetrahedron();
  const Triangle face = mesh.triangles[0];
  mesh.triangles.push_back({face[0], face[2], face[1]});
  const Topology topology = analyze_topology(mesh);
  EXPECT_EQ(topology.non_manifold_edges, 3u);
  EXPECT_EQ(topology.unpaired_non_manifold_edges, 3u);
  EXPECT_EQ(topology.inconsistent_edges, 0u);
  EXPECT_EQ(topology.boundary_edges, 0u);
  EXPECT_FALSE(topology.closed());
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

/// Edge counts by the definition, with an ordered map from each undirected edge to its uses in
/// each direction: the oracle for count_edge_uses' bucketed counting.
Topology edge_counts_by_map(const TriangleMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::pair<int, int>> uses;
  for (const Triangle& t : mesh.triangles) {
    for (int corner = 0; corner < 3; ++corner) {
      const std::uint32_t from = t[corner], to = t[(corner + 1) % 3];
      auto& [forward, backward] = uses[{std::min(from, to), std::max(from, to)}];
      (from < to ? forward : backward)++;
    }
  }
  Topology counts;
  for (const auto& [edge, use] : uses) {
    const auto [forward, backward] = use;
    if (forward + backward == 1) {
      ++counts.boundary_edges;
    } else if (forward + backward > 2) {
      ++counts.non_manifold_edges;
      if (forward != backward) ++counts.unpaired_non_manifold_edges;
    } else if (forward != backward) {
      ++counts.inconsistent_edges;
    }
  }
  return counts;
}

TEST(AnalyzeTopology, EdgeCountsMatchTheDefinitionOnDamagedMeshes) {
  // A closed torus damaged at random: faces removed, flipped and repeated (once or twice), and
  // fans around hub vertices, so buckets range from clean pairs through every kind of bad edge
  // to more than eight entries (the sorted fallback), on each of which the counts must agree.
  std::mt19937 random(11);
  for (int trial = 0; trial < 20; ++trial) {
    SCOPED_TRACE(trial);
    TriangleMesh mesh = torus_mesh(1.0, 0.4, 24, 12);
    const auto vertex_count = static_cast<std::uint32_t>(mesh.positions.size());
    std::uniform_int_distribution<std::size_t> face(0, mesh.triangles.size() - 1);
    std::uniform_int_distribution<std::uint32_t> vertex(0, vertex_count - 1);
    const int damage = trial % 4 == 0 ? 0 : 1 + trial;
    for (int k = 0; k < damage; ++k) {
      Triangle& t = mesh.triangles[face(random)];
      switch (random() % 4) {
        case 0:
          t = mesh.triangles.back(), mesh.triangles.pop_back();
          break;
        case 1:
          std::swap(t[1], t[2]);
          break;
        case 2:
          mesh.triangles.push_back(t);
          break;
        default:
          mesh.triangles.push_back({t[0], t[2], t[1]});
          break;
      }
    }
    // A hub joined to a ring of random vertices, closed or not.
    if (trial % 2 == 1) {
      mesh.positions.push_back(Eigen::Vector3d::Zero());
      const std::uint32_t hub = vertex_count;
      std::vector<std::uint32_t> ring(5 + trial);
      for (std::uint32_t& v : ring) v = vertex(random);
      for (std::size_t i = 0; i + (trial % 3 == 0 ? 0 : 1) < ring.size(); ++i) {
        mesh.triangles.push_back({hub, ring[i], ring[(i + 1) % ring.size()]});
      }
    }
    std::erase_if(mesh.triangles,
                  [](const Triangle& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; });
    const Topology expected = edge_counts_by_map(mesh);
    const Topology topology = analyze_topology(mesh);
    EXPECT_EQ(topology.boundary_edges, expected.boundary_edges);
    EXPECT_EQ(topology.inconsistent_edges, expected.inconsistent_edges);
    EXPECT_EQ(topology.non_manifold_edges, expected.non_manifold_edges);
    EXPECT_EQ(topology.unpaired_non_manifold_edges, expected.unpaired_non_manifold_edges);
    if (damage == 0 && trial % 2 == 0) {
      EXPECT_TRUE(topology.closed());
    }
  }
}

/// The mesh with every triangle's winding turned around.
TriangleMesh turned_inside_out(TriangleMesh mesh) {
  for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  return mesh;
}

/// `a` and `b` in one mesh (b's vertices after a's).
TriangleMesh side_by_side(const TriangleMesh& a, const TriangleMesh& b) {
  TriangleMesh mesh = a;
  const auto base = static_cast<std::uint32_t>(a.positions.size());
  mesh.positions.insert(mesh.positions.end(), b.positions.begin(), b.positions.end());
  for (auto t : b.triangles) mesh.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  return mesh;
}

TEST(BoundsOutwardSolids, HoldsForClosedOutwardMeshesOfOneOrMoreParts) {
  EXPECT_TRUE(bounds_outward_solids(tetrahedron()));
  EXPECT_TRUE(bounds_outward_solids(box_mesh({1.0, 2.0, 3.0})));
  TriangleMesh far_box = box_mesh({1.0, 1.0, 1.0});
  for (auto& p : far_box.positions) p.x() += 5.0;
  EXPECT_TRUE(bounds_outward_solids(side_by_side(tetrahedron(), far_box)));
}

TEST(BoundsOutwardSolids, FailsForInvertedOpenRepeatedOrHollowMeshes) {
  EXPECT_FALSE(bounds_outward_solids(turned_inside_out(tetrahedron())));
  TriangleMesh open = box_mesh({1.0, 1.0, 1.0});
  open.triangles.pop_back();
  EXPECT_FALSE(bounds_outward_solids(open));
  // One face wound the other way: its three edges run twice in one direction.
  TriangleMesh inconsistent = tetrahedron();
  std::swap(inconsistent.triangles[0][1], inconsistent.triangles[0][2]);
  EXPECT_FALSE(bounds_outward_solids(inconsistent));
  TriangleMesh repeated = tetrahedron();
  repeated.triangles.push_back({0, 0, 1});
  repeated.triangles.push_back({1, 0, 0});
  EXPECT_FALSE(bounds_outward_solids(repeated));
  // A cavity (an inward box inside an outward one) and an inverted part beside an outward
  // one: closed, but an inward-facing part shows its back faces from somewhere outside it.
  TriangleMesh cavity = box_mesh({0.5, 0.5, 0.5});
  EXPECT_FALSE(
      bounds_outward_solids(side_by_side(box_mesh({2.0, 2.0, 2.0}), turned_inside_out(cavity))));
  TriangleMesh beside = box_mesh({1.0, 1.0, 1.0});
  for (auto& p : beside.positions) p.y() += 4.0;
  EXPECT_FALSE(bounds_outward_solids(side_by_side(tetrahedron(), turned_inside_out(beside))));
}

}  // namespace
}  // namespace tumble::engine
