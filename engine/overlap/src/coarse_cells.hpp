#pragma once
// The coarse cells of the overlap checks (face_pairs.cpp): each face listed in every cell its
// vertices' cells span, for certifying each cell's faces at once (region_certificate.hpp).
//
// A vertex's cell along each axis is p / c (clamped to +-2^30) rounded down (up to rounding:
// any monotone rounding serves), a face spans the cells from the least to the greatest of its
// vertices' (monotone, so a face touches every cell its exact box touches). A pair of faces whose
// boxes overlap belongs to the cell of the low corner of their boxes' intersection, the greatest of
// their lowest cells along each axis; both faces are listed there (pair_cell).

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
  std::size_t size() const { return coordinates_.size(); }
  /// The faces listed in cell `i`, and where it is.
  std::span<const std::uint32_t> faces(std::size_t i) const {
    return {faces_.data() + start_[i], faces_.data() + start_[i + 1]};
  }
  const CellCoordinates& coordinates(std::size_t i) const { return coordinates_[i]; }
  const CellCoordinates& vertex_cell(std::uint32_t v) const { return vertex_cell_[v]; }
  /// Whether all three vertices of face `t` lie in one cell (the face is listed there alone).
  bool in_one_cell(std::uint32_t t) const { return face_cell_[t] != kSpanning; }
  /// Whether a vertex's coordinates lie in the filter's range (certified_orientation.hpp).
  bool in_filter_range(std::uint32_t v) const { return in_range_[v] != 0; }
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
  void find_vertex_cells(unsigned threads);
  bool choose_layout();
  void list_faces(unsigned threads);
  void number_cells(std::vector<std::vector<std::uint32_t>>& count);
  std::size_t dense_index(const CellCoordinates& c) const;

  const TriangleMesh& mesh_;
  const double inverse_;
  bool usable_ = false;
  std::vector<CellCoordinates> vertex_cell_;
  std::vector<std::uint8_t> in_range_;
  CellCoordinates origin_{};                  ///< the least vertex cell
  std::array<std::int64_t, 3> extent_{};      ///< cells along each axis
  std::vector<CellCoordinates> coordinates_;  ///< of each non-empty cell
  std::vector<std::uint32_t> start_;          ///< its faces' start in faces_, then the end
  std::vector<std::uint32_t> faces_;
  std::vector<std::uint32_t> index_;  ///< per cell of the box: its index + 1, or 0 when empty
  std::vector<std::uint32_t> vertex_index_;  ///< per vertex: its cell's index in the box
  /// Per face: the index in the box of the one cell its vertices share, or kSpanning.
  std::vector<std::uint32_t> face_cell_;
  static constexpr std::uint32_t kSpanning = 0xffffffff;
};

}  // namespace tumble::engine::detail
