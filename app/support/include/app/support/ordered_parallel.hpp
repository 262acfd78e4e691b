#pragma once
/// @file Work items run on a few threads, their results handed on in input order.

#include <cstddef>
#include <functional>

namespace tumble::app {

/// Runs `work(i)` for every i in [0, count) on up to `jobs` threads (inline on the calling
/// thread when `jobs` <= 1), and calls `emit(i)` on the calling thread for i = 0, 1, ... in
/// order, each as soon as work i and every work before it have finished. At most `jobs` works
/// run at once, so at most that many items' data are in memory; a work's result must be kept
/// by `work` itself (in a slot of its own) until `emit` takes it. `work` must not throw (catch
/// into the slot); when `emit` throws, no further work starts and the threads are joined
/// before the exception leaves.
void run_ordered(std::size_t count, unsigned jobs, const std::function<void(std::size_t)>& work,
                 const std::function<void(std::size_t)>& emit);

}  // namespace tumble::app
