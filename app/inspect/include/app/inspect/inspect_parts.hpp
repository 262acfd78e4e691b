#pragma once
/// @file A shard of `tumble inspect` (`--shard I/N -o PART.jsonl`): every N-th file of the
/// expanded, ordered file list, written as JSON Lines whose first line is the part's manifest
/// and whose objects carry their file's place in the whole list ("item").

#include <cstddef>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/farm/part_kind.hpp"
#include "app/farm/part_manifest.hpp"
#include "app/inspect/inspect_inputs.hpp"
#include "app/inspect/inspect_options.hpp"

namespace tumble::app {

/// The inspect job: the command, the inputs as given, the count and a digest of the expanded
/// file list (so a folder that gained a file is another job), whether it is a batch, and the
/// options that change the reports (density, mass, scale, shell, overlap, recursion). Each
/// file's digest is in the payload of the part that inspected it (a shard reads only its own
/// files).
nlohmann::json inspect_job(const InspectOptions& options, const std::vector<InspectInput>& inputs,
                           bool batch);

/// The first line of a part: its manifest, with the shard's items and their files' digests.
std::string inspect_part_line(const nlohmann::json& job, Shard shard, std::size_t total,
                              const std::vector<std::size_t>& items,
                              const std::vector<std::string>& digests);

/// The digest of a file's bytes, or "unreadable".
std::string digest_or_unreadable(const std::filesystem::path& file);

/// The kind of `tumble inspect --shard` parts ("inspect"): merged into .jsonl or .json.
const PartKind& inspect_parts();

/// Checks one inspect part against its manifest: its objects are the files of its shard, each
/// once, in order. Throws InputError naming the part and line.
void check_inspect_part(const NamedManifest& part);

/// Merges inspect parts (`parts` in shard order, already checked by check_parts_cover_job) into
/// `output`: `.jsonl` (the lines of `tumble inspect --jsonl` over every file, in order) or
/// `.json` (what `tumble inspect --json` prints). Prints the summary line on `out`. Throws
/// InputError naming a part whose lines are not its shard's files.
void merge_inspect_parts(const std::vector<NamedManifest>& parts,
                         const std::filesystem::path& output, std::ostream& out);

}  // namespace tumble::app
