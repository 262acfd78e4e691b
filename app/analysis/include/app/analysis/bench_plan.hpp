#pragma once
/// @file What `tumble bench` and `tumble merge` share: the plan of a bench (its scenes and its
/// cases, in the order an unsharded run takes them) and the output folder written from its rows,
/// so that a merged bench is the unsharded one apart from the timings.

#include <filesystem>
#include <string>
#include <vector>

#include "app/analysis/bench_options.hpp"
#include "app/analysis/bench_report.hpp"
#include "app/support/output_folder.hpp"

namespace tumble::app {

/// A whole number in [minimum, ...] or an InputError naming the option.
long long parse_whole_number(const std::string& text, const char* option, long long minimum);

/// Loads the scenes and lays out every case (no reference yet), in the order the rows of
/// results.csv take. Throws InputError for bad options or scenes.
void plan_bench(const BenchOptions& options, std::vector<BenchScene>& scenes,
                std::vector<BenchCase>& cases);

/// A bench output: report.md under its title, beside results.csv.
extern const OutputFolderKind kBenchOutput;

/// Writes results.csv, the plots and report.md of `outcome` into the temporary folder `tmp` of
/// `output`; a failed write is named by its final name in `output`.
void write_bench_folder(const BenchOutcome& outcome, const std::filesystem::path& tmp,
                        const std::filesystem::path& output);

}  // namespace tumble::app
