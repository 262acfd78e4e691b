#pragma once
// assimp, kept at arm's length: the import runs in a child process with bounded CPU time and
// memory, so that assimp's own faults on malformed files (segfaults in its OFF and PLY readers,
// an endless loop in its PLY header parser, leaks in its STL reader, runaway allocations) end
// in a one-line refusal instead of taking tumble down. The child (fork, no exec) reads the file,
// checks and walks the scene exactly as an in-process import would, and sends the finished
// triangle mesh back through a pipe; the parent never touches an aiScene. import_mesh runs it
// in a persistent child of the same kind, an import worker (import_worker.hpp), which shares
// the pieces declared at the end of this header.

#include <sys/types.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>

#include "engine/import/mesh_import.hpp"

// AddressSanitizer reserves terabytes of address space for its shadow: no memory limit there.
#if defined(__SANITIZE_ADDRESS__)
#define TUMBLE_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TUMBLE_ADDRESS_SANITIZER 1
#endif
#endif

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

// --- The pieces run_isolated shares with the import workers (import_worker.hpp).

/// What an answer's first byte says it holds.
enum AnswerTag : std::uint8_t { kMesh = 1, kInputError = 2, kOutOfMemory = 3, kFailure = 4 };

/// A child's exit status when it cannot write its answer (no memory left for the file, or a
/// file size limit).
constexpr int kCannotAnswer = 3;

/// The lock every fork of an import child is made under: a child forked by another thread
/// while one thread's pipes are open at both ends would inherit them (isolated_import.cpp).
std::mutex& import_fork_mutex();

/// In a fresh child: no core file, and the default action of the signals that end it
/// (a crash, Ctrl+C, SIGXCPU), whatever handlers the parent installed.
void reset_child_signals();

/// The calling process's address space now, in bytes (to which the memory budget is added).
std::uint64_t current_address_space();

/// In a child: runs `work` and writes its outcome to `fd` from the fd's offset (a mesh and
/// its stats, or the error); returns the tag written. Ends the process (kCannotAnswer) when
/// the answer cannot be written.
std::uint8_t answer(int fd, const std::function<TriangleMesh(ImportStats&)>& work);

/// How a child ended: its wait status, whether it was killed for exceeding the wall-clock
/// deadline, and the CPU time it used (reading the file; the limit's SIGKILL is told from the
/// kernel's by it).
struct ChildEnd {
  int status = 0;
  bool timed_out = false;
  double cpu_seconds = 0.0;
};

/// Reaps `child` (blocking) and says how it ended.
ChildEnd reap(pid_t child, bool timed_out);

/// Reads the answer in `message` from its start and returns the mesh, or throws the
/// InputError naming `file` run_isolated throws. `end` is how the child ended, when it did
/// (an incomplete answer is then named by it); none for a child that said it had answered.
TriangleMesh judge_answer(const std::filesystem::path& file, const ImportLimits& limits,
                          const char* what, ImportStats& stats, int message,
                          const std::optional<ChildEnd>& end);

}  // namespace tumble::engine::detail
