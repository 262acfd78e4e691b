#pragma once
/// @file `tumble inspect` as library calls: inspect_files returns each file's report or error
/// (what a script or the Python module reads); write_inspection is the whole command, printing
/// in the options' format on streams or into -o FILE (a part with a shard).

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/inspect/inspect_options.hpp"
#include "engine/mass/mesh_analysis.hpp"

namespace tumble::app {

/// One input file's inspection: its report (with the unit hint among its warnings), or the
/// one-line error (bad input: "FILE: ...") that refused it.
struct InspectResult {
  std::filesystem::path file;
  std::optional<engine::MeshReport> report;
  std::string error;
};

/// Expands `options.files` (directories, @lists; options.recursive) and inspects every file with
/// `options.mass`, options.jobs at once, in input order. Only the inputs and mass options are
/// read (not format, output or shard). An input that is not a mesh gives a result with its error;
/// an error that is a bug in tumble is rethrown.
std::vector<InspectResult> inspect_files(const InspectOptions& options);

/// One report as the JSON object `tumble inspect --json` prints for it (SI units; inertia about
/// the centre of mass, file axes).
nlohmann::json inspect_json(const engine::MeshReport& report);

/// The whole `tumble inspect`: expands the inputs, inspects them (with a shard, only its files)
/// and prints in input order, on `out` or into -o FILE (atomically); errors and the summary on
/// `err`. Returns the exit status (0 when every file was inspected). Throws InputError for bad
/// options (a shard without a .jsonl -o) before any file is read.
int write_inspection(const InspectOptions& options, std::ostream& out, std::ostream& err);

}  // namespace tumble::app
