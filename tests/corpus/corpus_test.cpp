// The real-world corpus: every model file of Debian's assimp-testmodels through
// `tumble inspect --json`, as a user would run it (label `corpus`; skipped when the package is
// not installed).
//
// Each file runs under `timeout 10` and a 1 GiB address-space limit (`prlimit --as`; under
// AddressSanitizer `timeout 30` alone), as many files at a time as there are cores, and must end
// in one of two ways:
// - ok: status 0, and the volume agrees with an independent sum of signed tetrahedra over the
//   triangles assimp imports (read here with assimp's own triangulation, node transforms
//   applied in double precision; tumble's welding, checks and orientation are not involved);
// - refused: status 1, nothing on stdout, and exactly one line on stderr naming the file.
// Anything else (a crash, the time or memory limit, another status) fails the file.
//
// The outcome of every file is committed in tests/corpus/expected.tsv (file, outcome, and the
// refusal's reason or the volume to 9 digits), so a change of outcome shows in review: the test
// fails on any difference, and on files added to or gone from the corpus. After a deliberate
// change, rewrite the table with TUMBLE_CORPUS_UPDATE=1 (the test then writes it and passes)
// and review the diff. TUMBLE_CORPUS_DIR points the test at another copy of the models.
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <assimp/Importer.hpp>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/run_command.hpp"

namespace {

namespace fs = std::filesystem;
using tumble::testing::CommandResult;
using tumble::testing::run_command;

const fs::path kExpected = fs::path(TUMBLE_SOURCE_DIR) / "tests/corpus/expected.tsv";

/// Where the package puts its models (Debian's assimp-testmodels), or TUMBLE_CORPUS_DIR.
std::optional<fs::path> corpus_dir() {
  if (const char* dir = std::getenv("TUMBLE_CORPUS_DIR")) return fs::path(dir);
  for (const char* dir : {"/usr/share/assimp/models", "/usr/share/assimp-testmodels/models"}) {
    if (fs::is_directory(dir)) return fs::path(dir);
  }
  return std::nullopt;
}

/// Every regular file below `root` whose extension assimp reads, relative to `root`, sorted.
std::vector<std::string> model_files(const fs::path& root) {
  Assimp::Importer importer;
  std::vector<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (!entry.is_regular_file() || !entry.path().has_extension()) continue;
    if (!importer.IsExtensionSupported(entry.path().extension().string())) continue;
    files.push_back(fs::relative(entry.path(), root).generic_string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

/// One row of the table: "ok" with the volume, or "refused" with the reason.
struct Outcome {
  std::string outcome;
  std::string detail;
  bool operator==(const Outcome&) const = default;
};

std::map<std::string, Outcome> read_expected() {
  std::map<std::string, Outcome> table;
  std::ifstream in(kExpected);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const std::size_t first = line.find('\t');
    const std::size_t second = line.find('\t', first + 1);
    if (first == std::string::npos || second == std::string::npos) {
      ADD_FAILURE() << kExpected << ": malformed row: " << line;
      continue;
    }
    table[line.substr(0, first)] = {line.substr(first + 1, second - first - 1),
                                    line.substr(second + 1)};
  }
  return table;
}

void write_expected(const std::map<std::string, Outcome>& table) {
  std::ofstream out(kExpected);
  out << "# file\toutcome\treason or volume (tests/corpus/corpus_test.cpp; assimp-testmodels)\n";
  for (const auto& [file, row] : table)
    out << file << '\t' << row.outcome << '\t' << row.detail << '\n';
}

/// The volume of what assimp imports, by signed tetrahedra about the bounding-box centre.
struct Sum {
  double signed_volume = 0.0;
  double absolute_volume = 0.0;
};

void add_node(const aiScene& scene, const aiNode& node, const Eigen::Matrix4d& parent,
              std::vector<std::array<Eigen::Vector3d, 3>>& triangles) {
  const aiMatrix4x4& m = node.mTransformation;
  Eigen::Matrix4d local;
  local << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3,
      m.d4;
  const Eigen::Matrix4d transform = parent * local;
  const bool mirrored = transform.topLeftCorner<3, 3>().determinant() < 0.0;
  for (unsigned i = 0; i < node.mNumMeshes; ++i) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[i]];
    const auto corner = [&](unsigned v) {
      const aiVector3D& p = mesh.mVertices[v];
      return Eigen::Vector3d(transform.topLeftCorner<3, 3>() * Eigen::Vector3d(p.x, p.y, p.z) +
                             transform.topRightCorner<3, 1>());
    };
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;
      std::array<Eigen::Vector3d, 3> t{corner(face.mIndices[0]), corner(face.mIndices[1]),
                                       corner(face.mIndices[2])};
      if (mirrored) std::swap(t[1], t[2]);
      triangles.push_back(t);
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) {
    add_node(scene, *node.mChildren[c], transform, triangles);
  }
}

