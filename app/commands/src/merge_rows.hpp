#pragma once
/// @file `tumble merge` of the row-producing commands: bench and stability part folders into the
/// command's whole output folder, inspect's JSON Lines parts into one .jsonl or .json.

#include <filesystem>
#include <iosfwd>
#include <vector>

#include "app/farm/part_manifest.hpp"

namespace tumble::app {

/// Merges bench or stability parts (`parts` in shard order, already checked by
/// check_parts_cover_job) into the folder `output`, built by the code an unsharded run uses
/// from the rows in its order. Throws InputError naming a part whose rows are not what its
/// manifest says.
void merge_row_parts(const std::vector<NamedManifest>& parts, const std::filesystem::path& output,
                     std::ostream& out);

/// Merges inspect parts into `output`: `.jsonl` (the lines of `tumble inspect --jsonl` over
/// every file, in order) or `.json` (what `tumble inspect --json` prints).
void merge_inspect_parts(const std::vector<NamedManifest>& parts,
                         const std::filesystem::path& output, std::ostream& out);

/// The bench and stability halves of merge_row_parts.
void merge_bench_parts(const std::vector<NamedManifest>& parts, const std::filesystem::path& output,
                       std::ostream& out);
void merge_stability_parts(const std::vector<NamedManifest>& parts,
                           const std::filesystem::path& output, std::ostream& out);

}  // namespace tumble::app
