// Mesh import: tumble's own binary STL reader in this process, every other format through
// assimp in the import worker (import_worker.hpp), whose scene is checked and walked here
// (raw_scene.hpp).
#include "engine/import/mesh_import.hpp"

#include <cstdint>
#include <fstream>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "base/errors.hpp"
#include "binary_stl.hpp"
#include "declared_counts.hpp"
#include "import_worker.hpp"
#include "input_file.hpp"
#include "raw_scene.hpp"

namespace tumble::engine {
namespace {

using detail::fail;
/// What kind of thing a path that is not a regular file names.
std::string kind_of(std::filesystem::file_type type) {
  switch (type) {
    case std::filesystem::file_type::directory:
      return "is a directory, not a mesh file";
    case std::filesystem::file_type::fifo:
      return "is a FIFO (named pipe), not a regular file";
    case std::filesystem::file_type::socket:
      return "is a socket, not a regular file";
    case std::filesystem::file_type::block:
      return "is a block device, not a regular file";
    case std::filesystem::file_type::character:
      return "is a character device, not a regular file";
    default:
      return "is not a regular file";
  }
}

/// Says plainly what is wrong with the path before anything opens it (opening a FIFO would
/// block until a writer comes), and returns the file's size.
std::uintmax_t checked_size(const std::filesystem::path& file) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(file, error);
  if (error == std::errc::too_many_symbolic_link_levels) {
    fail(file, "is a loop of symbolic links");
  }
  if (status.type() == std::filesystem::file_type::not_found) {
    std::error_code link_error;
    if (std::filesystem::is_symlink(std::filesystem::symlink_status(file, link_error))) {
      fail(file, "is a symbolic link to a missing file (" +
                     std::filesystem::read_symlink(file, link_error).string() + ")");
    }
    fail(file, "no such file");
  }
  if (error) fail(file, "cannot be examined (" + error.message() + ")");
  if (status.type() != std::filesystem::file_type::regular) fail(file, kind_of(status.type()));
  const std::uintmax_t size = std::filesystem::file_size(file, error);
  if (error) fail(file, "cannot be examined (" + error.message() + ")");
  if (size == 0) fail(file, "is empty");
  return size;
}

/// Refuses a file whose faces did not all arrive: tumble never reports the mass properties of
/// less than the file holds.
void require_all_faces(const std::filesystem::path& file,
                       const std::optional<detail::DeclaredFaces>& declared,
                       std::uint64_t imported) {
  if (!declared || imported >= declared->faces) return;
  const bool obj = declared->source == "OBJ f lines";
  fail(file, (obj ? "has " + std::to_string(declared->faces) + " face lines ('f')"
                  : "the " + declared->source + " declares " + std::to_string(declared->faces) +
                        " faces") +
                 ", but assimp read only " + std::to_string(imported) +
                 ": the rest were dropped (malformed or truncated), so the mass properties "
                 "would be those of part of the file");
}

/// The file read by assimp in this thread's import worker, then checked and walked here.
TriangleMesh import_through_worker(const std::filesystem::path& file, std::uintmax_t size,
                                   const ImportLimits& limits, ImportStats& stats) {
  // What the header declares is checked before assimp trusts it (declared_counts.hpp).
  detail::check_binary_stl_size(file, size);
  const std::optional<detail::DeclaredFaces> declared = detail::check_declared_counts(file, size);
  std::error_code error;
  const std::filesystem::path absolute = std::filesystem::absolute(file, error);
  const detail::WorkerAnswer answer = detail::run_in_worker(
      file, detail::effective_limits(limits, size), "assimp", detail::import_worker_program(),
      "assimp", {error ? file.string() : absolute.string(), file.string()});
  const detail::RawScene scene = detail::decode_raw_scene(answer.payload(), file);
  require_all_faces(file, declared, scene.faces_read);
  if (scene.skeleton_only) {
    fail(file,
         "holds no solid, only an animated skeleton (motion capture): the mesh assimp "
         "makes to show its bones is a placeholder, not a body");
  }
  return detail::walk_raw_scene(scene, file, stats);
}

}  // namespace

TriangleMesh import_mesh(const std::filesystem::path& file, ImportStats* stats,
                         StlReader stl_reader, const ImportLimits& limits) {
  const std::uintmax_t size = checked_size(file);
  ImportStats local;
  if (stats == nullptr) stats = &local;

  // Binary STL is read by tumble's own reader unless assimp is asked for.
  TriangleMesh mesh;
  std::optional<detail::BinaryStl> stl;
  if (stl_reader == StlReader::tumble) stl = detail::read_binary_stl(file, size);
  if (stl) {
    mesh = std::move(stl->mesh);
    stats->welded_vertices = stl->welded_vertices;
    stats->distinct_positions = true;  // one mesh, no transform, welded as a whole
    stats->own_stl_reader = true;
  } else {
    if (!std::ifstream(file, std::ios::binary)) fail(file, "cannot be opened for reading");
    mesh = import_through_worker(file, size, limits, *stats);
  }
  if (mesh.triangles.empty()) fail(file, "contains no triangles");
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    if (!mesh.positions[i].allFinite()) {
      fail(file, "vertex " + std::to_string(i + 1) + " has a non-finite coordinate");
    }
  }
  return mesh;
}

}  // namespace tumble::engine
