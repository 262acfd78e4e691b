#pragma once
// A certificate that no two faces of a set meet, except at the edges and vertices they share,
// found by projection (face_pairs.cpp certifies the faces touching each coarse cell with it).
//
// Let R be a set of faces, projected along a coordinate axis (x, y or z, either way), and let
// every face of R project with positive orientation. The projection is a piecewise linear map
// of the 2-chain R into the plane; at a point y off the projected edges, the number of faces
// whose projection contains y (each counted +1, all being positive) is the degree of the map
// at y, which equals the winding number around y of the projected boundary chain of R (the
// directed edges of R's faces that the other faces of R do not cancel). If that chain is one
// closed polygon that does not touch itself, its winding number is 1 inside and 0 outside, so
// the projections of R's faces have disjoint interiors. Then no two faces of R cross, repeat,
// mirror or fold onto each other, and no two of different parts meet: a meeting point would be
// covered twice or make the boundary polygon touch itself. (Degree of piecewise linear maps:
// e.g. Outerelo and Ruiz, "Mapping Degree Theory", AMS 2009; regions certified by a projection
// direction and a boundary contour, as here, are the normal-cone and contour tests of Volino and
// Magnenat-Thalmann 1994 and Schvartzman, Perez and Otaduy 2010, made exact: every sign used
// is certified by certified_orientation.hpp, and anything uncertain refuses the certificate.)
//
// The boundary chain is found from the edges that leave the region's cell alone: an edge
// whose vertices' cells span the region's cell is shared only by faces listed there, so in a
// closed, consistently wound mesh (every edge used as often each way) its uses cancel.
//
// A region that is not certified says nothing: its pairs are then tested one by one.

#include <cstdint>
#include <span>
#include <vector>

#include "coarse_cells.hpp"
#include "engine/geometry/triangle_mesh.hpp"

namespace tumble::engine::detail {

class RegionCertificate {
 public:
  /// For the faces of a closed, consistently wound mesh, listed in coarse cells.
  explicit RegionCertificate(const TriangleMesh& mesh) : mesh_(mesh) {}

  /// Whether no two of the faces listed in a cell meet beyond what they share (see above),
  /// given the entries of those that span several cells (CoarseCells::faces: each with the
  /// edges that lie outside the cell) and the directions along which every face listed there
  /// projects with certainly positive orientation (CoarseCells::directions: none when a
  /// coordinate lies outside the filter's range).
  bool certify(std::span<const std::uint32_t> spanning, std::uint8_t directions);

 private:
  struct Edge {
    std::uint32_t from, to;
  };
  struct EdgeBox {
    double low_u, high_u, low_v, high_v;
  };
  struct Slot {
    std::uint64_t key;
    std::int32_t uses;
  };
  bool find_boundary(std::span<const std::uint32_t> faces);
  bool trace_loop();
  bool loop_is_simple();
  double u(std::uint32_t v) const { return mesh_.positions[v][axis_u_]; }
  double v(std::uint32_t v) const { return mesh_.positions[v][axis_v_]; }

  const TriangleMesh& mesh_;
  int axis_u_ = 0, axis_v_ = 1;  ///< the plane's coordinates, counter-clockwise seen along d
  std::vector<Slot> slots_;
  std::vector<Edge> boundary_;
  std::vector<std::uint32_t> starting_;  ///< trace_loop's table: boundary_ by start
  std::vector<std::uint32_t> loop_;
  std::vector<double> plane_;          ///< the loop's vertices: u, v, the first again at the end
  std::vector<EdgeBox> boxes_;         ///< of the loop's edges
  std::vector<std::uint32_t> order_;   ///< edges by least u
  std::vector<std::uint32_t> active_;  ///< edges the sweep line crosses
};

}  // namespace tumble::engine::detail
