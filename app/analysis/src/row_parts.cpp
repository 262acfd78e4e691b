// The pieces bench and stability parts share: inputs with digests, exact numbers in JSON, the
// part folder and the check of a part's CSV against its manifest.
#include "app/analysis/row_parts.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "app/scene/scene.hpp"
#include "app/support/file_write.hpp"
#include "app/support/text_file.hpp"
#include "base/errors.hpp"

namespace tumble::app {

namespace {
using nlohmann::json;  // file-local (a namespace-wide name would shadow `json` members)
}  // namespace

json scene_inputs_json(const std::vector<std::filesystem::path>& scenes) {
  json inputs = json::array();
  for (const std::filesystem::path& file : scenes) {
    json meshes = json::array();
    const std::vector<std::filesystem::path> files = scene_inputs(load_scene(file));
    for (std::size_t i = 1; i < files.size(); ++i) {  // [0] is the scene file itself
      meshes.push_back({{"path", files[i].string()}, {"digest", file_digest(files[i])}});
    }
    inputs.push_back({{"path", file.string()}, {"digest", file_digest(file)}, {"meshes", meshes}});
  }
  return inputs;
}

namespace {

void check_digest(const json& entry) {
  const std::string path = entry.at("path").get<std::string>();
  std::string now;
  try {
    now = file_digest(path);
  } catch (const InputError&) {
    now = "missing";
  }
  if (now != entry.at("digest").get<std::string>()) {
    throw InputError(path + ": changed since the parts were made (or is missing): its digest is " +
                     now + ", the parts' " + entry.at("digest").get<std::string>());
  }
}

}  // namespace

std::vector<std::filesystem::path> unchanged_scene_inputs(const json& inputs) {
  std::vector<std::filesystem::path> scenes;
  for (const json& scene : inputs) {
    check_digest(scene);
    for (const json& mesh : scene.at("meshes")) check_digest(mesh);
    scenes.emplace_back(scene.at("path").get<std::string>());
  }
  return scenes;
}

json optional_text(const std::optional<std::string>& text) {
  return text ? json(*text) : json(nullptr);
}

std::optional<std::string> text_option(const json& value) {
  if (value.is_string()) return value.get<std::string>();
  return std::nullopt;
}

json exact_number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return value;  // nlohmann writes the shortest text that reads back to the same double
}

double exact_number_value(const json& value, const std::string& source, const std::string& field) {
  if (value.is_number()) return value.get<double>();
  if (value == "nan") return std::numeric_limits<double>::quiet_NaN();
  if (value == "inf") return std::numeric_limits<double>::infinity();
  if (value == "-inf") return -std::numeric_limits<double>::infinity();
  throw InputError(source + ": field '" + field + "': expected a number");
}

OutputFolderKind part_folder_kind(const std::string& command, const std::string& data) {
  return OutputFolderKind{command + " part", std::string(kPartManifestFile), "{", data};
}

PartManifest row_part_manifest(const std::string& kind, json job, Shard shard, std::size_t total,
                               json payload) {
  PartManifest manifest;
  manifest.kind = kind;
  manifest.tumble_version = TUMBLE_VERSION;
  manifest.job = std::move(job);
  manifest.shard = shard;
  manifest.total = total;
  manifest.split = ShardSplit::kStrided;
  manifest.payload = std::move(payload);
  return manifest;
}

namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

}  // namespace

void check_part_csv(const std::filesystem::path& part, const std::string& file,
                    const std::string& expected) {
  const std::filesystem::path path = part / file;
  std::string text;
  try {
    text = read_text_file(path, "part rows");
  } catch (const InputError&) {
    throw InputError(path.string() + ": missing or unreadable (a part holds its rows there)");
  }
  if (text == expected) return;
  const std::vector<std::string> have = lines_of(text);
  const std::vector<std::string> want = lines_of(expected);
  for (std::size_t i = 0; i < std::min(have.size(), want.size()); ++i) {
    if (have[i] != want[i]) {
      throw InputError(path.string() + ": " + (i == 0 ? "header" : "row " + std::to_string(i)) +
                       " is not the one the part's manifest holds (an edited or foreign row)");
    }
  }
  throw InputError(path.string() + ": " + std::to_string(have.empty() ? 0 : have.size() - 1) +
                   " rows, but the part's manifest holds " + std::to_string(want.size() - 1) +
                   " (a missing or extra row)");
}

std::vector<std::size_t> index_list(const json& value, const std::string& source,
                                    const std::string& field) {
  if (!value.is_array()) throw InputError(source + ": field '" + field + "': expected an array");
  std::vector<std::size_t> items;
  for (const json& item : value) {
    if (!item.is_number_unsigned()) {
      throw InputError(source + ": field '" + field + "': expected whole numbers");
    }
    items.push_back(item.get<std::size_t>());
  }
  return items;
}

}  // namespace tumble::app
