// Speed of the mass-property pipeline on a 1M-triangle mesh.
//
//   BM_SolidIntegrals        the integration kernel alone (triangles/s on one core)
//   BM_AssimpReadStl         assimp reading a 1M-triangle binary STL, no post-processing
//   BM_InspectStl            `tumble inspect` end to end on that file: import, weld, checks,
//                            integrals, principal axes (the budget: 2x assimp's read)
//   BM_InspectStlSkippingChecks  the same without the faces' overlap checks (issue 27's budget:
//                            BM_InspectStl at most 1.3x this, and 1.5x BM_AssimpReadStl)
//   BM_InspectStlThroughAssimp  the same with assimp reading the file (tumble's own binary
//                            STL reader bypassed), for comparison
//   BM_AssimpReadShuffledStl, BM_InspectShuffledStl  the first two on the same torus with
//                            its triangles shuffled (the worst case for locality)
//   BM_Weld, BM_Topology     the two linear-time passes, for the breakdown
#include <benchmark/benchmark.h>

#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <filesystem>
#include <random>

#include "app/scene/mesh_inspection.hpp"
#include "engine/geometry/mesh_topology.hpp"
#include "engine/geometry/primitive_meshes.hpp"
#include "engine/import/mesh_import.hpp"
#include "engine/mass/mass_properties.hpp"
#include "engine/mass/mesh_analysis.hpp"
#include "support/stl_writer.hpp"

namespace {

using namespace tumble;

/// A torus of 1000 x 500 segments: 1,000,000 triangles.
const engine::TriangleMesh& million_triangle_mesh() {
  static const engine::TriangleMesh mesh = engine::torus_mesh(1.0, 0.3, 1000, 500);
  return mesh;
}

const std::filesystem::path& million_triangle_stl() {
  static const std::filesystem::path file = [] {
    const auto path = std::filesystem::temp_directory_path() / "tumble_bench_torus_1m.stl";
    testing::write_binary_stl(path, million_triangle_mesh());
    return path;
  }();
  return file;
}

/// The same torus with its triangles in random order: neighbours far apart in the file, so the
/// weld's cache of recent positions catches almost nothing and every pass reads its vertices at
/// random. The worst case for locality.
const std::filesystem::path& shuffled_million_triangle_stl() {
  static const std::filesystem::path file = [] {
    engine::TriangleMesh mesh = million_triangle_mesh();
    std::mt19937 random(3);
    std::shuffle(mesh.triangles.begin(), mesh.triangles.end(), random);
    const auto path = std::filesystem::temp_directory_path() / "tumble_bench_torus_1m_shuffled.stl";
    testing::write_binary_stl(path, mesh);
    return path;
  }();
  return file;
}

void BM_SolidIntegrals(benchmark::State& state) {
  const engine::TriangleMesh& mesh = million_triangle_mesh();
  const Eigen::Vector3d reference(0.01, 0.02, 0.03);
  for (auto _ : state) benchmark::DoNotOptimize(engine::solid_integrals(mesh, reference));
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(mesh.triangles.size()));
}
BENCHMARK(BM_SolidIntegrals)->Unit(benchmark::kMillisecond);

void BM_Weld(benchmark::State& state) {
  // The soup of the binary STL: three vertices per triangle.
  engine::TriangleMesh soup;
  for (const auto& t : million_triangle_mesh().triangles) {
    const auto base = static_cast<std::uint32_t>(soup.positions.size());
    for (const auto v : t) soup.positions.push_back(million_triangle_mesh().positions[v]);
    soup.triangles.push_back({base, base + 1, base + 2});
  }
  for (auto _ : state) {
    state.PauseTiming();
    engine::TriangleMesh copy = soup;
    state.ResumeTiming();
    benchmark::DoNotOptimize(engine::weld_by_position(copy));
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(soup.triangles.size()));
}
BENCHMARK(BM_Weld)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Topology(benchmark::State& state) {
  const engine::TriangleMesh& mesh = million_triangle_mesh();
  for (auto _ : state) benchmark::DoNotOptimize(engine::analyze_topology(mesh));
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(mesh.triangles.size()));
}
BENCHMARK(BM_Topology)->Unit(benchmark::kMillisecond);

void assimp_read(benchmark::State& state, const std::filesystem::path& file) {
  for (auto _ : state) {
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(file.string(), 0);
    if (scene == nullptr) state.SkipWithError("assimp could not read the file");
    benchmark::DoNotOptimize(scene);
  }
  state.SetItemsProcessed(state.iterations() * 1'000'000);
}

void inspect(benchmark::State& state, const std::filesystem::path& file,
             const engine::MassOptions& options = {}) {
  for (auto _ : state) benchmark::DoNotOptimize(app::inspect_file(file, options));
  state.SetItemsProcessed(state.iterations() * 1'000'000);
}

void BM_AssimpReadStl(benchmark::State& state) {
  assimp_read(state, million_triangle_stl());
}
BENCHMARK(BM_AssimpReadStl)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_InspectStl(benchmark::State& state) {
  inspect(state, million_triangle_stl());
}
BENCHMARK(BM_InspectStl)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_InspectStlSkippingChecks(benchmark::State& state) {
  engine::MassOptions options;
  options.check_overlap = false;
  inspect(state, million_triangle_stl(), options);
}
BENCHMARK(BM_InspectStlSkippingChecks)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_AssimpReadShuffledStl(benchmark::State& state) {
  assimp_read(state, shuffled_million_triangle_stl());
}
BENCHMARK(BM_AssimpReadShuffledStl)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_InspectShuffledStl(benchmark::State& state) {
  inspect(state, shuffled_million_triangle_stl());
}
BENCHMARK(BM_InspectShuffledStl)->Unit(benchmark::kMillisecond)->UseRealTime();

/// The same inspection with assimp reading the file instead of tumble's binary STL reader: the
/// pipeline as it was before that reader, for the record.
void BM_InspectStlThroughAssimp(benchmark::State& state) {
  const auto& file = million_triangle_stl();
  for (auto _ : state) {
    engine::ImportStats stats;
    engine::TriangleMesh mesh = engine::import_mesh(file, &stats, engine::StlReader::assimp);
    benchmark::DoNotOptimize(
        engine::analyze_mesh(std::move(mesh), {}, file.string(), stats.distinct_positions));
  }
  state.SetItemsProcessed(state.iterations() * 1'000'000);
}
BENCHMARK(BM_InspectStlThroughAssimp)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
