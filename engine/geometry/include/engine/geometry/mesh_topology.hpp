#pragma once
/// @file Welding and edge topology of triangle soups: what makes a mesh a closed solid.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/geometry/triangle_mesh.hpp"

namespace tumble::engine {

/// Merges vertices whose positions are bit-identical (with -0 equal to +0), keeping the
/// vertices in order of first use, and rewrites the triangles. Returns how many vertices were
/// merged away. Linear in the vertex count (engine/src/vertex_welding.hpp; no assimp post-process).
std::size_t weld_by_position(TriangleMesh& mesh);

/// Removes triangles that use a vertex twice (after welding, the only exact degeneracy that
/// breaks the edge topology; zero-area triangles with three distinct vertices stay, they add
/// nothing to the integrals). Returns how many were removed.
std::size_t remove_degenerate_triangles(TriangleMesh& mesh);

/// Removes vertices that no triangle uses, keeping the others in order. Returns how many.
std::size_t remove_unreferenced_vertices(TriangleMesh& mesh);

/// How the triangles share their edges, and into how many connected parts they fall.
struct Topology {
  /// Edges used by exactly one triangle: the surface is open there.
  std::size_t boundary_edges = 0;
  /// Edges used twice in the same direction (two neighbours that disagree on the winding).
  std::size_t inconsistent_edges = 0;
  /// Edges shared by three or more triangles (not a 2-manifold), whatever their directions.
  std::size_t non_manifold_edges = 0;
  /// Those of the non-manifold edges used more often in one direction than in the other (an odd
  /// count, or fins that do not pair up): the surface does not bound a volume there.
  std::size_t unpaired_non_manifold_edges = 0;
  /// Connected parts (triangles joined through shared vertices).
  std::size_t parts = 0;
  /// Part of each triangle, numbered 0..parts-1 in order of each part's first triangle.
  std::vector<std::uint32_t> triangle_part;

  bool closed() const {
    return boundary_edges == 0 && inconsistent_edges == 0 && unpaired_non_manifold_edges == 0;
  }
};

/// Edge use and connected parts of a welded mesh without repeated-vertex triangles.
Topology analyze_topology(const TriangleMesh& mesh);

/// The two independent halves of analyze_topology, which may run on two threads at once:
/// the edge counts (boundary, inconsistent, non-manifold) and the parts (parts,
/// triangle_part). Each sets only its own fields of `topology`.
void count_edge_uses(const TriangleMesh& mesh, Topology& topology);
void find_parts(const TriangleMesh& mesh, Topology& topology);

/// True when the welded `mesh` bounds solids and faces out of them: no triangle repeats a
/// vertex, every edge is run as often in one direction as in the other (Topology::closed), and
/// every connected part encloses a positive volume. Seen from outside, such a mesh shows only
/// the front of its triangles (a renderer may skip the backs). False for open surfaces,
/// inconsistent windings, inverted parts and cavities.
bool bounds_outward_solids(const TriangleMesh& mesh);

}  // namespace tumble::engine
