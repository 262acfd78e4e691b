#pragma once
// assimp, kept at arm's length: the import runs in a child process with bounded CPU time and
// memory, so that assimp's own faults on malformed files (segfaults in its OFF and PLY readers,
// an endless loop in its PLY header parser, leaks in its STL reader, runaway allocations) end
// in a one-line refusal instead of taking tumble down. The child (fork, no exec) reads the file,
// checks and walks the scene exactly as an in-process import would, and sends the finished
// triangle mesh back through a pipe; the parent never touches an aiScene.

#include <cstdint>
#include <filesystem>
#include <functional>

#include "engine/mesh_import.hpp"

namespace tumble::engine::detail {

/// The limits actually applied to reading a file of `size` bytes: `requested`'s where set
/// (non-zero), otherwise the defaults of mesh_import.hpp.
ImportLimits effective_limits(const ImportLimits& requested, std::uintmax_t size);

/// Runs `work` in a child process under `limits` and returns what it returned. An InputError
/// thrown in the child is thrown again here with the same message; a child that dies (a
/// signal), runs out of CPU time or memory, or sends something incomplete is refused with an
/// InputError naming `file` and what happened. `what` names the reader in those messages
/// ("assimp").
TriangleMesh run_isolated(const std::filesystem::path& file, const ImportLimits& limits,
                          const char* what, ImportStats& stats,
                          const std::function<TriangleMesh(ImportStats&)>& work);

}  // namespace tumble::engine::detail
