// `tumble inspect --shard I/N -o PART.jsonl` and `tumble merge` of its parts into the JSON Lines
// and the JSON an unsharded inspect prints; a scene edited between the parts and the merge.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/run_command.hpp"
#include "support/scene_builder.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;
using tumble::testing::CommandResult;
using tumble::testing::fresh_directory;
using tumble::testing::read_text;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;

namespace fs = std::filesystem;

class ShardMergeInspect : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fresh_directory("shard_merge_inspect");
    meshes_ = dir_ / "meshes";
    fs::create_directory(meshes_);
    for (const auto& entry :
         fs::directory_iterator(fs::path(TUMBLE_SOURCE_DIR) / "assets/meshes")) {
      if (entry.path().extension() == ".obj") fs::copy(entry.path(), meshes_);
    }
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string inspect(const std::string& arguments) const {
    return tumble_executable() + " inspect '" + meshes_.string() + "' " + arguments;
  }
  /// `count` parts of the meshes folder; their names, in reverse shard order.
  std::vector<fs::path> parts(int count) const {
    std::vector<fs::path> names;
    for (int i = count - 1; i >= 0; --i) {
      names.push_back(dir_ / ("part-" + std::to_string(i) + ".jsonl"));
      const CommandResult result =
          run_command(inspect("--shard " + std::to_string(i) + "/" + std::to_string(count) +
                              " -o '" + names.back().string() + "'"));
      // 1 when a file of the shard is refused, as unsharded; the part is written either way.
      EXPECT_TRUE(result.status == 0 || result.status == 1) << result.err;
      EXPECT_TRUE(fs::exists(names.back())) << result.err;
    }
    return names;
  }
  static CommandResult merge(const std::vector<fs::path>& parts, const fs::path& out) {
    std::string command = tumble_executable() + " merge";
    for (const fs::path& p : parts) command += " '" + p.string() + "'";
    return run_command(command + " -o '" + out.string() + "'");
  }
  static std::vector<std::string> lines(const fs::path& file) {
    std::vector<std::string> out;
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
  }

  fs::path dir_;
  fs::path meshes_;
};

TEST_F(ShardMergeInspect, PartsMergeIntoTheUnshardedJsonLinesAndJson) {
  const CommandResult jsonl = run_command(inspect("--jsonl"));
  const CommandResult as_json = run_command(inspect("--json"));
  ASSERT_EQ(jsonl.status, 0) << jsonl.err;
  ASSERT_EQ(as_json.status, 0) << as_json.err;
  const std::vector<fs::path> names = parts(4);
  // 6 files in 4 shards: 2, 2, 1, 1, each file once; the manifest first, then its objects with
  // their place in the whole list.
  std::vector<std::size_t> items;
  for (const fs::path& name : names) {
    const std::vector<std::string> part = lines(name);
    ASSERT_FALSE(part.empty());
    const auto manifest = nlohmann::json::parse(part.front());
    EXPECT_EQ(manifest["kind"], "inspect");
    EXPECT_EQ(manifest["items"]["total"], 6);
    const int index = manifest["shard"]["index"];
    EXPECT_EQ(part.size() - 1, index < 2 ? 2u : 1u) << name;
    for (std::size_t k = 1; k < part.size(); ++k) {
      const std::size_t item = nlohmann::json::parse(part[k])["item"];
      EXPECT_EQ(item % 4, static_cast<std::size_t>(index));
      items.push_back(item);
    }
  }
  std::sort(items.begin(), items.end());
  EXPECT_EQ(items, (std::vector<std::size_t>{0, 1, 2, 3, 4, 5}));
  ASSERT_EQ(merge(names, dir_ / "all.jsonl").status, 0);
  EXPECT_EQ(read_text(dir_ / "all.jsonl"), jsonl.out);
  ASSERT_EQ(merge(names, dir_ / "all.json").status, 0);
  EXPECT_EQ(read_text(dir_ / "all.json"), as_json.out);
  // -o without --shard writes what stdout would get.
  ASSERT_EQ(run_command(inspect("--json -o '" + (dir_ / "direct.json").string() + "'")).status, 0);
  EXPECT_EQ(read_text(dir_ / "direct.json"), as_json.out);
}

