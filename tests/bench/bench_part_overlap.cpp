// Cost of the exact overlap checks of `tumble inspect` (engine/src/part_overlap.hpp).
//
//   BM_AnalyzeTorus           analyze_mesh on a 1,000,000-triangle torus (one part), in memory:
//                             weld, topology, overlap checks, integrals, principal axes
//   BM_OverlapCheckTorus      the overlap checks alone on that mesh (self-intersection pass),
//                             one thread, by the default method (regions certified whole);
//                             ...Filtered, ...Exact, ...Reference: the other methods
//                             (part_overlap.hpp), ...TwoThreads: the default on two threads
//   BM_AnalyzeHollowBalls     analyze_mesh on 1000 hollow balls (2000 parts, 640,000
//                             triangles): each ball's cavity needs an exact containment test
//   BM_OverlapCheckHollowBalls  the checks alone on that mesh
#include <benchmark/benchmark.h>

#include "engine/geometry/mesh_topology.hpp"
#include "engine/geometry/primitive_meshes.hpp"
#include "engine/mass/mesh_analysis.hpp"
#include "engine/overlap/part_overlap.hpp"

namespace {

using namespace tumble;

const engine::TriangleMesh& torus() {
  static const engine::TriangleMesh mesh = engine::torus_mesh(1.0, 0.3, 1000, 500);
  return mesh;
}

/// 10 x 10 x 10 balls of radius 1 (320 triangles) 2.05 apart, each with an inward ball of
/// radius 0.5 inside (a cavity).
const engine::TriangleMesh& hollow_balls() {
  static const engine::TriangleMesh mesh = [] {
    engine::TriangleMesh all;
    const engine::TriangleMesh outer = engine::icosphere_mesh(1.0, 2);
    engine::TriangleMesh inner = engine::icosphere_mesh(0.5, 2);
    for (auto& t : inner.triangles) std::swap(t[1], t[2]);
    for (int i = 0; i < 1000; ++i) {
      const Eigen::Vector3d centre(2.05 * (i % 10), 2.05 * (i / 10 % 10), 2.05 * (i / 100));
      for (const engine::TriangleMesh* part :
           {&outer, static_cast<const engine::TriangleMesh*>(&inner)}) {
        engine::TriangleMesh moved = *part;
        engine::transform_mesh(moved, Eigen::Matrix3d::Identity(), centre);
        engine::append_mesh(all, moved);
      }
    }
    return all;
  }();
  return mesh;
}

void analyze(benchmark::State& state, const engine::TriangleMesh& mesh) {
  for (auto _ : state) {
    benchmark::DoNotOptimize(engine::analyze_mesh(mesh, {}, "bench", true));
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(mesh.triangles.size()));
}

/// The checks by `method` on `threads` threads; counters: the pairs of faces judged one by
/// one, those the exact predicates judged, and the share of coarse regions certified whole.
void check(benchmark::State& state, const engine::TriangleMesh& mesh,
           engine::detail::FacePairMethod method = engine::detail::FacePairMethod::kCertified,
           unsigned threads = 1) {
  const engine::Topology topology = engine::analyze_topology(mesh);
  engine::detail::OverlapOptions options;
  options.method = method;
  options.threads = threads;
  engine::detail::FacePairStats stats;
  for (auto _ : state) {
    const auto overlaps =
        engine::detail::find_part_overlaps(mesh, topology.triangle_part, topology.parts, options);
    stats = overlaps.stats;
    benchmark::DoNotOptimize(overlaps);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(mesh.triangles.size()));
  state.counters["pairs"] = static_cast<double>(stats.candidates);
  state.counters["exact"] = static_cast<double>(stats.deferred);
  state.counters["certified"] = stats.regions == 0 ? 0.0
                                                   : static_cast<double>(stats.certified) /
                                                         static_cast<double>(stats.regions);
}

void BM_AnalyzeTorus(benchmark::State& state) {
  analyze(state, torus());
}
BENCHMARK(BM_AnalyzeTorus)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_OverlapCheckTorus(benchmark::State& state) {
  check(state, torus());
}
BENCHMARK(BM_OverlapCheckTorus)->Unit(benchmark::kMillisecond)->UseRealTime();

// The torus's checks by each method on one thread, and by the default on two.
void BM_OverlapCheckTorusFiltered(benchmark::State& state) {
  check(state, torus(), engine::detail::FacePairMethod::kFiltered);
}
BENCHMARK(BM_OverlapCheckTorusFiltered)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_OverlapCheckTorusExact(benchmark::State& state) {
  check(state, torus(), engine::detail::FacePairMethod::kExact);
}
BENCHMARK(BM_OverlapCheckTorusExact)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_OverlapCheckTorusReference(benchmark::State& state) {
  check(state, torus(), engine::detail::FacePairMethod::kReference);
}
BENCHMARK(BM_OverlapCheckTorusReference)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_OverlapCheckTorusTwoThreads(benchmark::State& state) {
  check(state, torus(), engine::detail::FacePairMethod::kCertified, 2);
}
BENCHMARK(BM_OverlapCheckTorusTwoThreads)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_AnalyzeHollowBalls(benchmark::State& state) {
  analyze(state, hollow_balls());
}
BENCHMARK(BM_AnalyzeHollowBalls)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_OverlapCheckHollowBalls(benchmark::State& state) {
  check(state, hollow_balls());
}
BENCHMARK(BM_OverlapCheckHollowBalls)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
