// The registry of part kinds, and merge: every part checked by its kind, then merged by the
// first part's kind.
#include "app/farm/part_kind.hpp"

#include <stdexcept>

#include "base/errors.hpp"

namespace tumble::app {

PartKinds::PartKinds(std::vector<const PartKind*> kinds) : kinds_(std::move(kinds)) {
  for (std::size_t i = 0; i < kinds_.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (kinds_[i]->name() == kinds_[j]->name()) {
        throw std::invalid_argument("PartKinds: the kind '" + kinds_[i]->name() + "' twice");
      }
    }
  }
}

const PartKind& PartKinds::of(const NamedManifest& part) const {
  for (const PartKind* kind : kinds_) {
    if (kind->name() == part.manifest.kind) return *kind;
  }
  throw InputError(part.part.string() + ": " + part.manifest.kind +
                   " parts cannot be merged by this tumble");
}

std::vector<std::string> PartKinds::names() const {
  std::vector<std::string> names;
  for (const PartKind* kind : kinds_) names.push_back(kind->name());
  return names;
}

MergeOutcome merge_parts(const PartKinds& kinds, const std::vector<std::filesystem::path>& parts,
                         const std::filesystem::path& output,
                         const std::function<bool()>& interrupted) {
  std::vector<NamedManifest> read;
  for (const std::filesystem::path& part : parts) read.push_back({part, read_part_manifest(part)});
  if (read.empty()) throw InputError("no parts to merge");
  // Each part checked on its own by its kind before any merging starts: a truncated or
  // mismatched part is named before the output is opened.
  for (const NamedManifest& part : read) kinds.of(part).check(part);
  return kinds.of(read.front()).merge(read, output, interrupted);
}

}  // namespace tumble::app
