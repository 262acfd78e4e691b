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

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "engine/geometry/triangle_mesh.hpp"

namespace tumble::engine::detail {

using CellCoordinates = std::array<std::int32_t, 3>;

class CoarseCells {
 public:
  /// Lists the faces of `mesh` in cells of size `cell`, on `threads` threads. Gives up
  /// (usable() false) when the faces would be listed more than four times each on average.
  CoarseCells(const TriangleMesh& mesh, double cell, unsigned threads);

  bool usable() const { return usable_; }
  /// The cells where some face is listed.
  std::size_t size() const { return coordinates_.size(); }
  /// The faces listed in cell `i` that span several cells, and where it is.
  std::span<const std::uint32_t> faces(std::size_t i) const {
    return {faces_.data() + start_[i], faces_.data() + start_[i + 1]};
  }
  const CellCoordinates& coordinates(std::size_t i) const { return coordinates_[i]; }
  /// Bit 2a (2a + 1) set: every face listed in cell `i` projects along +axis a (-axis a) with
  /// certainly positive orientation (certified_orientation.hpp), its corners in the filter's
  /// range.
  std::uint8_t directions(std::size_t i) const { return directions_[i]; }
  const CellCoordinates& vertex_cell(std::uint32_t v) const { return vertex_cell_[v]; }
  /// Whether all three vertices of face `t` lie in one cell (the face is listed there alone).
  bool in_one_cell(std::uint32_t t) const { return face_cell_[t] != kSpanning; }
  /// The index of the one cell face `t` lies in, given in_one_cell(t).
  std::size_t cell_of_face(std::uint32_t t) const { return index_[face_cell_[t]] - 1; }
  /// The cell a pair of faces whose boxes overlap belongs to (see above).
  CellCoordinates pair_cell(std::uint32_t t, std::uint32_t u) const;
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
  Range range(std::uint32_t t) const;
  Listing listing(std::uint32_t t) const;
  std::uint8_t face_directions(std::uint32_t t) const;
  void find_vertex_cells(unsigned threads);
  bool choose_layout();
  void list_faces(unsigned threads);
  void number_cells(std::vector<std::vector<std::uint32_t>>& count,
                    const std::vector<std::vector<std::uint8_t>>& directions);
  std::size_t dense_index(const CellCoordinates& c) const;

  const TriangleMesh& mesh_;
  const double inverse_;
  bool usable_ = false;
  bool all_in_range_ = true;
  std::vector<CellCoordinates> vertex_cell_;
  std::vector<std::uint8_t> in_range_;
  CellCoordinates origin_{};                  ///< the least vertex cell
  std::array<std::int64_t, 3> extent_{};      ///< cells along each axis
  std::vector<CellCoordinates> coordinates_;  ///< of each cell where a face is listed
  std::vector<std::uint8_t> directions_;      ///< of each such cell
  std::vector<std::uint32_t> start_;          ///< its spanning faces' start in faces_, then the end
  std::vector<std::uint32_t> faces_;
  std::vector<std::uint32_t> index_;  ///< per cell of the box: its index + 1, or 0 when empty
  std::vector<std::uint32_t> vertex_index_;  ///< per vertex: its cell's index in the box
  /// Per face: the index in the box of the one cell its vertices share, or kSpanning.
  std::vector<std::uint32_t> face_cell_;
  static constexpr std::uint32_t kSpanning = 0xffffffff;
  static constexpr std::uint8_t kAllDirections = 0x3f;
};

}  // namespace tumble::engine::detail
