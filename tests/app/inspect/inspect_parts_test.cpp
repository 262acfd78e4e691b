// The inspect part kind (app/inspect/inspect_parts.hpp): parts written by a sharded inspect
// checked on their own and merged back into what the unsharded inspect prints; a tampered, a
// foreign and a missing part refused with the part named.
#include "app/inspect/inspect_parts.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "app/inspect/inspect_run.hpp"
#include "base/errors.hpp"
#include "support/box_files.hpp"
#include "support/command_test.hpp"
#include "support/run_command.hpp"

namespace tumble::app {
namespace {

using ::testing::HasSubstr;

class InspectParts : public testing::CommandTest {
 protected:
  /// Three boxes inspected as shard I of 2 into part-I.jsonl; returns the parts' paths.
  std::vector<std::filesystem::path> write_parts() {
    for (int i = 1; i <= 3; ++i) {
      testing::write_box_binary_stl(dir_ / ("box" + std::to_string(i) + ".stl"),
                                    testing::BoxMesh({0.1 * i, 0.2, 0.3}));
    }
    std::vector<std::filesystem::path> parts;
    for (int shard = 0; shard < 2; ++shard) {
      InspectOptions options;
      options.files = {dir_ / "box1.stl", dir_ / "box2.stl", dir_ / "box3.stl"};
      options.shard = std::to_string(shard) + "/2";
      options.output = dir_ / ("part-" + std::to_string(shard) + ".jsonl");
      std::ostringstream out, err;
      EXPECT_EQ(write_inspection(options, out, err), 0) << err.str();
      parts.push_back(*options.output);
    }
    return parts;
  }

  static std::vector<NamedManifest> read(const std::vector<std::filesystem::path>& parts) {
    std::vector<NamedManifest> named;
    for (const auto& part : parts) named.push_back({part, read_part_manifest(part)});
    return named;
  }
};

TEST_F(InspectParts, MergedPartsAreTheUnshardedJsonLines) {
  const std::vector<std::filesystem::path> parts = write_parts();
  for (const NamedManifest& part : read(parts)) EXPECT_NO_THROW(inspect_parts().check(part));
  // In reverse order: the merge puts the files back in the list's order.
  const MergeOutcome merged =
      inspect_parts().merge(read({parts[1], parts[0]}), dir_ / "all.jsonl", {});
  EXPECT_FALSE(merged.interrupted);
  EXPECT_THAT(merged.summary, HasSubstr("2 inspect parts, 3 files"));
  InspectOptions whole;
  whole.files = {dir_ / "box1.stl", dir_ / "box2.stl", dir_ / "box3.stl"};
  whole.format = InspectFormat::jsonl;
  std::ostringstream out, err;
  ASSERT_EQ(write_inspection(whole, out, err), 0) << err.str();
  EXPECT_EQ(testing::read_text(dir_ / "all.jsonl"), out.str());
}

TEST_F(InspectParts, TamperedLineIsRefusedNamingPartAndLine) {
  const std::vector<std::filesystem::path> parts = write_parts();
  std::string text = testing::read_text(parts[0]);
  text.replace(text.find("\"item\":0"), 8, "\"item\":1");
  std::ofstream(parts[0]) << text;
  try {
    inspect_parts().check(read({parts[0]}).front());
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr(parts[0].string() + ": line 2: file 1 is not the next"));
  }
}

TEST_F(InspectParts, MissingShardIsRefused) {
  const std::vector<std::filesystem::path> parts = write_parts();
  EXPECT_THROW(inspect_parts().merge(read({parts[0]}), dir_ / "all.jsonl", {}), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir_ / "all.jsonl"));
}

}  // namespace
}  // namespace tumble::app
