// Work on a few threads, results in input order (the batches of `tumble inspect`).
#include "app/support/ordered_parallel.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace tumble::app {

void run_ordered(std::size_t count, unsigned jobs, const std::function<void(std::size_t)>& work,
                 const std::function<void(std::size_t)>& emit) {
  if (jobs <= 1 || count <= 1) {
    for (std::size_t i = 0; i < count; ++i) {
      work(i);
      emit(i);
    }
    return;
  }
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex mutex;
  std::condition_variable finished;
  std::vector<char> done(count, 0);
  const auto worker = [&] {
    while (!stop.load()) {
      const std::size_t i = next.fetch_add(1);
      if (i >= count) return;
      work(i);
      {
        const std::lock_guard lock(mutex);
        done[i] = 1;
      }
      finished.notify_one();
    }
  };
  // Joins the threads however the loop below ends.
  struct Threads {
    std::atomic<bool>& stop;
    std::vector<std::thread> threads;
    ~Threads() {
      stop.store(true);
      for (std::thread& thread : threads) thread.join();
    }
  } pool{stop, {}};
  const std::size_t threads = std::min<std::size_t>(jobs, count);
  for (std::size_t t = 0; t < threads; ++t) pool.threads.emplace_back(worker);
  for (std::size_t i = 0; i < count; ++i) {
    {
      std::unique_lock lock(mutex);
      finished.wait(lock, [&] { return done[i] != 0; });
    }
    emit(i);
  }
}

}  // namespace tumble::app
