// What reading files through the import worker costs (engine/import/src/import_worker.hpp): the
// worker is a program of its own (tumble-import), started with posix_spawn on a thread's first
// file and kept for the next ones; it sends the scene as assimp returned it, and this process
// welds and places it.
//
//   BM_FreshWorkerObj/12        a 12-triangle OBJ cube, each read by a newly started worker:
//                               spawn, exec, assimp's start-up, the read, the answer
//   BM_WarmWorkerObj/12         the cube again and again through one worker
//   BM_WarmWorkerObj/200000     a 200,000-triangle OBJ torus through one worker
//   BM_AssimpInProcess/200000   the same file read by assimp in this process (no walk, no weld)
// The difference between the last two is what the isolation costs on a large file: the copy
// of the scene through the memory file and the weld done here.
#include <benchmark/benchmark.h>

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <unistd.h>
#include <assimp/Importer.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "engine/geometry/primitive_meshes.hpp"
#include "engine/import/mesh_import.hpp"
#include "import_worker.hpp"

namespace {

using namespace tumble;

/// An OBJ file of a cube (12 triangles) or a torus (`triangles` of them), written once.
const std::filesystem::path& obj_file(std::int64_t triangles) {
  static const auto write = [](const engine::TriangleMesh& mesh, const std::string& name) {
    const std::filesystem::path file =
        std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()) + ".obj");
    std::ofstream out(file);
    for (const auto& p : mesh.positions)
      out << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    for (const auto& t : mesh.triangles) {
      out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
    }
    return file;
  };
  static const std::filesystem::path cube =
      write(engine::box_mesh(Eigen::Vector3d(1.0, 2.0, 3.0)), "bench-cube");
  static const std::filesystem::path torus =
      write(engine::torus_mesh(1.0, 0.3, 400, 250), "bench-torus");
  return triangles <= 12 ? cube : torus;
}

void BM_FreshWorkerObj(benchmark::State& state) {
  const std::filesystem::path& file = obj_file(state.range(0));
  for (auto _ : state) {
    engine::detail::stop_import_worker();
    const engine::TriangleMesh mesh = engine::import_mesh(file);
    benchmark::DoNotOptimize(mesh.triangles.data());
  }
  engine::detail::stop_import_worker();
}
BENCHMARK(BM_FreshWorkerObj)->Arg(12)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_WarmWorkerObj(benchmark::State& state) {
  const std::filesystem::path& file = obj_file(state.range(0));
  engine::import_mesh(file);
  for (auto _ : state) {
    const engine::TriangleMesh mesh = engine::import_mesh(file);
    benchmark::DoNotOptimize(mesh.triangles.data());
  }
  engine::detail::stop_import_worker();
}
BENCHMARK(BM_WarmWorkerObj)->Arg(12)->Arg(200000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_AssimpInProcess(benchmark::State& state) {
  const std::filesystem::path& file = obj_file(state.range(0));
  for (auto _ : state) {
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(file.string(), 0);
    benchmark::DoNotOptimize(scene);
  }
}
BENCHMARK(BM_AssimpInProcess)->Arg(200000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
