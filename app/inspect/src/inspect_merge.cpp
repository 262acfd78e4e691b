// `tumble merge` of inspect parts: each part's objects checked to be its shard's files, put back
// in the whole list's order, written as JSON Lines or as the JSON `tumble inspect --json`
// prints.
#include "app/inspect/inspect_parts.hpp"

#include <fstream>
#include <ostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/farm/shard.hpp"
#include "app/support/csv_writer.hpp"
#include "base/errors.hpp"

namespace tumble::app {
namespace {

using nlohmann::json;

/// The objects of part `part` (the lines after its manifest), each checked to be the next file
/// of its shard, put at their places in `objects` without their "item".
void read_inspect_part(const NamedManifest& part, std::vector<json>& objects,
                       std::vector<std::size_t>& owner, std::size_t part_index) {
  const std::string name = part.part.string();
  const std::vector<std::size_t> expected = shard_items(part.manifest.total, part.manifest.shard);
  std::ifstream in(part.part);
  std::string line;
  std::getline(in, line);  // the manifest
  std::size_t k = 0;
  for (std::size_t number = 2; std::getline(in, line); ++number) {
    json object = json::parse(line, nullptr, false);
    const std::string where = name + ": line " + std::to_string(number);
    if (object.is_discarded() || !object.is_object())
      throw InputError(where + ": not a JSON object");
    const auto item = object.find("item");
    if (item == object.end() || !item->is_number_unsigned()) {
      throw InputError(where + ": no \"item\" (the file's place in the whole list)");
    }
    const auto at = item->get<std::size_t>();
    if (k >= expected.size() || at != expected[k]) {
      throw InputError(where + ": file " + std::to_string(at) + " is not the next of shard " +
                       part.manifest.shard.text() + " (a foreign or misplaced line)");
    }
    object.erase("item");
    objects[at] = std::move(object);
    owner[at] = part_index;
    ++k;
  }
  if (in.bad()) throw InputError("cannot read part '" + name + "'");
  if (k != expected.size()) {
    throw InputError(name + ": " + std::to_string(k) + " files, but shard " +
                     part.manifest.shard.text() + " has " + std::to_string(expected.size()) +
                     " (a missing line)");
  }
}

/// The inspect part kind.
class InspectPartKind : public PartKind {
 public:
  std::string name() const override { return "inspect"; }

  void check(const NamedManifest& part) const override { check_inspect_part(part); }

  MergeOutcome merge(const std::vector<NamedManifest>& parts, const std::filesystem::path& output,
                     const std::function<bool()>& /*interrupted*/) const override {
    std::vector<NamedManifest> ordered;
    for (const std::size_t i : check_parts_cover_job(parts)) ordered.push_back(parts[i]);
    std::ostringstream summary;
    merge_inspect_parts(ordered, output, summary);
    return {false, summary.str()};
  }
};

}  // namespace

const PartKind& inspect_parts() {
  static const InspectPartKind kind;
  return kind;
}

void check_inspect_part(const NamedManifest& part) {
  std::vector<json> objects(part.manifest.total);
  std::vector<std::size_t> owner(part.manifest.total, 0);
  read_inspect_part(part, objects, owner, 0);
}

void merge_inspect_parts(const std::vector<NamedManifest>& parts,
                         const std::filesystem::path& output, std::ostream& out) {
  const std::string extension = output.extension().string();
  if (extension != ".jsonl" && extension != ".json") {
    throw InputError("-o " + output.string() +
                     ": inspect parts merge into a .jsonl or a .json file");
  }
  const PartManifest& first = parts.front().manifest;
  std::vector<json> objects(first.total);
  std::vector<std::size_t> owner(first.total, 0);
  for (std::size_t p = 0; p < parts.size(); ++p) read_inspect_part(parts[p], objects, owner, p);
  std::string text;
  if (extension == ".jsonl") {
    for (const json& object : objects) text += object.dump() + "\n";
  } else {
    for (std::size_t i = 0; i < objects.size(); ++i) {
      if (objects[i].contains("error")) {
        throw InputError(parts[owner[i]].part.string() + ": " +
                         objects[i].value("file", std::string("a file")) + " was not inspected (" +
                         objects[i]["error"].dump() +
                         "); a .json merge needs every file, as inspect --json does (merge to "
                         ".jsonl to keep the errors)");
      }
    }
    const bool batch = first.job.value("batch", true);
    text = (objects.size() == 1 && !batch ? objects.front() : json(objects)).dump(2) + "\n";
  }
  AtomicFile file(output);
  file.write(text);
  file.commit();
  out << "tumble merge: " << parts.size() << " inspect parts, " << objects.size()
      << " files; wrote " << output.string() << "\n";
}

}  // namespace tumble::app
