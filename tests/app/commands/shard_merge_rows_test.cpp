// `--shard I/N` of bench and stability and `tumble merge` of their parts: three shards merged
// (given in any order) against the unsharded run, row for row and report line for line apart
// from the timings; the shards balanced and disjoint.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/csv_reader.hpp"
#include "support/run_command.hpp"

namespace tumble::app {
namespace {

using ::testing::ElementsAre;
using tumble::testing::CommandResult;
using tumble::testing::directory_entries;
using tumble::testing::fresh_directory;
using tumble::testing::read_csv;
using tumble::testing::read_text;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;

namespace fs = std::filesystem;

/// The table's records without the columns named in `dropped`.
std::vector<std::vector<std::string>> records_without(const testing::CsvTable& table,
                                                      const std::set<std::string>& dropped) {
  std::vector<std::vector<std::string>> out;
  for (const auto& record : table.records) {
    std::vector<std::string> kept;
    for (std::size_t i = 0; i < record.size(); ++i) {
      if (!dropped.count(table.header[i])) kept.push_back(record[i]);
    }
    out.push_back(kept);
  }
  return out;
}

/// report.md without what depends on timing: the "Ran on" paragraph (which names the run's
/// cores, or each shard's), the time cells of the runs tables (time, min - max, ns/step) and the
/// rows of the "Fastest to each accuracy" tables.
std::vector<std::string> report_without_timings(const std::string& report) {
  std::vector<std::string> out;
  std::istringstream in(report);
  std::string line;
  std::string section;
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) == 0) section = "runs";
    if (line.rfind("### ", 0) == 0) section = line;
    if (line.rfind("Ran ", 0) == 0) continue;
    if (line.rfind("| ", 0) == 0 && section.find("Fastest") != std::string::npos) continue;
    if (line.rfind("| ", 0) == 0 && section == "runs") {
      std::vector<std::string> cells;
      std::stringstream row(line);
      std::string cell;
      while (std::getline(row, cell, '|')) cells.push_back(cell);
      if (cells.size() > 8) cells.erase(cells.begin() + 6, cells.begin() + 9);
      line.clear();
      for (const std::string& c : cells) line += c + "|";
    }
    out.push_back(line);
  }
  return out;
}

const std::set<std::string> kBenchTimings = {"seconds_median", "seconds_min", "seconds_max",
                                             "ns_per_step", "core"};

class ShardMergeRows : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fresh_directory("shard_merge_rows");
    // The tennis racket loads a mesh: its digest is part of the job too.
    const std::string bench = tumble_executable() + " bench '" + kScene +
                              "' --integrators rk4,splitting,explicit-euler --dts 0.01,0.005 "
                              "--duration 1 --repeat 1 ";
    full_ = run_command(bench + "-o '" + (dir_ / "full").string() + "'");
    for (int i = 0; i < 3; ++i) {
      shards_[i] =
          run_command(bench + "--shard " + std::to_string(i) + "/3 -o '" + part(i).string() + "'");
    }
    merge_ = merge({part(2), part(0), part(1)}, dir_ / "merged");
    const std::string stability = tumble_executable() + " stability --suite quick ";
    stability_full_ = run_command(stability + "-o '" + (dir_ / "sfull").string() + "'");
    for (int i = 0; i < 3; ++i) {
      run_command(stability + "--shard " + std::to_string(i) + "/3 -o '" +
                  stability_part(i).string() + "'");
    }
    stability_merge_ =
        merge({stability_part(1), stability_part(2), stability_part(0)}, dir_ / "smerged");
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

 public:
  static fs::path part(int i) { return dir_ / ("part-" + std::to_string(i)); }
  static fs::path stability_part(int i) { return dir_ / ("spart-" + std::to_string(i)); }
  static CommandResult merge(const std::vector<fs::path>& parts, const fs::path& out) {
    std::string command = tumble_executable() + " merge";
    for (const fs::path& p : parts) command += " '" + p.string() + "'";
    return run_command(command + " -o '" + out.string() + "'");
  }

  static inline const std::string kScene =
      std::string(TUMBLE_SOURCE_DIR) + "/assets/scenes/tennis_racket.json";
  static inline fs::path dir_;
  static inline CommandResult full_, merge_, stability_full_, stability_merge_;
  static inline CommandResult shards_[3];
};

