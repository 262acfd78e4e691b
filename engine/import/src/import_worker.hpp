#pragma once
// assimp, kept at arm's length: files are read by an import worker, a program of its own
// (tumble-import) that tumble starts with posix_spawn, so that assimp's faults on malformed
// files (segfaults in its OFF and PLY readers, an endless loop in its PLY header parser, leaks
// in its STL reader, runaway allocations) end in a one-line refusal instead of taking tumble,
// or the Python interpreter that loaded tumble, down. The worker is a fresh program, not a
// fork: nothing of the caller's memory, threads or signal handlers is copied into it.
//
// Each thread has its own worker, started on its first file and kept for the next ones, so
// that assimp's heap (its OBJ reader's 16 MiB stream buffer above all) is faulted in once
// rather than once per file. Each file has its own CPU-time and memory budget (soft limits set
// before each file, counted from what the worker has used so far) and a wall-clock backstop; a
// worker that dies on a file (a crash, a limit, the kernel's out-of-memory killer, an answer it
// cannot write) is reaped and the next file gets a fresh one. A worker is also replaced after
// an allocation failure or an unexpected exception (not after a refusal: assimp unwinds its
// readers' errors), after kWorkerFiles files, and when its resident memory has grown by
// kWorkerGrowth. The worker only reads: it sends the scene back as assimp returned it
// (raw_scene.hpp), and this process checks and walks it.

#include <sys/types.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

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

/// Files a worker reads before it is replaced (assimp leaks on some files).
constexpr unsigned kWorkerFiles = 200;

/// Growth of a worker's resident memory since it started past which it is replaced (the OBJ
/// reader's buffer and a small file take 16 MiB; what it retains counts towards the next file's
/// memory budget). Under AddressSanitizer freed memory waits in its quarantine (256 MiB by
/// default) and every byte has shadow, so resident memory grows for a while whatever the
/// files: the bound there is 1 GiB.
#ifdef TUMBLE_ADDRESS_SANITIZER
constexpr std::uint64_t kWorkerGrowth = std::uint64_t{1} << 30;
#else
constexpr std::uint64_t kWorkerGrowth = std::uint64_t{64} << 20;
#endif

/// The limits actually applied to reading a file of `size` bytes: `requested`'s where set
/// (non-zero), otherwise the defaults of mesh_import.hpp.
ImportLimits effective_limits(const ImportLimits& requested, std::uintmax_t size);

/// The worker program: $TUMBLE_IMPORT_WORKER when set; else tumble-import in the folder of the
/// executable or shared library this code is part of (tumble's, or the Python module's); else
/// the one of the build tree, then the installed one. Throws std::runtime_error naming the
/// places looked in when none exists.
std::filesystem::path import_worker_program();

/// A worker's answer: its payload, mapped from the worker's memory file. Valid until the next
/// request of the same thread (which reuses the file); run_in_worker refuses a request while an
/// earlier answer of the thread is alive.
class WorkerAnswer {
 public:
  WorkerAnswer(const void* mapping, std::size_t mapped, std::size_t payload_offset);
  WorkerAnswer(WorkerAnswer&& other) noexcept;
  WorkerAnswer& operator=(WorkerAnswer&&) = delete;
  WorkerAnswer(const WorkerAnswer&) = delete;
  ~WorkerAnswer();

  std::span<const std::byte> payload() const;

 private:
  const void* mapping_ = nullptr;
  std::size_t mapped_ = 0;
  std::size_t offset_ = 0;
};

/// Runs the task `task` of `program` on `request` in the calling thread's worker of that
/// program (started when it has none) under `limits`, and returns its answer. What goes wrong
/// is an InputError naming `file`, with `what` naming the reader ("assimp"): an InputError the
/// task threw, word for word; a crash, a limit, an answer that could not be written. A worker
/// that dies on a file after it had read others is given one more try in a fresh worker, so that
/// a fault an earlier file left behind is never blamed on this one.
WorkerAnswer run_in_worker(const std::filesystem::path& file, const ImportLimits& limits,
                           const char* what, const std::filesystem::path& program,
                           const std::string& task, const std::vector<std::string>& request);

/// The process id of the calling thread's worker, if it has one (tests).
std::optional<pid_t> import_worker_pid();

/// Ends the calling thread's worker and reaps it, if it has one. A thread's worker also ends
/// when the thread does (PR_SET_PDEATHSIG), and when its request socket closes.
void stop_import_worker();

}  // namespace tumble::engine::detail
