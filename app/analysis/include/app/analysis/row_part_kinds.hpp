#pragma once
/// @file The part kinds of the row-producing commands (app/farm/part_kind.hpp): bench and
/// stability part folders, each merged into the command's whole output folder by the code an
/// unsharded run uses, from the rows in the whole job's order.

#include <filesystem>
#include <iosfwd>
#include <vector>

#include "app/farm/part_kind.hpp"
#include "app/farm/part_manifest.hpp"

namespace tumble::app {

/// The kind of `tumble bench --shard` parts ("bench").
const PartKind& bench_parts();
/// The kind of `tumble stability --shard` parts ("stability").
const PartKind& stability_parts();

/// Checks one bench part against its manifest: the job planned again (its scenes unchanged),
/// its rows the cases of its shard and what its results.csv holds. Throws InputError naming
/// the part.
void check_bench_part(const NamedManifest& part);
/// Merges bench parts (in shard order, already checked by check_parts_cover_job) into the
/// folder `output`; the summary line on `out`. Throws InputError naming a part whose rows are
/// not what its manifest says.
void merge_bench_parts(const std::vector<NamedManifest>& parts, const std::filesystem::path& output,
                       std::ostream& out);

/// check_bench_part and merge_bench_parts for stability parts (runs, stability.csv).
void check_stability_part(const NamedManifest& part);
void merge_stability_parts(const std::vector<NamedManifest>& parts,
                           const std::filesystem::path& output, std::ostream& out);

}  // namespace tumble::app
