// A certificate by projection that no two faces of a set meet (region_certificate.hpp).
#include "region_certificate.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <utility>

#include "certified_orientation.hpp"

namespace tumble::engine::detail {
namespace {

constexpr std::uint64_t kNoBoundaryEdge = std::numeric_limits<std::uint64_t>::max();
constexpr std::uint32_t kNoEdge = std::numeric_limits<std::uint32_t>::max();

/// Whether (b - a) . (c - b) > 0 certainly: going on from b, not back. A sum of two products
/// of rounded differences, as orient2d's terms, so its error is below 8 eps times the sum of
/// their magnitudes (Shewchuk's analysis of orient2d, with one more rounding).
bool certainly_onward(double au, double av, double bu, double bv, double cu, double cv) {
  const double first = (bu - au) * (cu - bu), second = (bv - av) * (cv - bv);
  return first + second > 0x1p-50 * (std::abs(first) + std::abs(second));
}

}  // namespace

/// The boundary chain: the uses of each edge leaving the cell, +1 from its smaller vertex, -1
/// from its larger; what does not cancel is the boundary, which must be single (net +-1).
bool RegionCertificate::find_boundary(std::span<const std::uint32_t> faces) {
  boundary_.clear();
  for (const std::uint32_t entry : faces) {
    const auto& t = mesh_.triangles[entry & ((1u << CoarseCells::kFaceBits) - 1)];
    const std::uint32_t outside = entry >> CoarseCells::kFaceBits;
    for (int corner = 0; corner < 3; ++corner) {
      if ((outside >> corner & 1) != 0)
        boundary_.push_back({t[corner], t[corner == 2 ? 0 : corner + 1]});
    }
  }
  const std::size_t size = std::bit_ceil(std::max<std::size_t>(8, 2 * boundary_.size()));
  const int shift = 64 - std::countr_zero(size);
  slots_.assign(size, Slot{kNoBoundaryEdge, 0});
  for (const Edge& edge : boundary_) {
    const std::uint64_t key =
        std::uint64_t{std::min(edge.from, edge.to)} << 32 | std::max(edge.from, edge.to);
    std::size_t slot = (key * 0x9e3779b97f4a7c15ull) >> shift;
    while (slots_[slot].key != key && slots_[slot].key != kNoBoundaryEdge)
      slot = (slot + 1) & (size - 1);
    slots_[slot].key = key;
    slots_[slot].uses += edge.from < edge.to ? 1 : -1;
  }
  boundary_.clear();
  for (const Slot& slot : slots_) {
    if (slot.uses == 0) continue;
    if (slot.uses != 1 && slot.uses != -1) return false;
    const auto low = static_cast<std::uint32_t>(slot.key >> 32);
    const auto high = static_cast<std::uint32_t>(slot.key);
    boundary_.push_back(slot.uses == 1 ? Edge{low, high} : Edge{high, low});
  }
  return boundary_.size() >= 3;
}

/// The boundary as one closed loop of vertices: each vertex starts one edge, and following
/// them from any edge visits all.
bool RegionCertificate::trace_loop() {
  // Each edge by its start, in an open-addressed table (sorting the edges by start and searching
  // them at every step had been over a quarter of the certificates' time on the 1M-triangle
  // torus); the loop starts at the least start, as it did then.
  const std::size_t m = boundary_.size();
  const std::size_t size = std::bit_ceil(std::max<std::size_t>(8, 2 * m));
  const int shift = 64 - std::countr_zero(size);
  const auto home = [&](std::uint32_t v) {
    return static_cast<std::size_t>((std::uint64_t{v} * 0x9e3779b97f4a7c15ull) >> shift);
  };
  starting_.assign(size, kNoEdge);
  std::size_t first = 0;
  for (std::size_t i = 0; i < m; ++i) {
    const std::uint32_t from = boundary_[i].from;
    std::size_t slot = home(from);
    for (; starting_[slot] != kNoEdge; slot = (slot + 1) & (size - 1)) {
      if (boundary_[starting_[slot]].from == from) return false;  // two edges leave one vertex
    }
    starting_[slot] = static_cast<std::uint32_t>(i);
    if (from < boundary_[first].from) first = i;
  }
  loop_.clear();
  const std::uint32_t start = boundary_[first].from;
  Edge edge = boundary_[first];
  do {
    loop_.push_back(edge.from);
    std::size_t slot = home(edge.to);
    while (starting_[slot] != kNoEdge && boundary_[starting_[slot]].from != edge.to) {
      slot = (slot + 1) & (size - 1);
    }
    if (starting_[slot] == kNoEdge) return false;
    edge = boundary_[starting_[slot]];
  } while (edge.from != start && loop_.size() < m);
  return edge.from == start && loop_.size() == m;
}

/// Whether the projected loop is a simple polygon: consecutive edges meet only where they
/// join (they turn, or go on along one line), and edges that are not consecutive are certainly
/// apart. Pairs are found by a sweep along u over the edges' boxes (exact coordinates, so the
/// boxes are exact too). The loop's first vertex is repeated at its end, so edge i runs from
/// point i to point i + 1, and each edge's box is computed once (sorting by a box computed in
/// the comparison, with two remainders per side, took a fifth of the certificates' time).
bool RegionCertificate::loop_is_simple() {
  const std::size_t m = loop_.size();
  plane_.resize(2 * (m + 1));
  for (std::size_t i = 0; i <= m; ++i) {
    plane_[2 * i] = u(loop_[i == m ? 0 : i]);
    plane_[2 * i + 1] = v(loop_[i == m ? 0 : i]);
  }
  const auto pu = [&](std::size_t i) { return plane_[2 * i]; };
  const auto pv = [&](std::size_t i) { return plane_[2 * i + 1]; };
  const auto orient = [&](std::size_t a, std::size_t b, std::size_t c) {
    return certified_orientation_2d(pu(a), pv(a), pu(b), pv(b), pu(c), pv(c));
  };
  for (std::size_t b = 0; b < m; ++b) {
    const std::size_t a = b == 0 ? m - 1 : b - 1, c = b + 1;
    if (orient(a, b, c) == 0 && !certainly_onward(pu(a), pv(a), pu(b), pv(b), pu(c), pv(c))) {
      return false;
    }
  }
  boxes_.resize(m);
  order_.resize(m);
  for (std::size_t i = 0; i < m; ++i) {
    boxes_[i] = {std::min(pu(i), pu(i + 1)), std::max(pu(i), pu(i + 1)), std::min(pv(i), pv(i + 1)),
                 std::max(pv(i), pv(i + 1))};
    order_[i] = static_cast<std::uint32_t>(i);
  }
  std::sort(order_.begin(), order_.end(),
            [&](std::uint32_t a, std::uint32_t b) { return boxes_[a].low_u < boxes_[b].low_u; });
  active_.clear();
  for (const std::uint32_t i : order_) {
    const EdgeBox& box = boxes_[i];
    std::erase_if(active_, [&](std::uint32_t j) { return boxes_[j].high_u < box.low_u; });
    for (const std::uint32_t j : active_) {
      if (i + 1 == j || j + 1 == i || (i == 0 && j + 1 == m) || (j == 0 && i + 1 == m)) {
        continue;  // consecutive: checked above
      }
      if (box.high_v < boxes_[j].low_v || boxes_[j].high_v < box.low_v) continue;
      const int first = orient(i, i + 1, j), second = orient(i, i + 1, j + 1);
      if (first != 0 && first == second) continue;
      const int third = orient(j, j + 1, i), fourth = orient(j, j + 1, i + 1);
      if (third != 0 && third == fourth) continue;
      return false;
    }
    active_.push_back(i);
  }
  return true;
}

bool RegionCertificate::certify(std::span<const std::uint32_t> spanning, std::uint8_t directions) {
  if (directions == 0 || !find_boundary(spanning) || !trace_loop()) return false;
  // Each direction every face allows, in turn, until the loop projects simple along one.
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      if ((directions >> (2 * axis + side) & 1) == 0) continue;
      // (u, v, axis) right-handed: counter-clockwise in (u, v) is a normal along +axis.
      axis_u_ = (axis + 1) % 3;
      axis_v_ = (axis + 2) % 3;
      if (side == 1) std::swap(axis_u_, axis_v_);
      if (loop_is_simple()) return true;
    }
  }
  return false;
}

}  // namespace tumble::engine::detail