Sum assimp_volume(const fs::path& file) {
  Assimp::Importer importer;
  const aiScene* scene =
      importer.ReadFile(file.string(), aiProcess_Triangulate | aiProcess_SortByPType);
  std::vector<std::array<Eigen::Vector3d, 3>> triangles;
  if (scene == nullptr || scene->mRootNode == nullptr) return {};
  add_node(*scene, *scene->mRootNode, Eigen::Matrix4d::Identity(), triangles);
  if (triangles.empty()) return {};
  Eigen::Vector3d low = triangles[0][0], high = low;
  for (const auto& t : triangles) {
    for (const auto& p : t) low = low.cwiseMin(p), high = high.cwiseMax(p);
  }
  const Eigen::Vector3d centre = 0.5 * (low + high);
  Sum sum;
  for (const auto& t : triangles) {
    const double det = (t[0] - centre).dot((t[1] - centre).cross(t[2] - centre)) / 6.0;
    sum.signed_volume += det;
    sum.absolute_volume += std::abs(det);
  }
  return sum;
}

std::string quoted(const fs::path& file) {
  return "'" + file.string() + "'";
}

std::string nine_digits(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

#if defined(__SANITIZE_ADDRESS__)
#define TUMBLE_CORPUS_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TUMBLE_CORPUS_ASAN 1
#endif
#endif

/// The limits of one run. AddressSanitizer reserves terabytes of address space for its shadow
/// and runs several times slower: under it (the sanitizer build of CI) only the time limit
/// applies, three times as long.
std::string limits() {
#ifdef TUMBLE_CORPUS_ASAN
  return "timeout 30 ";
#else
  return "timeout 10 prlimit --as=1073741824 ";
#endif
}

/// The runs of tumble on every file, as many at a time as there are cores (at least 2). Each is
/// its own process, and under AddressSanitizer one takes about 0.8 s however small the file
/// (the sanitizer's start and exit): 415 files one at a time outlasted the test's time limit.
std::vector<CommandResult> run_all(const fs::path& root, const std::vector<std::string>& files) {
  std::vector<CommandResult> runs(files.size());
  std::atomic<std::size_t> next{0};
  const auto work = [&] {
    for (std::size_t i = next++; i < files.size(); i = next++) {
      runs[i] = run_command(limits() + tumble::testing::tumble_executable() + " inspect --json " +
                            quoted(root / files[i]));
    }
  };
  std::vector<std::thread> workers;
  for (unsigned j = 1; j < std::max(2u, std::thread::hardware_concurrency()); ++j) {
    workers.emplace_back(work);
  }
  work();
  for (std::thread& worker : workers) worker.join();
  return runs;
}

/// Checks tumble's run on one file against the run's own rules; returns its outcome.
Outcome evaluate(const fs::path& root, const std::string& name, const CommandResult& run) {
  const fs::path file = root / name;
  if (run.status == 0) {
    const nlohmann::json report = nlohmann::json::parse(run.out);
    const double volume = report.at("volume").get<double>();
    // --overlap union (the default) takes out the volume overlapping parts share: the raw sum
    // of the tetrahedra counts it twice.
    const double shared = report.value("shared_volume", 0.0);
    const Sum sum = assimp_volume(file);
    // The coordinates are float32: where two meshes coincide (BLEND/MirroredCube_252.blend
    // holds a cube and its mirror image in one place) tumble's weld makes them cancel exactly,
    // the raw sum only to their rounding, a few float epsilons of the absolute volume.
    EXPECT_NEAR(volume + shared, std::abs(sum.signed_volume),
                4 * 1.2e-7 * sum.absolute_volume + 1e-9 * std::abs(sum.signed_volume))
        << name << ": tumble's volume differs from the tetrahedra of what assimp imports";
    return {"ok", nine_digits(volume)};
  }
  // tumble's line comes last; assimp's OpenDDL parser prints lines of its own to stderr before
  // it (OpenGEX/empty_camera.ogex), which the table records with the reason.
  const std::string prefix = "tumble inspect: error: " + file.string() + ": ";
  const std::size_t last = run.err.rfind('\n', run.err.size() >= 2 ? run.err.size() - 2 : 0);
  const std::string own = last == std::string::npos ? run.err : run.err.substr(last + 1);
  const std::string before = last == std::string::npos ? "" : run.err.substr(0, last + 1);
  const bool one_line = own.starts_with(prefix) && own.ends_with("\n") &&
                        before.find("tumble inspect:") == std::string::npos;
  EXPECT_EQ(run.status, 1) << name << " (124: the time limit; 128 + n: signal n)\n" << run.err;
  EXPECT_TRUE(one_line) << name << ": a refusal is one line naming the file, not\n" << run.err;
  EXPECT_EQ(run.out, "") << name;
  if (run.status != 1 || !one_line) return {"status " + std::to_string(run.status), run.err};
  std::string reason = own.substr(prefix.size(), own.size() - prefix.size() - 1);
  if (!before.empty()) {
    std::string noise = before.substr(0, before.size() - 1);
    std::replace(noise.begin(), noise.end(), '\n', ' ');
    reason += " [assimp printed: " + noise + "]";
  }
  return {"refused", reason};
}

/// Expected and actual agree: the same outcome, the same reason, the volume to 1e-6.
bool agrees(const Outcome& expected, const Outcome& actual) {
  if (expected.outcome != actual.outcome) return false;
  if (actual.outcome != "ok") return expected.detail == actual.detail;
  const double want = std::stod(expected.detail), got = std::stod(actual.detail);
  return std::abs(want - got) <= 1e-6 * std::abs(want);
}

TEST(Corpus, EveryModelIsInspectedOrRefusedInOneLineAsTheTableSays) {
  const std::optional<fs::path> root = corpus_dir();
  if (!root)
    GTEST_SKIP() << "assimp-testmodels is not installed (apt-get install assimp-testmodels)";
  const std::vector<std::string> files = model_files(*root);
  ASSERT_FALSE(files.empty()) << *root;

  const std::vector<CommandResult> runs = run_all(*root, files);
  std::map<std::string, Outcome> actual;
  for (std::size_t i = 0; i < files.size(); ++i)
    actual[files[i]] = evaluate(*root, files[i], runs[i]);
  if (std::getenv("TUMBLE_CORPUS_UPDATE") != nullptr) {
    write_expected(actual);
    return;
  }
  const std::map<std::string, Outcome> expected = read_expected();
  for (const auto& [name, row] : actual) {
    const auto it = expected.find(name);
    if (it == expected.end()) {
      ADD_FAILURE() << name << ": not in " << kExpected << " (" << row.outcome << "\t" << row.detail
                    << ")";
    } else if (!agrees(it->second, row)) {
      ADD_FAILURE() << name << ": expected " << it->second.outcome << " (" << it->second.detail
                    << "), got " << row.outcome << " (" << row.detail << ")";
    }
  }
  for (const auto& [name, row] : expected) {
    EXPECT_TRUE(actual.contains(name)) << name << ": in the table but not in " << *root;
  }
}

TEST(Corpus, UnitedPartsGiveTheSameBitsWhenTheFileIsInspectedAgain) {
  // Two models whose overlapping parts are united (--overlap union, the default), inspected in
  // turn in one run: A A B A B. The union comes out of CGAL's corefinement in an order that
  // varied from one call to the next (the same file's last digits differed within a run); the
  // integrals over it must not depend on that order.
  const std::optional<fs::path> root = corpus_dir();
  if (!root)
    GTEST_SKIP() << "assimp-testmodels is not installed (apt-get install assimp-testmodels)";
  const fs::path a = *root / "MDL/MDL5 (3DGS A5)/PhosphoricAcid_MDl5.mdl";
  const fs::path b = *root / "LWO/LWO2/hierarchy.lwo";
  ASSERT_TRUE(fs::is_regular_file(a) && fs::is_regular_file(b)) << *root;
  const CommandResult run =
      run_command(tumble::testing::tumble_executable() + " inspect --jsonl " + quoted(a) + " " +
                  quoted(a) + " " + quoted(b) + " " + quoted(a) + " " + quoted(b));
  ASSERT_EQ(run.status, 0) << run.err;
  std::vector<std::string> lines;
  std::istringstream out(run.out);
  for (std::string line; std::getline(out, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 5u) << run.out;
  EXPECT_NE(lines[0].find("\"shared_volume\""), std::string::npos) << lines[0];
  EXPECT_NE(lines[2].find("\"shared_volume\""), std::string::npos) << lines[2];
  EXPECT_EQ(lines[1], lines[0]);
  EXPECT_EQ(lines[3], lines[0]);
  EXPECT_EQ(lines[4], lines[2]);
}

}  // namespace
