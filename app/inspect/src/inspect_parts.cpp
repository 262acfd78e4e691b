// An inspect shard's job and manifest line.
#include "app/inspect/inspect_parts.hpp"

#include "base/errors.hpp"

namespace tumble::app {

using nlohmann::json;

namespace {

json optional_number(const std::optional<double>& value) {
  return value ? json(*value) : json(nullptr);
}

}  // namespace

json inspect_job(const InspectOptions& options, const std::vector<InspectInput>& inputs,
                 bool batch) {
  json given = json::array();
  for (const std::filesystem::path& input : options.files) given.push_back(input.string());
  std::string list;
  for (const InspectInput& input : inputs) list += input.file.string() + "\n";
  const engine::MassOptions& mass = options.mass;
  return {{"command", "inspect"},
          {"inputs", given},
          {"files", {{"count", inputs.size()}, {"digest", digest_hex(list)}}},
          {"batch", batch},
          {"options",
           {{"density", optional_number(mass.density)},
            {"mass", optional_number(mass.mass)},
            {"scale", {mass.scale.x(), mass.scale.y(), mass.scale.z()}},
            {"shell", optional_number(mass.shell_thickness)},
            {"inertia", engine::inertia_method_name(mass.inertia)},
            {"overlap", engine::overlap_mode_name(mass.overlap)},
            {"recursive", options.recursive}}}};
}

std::string inspect_part_line(const json& job, Shard shard, std::size_t total,
                              const std::vector<std::size_t>& items,
                              const std::vector<std::string>& digests) {
  PartManifest manifest;
  manifest.kind = "inspect";
  manifest.tumble_version = TUMBLE_VERSION;
  manifest.job = job;
  manifest.shard = shard;
  manifest.total = total;
  manifest.split = ShardSplit::kStrided;
  manifest.payload = {{"items", items}, {"digests", digests}};
  return jsonl_manifest_line(manifest);
}

std::string digest_or_unreadable(const std::filesystem::path& file) {
  try {
    return file_digest(file);
  } catch (const InputError&) {
    return "unreadable";
  }
}

}  // namespace tumble::app
