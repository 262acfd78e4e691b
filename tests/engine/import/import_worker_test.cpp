// Tests of the import workers (engine/import/src/import_worker.hpp): a worker is a program of
// its own, never a fork of the caller; many answers through one worker arrive bit for bit;
// whatever goes wrong on one file (a crash, an endless loop, an allocation beyond the limit, an
// exception, an answer that cannot be written) is that file's one-line refusal, the dead worker
// is reaped and the next file gets a fresh one; workers are replaced after kWorkerFiles files and
// after any file not read cleanly; none outlives its thread. The first half drives a test worker
// (tests/engine/import_test_worker.cpp) whose tasks misbehave on request; the second, import_mesh
// with assimp, on the inputs on which assimp 5.2 itself crashes, loops or leaks (found by
// fuzzing, kept in tests/fuzz/corpus/mesh_import/).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "engine/geometry/primitive_meshes.hpp"
#include "engine/import/mesh_import.hpp"
#include "engine/mesh_fixtures.hpp"
#include "import_worker.hpp"
#include "support/input_error.hpp"

namespace tumble::engine {
namespace {

using detail::import_worker_pid;
using detail::stop_import_worker;
using ::testing::HasSubstr;
using tumble::testing::input_error_of;

const std::filesystem::path kFile = "model.obj";
const std::filesystem::path kTestWorker = TUMBLE_TEST_IMPORT_WORKER;

ImportLimits short_limits() {
  return ImportLimits{1.0, std::uint64_t{256} << 20};
}

/// The test worker's answer to `request` (its task's texts), copied out of the mapping.
std::string run(const std::vector<std::string>& request,
                const ImportLimits& limits = short_limits()) {
  const detail::WorkerAnswer answer =
      detail::run_in_worker(kFile, limits, "assimp", kTestWorker, "test", request);
  const std::span<const std::byte> bytes = answer.payload();
  return std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

/// The texts (u64 length, bytes) at the start of `answer`, `count` of them.
std::vector<std::string> texts_of(const std::string& answer, std::size_t count) {
  std::vector<std::string> texts;
  std::size_t at = 0;
  for (std::size_t i = 0; i < count; ++i) {
    std::uint64_t size = 0;
    std::memcpy(&size, answer.data() + at, sizeof size);
    texts.push_back(answer.substr(at + sizeof size, size));
    at += sizeof size + size;
  }
  return texts;
}

/// What the test worker echoes for {"echo", N}: the two texts, then N bytes of its pattern.
std::string echo_of(const std::string& tag, std::uint64_t count) {
  std::string expected;
  for (const std::string& text : {tag, std::to_string(count)}) {
    const std::uint64_t size = text.size();
    expected.append(reinterpret_cast<const char*>(&size), sizeof size);
    expected += text;
  }
  for (std::uint64_t i = 0; i < count; ++i) expected += static_cast<char>((i * 7 + 3) % 251);
  return expected;
}

/// The processes whose parent is this one.
std::vector<pid_t> children() {
  std::vector<pid_t> found;
  for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(entry.path() / "stat");
    const std::string line((std::istreambuf_iterator<char>(stat)), {});
    const auto close = line.rfind(')');
    if (close == std::string::npos) continue;
    char state = 0;
    pid_t parent = 0;
    if (std::sscanf(line.c_str() + close + 1, " %c %d", &state, &parent) == 2 &&
        parent == ::getpid()) {
      found.push_back(std::stoi(name));
    }
  }
  return found;
}

using mesh_fixtures::fuzz_input_as_file;

TEST(ImportWorker, ManyAnswersArriveBitForBitFromOneWorker) {
  stop_import_worker();
  // 1.2 MB: more than a socket's or a pipe's buffer.
  EXPECT_EQ(run({"echo", "1200000"}), echo_of("echo", 1200000));
  const auto pid = import_worker_pid();
  ASSERT_TRUE(pid.has_value());
  for (int i = 0; i < 5; ++i) {
    const std::string tag = "echo " + std::to_string(i);
    EXPECT_EQ(run({tag, std::to_string(70000 + i)}), echo_of(tag, 70000 + i));
  }
  EXPECT_EQ(import_worker_pid(), pid);
}

TEST(ImportWorker, TheWorkerIsItsOwnProgramNotAForkOfTheCaller) {
  stop_import_worker();
  run({"echo", "0"});
  const auto pid = import_worker_pid();
  ASSERT_TRUE(pid.has_value());
  const auto exe = std::filesystem::read_symlink("/proc/" + std::to_string(*pid) + "/exe");
  EXPECT_EQ(exe, std::filesystem::canonical(kTestWorker));
  EXPECT_NE(exe, std::filesystem::read_symlink("/proc/self/exe"));
}

TEST(ImportWorker, TheWorkerHoldsOnlyItsOwnDescriptors) {
  // A descriptor of ours that is not close-on-exec (as a caller's may be) stays out of it.
  int inherited[2];
  ASSERT_EQ(::pipe(inherited), 0);
  stop_import_worker();
  const std::string answer = run({"descriptors"});
  ::close(inherited[0]);
  ::close(inherited[1]);
  std::vector<std::string> held;
  for (std::size_t at = 0; at < answer.size();) {
    held.push_back(texts_of(answer.substr(at), 1).front());
    at += sizeof(std::uint64_t) + held.back().size();
  }
  std::sort(held.begin(), held.end());
  // stdin, stdout, stderr, the socket, the answer file, and the listing's own descriptor.
  ASSERT_EQ(held.size(), 6u) << ::testing::PrintToString(held);
  EXPECT_EQ(std::vector<std::string>(held.begin(), held.begin() + 5),
            (std::vector<std::string>{"0", "1", "2", "3", "4"}));
}

TEST(ImportWorker, ACrashInTheMiddleOfABatchIsThatFilesRefusalAndTheNextFilesRead) {
  stop_import_worker();
  run({"echo", "10"});
  run({"echo", "10"});
  const auto pid = import_worker_pid();
  EXPECT_EQ(input_error_of([] { run({"crash"}); }),
            "model.obj: assimp crashed reading it (SIGSEGV, Segmentation fault): the file is "
            "malformed in a way assimp does not survive");
  EXPECT_FALSE(import_worker_pid().has_value());  // reaped
  EXPECT_EQ(run({"echo", "10"}), echo_of("echo", 10));
  EXPECT_NE(import_worker_pid(), pid);
}

TEST(ImportWorker, EachFileHasItsOwnCpuBudgetAndALoopIsStillNamedSo) {
  stop_import_worker();
  // 2.1 s of CPU time in one worker, 0.7 s a file against a limit of 1 s: all read.
  for (int i = 0; i < 3; ++i) EXPECT_EQ(texts_of(run({"spin", "0.7"}), 1)[0], "spin");
  const auto pid = import_worker_pid();
  EXPECT_EQ(input_error_of([] { run({"loop"}); }),
            "model.obj: assimp used more than 1 s of CPU time reading it (it may loop on this "
            "file)");
  EXPECT_EQ(run({"echo", "1"}), echo_of("echo", 1));
  EXPECT_NE(import_worker_pid(), pid);
}

TEST(ImportWorker, AKillAfterEarlierFilesUsedCpuTimeIsNotCalledALoop) {
  // As the kernel's out-of-memory killer would end it, with almost no CPU time used.
  stop_import_worker();
  for (int i = 0; i < 2; ++i) run({"spin", "0.7"});
  EXPECT_EQ(input_error_of([] { run({"kill"}); }),
            "model.obj: assimp was killed (SIGKILL) reading it, perhaps by the kernel for want "
            "of memory");
}

TEST(ImportWorker, AnAllocationBeyondTheMemoryLimitIsARefusal) {
#ifdef TUMBLE_ADDRESS_SANITIZER
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: no memory limit there";
#else
  stop_import_worker();
  run({"echo", "1"});
  EXPECT_EQ(input_error_of([] { run({"allocate"}); }),
            "model.obj: assimp needs more than 0.25 GiB of memory to read it");
  EXPECT_FALSE(import_worker_pid().has_value());  // not trusted with another file
  EXPECT_EQ(run({"echo", "1"}), echo_of("echo", 1));
#endif
}

TEST(ImportWorker, ErrorsAreWordForWordAndTheWorkerIsReplacedOnlyAfterFailures) {
  stop_import_worker();
  run({"echo", "1"});
  const auto pid = import_worker_pid();
  // A refusal keeps the worker: assimp unwinds its errors.
  EXPECT_EQ(input_error_of([] {
              run({"error", "model.obj: face 3 is bad"});
            }),
            "model.obj: face 3 is bad");
  EXPECT_EQ(import_worker_pid(), pid);
  // An unexpected exception does not: the worker's heap may be in any state.
  EXPECT_EQ(input_error_of([] {
              run({"throw", "no such thing"});
            }),
            "model.obj: assimp failed reading it (no such thing)");
  EXPECT_FALSE(import_worker_pid().has_value());
  EXPECT_EQ(input_error_of([] { run({"exit"}); }),
            "model.obj: assimp ended without an answer (exit status 9)");
  EXPECT_EQ(run({"echo", "1"}), echo_of("echo", 1));
}

TEST(ImportWorker, AnAnswerThatCannotBeWrittenIsNamedSo) {
  stop_import_worker();
  EXPECT_EQ(input_error_of([] { run({"no-space"}); }),
            "model.obj: the mesh assimp read could not be passed back (no memory or file space "
            "left)");
}

TEST(ImportWorker, AWorkerIsReplacedAfterItsShareOfFiles) {
  stop_import_worker();
  run({"echo", "1"});
  const auto pid = import_worker_pid();
  for (unsigned i = 1; i + 1 < detail::kWorkerFiles; ++i) run({"echo", "1"});
  EXPECT_EQ(import_worker_pid(), pid);
  run({"echo", "1"});  // the last of its share: it is stopped after answering
  EXPECT_FALSE(import_worker_pid().has_value());
  run({"echo", "1"});
  EXPECT_NE(import_worker_pid(), pid);
}

TEST(ImportWorker, AnAnswerInUseBlocksTheNextRequestOfItsThread) {
  stop_import_worker();
  const detail::WorkerAnswer held =
      detail::run_in_worker(kFile, short_limits(), "assimp", kTestWorker, "test", {"echo", "4"});
  EXPECT_THROW(run({"echo", "1"}), std::logic_error);
  EXPECT_EQ(
      std::string(reinterpret_cast<const char*>(held.payload().data()), held.payload().size()),
      echo_of("echo", 4));
}

TEST(ImportWorker, AMissingWorkerProgramIsNamed) {
  stop_import_worker();
  try {
    detail::run_in_worker(kFile, short_limits(), "assimp", "/nonexistent/tumble-import", "test",
                          {"echo", "1"});
    FAIL() << "no error";
  } catch (const std::system_error& error) {
    EXPECT_THAT(error.what(), HasSubstr("cannot start reading model.obj (posix_spawn "
                                        "/nonexistent/tumble-import)"));
  }
}

TEST(ImportWorker, DefaultLimitsGrowWithTheFile) {
  const ImportLimits small = detail::effective_limits({}, 1000);
  EXPECT_EQ(small.cpu_seconds, 10.0);
  EXPECT_GE(small.memory_bytes, std::uint64_t{1} << 30);
  const ImportLimits large = detail::effective_limits({}, std::uint64_t{100} << 20);  // 100 MiB
  EXPECT_EQ(large.cpu_seconds, 210.0);
  const ImportLimits given = detail::effective_limits({3.0, 5000}, std::uint64_t{100} << 20);
  EXPECT_EQ(given.cpu_seconds, 3.0);
  EXPECT_EQ(given.memory_bytes, 5000u);
}

TEST(ImportWorker, TumbleImportIsFound) {
  const std::filesystem::path program = detail::import_worker_program();
  EXPECT_EQ(program.filename(), "tumble-import");
  EXPECT_TRUE(std::filesystem::exists(program));
}

// --- import_mesh through the workers

/// Files of several formats and sizes for assimp.
std::vector<std::filesystem::path> assorted_files(const mesh_fixtures::TempDir& dir) {
  std::vector<std::filesystem::path> files;
  for (int i = 0; i < 8; ++i) {
    const auto box = mesh_fixtures::box(Eigen::Vector3d(-0.1 * i, 0, 0),
                                        Eigen::Vector3d(1.0 + i, 2.0, 3.0 + 0.5 * i));
    const std::string name = "part" + std::to_string(i);
    files.push_back(dir / (name + ".obj"));
    mesh_fixtures::write_obj(files.back(), {box});
    files.push_back(dir / (name + ".ply"));
    mesh_fixtures::write_ply(files.back(), box, i % 2 == 0);
    files.push_back(dir / (name + ".off"));
    mesh_fixtures::write_off(files.back(), box);
    files.push_back(dir / (name + "_ascii.stl"));
    mesh_fixtures::write_stl_ascii(files.back(), {mesh_fixtures::fan_triangulated(box)});
  }
  files.push_back(dir / "torus.obj");
  const TriangleMesh torus = torus_mesh(1.0, 0.3, 200, 100);
  mesh_fixtures::Polyhedron big{torus.positions, {}};
  for (const auto& t : torus.triangles) big.faces.push_back({t[0], t[1], t[2]});
  mesh_fixtures::write_obj(files.back(), {big});
  return files;
}

TEST(ImportWorker, ManyFilesThroughOneWorkerReadAsThroughFreshChildren) {
  mesh_fixtures::TempDir dir;
  const std::vector<std::filesystem::path> files = assorted_files(dir);
  std::vector<TriangleMesh> fresh;
  std::vector<ImportStats> fresh_stats(files.size());
  for (std::size_t i = 0; i < files.size(); ++i) {
    stop_import_worker();
    fresh.push_back(import_mesh(files[i], &fresh_stats[i]));
  }
  stop_import_worker();
  std::optional<pid_t> pid;
  for (std::size_t i = 0; i < files.size(); ++i) {
    ImportStats stats;
    const TriangleMesh mesh = import_mesh(files[i], &stats);
    if (i == 0) pid = import_worker_pid();
    EXPECT_EQ(import_worker_pid(), pid) << files[i];
    EXPECT_EQ(mesh.positions, fresh[i].positions) << files[i];
    EXPECT_EQ(mesh.triangles, fresh[i].triangles) << files[i];
    EXPECT_EQ(stats.welded_vertices, fresh_stats[i].welded_vertices) << files[i];
    EXPECT_EQ(stats.distinct_positions, fresh_stats[i].distinct_positions) << files[i];
    EXPECT_EQ(stats.warnings, fresh_stats[i].warnings) << files[i];
  }
  EXPECT_EQ(fresh.back().triangles.size(), 40000u);
}

TEST(ImportWorker, AssimpsSegfaultInTheMiddleOfABatchLeavesTheRestRead) {
  mesh_fixtures::TempDir dir;
  const std::vector<std::filesystem::path> files = assorted_files(dir);
  const auto crash = fuzz_input_as_file("regression_assimp_off_segv", dir);
  stop_import_worker();
  for (std::size_t i = 0; i < 4; ++i) import_mesh(files[i]);
  EXPECT_EQ(input_error_of([&] { import_mesh(crash); }),
            crash.string() +
                ": assimp crashed reading it (SIGSEGV, Segmentation fault): the file is "
                "malformed in a way assimp does not survive");
  for (std::size_t i = 4; i < files.size(); ++i)
    EXPECT_FALSE(import_mesh(files[i]).triangles.empty());
}

TEST(ImportWorker, TheWorkerFollowsTheWorkingDirectory) {
  mesh_fixtures::TempDir one;
  mesh_fixtures::TempDir two;
  mesh_fixtures::write_obj(one / "part.obj", {mesh_fixtures::box({0, 0, 0}, {1, 1, 1})});
  mesh_fixtures::write_obj(two / "part.obj", {mesh_fixtures::box({0, 0, 0}, {2, 1, 1})});
  const auto saved = std::filesystem::current_path();
  stop_import_worker();
  std::filesystem::current_path(one.path());
  const TriangleMesh first = import_mesh("part.obj");
  std::filesystem::current_path(two.path());
  const TriangleMesh second = import_mesh("part.obj");
  std::filesystem::current_path(saved);
  const auto max_x = [](const TriangleMesh& mesh) {
    double x = 0.0;
    for (const auto& p : mesh.positions) x = std::max(x, p.x());
    return x;
  };
  EXPECT_EQ(max_x(first), 1.0);
  EXPECT_EQ(max_x(second), 2.0);
}

TEST(ImportWorker, NoWorkerOutlivesItsThread) {
  mesh_fixtures::TempDir dir;
  const std::vector<std::filesystem::path> files = assorted_files(dir);
  stop_import_worker();
  EXPECT_TRUE(children().empty());
  std::vector<std::thread> threads;
  for (int t = 0; t < 2; ++t) {
    threads.emplace_back([&files, t] {
      for (std::size_t i = t; i < files.size(); i += 2) import_mesh(files[i]);
    });
  }
  for (std::thread& thread : threads) thread.join();
  EXPECT_TRUE(children().empty());
  import_mesh(files[0]);
  EXPECT_EQ(children().size(), 1u);
  stop_import_worker();
  EXPECT_TRUE(children().empty());
}

// --- assimp's own faults, through import_mesh

TEST(ImportWorker, AssimpsSegfaultOnAMalformedOffIsARefusal) {
  mesh_fixtures::TempDir dir;
  const auto file = fuzz_input_as_file("regression_assimp_off_segv", dir);
  const std::string message = input_error_of([&] { import_mesh(file); });
  EXPECT_EQ(message, file.string() +
                         ": assimp crashed reading it (SIGSEGV, Segmentation fault): the file is "
                         "malformed in a way assimp does not survive");
}

TEST(ImportWorker, ThePlyOnWhichAssimpCrashedLacksEndHeaderAndIsRefusedFirst) {
  mesh_fixtures::TempDir dir;
  const auto file = fuzz_input_as_file("regression_assimp_ply_segv", dir);
  EXPECT_EQ(input_error_of([&] { import_mesh(file); }),
            file.string() +
                ": the PLY header has no 'end_header' line (misspelt or missing), so where the "
                "data starts is unknown");
}

TEST(ImportWorker, AnAsciiStlThatMakesAssimpLeakIsRefusedInOneLine) {
  // The leak stays in the worker, which ends by _exit (LeakSanitizer's exit check never runs
  // there, so it cannot fail a sanitizer run either).
  mesh_fixtures::TempDir dir;
  const auto file = fuzz_input_as_file("regression_assimp_stl_ascii_leak", dir);
  EXPECT_EQ(input_error_of([&] { import_mesh(file); }),
            file.string() + ": cannot be read as a mesh (assimp: STL: Invalid number of vertices)");
}

TEST(ImportWorker, APlyWithoutEndHeaderIsRefusedAtOnceNotLeftToLoop) {
  mesh_fixtures::TempDir dir;
  const auto file = fuzz_input_as_file("regression_assimp_ply_no_end_header_hang", dir);
  EXPECT_EQ(input_error_of([&] { import_mesh(file, nullptr, StlReader::tumble, short_limits()); }),
            file.string() +
                ": the PLY header has no 'end_header' line (misspelt or missing), so where the "
                "data starts is unknown");
}

TEST(ImportWorker, AGoodFileReadsTheSameThroughTheChild) {
  mesh_fixtures::TempDir dir;
  const auto file = dir / "tetrahedron.obj";
  mesh_fixtures::write_file(file,
                            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 "
                            "4\nl 1 2\n");
  ImportStats stats;
  const TriangleMesh mesh = import_mesh(file, &stats);
  ASSERT_EQ(mesh.positions.size(), 4u);
  ASSERT_EQ(mesh.triangles.size(), 4u);
  double six_volume = 0.0;  // outward winding kept: 6 V = 1 for the unit right tetrahedron
  for (const auto& t : mesh.triangles) {
    six_volume += mesh.positions[t[0]].dot(mesh.positions[t[1]].cross(mesh.positions[t[2]]));
  }
  EXPECT_DOUBLE_EQ(six_volume, 1.0);
  EXPECT_EQ(stats.skipped_faces, 1u);
  ASSERT_EQ(stats.warnings.size(), 1u);
  EXPECT_THAT(stats.warnings[0], HasSubstr("skipped 1 face of fewer than three corners"));
}

}  // namespace
}  // namespace tumble::engine
