#pragma once
// Runs the cases of `tumble bench`: one measured run (errors sampled on the scene's grid), then
// N timed runs of the stepping loop alone, on worker threads pinned one per core.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/analysis/error_measures.hpp"
#include "engine/body/rigid_body.hpp"
#include "engine/dynamics/integrators.hpp"
#include "engine/simulation/simulation.hpp"

namespace tumble::app {

/// A compiled scene with its sampling grid and reference.
struct BenchScene {
  std::filesystem::path file;
  std::string name;   ///< the scene's own name
  std::string label;  ///< file-name-safe, unique among the scenes (plot file names)
  std::vector<engine::BodyModel> bodies;
  std::vector<engine::BodyState> initial;
  engine::SimulationSettings settings;  ///< duration and blow-up factor as the bench runs them
  SampleGrid grid;
  Reference reference;
  bool torque_free = true;   ///< |L| is an invariant of every body
  bool conservative = true;  ///< energy is an invariant of every body
};

/// One integrator at one step size (or tolerance) on one scene.
struct BenchCase {
  std::size_t scene = 0;
  std::string integrator;
  engine::IntegratorKind kind = engine::IntegratorKind::kRk4;
  int order = 0;
  bool adaptive = false;
  double dt = 0.0;                  ///< s (adaptive: the output step, the grid's interval)
  std::optional<double> tolerance;  ///< adaptive only
};

/// What one case measured.
struct CaseResult {
  std::size_t steps = 0;               ///< output steps completed
  std::size_t total_steps = 0;         ///< output steps the duration needs
  std::optional<double> blow_up_time;  ///< s, when the run blew up (no error figures then)
  std::string blow_up_reason;
  engine::StepCounts
      counts;  ///< of the measured run, summed over bodies (the timed runs repeat it)
  std::vector<double> seconds;  ///< the timed runs, stepping loop only
  double median_seconds = 0.0;
  double min_seconds = 0.0;
  double max_seconds = 0.0;
  ErrorFigures errors;
  int core = -1;  ///< the core the case ran on
};

/// Runs `c` once with the error meter, then `repeat` timed runs; the median of the timed runs.
/// `stop` (an interrupt) is asked every 1024 steps of every run, timed ones included (adaptive
/// runs: every output step); when it returns true the case is abandoned, nothing returned.
std::optional<CaseResult> run_case(const BenchScene& scene, const BenchCase& c, int repeat,
                                   const std::function<bool()>& stop = {});

/// The cores this process may run on (sched_getaffinity).
std::vector<int> available_cores();

/// Runs every case on min(jobs, cores) workers, each pinned to its own core, so no two timed
/// loops share a core. `done(index, result, finished_count)` is called (serialised) after each
/// case. Returns the results in the order of `cases`; when `stop` returns true (checked before
/// each case and within it, see run_case: an interrupt), the cases not finished are left out
/// and their results stay empty.
std::vector<CaseResult> run_cases(
    const std::vector<BenchScene>& scenes, const std::vector<BenchCase>& cases, int repeat,
    std::size_t workers,
    const std::function<void(std::size_t, const CaseResult&, std::size_t)>& done,
    const std::function<bool()>& stop = {});

}  // namespace tumble::app
