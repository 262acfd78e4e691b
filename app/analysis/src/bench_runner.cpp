#include "app/analysis/bench_runner.hpp"

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>
#include <thread>

namespace tumble::app {
namespace {

/// Steps between two looks at `stop` inside a fixed-step run: rare enough to leave the timings
/// alone (one call per 1024 steps of 50 ns or more), often enough to stop within milliseconds.
/// An adaptive run looks after each of its output steps (it may take many steps in one).
constexpr std::size_t kStopCheckSteps = 1024;

std::size_t stop_check_steps(const BenchCase& c) {
  return c.adaptive ? 1 : kStopCheckSteps;
}

engine::Simulation make_simulation(const BenchScene& scene, const BenchCase& c) {
  engine::SimulationSettings settings = scene.settings;
  settings.integrator = c.kind;
  settings.dt = c.dt;
  if (c.tolerance) settings.tolerance = *c.tolerance;
  return engine::Simulation(scene.bodies, scene.initial, settings);
}

/// Pins the calling thread to `core`; false when the system refuses.
bool pin_to_core(int core) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(core, &set);
  return pthread_setaffinity_np(pthread_self(), sizeof set, &set) == 0;
}

/// Steps `simulation` to its end (or its blow-up), asking `stop` every `every` steps. Returns
/// false when `stop` said so.
bool run_to_end(engine::Simulation& simulation, std::size_t every,
                const std::function<bool()>& stop) {
  if (!stop) {
    while (simulation.step()) {
    }
    return true;
  }
  for (;;) {
    for (std::size_t k = 0; k < every; ++k) {
      if (!simulation.step()) return true;
    }
    if (stop()) return false;
  }
}

}  // namespace

std::optional<CaseResult> run_case(const BenchScene& scene, const BenchCase& c, int repeat,
                                   const std::function<bool()>& stop) {
  CaseResult result;
  const std::size_t every = stop_check_steps(c);

  // The measured run: errors at every grid sample (every `ratio`-th step and the last).
  {
    engine::Simulation simulation = make_simulation(scene, c);
    result.total_steps = simulation.total_steps();
    // Fixed steps divide the sampling interval (`ratio` steps per sample); an output step may
    // also span `stride` samples (bench gives adaptive runs the interval itself: dopri takes its
    // own steps and interpolates the samples, engine/PHYSICS.md §3).
    const double interval = scene.grid.interval;
    const auto ratio = static_cast<std::size_t>(std::max(1LL, std::llround(interval / c.dt)));
    const auto stride = static_cast<std::size_t>(std::max(1LL, std::llround(c.dt / interval)));
    ErrorMeter meter(scene.bodies, scene.initial, scene.reference);
    const std::size_t samples = scene.grid.count();
    while (simulation.step()) {
      if (stop && simulation.steps() % every == 0 && stop()) return std::nullopt;
      const std::size_t k = simulation.steps() * stride / ratio;
      if (simulation.finished()) {
        meter.observe(samples, simulation.states());
      } else if (simulation.steps() % ratio == 0 && k < samples) {
        meter.observe(k, simulation.states());
      }
    }
    result.steps = simulation.steps();
    result.counts = simulation.step_counts();
    if (const auto& blow_up = simulation.blow_up()) {
      result.blow_up_time = blow_up->time;
      result.blow_up_reason = blow_up->reason;
    } else {
      result.errors = meter.figures();
    }
  }

  // The timed runs: the stepping loop alone (the measured run above was the warm-up).
  for (int run = 0; run < repeat; ++run) {
    engine::Simulation simulation = make_simulation(scene, c);
    const auto start = std::chrono::steady_clock::now();
    if (!run_to_end(simulation, every, stop)) return std::nullopt;
    const auto end = std::chrono::steady_clock::now();
    result.seconds.push_back(std::chrono::duration<double>(end - start).count());
  }
  std::vector<double> sorted = result.seconds;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t n = sorted.size();
  if (n > 0) {
    result.median_seconds = n % 2 == 1 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
    result.min_seconds = sorted.front();
    result.max_seconds = sorted.back();
  }
  return result;
}

std::vector<int> available_cores() {
  std::vector<int> cores;
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) {
    for (int core = 0; core < CPU_SETSIZE; ++core) {
      if (CPU_ISSET(core, &set)) cores.push_back(core);
    }
  }
  if (cores.empty()) cores.push_back(0);
  return cores;
}

std::vector<CaseResult> run_cases(
    const std::vector<BenchScene>& scenes, const std::vector<BenchCase>& cases, int repeat,
    std::size_t workers,
    const std::function<void(std::size_t, const CaseResult&, std::size_t)>& done,
    const std::function<bool()>& stop) {
  const std::vector<int> cores = available_cores();
  workers = std::clamp<std::size_t>(workers, 1, cores.size());
  std::vector<CaseResult> results(cases.size());
  std::atomic<std::size_t> next{0};
  std::mutex report;
  std::size_t finished = 0;
  std::exception_ptr failure;

  // Each worker takes the next case until none is left, on its own core.
  const auto work = [&](std::size_t worker) {
    const int core = cores[worker];
    const bool pinned = pin_to_core(core);
    for (std::size_t i = next++; i < cases.size(); i = next++) {
      if (stop && stop()) {
        next = cases.size();
        return;
      }
      std::optional<CaseResult> result;
      try {
        result = run_case(scenes[cases[i].scene], cases[i], repeat, stop);
      } catch (...) {  // e.g. an integrator refusing a body: stop everyone, rethrow after join
        const std::lock_guard lock(report);
        if (!failure) failure = std::current_exception();
        next = cases.size();
        return;
      }
      if (!result) {  // stopped within the case
        next = cases.size();
        return;
      }
      result->core = pinned ? core : -1;
      const std::lock_guard lock(report);
      results[i] = std::move(*result);
      ++finished;
      if (done) done(i, results[i], finished);
    }
  };
  std::vector<std::thread> threads;
  for (std::size_t w = 0; w < workers; ++w) threads.emplace_back(work, w);
  for (std::thread& thread : threads) thread.join();
  if (failure) std::rethrow_exception(failure);
  return results;
}

}  // namespace tumble::app
