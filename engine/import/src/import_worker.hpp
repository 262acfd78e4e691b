#pragma once
// The import child made persistent: an import worker is a fork of tumble that reads many files,
// one at a time, for one thread of the parent, so that assimp's heap (its OBJ reader's 16 MiB
// stream buffer above all) is faulted in once rather than once per file. Each file keeps the
// guarantees of run_isolated (isolated_import.hpp): its own CPU time budget and memory budget
// (soft limits set before each file, counted from what the worker has used so far), the same
// wall-clock backstop, and the same one-line refusals; a worker that dies on a file (a crash, a
// limit, the kernel's out-of-memory killer, an answer it cannot write) is reaped and the next
// file gets a fresh one. A worker is also replaced after any file it did not read cleanly,
// after kWorkerFiles files, when its resident memory has grown by kWorkerGrowth, and when the
// parent's working directory (against which relative paths resolve) is no longer its own.

#include <sys/types.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "engine/import/mesh_import.hpp"
#include "isolated_import.hpp"

namespace tumble::engine::detail {

/// What a worker runs for one file: a plain function, since the worker was forked before the
/// request existed (no closure crosses; the function is at the same address in the fork). It
/// gets the request's strings as sent.
using WorkerTask = TriangleMesh (*)(const std::vector<std::string>& request, ImportStats& stats);

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

/// Runs `task` on `request` in the calling thread's import worker (started, by fork, when it
/// has none) under `limits`, and returns what it returned. What goes wrong is refused exactly
/// as run_isolated refuses it, with an InputError naming `file`. A worker that dies on a file
/// after it had read others is given one more try in a fresh worker, so that a fault an earlier
/// file left behind is never blamed on this one.
TriangleMesh run_in_worker(const std::filesystem::path& file, const ImportLimits& limits,
                           const char* what, ImportStats& stats, WorkerTask task,
                           const std::vector<std::string>& request);

/// The process id of the calling thread's worker, if it has one (tests).
std::optional<pid_t> import_worker_pid();

/// Ends the calling thread's worker and reaps it, if it has one. A thread's worker also ends
/// when the thread does (and with it, PR_SET_PDEATHSIG), and when its request socket closes.
void stop_import_worker();

}  // namespace tumble::engine::detail
