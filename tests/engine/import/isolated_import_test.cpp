// Tests of the import in a child process (engine/src/isolated_import.hpp): what the child
// returns arrives whole and exact; whatever goes wrong in it (a crash, an endless loop, an
// allocation beyond the limit, an exception) is a one-line InputError naming the file, and the
// parent carries on. Then the real thing: the inputs on which assimp 5.2 itself crashes, loops
// or leaks (found by fuzzing, kept in tests/fuzz/corpus/mesh_import/) are refused by import_mesh.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/import/mesh_import.hpp"
#include "engine/mesh_fixtures.hpp"
#include "isolated_import.hpp"
#include "support/input_error.hpp"

#if defined(__SANITIZE_ADDRESS__)
#define TUMBLE_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TUMBLE_TEST_ASAN 1
#endif
#endif

namespace tumble::engine {
namespace {

using detail::run_isolated;
using ::testing::HasSubstr;
using tumble::testing::input_error_of;

const std::filesystem::path kIsolatedFile = "model.obj";

ImportLimits isolated_short_limits() {
  return ImportLimits{1.0, std::uint64_t{256} << 20};
}

using mesh_fixtures::fuzz_input_as_file;

TEST(IsolatedImport, TheChildsMeshAndStatsArriveBitForBit) {
  TriangleMesh sent;
  for (int i = 0; i < 100000; ++i) {  // 2.4 MB of positions: more than a pipe's buffer
    sent.positions.emplace_back(0.1 * i, -1.0 / (i + 1), 1e300 / (i + 1));
    sent.triangles.push_back({static_cast<std::uint32_t>(i), 7u, 4000000000u});
  }
  ImportStats stats;
  const TriangleMesh got =
      run_isolated(kIsolatedFile, isolated_short_limits(), "assimp", stats, [&](ImportStats& s) {
        s.welded_vertices = 12345678901ULL;
        s.skipped_faces = 3;
        s.distinct_positions = true;
        s.warnings = {"first warning", "", std::string(70000, 'w')};
        return sent;
      });
  EXPECT_EQ(got.positions, sent.positions);
  EXPECT_EQ(got.triangles, sent.triangles);
  EXPECT_EQ(stats.welded_vertices, 12345678901ULL);
  EXPECT_EQ(stats.skipped_faces, 3u);
  EXPECT_TRUE(stats.distinct_positions);
  EXPECT_FALSE(stats.own_stl_reader);
  EXPECT_EQ(stats.warnings,
            (std::vector<std::string>{"first warning", "", std::string(70000, 'w')}));
}

TEST(IsolatedImport, AnInputErrorInTheChildIsThrownAgainWordForWord) {
  ImportStats stats;
  const std::string message = input_error_of([&] {
    run_isolated(
        kIsolatedFile, isolated_short_limits(), "assimp", stats,
        [](ImportStats&) -> TriangleMesh { throw InputError("model.obj: face 3 is bad"); });
  });
  EXPECT_EQ(message, "model.obj: face 3 is bad");
}

TEST(IsolatedImport, ACrashInTheChildIsARefusalAndTheParentLivesOn) {
  // A handler of the parent's (as a sanitizer or a fuzzer installs) must not run in the child:
  // it would report assimp's fault as tumble's. The child restores the default action.
  struct sigaction parent_handler {};
  parent_handler.sa_handler = [](int) { ::_exit(42); };
  struct sigaction saved {};
  ASSERT_EQ(::sigaction(SIGSEGV, &parent_handler, &saved), 0);
  ImportStats stats;
  const std::string message = input_error_of([&] {
    run_isolated(kIsolatedFile, isolated_short_limits(), "assimp", stats,
                 [](ImportStats&) -> TriangleMesh {
                   std::raise(SIGSEGV);
                   return {};
                 });
  });
  ::sigaction(SIGSEGV, &saved, nullptr);
  EXPECT_EQ(message,
            "model.obj: assimp crashed reading it (SIGSEGV, Segmentation fault): the file is "
            "malformed in a way assimp does not survive");
}

TEST(IsolatedImport, AnEndlessLoopIsStoppedByTheCpuTimeLimit) {
  ImportStats stats;
  const std::string message = input_error_of([&] {
    run_isolated(kIsolatedFile, isolated_short_limits(), "assimp", stats,
                 [](ImportStats&) -> TriangleMesh {
                   volatile std::uint64_t spin = 0;
                   while (true) spin = spin + 1;
                 });
  });
  EXPECT_EQ(message,
            "model.obj: assimp used more than 1 s of CPU time reading it (it may loop on this "
            "file)");
}

TEST(IsolatedImport, AnAllocationBeyondTheMemoryLimitIsARefusal) {
#ifdef TUMBLE_TEST_ASAN
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: no memory limit there";
#else
  ImportStats stats;
  const std::string message = input_error_of([&] {
    run_isolated(
        kIsolatedFile, isolated_short_limits(), "assimp", stats, [](ImportStats&) -> TriangleMesh {
          std::vector<char> huge(std::size_t{1} << 30, 'x');  // 1 GiB against a 256 MiB limit
          return TriangleMesh{{Eigen::Vector3d::Constant(huge[12345])}, {}};
        });
  });
  EXPECT_EQ(message, "model.obj: assimp needs more than 0.25 GiB of memory to read it");
#endif
}

TEST(IsolatedImport, OtherExceptionsAreNamed) {
  ImportStats stats;
  const std::string message = input_error_of([&] {
    run_isolated(kIsolatedFile, isolated_short_limits(), "assimp", stats,
                 [](ImportStats&) -> TriangleMesh { throw std::runtime_error("no such thing"); });
  });
  EXPECT_EQ(message, "model.obj: assimp failed reading it (no such thing)");
}

TEST(IsolatedImport, AChildThatExitsWithoutAnAnswerIsARefusal) {
  ImportStats stats;
  const std::string message = input_error_of([&] {
    run_isolated(kIsolatedFile, isolated_short_limits(), "assimp", stats,
                 [](ImportStats&) -> TriangleMesh { ::_exit(9); });
  });
  EXPECT_EQ(message, "model.obj: assimp ended without an answer (exit status 9)");
}

TEST(IsolatedImport, AKillBeforeTheCpuLimitIsNotCalledALoop) {
  // As the kernel's out-of-memory killer would end it, with almost no CPU time used.
  ImportStats stats;
  const std::string message = input_error_of([&] {
    run_isolated(kIsolatedFile, isolated_short_limits(), "assimp", stats,
                 [](ImportStats&) -> TriangleMesh {
                   std::raise(SIGKILL);
                   return {};
                 });
  });
  EXPECT_EQ(message,
            "model.obj: assimp was killed (SIGKILL) reading it, perhaps by the kernel for want "
            "of memory");
}

TEST(IsolatedImport, AnAnswerThatCannotBeWrittenIsNamedSo) {
  // A file size limit (as `prlimit --fsize` sets) stops the write of the mesh to the memory file.
  ImportStats stats;
  const std::string message = input_error_of([&] {
    run_isolated(kIsolatedFile, isolated_short_limits(), "assimp", stats, [](ImportStats&) {
      std::signal(SIGXFSZ, SIG_IGN);
      const rlimit small{4096, 4096};
      ::setrlimit(RLIMIT_FSIZE, &small);
      TriangleMesh mesh;
      mesh.positions.assign(10000, Eigen::Vector3d::Ones());
      return mesh;
    });
  });
  EXPECT_EQ(message,
            "model.obj: the mesh assimp read could not be passed back (no memory or file space "
            "left)");
}

TEST(IsolatedImport, DefaultLimitsGrowWithTheFile) {
  const ImportLimits small = detail::effective_limits({}, 1000);
  EXPECT_EQ(small.cpu_seconds, 10.0);
  EXPECT_GE(small.memory_bytes, std::uint64_t{1} << 30);
  const ImportLimits large = detail::effective_limits({}, std::uint64_t{100} << 20);  // 100 MiB
  EXPECT_EQ(large.cpu_seconds, 210.0);
  const ImportLimits given = detail::effective_limits({3.0, 5000}, std::uint64_t{100} << 20);
  EXPECT_EQ(given.cpu_seconds, 3.0);
  EXPECT_EQ(given.memory_bytes, 5000u);
}

// --- assimp's own faults, through import_mesh

TEST(IsolatedImport, AssimpsSegfaultOnAMalformedOffIsARefusal) {
  mesh_fixtures::TempDir dir;
  const auto file = fuzz_input_as_file("regression_assimp_off_segv", dir);
  const std::string message = input_error_of([&] { import_mesh(file); });
  EXPECT_EQ(message, file.string() +
                         ": assimp crashed reading it (SIGSEGV, Segmentation fault): the file is "
                         "malformed in a way assimp does not survive");
}

TEST(IsolatedImport, ThePlyOnWhichAssimpCrashedLacksEndHeaderAndIsRefusedFirst) {
  mesh_fixtures::TempDir dir;
  const auto file = fuzz_input_as_file("regression_assimp_ply_segv", dir);
  EXPECT_EQ(input_error_of([&] { import_mesh(file); }),
            file.string() +
                ": the PLY header has no 'end_header' line (misspelt or missing), so where the "
                "data starts is unknown");
}

TEST(IsolatedImport, AnAsciiStlThatMakesAssimpLeakIsRefusedInOneLine) {
  // The leak stays in the child, which ends by _exit (LeakSanitizer's exit check never runs
  // there, so it cannot fail a sanitizer run either).
  mesh_fixtures::TempDir dir;
  const auto file = fuzz_input_as_file("regression_assimp_stl_ascii_leak", dir);
  EXPECT_EQ(input_error_of([&] { import_mesh(file); }),
            file.string() + ": cannot be read as a mesh (assimp: STL: Invalid number of vertices)");
}

TEST(IsolatedImport, APlyWithoutEndHeaderIsRefusedAtOnceNotLeftToLoop) {
  mesh_fixtures::TempDir dir;
  const auto file = fuzz_input_as_file("regression_assimp_ply_no_end_header_hang", dir);
  EXPECT_EQ(input_error_of(
                [&] { import_mesh(file, nullptr, StlReader::tumble, isolated_short_limits()); }),
            file.string() +
                ": the PLY header has no 'end_header' line (misspelt or missing), so where the "
                "data starts is unknown");
}

TEST(IsolatedImport, AGoodFileReadsTheSameThroughTheChild) {
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