TEST_F(ShardMergeRows, BenchPartsHoldOnlyTheirRowsAndAManifest) {
  ASSERT_EQ(full_.status, 0) << full_.err;
  std::set<std::string> seen;
  std::vector<std::size_t> sizes;
  for (int i = 0; i < 3; ++i) {
    ASSERT_EQ(shards_[i].status, 0) << shards_[i].err;
    EXPECT_THAT(directory_entries(part(i)), ElementsAre("part.json", "results.csv"));
    const auto manifest = nlohmann::json::parse(read_text(part(i) / "part.json"));
    EXPECT_EQ(manifest["kind"], "bench");
    EXPECT_EQ(manifest["shard"]["index"], i);
    EXPECT_EQ(manifest["shard"]["count"], 3);
    EXPECT_EQ(manifest["items"]["total"], 6);
    EXPECT_EQ(manifest["job"]["scenes"][0]["meshes"].size(), 1u);  // the racket's mesh
    const auto rows = read_csv(part(i) / "results.csv");
    sizes.push_back(rows.rows.size());
    for (const auto& row : rows.rows) {
      EXPECT_TRUE(seen.insert(row.at("integrator") + " " + row.at("dt")).second)
          << "a case in two shards: " << row.at("integrator") << " " << row.at("dt");
    }
  }
  // 6 cases in 3 shards: 2 each, disjoint, together every case of the unsharded run.
  EXPECT_THAT(sizes, ElementsAre(2u, 2u, 2u));
  std::set<std::string> all;
  for (const auto& row : read_csv(dir_ / "full" / "results.csv").rows) {
    all.insert(row.at("integrator") + " " + row.at("dt"));
  }
  EXPECT_EQ(seen, all);
}

TEST_F(ShardMergeRows, MergedBenchIsTheUnshardedOneApartFromTimings) {
  ASSERT_EQ(merge_.status, 0) << merge_.err;
  const auto full = read_csv(dir_ / "full" / "results.csv");
  const auto merged = read_csv(dir_ / "merged" / "results.csv");
  EXPECT_EQ(full.header, merged.header);
  ASSERT_EQ(merged.records.size(), 6u);
  EXPECT_EQ(records_without(full, kBenchTimings), records_without(merged, kBenchTimings));
  // The timing columns are measured, not copied: each row's run took some time.
  for (const auto& row : merged.rows) EXPECT_GT(std::stod(row.at("seconds_median")), 0.0);
  const std::string full_report = read_text(dir_ / "full" / "report.md");
  const std::string merged_report = read_text(dir_ / "merged" / "report.md");
  EXPECT_EQ(report_without_timings(full_report), report_without_timings(merged_report));
  EXPECT_THAT(merged_report, ::testing::HasSubstr("Ran as 3 shards"));
  // The same plots; those against evaluations (no timing in them) identical.
  EXPECT_EQ(directory_entries(dir_ / "full"), directory_entries(dir_ / "merged"));
  for (const std::string& name : directory_entries(dir_ / "full")) {
    if (name.find("_evaluations.svg") == std::string::npos) continue;
    EXPECT_EQ(read_text(dir_ / "full" / name), read_text(dir_ / "merged" / name)) << name;
  }
}

TEST_F(ShardMergeRows, MergedStabilityIsTheUnshardedOne) {
  ASSERT_EQ(stability_full_.status, 0) << stability_full_.err;
  ASSERT_EQ(stability_merge_.status, 0) << stability_merge_.err;
  const auto full = read_csv(dir_ / "sfull" / "stability.csv");
  const auto merged = read_csv(dir_ / "smerged" / "stability.csv");
  ASSERT_GT(full.records.size(), 30u);
  EXPECT_EQ(records_without(full, {"wall_seconds"}), records_without(merged, {"wall_seconds"}));
  // Nothing in the matrices or the heat map depends on timing.
  EXPECT_EQ(read_text(dir_ / "sfull" / "stability.md"),
            read_text(dir_ / "smerged" / "stability.md"));
  EXPECT_EQ(read_text(dir_ / "sfull" / "stability.svg"),
            read_text(dir_ / "smerged" / "stability.svg"));
  // Balanced and disjoint: sizes within one, every run once.
  std::vector<std::size_t> sizes;
  std::set<std::string> seen;
  for (int i = 0; i < 3; ++i) {
    const auto rows = read_csv(stability_part(i) / "stability.csv");
    sizes.push_back(rows.rows.size());
    for (const auto& row : rows.rows) {
      EXPECT_TRUE(
          seen.insert(row.at("case") + " " + row.at("integrator") + " " + row.at("dt")).second);
    }
  }
  EXPECT_LE(
      *std::max_element(sizes.begin(), sizes.end()) - *std::min_element(sizes.begin(), sizes.end()),
      1u);
  EXPECT_EQ(seen.size(), full.records.size());
}