TEST_F(ShardMergeInspect, RefusedFilesStayInJsonLinesAndStopAJsonMerge) {
  std::ofstream(meshes_ / "broken.stl") << "not a mesh at all\n";
  const CommandResult jsonl = run_command(inspect("--jsonl"));
  EXPECT_EQ(jsonl.status, 1);                    // as unsharded: a refused file is status 1
  const std::vector<fs::path> names = parts(2);  // 7 files: 4 and 3
  ASSERT_EQ(merge(names, dir_ / "all.jsonl").status, 0);
  EXPECT_EQ(read_text(dir_ / "all.jsonl"), jsonl.out);
  EXPECT_THAT(read_text(dir_ / "all.jsonl"), HasSubstr("broken.stl"));
  const CommandResult as_json = merge(names, dir_ / "all.json");
  EXPECT_EQ(as_json.status, 1);
  EXPECT_THAT(as_json.err, HasSubstr("broken.stl"));
  EXPECT_FALSE(fs::exists(dir_ / "all.json"));
}

TEST_F(ShardMergeInspect, BadPartsAndShardsAreOneLineErrors) {
  const std::vector<fs::path> names = parts(2);
  // A line moved from one part into the other.
  const fs::path moved = dir_ / "moved.jsonl";
  const std::vector<std::string> first = lines(names[1]);   // shard 0/2
  const std::vector<std::string> second = lines(names[0]);  // shard 1/2
  std::ofstream(moved) << first[0] << "\n" << first[1] << "\n" << second[1] << "\n";
  for (const auto& [result, named] :
       {std::pair{merge({names[0], moved}, dir_ / "o.jsonl"), moved.string()},
        {merge({names[0]}, dir_ / "o.jsonl"), std::string("shard 0/2 missing")},
        {merge({names[0], names[0], names[1]}, dir_ / "o.jsonl"), names[0].string()},
        {merge(names, dir_ / "o.txt"), std::string("-o")},
        {run_command(inspect("--shard 0/2")), std::string("--shard: -o")},
        {run_command(inspect("--shard 2/2 -o '" + (dir_ / "o.jsonl").string() + "'")),
         std::string("--shard")},
        {run_command(inspect("--shard 0/2 --json -o '" + (dir_ / "o.jsonl").string() + "'")),
         std::string("--shard")}}) {
    EXPECT_EQ(result.status, 1) << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_THAT(result.err, HasSubstr(named));
  }
  EXPECT_FALSE(fs::exists(dir_ / "o.jsonl"));
  EXPECT_FALSE(fs::exists(dir_ / "o.txt"));
}

TEST_F(ShardMergeInspect, AStabilitySceneEditedAfterThePartsIsRefused) {
  const fs::path scene = dir_ / "spinner.json";
  const auto write_scene = [&](double wx) {
    std::ofstream(scene) << testing::SceneBuilder()
                                .name("spinner")
                                .duration(1.0)
                                .dt(0.01)
                                .body(testing::BodyBuilder("b").mass(1.0).angular_velocity(
                                    {wx, 0.8, 0.6}, "body"))
                                .json()
                                .dump(2);
  };
  write_scene(0.4);
  std::vector<fs::path> names;
  for (int i = 0; i < 2; ++i) {
    names.push_back(dir_ / ("s" + std::to_string(i)));
    ASSERT_EQ(run_command(tumble_executable() + " stability '" + scene.string() +
                          "' --integrators rk4,splitting --shard " + std::to_string(i) + "/2 -o '" +
                          names.back().string() + "'")
                  .status,
              0);
  }
  ASSERT_EQ(merge(names, dir_ / "ok").status, 0);
  write_scene(0.5);
  const CommandResult result = merge(names, dir_ / "changed");
  EXPECT_EQ(result.status, 1);
  EXPECT_THAT(result.err, HasSubstr(scene.string() + ": changed since the parts were made"));
  EXPECT_FALSE(fs::exists(dir_ / "changed"));
}

}  // namespace
}  // namespace tumble::app
