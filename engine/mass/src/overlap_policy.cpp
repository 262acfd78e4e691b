// Overlap findings as one-line errors or warnings (overlap_policy.hpp).
#include "overlap_policy.hpp"

#include <algorithm>
#include <sstream>

#include "base/errors.hpp"

namespace tumble::engine::detail {
namespace {

std::string volume_text(const std::optional<double>& volume) {
  if (!volume) return "unknown: the exact Boolean of the two could not be computed";
  std::ostringstream out;
  out.precision(6);
  out << *volume << " m^3";
  return out.str();
}

}  // namespace

std::string OverlapPolicy::counts_twice() const {
  switch (mode_) {
    case OverlapMode::kSum:
      return "counts twice";
    case OverlapMode::kUnion:
      return "counts once (exact union)";
    case OverlapMode::kRefuse:
      break;
  }
  return "would count twice";
}

std::vector<std::uint32_t> OverlapPolicy::united() const {
  std::vector<std::uint32_t> parts = united_;
  std::sort(parts.begin(), parts.end());
  parts.erase(std::unique(parts.begin(), parts.end()), parts.end());
  return parts;
}

std::string OverlapPolicy::part(std::uint32_t index) const {
  return "part " + std::to_string(index + 1) + " of " + std::to_string(parts_);
}

std::string OverlapPolicy::describe(const OverlapFinding& f) const {
  const std::string pair = "parts " + std::to_string(f.first + 1) + " and " +
                           std::to_string(f.second + 1) + " of " + std::to_string(parts_);
  const std::string pairs =
      std::to_string(f.face_pairs) + " pair" + (f.face_pairs == 1 ? "" : "s") + " of faces";
  switch (f.kind) {
    case OverlapKind::kSelfIntersection:
      return part(f.first) + " intersects itself (" + pairs +
             " cross or overlap), so the volume it encloses is not well defined: where its "
             "surface passes through itself, matter " +
             (mode_ == OverlapMode::kUnion ? std::string("would count twice") : counts_twice());
    case OverlapKind::kDuplicate:
      return part(f.first) + " repeats itself: the same surface twice at the same place (" + pairs +
             " repeated with the same orientation), so its volume (" +
             volume_text(f.shared_volume) + ") " + counts_twice();
    case OverlapKind::kCancelling:
      if (f.approximate) {
        return part(f.first) +
               " is a surface and an inverted copy of it at the same place, apart from "
               "rounding (its faces cross at " +
               pairs +
               " and its signed volume cancels to 1e-6 of theirs): the two cancel, so "
               "it adds no volume";
      }
      return part(f.first) + " is a surface and its mirror image at the same place (" + pairs +
             " repeated with opposite orientations): the two cancel, so it adds no volume";
    case OverlapKind::kCross:
      if (f.cavity) {
        return pair + " overlap (their surfaces cross): part " + std::to_string(f.second + 1) +
               " faces the other way, as a cavity would, but reaches outside part " +
               std::to_string(f.first + 1) + ", so a volume (" + volume_text(f.shared_volume) +
               ") that is not matter " + (mode_ == OverlapMode::kSum ? "is" : "would be") +
               " taken out";
      }
      return pair + " overlap (their surfaces cross), so their shared volume (" +
             volume_text(f.shared_volume) + ") " + counts_twice();
    case OverlapKind::kUndecided:
      break;
  }
  return pair + ": their surfaces meet (" + pairs +
         "), and whether their volumes overlap could not be decided (a part is not a "
         "2-manifold, or the exact Boolean failed), so their shared volume may count twice";
}

void OverlapPolicy::findings(const PartOverlaps& overlaps) {
  for (const OverlapFinding& finding : overlaps.findings) {
    if (finding.kind != OverlapKind::kCancelling) {
      // A union needs parts free of self-intersections, and an inward part is no solid.
      const bool unitable = finding.kind != OverlapKind::kSelfIntersection && !finding.cavity;
      if (mode_ == OverlapMode::kUnion && !unitable) {
        refused_.push_back(describe(finding));
      } else {
        problems_.push_back(describe(finding));
        unite(finding.first);
        unite(finding.second);
      }
      continue;
    }
    notes_.push_back(describe(finding));
    if (cancelled_.empty()) cancelled_ = notes_.back();
  }
}

void OverlapPolicy::nested(std::uint32_t inner, double volume,
                           const std::vector<std::uint32_t>& outers) {
  unite(inner);
  for (const std::uint32_t outer : outers) unite(outer);
  problems_.push_back(part(inner) +
                      " lies inside another part with the same orientation, so its volume (" +
                      volume_text(volume) + ") " + counts_twice() +
                      " (reverse its winding if it is meant as a cavity)");
}

void OverlapPolicy::settle(MeshReport& report) {
  for (std::string& note : notes_) report.warnings.push_back(std::move(note));
  notes_.clear();
  if (mode_ == OverlapMode::kUnion && !refused_.empty()) {
    std::string message = source_ + ": " + refused_.front();
    if (refused_.size() > 1) {
      message += " (and " + std::to_string(refused_.size() - 1) + " more)";
    }
    throw InputError(message +
                     "; their exact union cannot be computed (it needs closed, outward parts "
                     "free of self-intersections): give --overlap sum to count each part as "
                     "wound (\"overlap\": \"sum\" in a scene)");
  }
  if (problems_.empty()) return;
  if (mode_ == OverlapMode::kRefuse) {
    std::string message = source_ + ": " + problems_.front();
    if (problems_.size() > 1) {
      message += " (and " + std::to_string(problems_.size() - 1) + " more overlap" +
                 (problems_.size() == 2 ? "" : "s") + ")";
    }
    throw InputError(message +
                     "; give --overlap union to take their exact union or --overlap sum to "
                     "count each part whole (\"overlap\" in a scene)");
  }
  for (std::string& problem : problems_) report.warnings.push_back(std::move(problem));
  problems_.clear();
}

}  // namespace tumble::engine::detail