/// A merge that must fail: status 1, one line naming `named`, nothing at the output.
void expect_refused(const CommandResult& result, const fs::path& out, const std::string& named,
                    const std::string& why) {
  EXPECT_EQ(result.status, 1) << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_THAT(result.err, ::testing::HasSubstr(named));
  EXPECT_THAT(result.err, ::testing::HasSubstr(why));
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(ShardMergeRows, BadPartsAreRefusedNamingThePart) {
  const fs::path out = dir_ / "refused";
  expect_refused(merge({part(0), part(2)}, out), out, "shard 1/3", "missing");
  expect_refused(merge({part(0), part(1), part(1), part(2)}, out), out, part(1).string(), "again");
  expect_refused(merge({part(0), part(1), stability_part(2)}, out), out, stability_part(2).string(),
                 "a stability part");
  // Another job: a shard of the same bench with other steps.
  const fs::path other = dir_ / "other-1";
  ASSERT_EQ(run_command(tumble_executable() + " bench '" + kScene +
                        "' --integrators rk4,splitting,explicit-euler --dts 0.01,0.0025 "
                        "--duration 1 --repeat 1 --shard 1/3 -o '" +
                        other.string() + "'")
                .status,
            0);
  expect_refused(merge({part(0), other, part(2)}, out), out, other.string(), "options.dts");
  // An edited manifest: its job no longer matches its digest.
  const fs::path edited = dir_ / "edited-1";
  fs::copy(part(1), edited);
  std::string manifest = read_text(edited / "part.json");
  manifest.replace(manifest.find("\"repeat\": \"1\""), 13, "\"repeat\": \"2\"");
  std::ofstream(edited / "part.json") << manifest;
  expect_refused(merge({part(0), edited, part(2)}, out), out, edited.string(), "job_digest");
  // A row of another shard in place of one of its own.
  const fs::path foreign = dir_ / "foreign-1";
  fs::copy(part(1), foreign);
  std::vector<std::string> lines;
  std::istringstream rows(read_text(part(1) / "results.csv"));
  for (std::string line; std::getline(rows, line);) lines.push_back(line);
  std::istringstream others(read_text(part(0) / "results.csv"));
  std::string header, first_other;
  std::getline(others, header);
  std::getline(others, first_other);
  std::ofstream(foreign / "results.csv") << lines[0] << "\n"
                                         << first_other << "\n"
                                         << lines[2] << "\n";
  expect_refused(merge({part(0), foreign, part(2)}, out), out, foreign.string(), "row 1");
  // A missing row.
  std::ofstream(foreign / "results.csv") << lines[0] << "\n" << lines[1] << "\n";
  expect_refused(merge({part(0), foreign, part(2)}, out), out, foreign.string(), "missing");
}

TEST_F(ShardMergeRows, BadShardOptionsAreOneLineErrors) {
  for (const std::string& command :
       {" bench '" + kScene + "' --shard 3/3 -o '" + (dir_ / "x").string() + "'",
        " bench '" + kScene + "' --shard 1/2", std::string(" stability --suite quick --shard 1/2"),
        " stability --suite quick --shard a/2 -o '" + (dir_ / "x").string() + "'"}) {
    const CommandResult result = run_command(tumble_executable() + command);
    EXPECT_EQ(result.status, 1) << command;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_THAT(result.err, ::testing::HasSubstr("--shard"));
    EXPECT_FALSE(fs::exists(dir_ / "x"));
  }
}

}  // namespace
}  // namespace tumble::app
