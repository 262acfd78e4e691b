// Part manifests: writing, reading with field-naming errors, and the check that parts cover a
// job exactly once.
#include "app/farm/part_manifest.hpp"

#include <cstdint>
#include <fstream>
#include <iterator>
#include <map>

#include "app/support/file_write.hpp"
#include "base/errors.hpp"
#include "media/video_probe.hpp"

namespace tumble::app {

namespace {

using nlohmann::json;

[[noreturn]] void bad_field(const std::string& source, std::string_view field,
                            std::string_view what) {
  throw InputError(source + ": field '" + std::string(field) + "': " + std::string(what));
}

const json& member(const json& object, std::string_view key, const std::string& source,
                   std::string_view field) {
  const auto found = object.find(key);
  if (found == object.end()) bad_field(source, field, "missing");
  return *found;
}

std::string string_member(const json& object, std::string_view key, const std::string& source,
                          std::string_view field) {
  const json& value = member(object, key, source, field);
  if (!value.is_string()) bad_field(source, field, "expected a string");
  return value.get<std::string>();
}

std::int64_t integer_member(const json& object, std::string_view key, const std::string& source,
                            std::string_view field) {
  const json& value = member(object, key, source, field);
  if (!value.is_number_integer()) bad_field(source, field, "expected an integer");
  return value.get<std::int64_t>();
}

const json& object_member(const json& object, std::string_view key, const std::string& source,
                          std::string_view field) {
  const json& value = member(object, key, source, field);
  if (!value.is_object()) bad_field(source, field, "expected an object");
  return value;
}

Shard parse_manifest_shard(const json& top, const std::string& source) {
  const json& shard = object_member(top, "shard", source, "shard");
  const std::int64_t count = integer_member(shard, "count", source, "shard.count");
  if (count < 1 || count > kMaxShards) {
    bad_field(source, "shard.count", "expected 1 to " + std::to_string(kMaxShards));
  }
  const std::int64_t index = integer_member(shard, "index", source, "shard.index");
  if (index < 0 || index >= count) bad_field(source, "shard.index", "expected 0 to count - 1");
  return Shard{static_cast<int>(index), static_cast<int>(count)};
}

/// The first key path at which `a` and `b` differ ("options.fps"), and both values there.
std::string first_difference(const json& a, const json& b, const std::string& path) {
  if (a.is_object() && b.is_object()) {
    for (const auto& [key, value] : a.items()) {
      const std::string here = path.empty() ? key : path + "." + key;
      const auto other = b.find(key);
      if (other == b.end()) return "'" + here + "' only in one";
      if (value != *other) return first_difference(value, *other, here);
    }
    for (const auto& [key, value] : b.items()) {
      if (!a.contains(key)) return "'" + (path.empty() ? key : path + "." + key) + "' only in one";
    }
  }
  return "'" + path + "': " + b.dump() + ", not " + a.dump();
}

std::string shard_list(const std::vector<int>& indexes, int count) {
  std::string text;
  for (const int index : indexes) {
    text += (text.empty() ? "" : ", ") + Shard{index, count}.text();
  }
  return text;
}

/// A video part's manifest: its container's comment tag, which `--shard` sets (MP4: the
/// ilst comment atom; WebM: the Matroska COMMENT tag), read with one small ffprobe call.
PartManifest read_video_manifest(const std::filesystem::path& part) {
  const std::string name = part.string();
  const std::string comment = media::video_comment(part);
  const json top = json::parse(comment, nullptr, false);
  if (comment.empty() || top.is_discarded() || !top.is_object() || !top.contains("tumble_part")) {
    throw InputError(name +
                     ": not a tumble part (its comment tag holds no part manifest; "
                     "render with --shard I/N)");
  }
  return parse_manifest(top, name);
}

}  // namespace

std::string digest_hex(std::string_view bytes) {
  std::uint64_t hash = 14695981039346656037ULL;  // FNV-1a offset basis and prime (64-bit)
  for (const char byte : bytes) {
    hash ^= static_cast<unsigned char>(byte);
    hash *= 1099511628211ULL;
  }
  static constexpr char kHex[] = "0123456789abcdef";
  std::string text(16, '0');
  for (int digit = 15; digit >= 0; --digit, hash >>= 4) {
    text[static_cast<std::size_t>(digit)] = kHex[hash & 15U];
  }
  return text;
}

std::string file_digest(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("cannot read '" + file.string() + "'");
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError("cannot read '" + file.string() + "'");
  return digest_hex(bytes);
}

std::string job_digest(const json& job) {
  return digest_hex(job.dump());
}

json manifest_json(const PartManifest& manifest) {
  return json{{"tumble_part", kPartFormat},
              {"tumble_version", manifest.tumble_version},
              {"kind", manifest.kind},
              {"job", manifest.job},
              {"job_digest", job_digest(manifest.job)},
              {"shard", {{"index", manifest.shard.index}, {"count", manifest.shard.count}}},
              {"items", {{"total", manifest.total}, {"split", split_name(manifest.split)}}},
              {"payload", manifest.payload}};
}

PartManifest parse_manifest(const json& top, const std::string& source) {
  if (!top.is_object()) throw InputError(source + ": not a tumble part (no manifest object)");
  if (integer_member(top, "tumble_part", source, "tumble_part") != kPartFormat) {
    bad_field(source, "tumble_part", "expected part format " + std::to_string(kPartFormat));
  }
  PartManifest manifest;
  manifest.tumble_version = string_member(top, "tumble_version", source, "tumble_version");
  manifest.kind = string_member(top, "kind", source, "kind");
  manifest.job = object_member(top, "job", source, "job");
  if (string_member(top, "job_digest", source, "job_digest") != job_digest(manifest.job)) {
    bad_field(source, "job_digest", "does not match the job (the manifest was edited)");
  }
  manifest.shard = parse_manifest_shard(top, source);
  const json& items = object_member(top, "items", source, "items");
  const std::int64_t total = integer_member(items, "total", source, "items.total");
  if (total < 0) bad_field(source, "items.total", "expected a count >= 0");
  manifest.total = static_cast<std::size_t>(total);
  if (!parse_split_name(string_member(items, "split", source, "items.split"), manifest.split)) {
    bad_field(source, "items.split", "expected contiguous or strided");
  }
  manifest.payload = object_member(top, "payload", source, "payload");
  return manifest;
}

void write_folder_manifest(const std::filesystem::path& folder, const PartManifest& manifest) {
  write_text_file(folder / kPartManifestFile, manifest_json(manifest).dump(2) + "\n");
}

std::string jsonl_manifest_line(const PartManifest& manifest) {
  return manifest_json(manifest).dump() + "\n";
}

PartManifest read_part_manifest(const std::filesystem::path& part) {
  const std::string name = part.string();
  std::error_code error;
  if (std::filesystem::is_directory(part, error)) {
    const std::filesystem::path file = part / kPartManifestFile;
    std::ifstream in(file);
    if (!in) throw InputError(name + ": not a tumble part (no " + file.string() + ")");
    const json top = json::parse(in, nullptr, false);
    if (top.is_discarded()) throw InputError(file.string() + ": not valid JSON");
    return parse_manifest(top, file.string());
  }
  std::ifstream in(part);
  if (!in) throw InputError("cannot read part '" + name + "'");
  if (part.extension() == ".mp4" || part.extension() == ".webm") return read_video_manifest(part);
  if (part.extension() != ".jsonl") {
    throw InputError(name +
                     ": not a tumble part (expected a part folder, a .mp4, .webm or .jsonl part)");
  }
  std::string first;
  std::getline(in, first);
  const json top = json::parse(first, nullptr, false);
  if (top.is_discarded() || !top.is_object() || !top.contains("tumble_part")) {
    throw InputError(name + ": not a tumble part (its first line is no part manifest)");
  }
  return parse_manifest(top, name);
}

std::vector<std::size_t> check_parts_cover_job(const std::vector<NamedManifest>& parts) {
  if (parts.empty()) throw InputError("no parts given");
  const NamedManifest& first = parts.front();
  const std::string first_name = "'" + first.part.string() + "'";
  const int count = first.manifest.shard.count;
  std::map<int, std::size_t> by_index;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const PartManifest& m = parts[i].manifest;
    const std::string name = parts[i].part.string() + ": ";
    if (m.kind != first.manifest.kind) {
      throw InputError(name + "a " + m.kind + " part, not " + first.manifest.kind + " like " +
                       first_name);
    }
    if (m.tumble_version != first.manifest.tumble_version) {
      throw InputError(name + "written by tumble " + m.tumble_version + ", " + first_name + " by " +
                       first.manifest.tumble_version);
    }
    if (m.job != first.manifest.job) {
      throw InputError(name + "a part of another job than " + first_name + " (job field " +
                       first_difference(first.manifest.job, m.job, "") + ")");
    }
    if (m.shard.count != count || m.total != first.manifest.total ||
        m.split != first.manifest.split) {
      throw InputError(name + "shard " + m.shard.text() + " of " + std::to_string(m.total) +
                       " items does not match " + first_name + "'s " + first.manifest.shard.text() +
                       " of " + std::to_string(first.manifest.total));
    }
    const auto [at, inserted] = by_index.emplace(m.shard.index, i);
    if (!inserted) {
      throw InputError(name + "shard " + m.shard.text() + " again (also '" +
                       parts[at->second].part.string() + "')");
    }
  }
  std::vector<int> missing;
  std::vector<int> given;
  for (int index = 0; index < count; ++index) {
    (by_index.count(index) ? given : missing).push_back(index);
  }
  if (!missing.empty()) {
    throw InputError("shard" + std::string(missing.size() > 1 ? "s " : " ") +
                     shard_list(missing, count) + " missing (given: " + shard_list(given, count) +
                     ")");
  }
  std::vector<std::size_t> order;
  for (const auto& [index, position] : by_index) order.push_back(position);
  return order;
}

}  // namespace tumble::app
