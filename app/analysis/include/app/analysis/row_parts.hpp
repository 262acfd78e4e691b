#pragma once
/// @file What the row-producing commands' parts share (bench, stability;
/// docs/merge.md): the inputs of a job with their digests, numbers that survive JSON exactly, the
/// folder a part is written to and the check that a part's CSV is the rows its manifest holds.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/farm/part_manifest.hpp"
#include "app/support/output_folder.hpp"

namespace tumble::app {

/// The scene files of a job with their bytes' digests and those of the meshes they name:
/// [{"path": "a.json", "digest": "...", "meshes": [{"path": "m.stl", "digest": "..."}]}].
nlohmann::json scene_inputs_json(const std::vector<std::filesystem::path>& scenes);

/// The scene paths of scene_inputs_json's list, after checking that every file still has the
/// digest the parts were made with. Throws InputError "FILE: changed since the parts were made
/// (or is missing)".
std::vector<std::filesystem::path> unchanged_scene_inputs(const nlohmann::json& inputs);

/// An option as typed, or null.
nlohmann::json optional_text(const std::optional<std::string>& text);
/// The option back from optional_text's JSON.
std::optional<std::string> text_option(const nlohmann::json& value);

/// A double as JSON that reads back exactly: a number, or "nan", "inf", "-inf".
nlohmann::json exact_number(double value);
/// exact_number's value back; throws InputError "SOURCE: field 'FIELD': expected a number".
double exact_number_value(const nlohmann::json& value, const std::string& source,
                          const std::string& field);

/// A part folder: part.json beside the data CSV (stability.csv, results.csv); written as
/// .DIR.tmp-PID like every output folder. An existing DIR must be empty or an earlier part.
OutputFolderKind part_folder_kind(const std::string& command, const std::string& data);

/// The manifest of a bench or stability part written by this tumble.
PartManifest row_part_manifest(const std::string& kind, nlohmann::json job, Shard shard,
                               std::size_t total, nlohmann::json payload);

/// Checks that the CSV `file` of part `part` holds exactly `expected` (the rows its manifest
/// gives, written as the command writes them). Throws InputError naming the part and the first
/// row that differs.
void check_part_csv(const std::filesystem::path& part, const std::string& file,
                    const std::string& expected);

/// The integers of `value` (an array of them); throws InputError naming `source` and `field`.
std::vector<std::size_t> index_list(const nlohmann::json& value, const std::string& source,
                                    const std::string& field);

}  // namespace tumble::app
