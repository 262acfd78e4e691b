#pragma once
/// @file One interface for every kind of part a sharded job writes (docs/merge.md): bench and
/// stability row folders, inspect JSON Lines, render and compare frames or segments. Each job
/// implements it beside its own code (app/analysis, app/inspect, app/video_parts), and `tumble
/// merge` looks the kind up by the name in a part's manifest (PartKinds), never comparing kind
/// strings itself.
///
/// A kind does three things. It writes a part: its manifest and its data, atomically; the data
/// differs by kind (rows of results, JSON objects, frames through an image sink), so each kind's
/// writer is a typed function of its job (write_bench_part, write_stability_part, the inspect and
/// render shards). It checks a part on its own against its manifest (PartKind::check). It merges
/// one job's parts into the output the unsharded job would have written (PartKind::merge),
/// checking each part as it reads it.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "app/farm/part_manifest.hpp"

namespace tumble::app {

/// What a merge came to.
struct MergeOutcome {
  bool interrupted = false;  ///< `interrupted` said so; nothing was written
  /// What was written, for the user, with its line end: "tumble merge: 3 bench parts, 24 runs;
  /// wrote res/report.md\n".
  std::string summary;
};

/// One kind of part; see the file comment.
class PartKind {
 public:
  virtual ~PartKind() = default;

  /// The kind's name, as its manifests give it ("bench").
  virtual std::string name() const = 0;

  /// Checks one part (its manifest read) on its own: that its data is what its manifest says
  /// for its shard of its job. Throws tumble::InputError naming the part and what differs.
  virtual void check(const NamedManifest& part) const = 0;

  /// Merges `parts` (their manifests read, in any order, all of this kind) into `output`: checks
  /// that they are one job's shards, each exactly once (check_parts_cover_job), checks each
  /// against its manifest, and writes what the unsharded job would have written, atomically.
  /// `interrupted`, when given, is asked during long work; when it says so nothing is written
  /// and the outcome says so. Throws tumble::InputError naming the offending part (or the
  /// output).
  virtual MergeOutcome merge(const std::vector<NamedManifest>& parts,
                             const std::filesystem::path& output,
                             const std::function<bool()>& interrupted) const = 0;
};

/// The kinds one `tumble merge` knows, found by name.
class PartKinds {
 public:
  /// `kinds` must outlive this and have distinct names (std::invalid_argument otherwise).
  explicit PartKinds(std::vector<const PartKind*> kinds);

  /// The kind of `part`'s manifest. Throws tumble::InputError "PART: KIND parts cannot be merged
  /// by this tumble" for a kind none of them is.
  const PartKind& of(const NamedManifest& part) const;

  /// The names of the kinds known, in the order given.
  std::vector<std::string> names() const;

 private:
  std::vector<const PartKind*> kinds_;
};

/// The parts' manifests read (read_part_manifest), each part checked by its kind
/// (PartKind::check) before anything is written, then merged by the kind of the first part.
/// Throws tumble::InputError for an unreadable manifest, an unknown kind or a part its check
/// refuses, naming the part.
MergeOutcome merge_parts(const PartKinds& kinds, const std::vector<std::filesystem::path>& parts,
                         const std::filesystem::path& output,
                         const std::function<bool()>& interrupted);

}  // namespace tumble::app
