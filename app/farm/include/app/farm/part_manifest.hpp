#pragma once
/// @file What a shard's output says about itself, so that `tumble merge` can check that parts
/// belong to one job and cover it exactly once.
///
/// The manifest is JSON:
///   {"tumble_part": 1, "tumble_version": "0.1.0", "kind": "render",
///    "job": {...}, "job_digest": "3f0c...", "shard": {"index": 0, "count": 4},
///    "items": {"total": 480, "split": "contiguous"}, "payload": {...}}
/// `job` describes the whole job the part is a shard of: the command, its inputs (with a digest
/// of each input file's bytes, so an edited scene is a different job) and every option that
/// changes the output, but not `--shard` nor `-o`. Parts of one job have equal `job`s. `payload`
/// says what this part holds (kind-specific: file names, frame range, columns).
///
/// Where it is kept: a folder part (PNG frames, bench or stability rows) holds it as
/// `part.json`; a JSON Lines part has it as its first line; an MP4 or WebM segment holds it
/// (compact JSON) as its container's `comment` tag (ffmpeg `-metadata comment=...`).

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/farm/shard.hpp"

namespace tumble::app {

/// The manifest format's version ("tumble_part").
inline constexpr int kPartFormat = 1;
/// A folder part's manifest file.
inline constexpr std::string_view kPartManifestFile = "part.json";

struct PartManifest {
  std::string kind;            ///< render, compare, bench, stability, inspect
  std::string tumble_version;  ///< of the tumble that wrote it
  nlohmann::json job = nlohmann::json::object();
  Shard shard;
  std::size_t total = 0;  ///< items (frames, cases, files) in the whole job
  ShardSplit split = ShardSplit::kContiguous;
  nlohmann::json payload = nlohmann::json::object();
};

/// A manifest and the part it came from, for messages.
struct NamedManifest {
  std::filesystem::path part;
  PartManifest manifest;
};

/// 16 hex digits of FNV-1a (64-bit) over `bytes`: an identity, not a security measure.
std::string digest_hex(std::string_view bytes);
/// digest_hex of a file's bytes; throws InputError naming the file if it cannot be read.
std::string file_digest(const std::filesystem::path& file);
/// digest_hex of `job` in its canonical form (keys sorted, no spaces).
std::string job_digest(const nlohmann::json& job);

/// The manifest as JSON, with its format version and job digest.
nlohmann::json manifest_json(const PartManifest& manifest);
/// Reads a manifest; throws InputError "SOURCE: field 'FIELD': ..." for anything missing,
/// mistyped or inconsistent (a digest that does not match its job, a shard out of range).
PartManifest parse_manifest(const nlohmann::json& json, const std::string& source);

/// Writes `manifest` as `folder/part.json` (whole, every write checked).
void write_folder_manifest(const std::filesystem::path& folder, const PartManifest& manifest);
/// The first line of a JSON Lines part.
std::string jsonl_manifest_line(const PartManifest& manifest);

/// Reads the manifest of the part at `part`: `part.json` in a folder, the first line of a
/// `.jsonl` file, the comment tag of a `.mp4` or `.webm` file (through ffprobe, which must be on
/// PATH). Throws InputError naming the part if it is not a tumble part or its manifest
/// is bad.
PartManifest read_part_manifest(const std::filesystem::path& part);

/// Checks that `parts` are of one kind, one tumble version and one job, and that their shards
/// are 0..N-1 of one N, each exactly once. Throws InputError naming the offending part: "PART:
/// a part of another job than 'FIRST' (job field 'options.fps': 30, not 24)", "PART: shard
/// 1/4 again (also 'OTHER')", "shards 2/4, 3/4 missing (given: 0/4, 1/4)". Returns the parts'
/// positions in `parts` in shard order.
std::vector<std::size_t> check_parts_cover_job(const std::vector<NamedManifest>& parts);

}  // namespace tumble::app
