// The real robot files Debian ships: every MJCF model of libmujoco-samples through
// `tumble inertials --inertia auto --json`, as a user would run it (label `corpus`; skipped when
// the package is not installed).
//
// Each file must end in one of two ways:
// - ok: status 0, and every link either answered (a computed inertial whose method is named:
//   exact, convex, shell or primitive) or refused with its reason (the link's "error");
// - refused: status 1, nothing on stdout, exactly one line on stderr naming the file.
// The outcome of every file is in tests/corpus/robots_expected.tsv: for ok, the links, how many
// were answered, the methods used and the computed total mass (to 6 digits); for refused, the
// reason. The test fails on any difference; after a deliberate change rewrite the table with
// TUMBLE_CORPUS_UPDATE=1 and review the diff. (MuJoCo itself checks the numbers of the models
// it can compile alone: tests/app/robot/mjcf_mujoco_test.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "support/run_command.hpp"

namespace {

namespace fs = std::filesystem;
using tumble::testing::CommandResult;
using tumble::testing::run_command;

const fs::path kRobotsExpected = fs::path(TUMBLE_SOURCE_DIR) / "tests/corpus/robots_expected.tsv";
const fs::path kMujocoSamples = "/usr/share/mujoco/model";

/// Every .xml below the samples folder, relative to it, sorted.
std::vector<std::string> robot_files() {
  std::vector<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(kMujocoSamples)) {
    if (entry.is_regular_file() && entry.path().extension() == ".xml") {
      files.push_back(fs::relative(entry.path(), kMujocoSamples).generic_string());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

/// One file's outcome: "ok" with what was answered, or "refused" with the reason.
std::pair<std::string, std::string> robot_outcome(const std::string& name,
                                                  const CommandResult& run) {
  const fs::path file = kMujocoSamples / name;
  if (run.status == 0) {
    const nlohmann::json report = nlohmann::json::parse(run.out);
    std::size_t answered = 0;
    std::set<std::string> methods;
    double mass = 0.0;
    for (const nlohmann::json& link : report.at("links")) {
      const nlohmann::json& computed = link.value("computed", nlohmann::json());
      if (computed.is_object()) {
        ++answered;
        EXPECT_TRUE(computed.contains("method")) << name << ": a computed link names no method";
        for (const nlohmann::json& method : computed.value("methods", nlohmann::json::array())) {
          methods.insert(method.get<std::string>());
        }
        mass += computed.at("mass").get<double>();
      } else {
        EXPECT_TRUE(link.contains("error"))
            << name << ": link " << link.value("name", "?") << " is neither answered nor refused";
      }
    }
    std::string method_list;
    for (const std::string& method : methods)
      method_list += (method_list.empty() ? "" : ",") + method;
    char text[200];
    std::snprintf(text, sizeof text, "%zu links, %zu answered, methods %s, mass %.6g",
                  report.at("links").size(), answered,
                  method_list.empty() ? "none" : method_list.c_str(), mass);
    return {"ok", text};
  }
  const std::string prefix = "tumble inertials: error: " + file.string() + ": ";
  const bool one_line = run.err.starts_with(prefix) && run.err.ends_with("\n") &&
                        std::count(run.err.begin(), run.err.end(), '\n') == 1;
  EXPECT_EQ(run.status, 1) << name << "\n" << run.err;
  EXPECT_TRUE(one_line) << name << ": a refusal is one line naming the file, not\n" << run.err;
  EXPECT_EQ(run.out, "") << name;
  if (run.status != 1 || !one_line) return {"status " + std::to_string(run.status), run.err};
  return {"refused", run.err.substr(prefix.size(), run.err.size() - prefix.size() - 1)};
}

TEST(RobotCorpus, EveryMujocoSampleIsAnsweredOrRefusedInOneLineAsTheTableSays) {
  if (!fs::is_directory(kMujocoSamples)) {
    GTEST_SKIP() << "libmujoco-samples is not installed (apt-get install libmujoco-samples)";
  }
  std::map<std::string, std::pair<std::string, std::string>> actual;
  for (const std::string& name : robot_files()) {
    const CommandResult run =
        run_command(tumble::testing::tumble_executable() + " inertials --inertia auto --json '" +
                    (kMujocoSamples / name).string() + "'");
    actual[name] = robot_outcome(name, run);
  }
  ASSERT_FALSE(actual.empty()) << kMujocoSamples;
  if (std::getenv("TUMBLE_CORPUS_UPDATE") != nullptr) {
    std::ofstream out(kRobotsExpected);
    out << "# file\toutcome\tanswer or reason (tests/corpus/robot_corpus_test.cpp; "
           "libmujoco-samples)\n";
    for (const auto& [name, row] : actual)
      out << name << '\t' << row.first << '\t' << row.second << '\n';
    return;
  }
  std::map<std::string, std::pair<std::string, std::string>> expected;
  std::ifstream in(kRobotsExpected);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const std::size_t first = line.find('\t');
    const std::size_t second = line.find('\t', first + 1);
    ASSERT_NE(second, std::string::npos) << kRobotsExpected << ": malformed row: " << line;
    expected[line.substr(0, first)] = {line.substr(first + 1, second - first - 1),
                                       line.substr(second + 1)};
  }
  for (const auto& [name, row] : actual) {
    const auto it = expected.find(name);
    if (it == expected.end()) {
      ADD_FAILURE() << name << ": not in " << kRobotsExpected << " (" << row.first << "\t"
                    << row.second << ")";
    } else {
      EXPECT_EQ(it->second, row) << name;
    }
  }
  for (const auto& [name, row] : expected) {
    EXPECT_TRUE(actual.contains(name)) << name << ": in the table but not in " << kMujocoSamples;
  }
}

}  // namespace
