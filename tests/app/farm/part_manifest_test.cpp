// Part manifests: written and read back, bad ones refused naming the field, and the check that
// parts are of one job and cover it exactly once naming the part that is not.
#include "app/farm/part_manifest.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "base/errors.hpp"

namespace tumble::app {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using ::testing::HasSubstr;

PartManifest render_part(int index, int count) {
  PartManifest manifest;
  manifest.kind = "render";
  manifest.tumble_version = "0.1.0";
  manifest.job = json{{"command", "render"},
                      {"scene", {{"path", "demo.json"}, {"digest", "0123456789abcdef"}}},
                      {"options", {{"fps", 30}, {"size", "1280x720"}}}};
  manifest.shard = Shard{index, count};
  manifest.total = 480;
  manifest.split = ShardSplit::kContiguous;
  manifest.payload = json{{"segment", "part.mp4"}};
  return manifest;
}

/// The InputError message of `action()`; fails the test when nothing is thrown.
template <typename Action>
std::string part_manifest_error_of(Action&& action) {
  try {
    action();
  } catch (const InputError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

std::vector<NamedManifest> parts_of(const std::vector<PartManifest>& manifests) {
  std::vector<NamedManifest> parts;
  for (const PartManifest& manifest : manifests) {
    parts.push_back({"p" + manifest.shard.text(), manifest});
  }
  return parts;
}

TEST(PartManifest, DigestIsFnv1a64) {
  // The published FNV-1a 64-bit test vectors.
  EXPECT_EQ(digest_hex(""), "cbf29ce484222325");
  EXPECT_EQ(digest_hex("a"), "af63dc4c8601ec8c");
  EXPECT_EQ(digest_hex("foobar"), "85944171f73967e8");
}

TEST(PartManifest, RoundTripsThroughJson) {
  const PartManifest written = render_part(2, 4);
  const PartManifest read = parse_manifest(manifest_json(written), "x");
  EXPECT_EQ(read.kind, "render");
  EXPECT_EQ(read.tumble_version, "0.1.0");
  EXPECT_EQ(read.job, written.job);
  EXPECT_EQ(read.shard, (Shard{2, 4}));
  EXPECT_EQ(read.total, 480U);
  EXPECT_EQ(read.split, ShardSplit::kContiguous);
  EXPECT_EQ(read.payload, written.payload);
}

TEST(PartManifest, RefusesBadFieldsNamingThem) {
  const json good = manifest_json(render_part(0, 2));
  // Each field made the wrong type (null), and one left out.
  const std::vector<std::pair<std::string, std::string>> cases{
      {"/tumble_part", "field 'tumble_part': expected an integer"},
      {"/shard/index", "field 'shard.index': expected an integer"},
      {"/items/split", "field 'items.split': expected a string"},
      {"/job_digest", "field 'job_digest': expected a string"},
      {"/payload", "field 'payload': expected an object"}};
  for (const auto& [pointer, expected] : cases) {
    json bad = good;
    bad[json::json_pointer(pointer)] = nullptr;
    EXPECT_THAT(part_manifest_error_of([&] { parse_manifest(bad, "parts/a"); }),
                ::testing::AllOf(::testing::StartsWith("parts/a: "), HasSubstr(expected)))
        << pointer;
  }
  json no_kind = good;
  no_kind.erase("kind");
  EXPECT_EQ(part_manifest_error_of([&] { parse_manifest(no_kind, "parts/a"); }),
            "parts/a: field 'kind': missing");
  json out_of_range = good;
  out_of_range["shard"]["index"] = 2;
  EXPECT_THAT(part_manifest_error_of([&] { parse_manifest(out_of_range, "m"); }),
              HasSubstr("field 'shard.index': expected 0 to count - 1"));
  json edited = good;
  edited["job"]["options"]["fps"] = 60;
  EXPECT_THAT(part_manifest_error_of([&] { parse_manifest(edited, "m"); }),
              HasSubstr("field 'job_digest': does not match the job"));
}

TEST(PartManifest, ReadsFolderAndJsonlParts) {
  const fs::path dir = fs::temp_directory_path() / ("tumble_part_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "folder");
  write_folder_manifest(dir / "folder", render_part(1, 3));
  EXPECT_EQ(read_part_manifest(dir / "folder").shard, (Shard{1, 3}));

  PartManifest inspect = render_part(0, 3);
  inspect.kind = "inspect";
  std::ofstream(dir / "rows.jsonl") << jsonl_manifest_line(inspect) << "{\"mesh\": \"a.stl\"}\n";
  EXPECT_EQ(read_part_manifest(dir / "rows.jsonl").kind, "inspect");

  std::ofstream(dir / "plain.jsonl") << "{\"mesh\": \"a.stl\"}\n";
  EXPECT_THAT(part_manifest_error_of([&] { read_part_manifest(dir / "plain.jsonl"); }),
              HasSubstr("plain.jsonl: not a tumble part"));
  fs::create_directories(dir / "empty");
  EXPECT_THAT(part_manifest_error_of([&] { read_part_manifest(dir / "empty"); }),
              HasSubstr("empty: not a tumble part (no "));
  EXPECT_THAT(part_manifest_error_of([&] { read_part_manifest(dir / "absent.jsonl"); }),
              HasSubstr("cannot read part"));
  fs::remove_all(dir);
}

TEST(PartManifest, PartsOfOneJobComeBackInShardOrder) {
  const auto parts = parts_of({render_part(2, 3), render_part(0, 3), render_part(1, 3)});
  EXPECT_THAT(check_parts_cover_job(parts), ::testing::ElementsAre(1U, 2U, 0U));
  EXPECT_THAT(check_parts_cover_job(parts_of({render_part(0, 1)})), ::testing::ElementsAre(0U));
}

TEST(PartManifest, MissingDuplicateAndForeignPartsAreNamed) {
  EXPECT_EQ(part_manifest_error_of([&] {
              check_parts_cover_job(parts_of({render_part(0, 4), render_part(1, 4)}));
            }),
            "shards 2/4, 3/4 missing (given: 0/4, 1/4)");
  EXPECT_EQ(
      part_manifest_error_of([&] {
        check_parts_cover_job(parts_of({render_part(0, 2), render_part(1, 2), render_part(1, 2)}));
      }),
      "p1/2: shard 1/2 again (also 'p1/2')");
  PartManifest foreign = render_part(1, 2);
  foreign.job["options"]["fps"] = 24;
  EXPECT_EQ(part_manifest_error_of([&] {
              check_parts_cover_job(parts_of({render_part(0, 2), foreign}));
            }),
            "p1/2: a part of another job than 'p0/2' (job field 'options.fps': 24, not 30)");
  PartManifest other_kind = render_part(1, 2);
  other_kind.kind = "compare";
  EXPECT_THAT(part_manifest_error_of([&] {
                check_parts_cover_job(parts_of({render_part(0, 2), other_kind}));
              }),
              HasSubstr("p1/2: a compare part, not render"));
  PartManifest other_version = render_part(1, 2);
  other_version.tumble_version = "0.2.0";
  EXPECT_THAT(part_manifest_error_of([&] {
                check_parts_cover_job(parts_of({render_part(0, 2), other_version}));
              }),
              HasSubstr("written by tumble 0.2.0"));
  EXPECT_THAT(part_manifest_error_of([&] {
                check_parts_cover_job(parts_of({render_part(0, 2), render_part(1, 3)}));
              }),
              HasSubstr("p1/3: shard 1/3 of 480 items does not match"));
  EXPECT_EQ(part_manifest_error_of([&] { check_parts_cover_job({}); }), "no parts given");
}

}  // namespace
}  // namespace tumble::app
