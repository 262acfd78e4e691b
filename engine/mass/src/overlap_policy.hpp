#pragma once
// What `tumble inspect` says about overlapping, self-intersecting and repeated parts
// (part_overlap.hpp finds them): an error naming the parts, or with
// MassOptions::allow_overlap a warning saying what counts twice.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/mass/mesh_analysis.hpp"
#include "engine/overlap/part_overlap.hpp"

namespace tumble::engine::detail {

class OverlapPolicy {
 public:
  OverlapPolicy(bool allow, std::string source, std::size_t parts)
      : allow_(allow), source_(std::move(source)), parts_(parts) {}

  /// Notes what the exact tests found within and between parts.
  void findings(const PartOverlaps& overlaps);
  /// Notes that part `inner` lies inside matter with the same orientation: `volume` twice.
  void nested(std::uint32_t inner, double volume);
  /// Throws InputError with the first problem noted (and how many more) unless overlaps are
  /// allowed; then each becomes a warning. Surfaces that cancel their mirror image are always
  /// a warning (they add nothing; if nothing else is left, the volume is zero). Clears the
  /// notes.
  void settle(MeshReport& report);
  /// The first surface found to cancel its mirror image, or empty: why a volume is zero.
  const std::string& cancelled() const { return cancelled_; }

 private:
  std::string part(std::uint32_t index) const;
  std::string counts_twice() const { return allow_ ? "counts twice" : "would count twice"; }
  std::string describe(const OverlapFinding& finding) const;

  bool allow_;
  std::string source_;
  std::size_t parts_;
  std::vector<std::string> problems_;
  std::vector<std::string> notes_;
  std::string cancelled_;
};

}  // namespace tumble::engine::detail
