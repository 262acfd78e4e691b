#pragma once
// What `tumble inspect` says about overlapping, self-intersecting and repeated parts
// (part_overlap.hpp finds them), by MassOptions::overlap: an error naming the parts (refuse), a
// warning saying what counts twice (sum), or the parts noted for their exact union (union: a
// part that intersects itself, or a cavity reaching outside its part, is still an error).

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "engine/mass/mesh_analysis.hpp"
#include "engine/overlap/part_overlap.hpp"

namespace tumble::engine::detail {

class OverlapPolicy {
 public:
  OverlapPolicy(OverlapMode mode, std::string source, std::size_t parts)
      : mode_(mode), source_(std::move(source)), parts_(parts) {}

  /// Notes what the exact tests found within and between parts.
  void findings(const PartOverlaps& overlaps);
  /// Notes that part `inner` lies inside matter with the same orientation: `volume` twice.
  void nested(std::uint32_t inner, double volume, const std::vector<std::uint32_t>& outers);
  /// Throws InputError with the first problem noted (and how many more) with kRefuse, or
  /// with kUnion for problems a union cannot answer; otherwise each becomes a warning. Surfaces
  /// that cancel their mirror image are always a warning (they add nothing; if nothing else is
  /// left, the volume is zero). Clears the notes.
  void settle(MeshReport& report);
  /// The first surface found to cancel its mirror image, or empty: why a volume is zero.
  const std::string& cancelled() const { return cancelled_; }
  /// The parts to replace by their exact union (kUnion), in order; empty if none.
  std::vector<std::uint32_t> united() const;

 private:
  std::string part(std::uint32_t index) const;
  std::string counts_twice() const;
  std::string describe(const OverlapFinding& finding) const;

  void unite(std::uint32_t part) { united_.push_back(part); }

  OverlapMode mode_;
  std::string source_;
  std::size_t parts_;
  std::vector<std::string> problems_;
  std::vector<std::string> refused_;  ///< problems a union cannot answer (kUnion)
  std::vector<std::uint32_t> united_;
  std::vector<std::string> notes_;
  std::string cancelled_;
};

}  // namespace tumble::engine::detail
