// `tumble inspect` over a folder of small files, in one process (run_inspect, output to
// memory): the batch rate in files per second, one thread and two.
//
//   BM_InspectBatch/0/J   200 files: 100 binary STL (tumble's reader) and 100 OBJ (assimp's,
//                         in its forked child), jobs J
//   BM_InspectBatch/1/J   200 binary STL only
//   BM_InspectBatch/2/J   200 OBJ only
// Each file is a box of 12 triangles (about 700 bytes); the counter files_per_second is the
// batch's wall-clock rate.
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "app/commands/inspect_command.hpp"
#include "support/box_files.hpp"

namespace {

using namespace tumble;
namespace fs = std::filesystem;

constexpr int kFiles = 200;

/// A folder of kFiles boxes of the given kind (0 mixed, 1 STL, 2 OBJ), written once.
fs::path folder_of(int kind) {
  const fs::path dir =
      fs::temp_directory_path() /
      ("tumble_bench_inspect_" + std::to_string(::getpid()) + "_" + std::to_string(kind));
  if (fs::exists(dir)) return dir;
  fs::create_directories(dir);
  for (int i = 0; i < kFiles; ++i) {
    const testing::BoxMesh box({0.1 + 0.001 * i, 0.2, 0.3});
    const std::string name = (dir / ("part" + std::to_string(1000 + i))).string();
    const bool stl = kind == 1 || (kind == 0 && i % 2 == 0);
    if (stl) {
      testing::write_box_binary_stl(name + ".stl", box);
    } else {
      testing::write_box_obj(name + ".obj", box);
    }
  }
  return dir;
}

void BM_InspectBatch(benchmark::State& state) {
  app::InspectOptions options;
  options.files = {folder_of(static_cast<int>(state.range(0)))};
  options.jobs = static_cast<unsigned>(state.range(1));
  options.format = app::InspectFormat::jsonl;
  for (auto _ : state) {
    std::ostringstream out, err;
    if (app::run_inspect(options, out, err) != 0) state.SkipWithError(err.str().c_str());
    benchmark::DoNotOptimize(out.str().size());
  }
  state.counters["files_per_second"] =
      benchmark::Counter(kFiles, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_InspectBatch)
    ->ArgsProduct({{0, 1, 2}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// Removes the folders when the benchmark ends.
struct Cleanup {
  ~Cleanup() {
    for (int kind = 0; kind < 3; ++kind) {
      fs::remove_all(
          fs::temp_directory_path() /
          ("tumble_bench_inspect_" + std::to_string(::getpid()) + "_" + std::to_string(kind)));
    }
  }
} cleanup;

}  // namespace

BENCHMARK_MAIN();
