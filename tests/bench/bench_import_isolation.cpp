// What running assimp in a child process costs (engine/src/isolated_import.hpp): the fork, the
// pipe and the copy of the mesh back, without assimp's own work.
//
//   BM_IsolatedRoundTrip/12        a 12-triangle cube back from the child: fork, pipe, reap
//   BM_IsolatedRoundTrip/1000000   the 1M-triangle torus (500k vertices, 24 MB) back
//   BM_WorkerRoundTrip/12          the cube back from this thread's persistent import worker
//                                  (import_worker.hpp): request, answer, no fork
//   BM_WorkerRoundTrip/1000000     the torus back from the worker
//   BM_InProcessCopy/1000000       the same mesh copied in one process, for comparison
// Compare with BM_InspectStlThroughAssimp (bench_mass_properties): assimp reading and tumble
// inspecting a 1M-triangle file.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "engine/geometry/primitive_meshes.hpp"
#include "import_worker.hpp"
#include "isolated_import.hpp"

namespace {

using namespace tumble;

const engine::TriangleMesh& mesh_of(std::int64_t triangles) {
  static const engine::TriangleMesh cube = engine::box_mesh(Eigen::Vector3d(1.0, 2.0, 3.0));
  static const engine::TriangleMesh torus = engine::torus_mesh(1.0, 0.3, 1000, 500);
  return triangles <= 12 ? cube : torus;
}

void BM_IsolatedRoundTrip(benchmark::State& state) {
  const engine::TriangleMesh& mesh = mesh_of(state.range(0));
  for (auto _ : state) {
    engine::ImportStats stats;
    const engine::TriangleMesh got = engine::detail::run_isolated(
        "bench.obj", engine::ImportLimits{10.0, std::uint64_t{4} << 30}, "assimp", stats,
        [&](engine::ImportStats&) { return mesh; });
    benchmark::DoNotOptimize(got.triangles.data());
  }
  state.counters["triangles"] = static_cast<double>(mesh.triangles.size());
}
BENCHMARK(BM_IsolatedRoundTrip)
    ->Arg(12)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// The worker's side of BM_WorkerRoundTrip: request[0] is the triangle count.
engine::TriangleMesh mesh_task(const std::vector<std::string>& request, engine::ImportStats&) {
  return mesh_of(std::stoll(request.at(0)));
}

void BM_WorkerRoundTrip(benchmark::State& state) {
  const std::vector<std::string> request{std::to_string(state.range(0))};
  for (auto _ : state) {
    engine::ImportStats stats;
    const engine::TriangleMesh got = engine::detail::run_in_worker(
        "bench.obj", engine::ImportLimits{10.0, std::uint64_t{4} << 30}, "assimp", stats, mesh_task,
        request);
    benchmark::DoNotOptimize(got.triangles.data());
  }
  engine::detail::stop_import_worker();
  state.counters["triangles"] = static_cast<double>(mesh_of(state.range(0)).triangles.size());
}
BENCHMARK(BM_WorkerRoundTrip)->Arg(12)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_InProcessCopy(benchmark::State& state) {
  const engine::TriangleMesh& mesh = mesh_of(state.range(0));
  for (auto _ : state) {
    engine::TriangleMesh copy = mesh;
    benchmark::DoNotOptimize(copy.triangles.data());
  }
}
BENCHMARK(BM_InProcessCopy)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
