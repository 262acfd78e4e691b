#pragma once
// The coarse cells of the overlap checks (face_pairs.cpp): each face listed in every cell its
// vertices' cells span, for certifying each cell's faces at once (region_certificate.hpp).
//
// A vertex's cell along each axis is p / c (clamped to +-2^30) rounded down (up to rounding:
// any monotone rounding serves), a face spans the cells from the least to the greatest of its
// vertices' (monotone, so a face touches every cell its exact box touches). A pair of faces whose
// boxes overlap belongs to the cell of the low corner of their boxes' intersection, the greatest of
// their lowest cells along each axis; both faces are listed there (pair_cell).
//
// What a certificate needs of a cell's faces is found in the pass that counts them, face by
// face in the mesh's order: along which of the six directions (+-x, +-y, +-z) every face listed
// there projects with certainly positive orientation (directions()), and which faces span
// several cells (faces(): only those carry the edges that leave a cell). Faces lying in one
// cell, most of them, are never listed one by one: listing them all, and reading their corners
// again in cell order to test them, had cost more than the rest of the checks.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "engine/geometry/triangle_mesh.hpp"

namespace tumble::engine::detail {

using CellCoordinates = std::array<std::int32_t, 3>;

class CoarseCells {
 public:
  /// The least and greatest coordinates of a mesh's vertices.
  using Bounds = std::pair<Eigen::Vector3d, Eigen::Vector3d>;

  /// Lists the faces of `mesh` in cells of size `cell`, on `threads` threads, given the
  /// vertices' bounds if known. Gives up (usable() false) when the faces would be listed more
  /// than four times each on average.
  CoarseCells(const TriangleMesh& mesh, double cell, unsigned threads,
              const std::optional<Bounds>& bounds = std::nullopt);

  bool usable() const { return usable_; }
  /// The cells where some face is listed.
  std::size_t size() const { return coordinates_.size(); }
  /// The faces listed in cell `i` that span several cells, and where it is. Each entry is a
  /// face (its low kFaceBits bits) and which of its edges lie outside the cell (bit k above
  /// them: the edge from corner k to corner k + 1; see edges_outside).
  std::span<const std::uint32_t> faces(std::size_t i) const {
    return {faces_.data() + start_[i], faces_.data() + start_[i + 1]};
  }
  static constexpr unsigned kFaceBits = 29;  ///< faces are fewer than 2^29 (find_face_pairs)
  const CellCoordinates& coordinates(std::size_t i) const { return coordinates_[i]; }
  /// Bit 2a (2a + 1) set: every face listed in cell `i` projects along +axis a (-axis a) with
  /// certainly positive orientation (certified_orientation.hpp), its corners in the filter's
  /// range.
  std::uint8_t directions(std::size_t i) const { return directions_[i]; }
  /// Vertex v's cell, from its coordinates (a table of them, the size of the vertices, cost
  /// more to fill than the few lookups of spanning faces' corners cost to compute).
  CellCoordinates vertex_cell(std::uint32_t v) const {
    const Eigen::Vector3d& p = mesh_.positions[v];
    return {cell_of(p.x()), cell_of(p.y()), cell_of(p.z())};
  }
  /// Whether all three vertices of face `t` lie in one cell (the face is listed there alone).
  bool in_one_cell(std::uint32_t t) const {
    const auto& f = mesh_.triangles[t];
    return vertex_index_[f[0]] == vertex_index_[f[1]] && vertex_index_[f[0]] == vertex_index_[f[2]];
  }
  /// The index of the one cell face `t` lies in, given in_one_cell(t).
  std::size_t cell_of_face(std::uint32_t t) const {
    return index_[vertex_index_[mesh_.triangles[t][0]]] - 1;
  }
  /// The lowest cell face t touches: the cell of its least coordinates.
  CellCoordinates low_cell(std::uint32_t t) const;
  /// The cell a pair of faces whose boxes overlap belongs to (see above), given their
  /// low_cell()s.
  static CellCoordinates pair_cell(const CellCoordinates& a, const CellCoordinates& b) {
    return {std::max(a[0], b[0]), std::max(a[1], b[1]), std::max(a[2], b[2])};
  }
  /// The index of the cell at `c`, none when no face is listed there.
  std::optional<std::size_t> find(const CellCoordinates& c) const;

 private:
  struct Range {
    CellCoordinates low, high;
  };
  /// Where a face is listed: its lowest cell's index in the box, and its span along each axis.
  struct Listing {
    std::uint32_t low;
    std::array<std::uint16_t, 3> span;
  };
  /// A face spanning several cells, and its corners' cells.
  struct SpanningFace {
    std::uint32_t face;
    CellCoordinates corner[3];
  };
  static Range range(const CellCoordinates (&corner)[3]);
  Listing listing(const Range& r) const;
  std::uint8_t face_directions(std::uint32_t t) const;
  static std::uint32_t edges_outside(const CellCoordinates (&corner)[3],
                                     const CellCoordinates& cell);
  CellCoordinates cell_at(std::size_t cell) const;
  std::size_t dense_index(const CellCoordinates& c) const {
    return static_cast<std::size_t>(
        ((std::int64_t{c[2]} - origin_[2]) * extent_[1] + (std::int64_t{c[1]} - origin_[1])) *
            extent_[0] +
        (std::int64_t{c[0]} - origin_[0]));
  }
  /// v / cell rounded down, but for the rounding of the offset: monotone in v, so the cells of
  /// the least and the greatest coordinates bound every vertex's. Clamped by min and max rather
  /// than std::clamp, whose comparisons compile to branches (v is finite).
  std::int32_t cell_of(double v) const {
    const double scaled = std::min(std::max(v * inverse_, -kCellLimit), kCellLimit);
    return static_cast<std::int32_t>(static_cast<std::int64_t>(scaled + kCellLimit) -
                                     static_cast<std::int64_t>(kCellLimit));
  }
  void find_box(unsigned threads);
  void set_box(const Bounds& bounds);
  bool choose_layout();
  bool find_vertex_cells(unsigned threads);
  void find_in_range();
  void list_faces(unsigned threads);
  void number_cells(std::vector<std::vector<std::uint32_t>>& count,
                    const std::vector<std::vector<std::uint8_t>>& directions);
  void list_spanning(unsigned threads, std::vector<std::vector<std::uint32_t>>& count,
                     const std::vector<std::vector<SpanningFace>>& spanning);

  const TriangleMesh& mesh_;
  const double inverse_;
  bool usable_ = false;
  bool all_in_range_ = true;
  std::vector<std::uint8_t> in_range_;        ///< per vertex, only when some vertex is out of range
  CellCoordinates origin_{};                  ///< the least vertex cell
  std::array<std::int64_t, 3> extent_{};      ///< cells along each axis
  std::vector<CellCoordinates> coordinates_;  ///< of each cell where a face is listed
  std::vector<std::uint8_t> directions_;      ///< of each such cell
  std::vector<std::uint32_t> start_;          ///< its spanning faces' start in faces_, then the end
  std::vector<std::uint32_t> faces_;
  std::vector<std::uint32_t> index_;  ///< per cell of the box: its index + 1, or 0 when empty
  std::vector<std::uint32_t> vertex_index_;  ///< per vertex: its cell's index in the box
  static constexpr std::uint8_t kAllDirections = 0x3f;
  static constexpr double kCellLimit = 0x1p30;  ///< cell coordinates are clamped to +-2^30
};

}  // namespace tumble::engine::detail
