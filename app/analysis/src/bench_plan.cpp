// `tumble bench`'s plan: the sweep the options ask for, the scenes loaded and every case laid
// out in the order an unsharded run takes them (and `tumble merge` rebuilds), and the output
// folder written from the rows.
#include "app/analysis/bench_plan.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <set>
#include <stdexcept>

#include "app/analysis/bench_report.hpp"
#include "app/scene/option_lists.hpp"
#include "app/scene/scene.hpp"
#include "app/support/output_folder.hpp"
#include "app/support/printf_number.hpp"
#include "base/errors.hpp"
#include "engine/dynamics/integrators.hpp"

namespace tumble::app {

using tumble::InputError;

/// A whole number in [minimum, ...] or an error naming the option.
long long parse_whole_number(const std::string& text, const char* option, long long minimum) {
  std::size_t used = 0;
  long long value = 0;
  try {
    value = std::stoll(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || value < minimum) {
    throw InputError(std::string(option) + ": expected a whole number >= " +
                     std::to_string(minimum) + ", got '" + text + "'");
  }
  return value;
}

namespace {

/// A list of positive numbers, largest first, each once.
std::vector<double> descending_positive_list(const std::string& text, const char* option) {
  std::vector<double> values = parse_positive_list(text, option);
  std::sort(values.begin(), values.end(), std::greater<>());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  return values;
}

/// The integrators to run: the list given, or every one but the exact solution.
std::vector<const engine::IntegratorInfo*> chosen_integrators(const BenchOptions& options) {
  std::vector<const engine::IntegratorInfo*> chosen;
  if (!options.integrators) {
    for (const auto& info : engine::integrator_catalog()) {
      if (info.kind != engine::IntegratorKind::kExact) chosen.push_back(&info);
    }
    return chosen;
  }
  chosen = parse_integrator_list(*options.integrators, "--integrators");
  for (const engine::IntegratorInfo* info : chosen) {
    if (info->kind == engine::IntegratorKind::kExact) {
      throw InputError("--integrators: 'exact' is the reference, not a benchmarked integrator");
    }
  }
  if (chosen.empty()) throw InputError("--integrators: expected a non-empty list");
  return chosen;
}

/// A file-name-safe label from the scene file's stem, unique among `taken`.
std::string scene_label(const std::filesystem::path& file, std::set<std::string>& taken) {
  std::string label = file.stem().string();
  for (char& c : label) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  }
  if (label.empty()) label = "scene";
  std::string unique = label;
  for (int n = 2; taken.count(unique); ++n) unique = label + "-" + std::to_string(n);
  taken.insert(unique);
  return unique;
}

/// The sweep the options ask for, checked against the integrators chosen.
struct Sweep {
  std::vector<const engine::IntegratorInfo*> integrators;
  bool any_fixed = false;
  std::optional<std::vector<double>> dts;  ///< the given steps, else the scenes' defaults
  std::vector<double> tolerances;
  std::optional<double> duration;  ///< replaces every scene's duration
};

Sweep parse_sweep(const BenchOptions& options) {
  Sweep sweep;
  sweep.integrators = chosen_integrators(options);
  const auto& integrators = sweep.integrators;
  sweep.any_fixed = std::any_of(integrators.begin(), integrators.end(),
                                [](const auto* info) { return !info->adaptive; });
  const bool any_adaptive = std::any_of(integrators.begin(), integrators.end(),
                                        [](const auto* info) { return info->adaptive; });
  if (options.dts && !sweep.any_fixed) {
    throw InputError("--dts: no fixed-step integrator chosen (adaptive ones take --tolerances)");
  }
  if (options.tolerances && !any_adaptive) {
    throw InputError("--tolerances: no adaptive integrator chosen (only dopri takes one)");
  }
  if (options.dts) sweep.dts = descending_positive_list(*options.dts, "--dts");
  sweep.tolerances.assign(std::begin(kDefaultTolerances), std::end(kDefaultTolerances));
  if (options.tolerances) {
    sweep.tolerances = descending_positive_list(*options.tolerances, "--tolerances");
  }
  if (options.duration) {
    const std::vector<double> values = parse_positive_list(*options.duration, "--duration");
    if (values.size() != 1) {
      throw InputError("--duration: expected one positive number, got '" + *options.duration + "'");
    }
    sweep.duration = values.front();
  }
  return sweep;
}

/// The steps of one scene: the given steps, or the default factors of the scene's dt that fit;
/// none when every integrator is adaptive (they take tolerances, and their samples are on the
/// scene's dt).
std::vector<double> scene_steps(const Sweep& sweep, const SceneDescription& description,
                                const std::filesystem::path& file) {
  std::vector<double> steps;
  if (!sweep.any_fixed) return steps;
  if (sweep.dts) {
    steps = *sweep.dts;
    for (double dt : steps) {
      if (auto problem = step_problem(dt, description.duration)) {
        throw InputError("--dts: " + printf_number(dt) + ": " + *problem);
      }
    }
    return steps;
  }
  for (double factor : kDefaultStepFactors) {
    const double dt = description.dt * factor;
    if (!step_problem(dt, description.duration)) steps.push_back(dt);
  }
  if (steps.empty()) throw InputError(file.string() + ": dt: longer than the duration");
  return steps;
}

/// The sampling interval: the largest step, which every step must divide.
double sampling_interval(const Sweep& sweep, const std::vector<double>& steps,
                         const SceneDescription& description) {
  const double interval = sweep.any_fixed ? steps.front() : description.dt;
  for (double dt : steps) {
    const double ratio = interval / dt;
    if (std::abs(ratio - std::round(ratio)) > 1e-9 * ratio) {
      throw InputError("--dts: " + printf_number(dt) + " does not divide the largest step " +
                       printf_number(interval) + " (the errors are sampled on its grid)");
    }
  }
  return interval;
}

BenchScene bench_scene(const std::filesystem::path& file, const SceneDescription& description,
                       double interval, std::set<std::string>& labels) {
  CompiledScene compiled = compile_scene(description);
  BenchScene scene;
  scene.file = file;
  scene.name = description.name;
  scene.label = scene_label(file, labels);
  scene.settings = compiled.settings;
  scene.grid = {interval, description.duration};
  scene.torque_free = std::all_of(compiled.bodies.begin(), compiled.bodies.end(),
                                  [](const auto& body) { return body.torque_free(); });
  scene.conservative = std::all_of(compiled.bodies.begin(), compiled.bodies.end(),
                                   [](const auto& body) { return body.conservative(); });
  scene.bodies = std::move(compiled.bodies);
  scene.initial = std::move(compiled.initial);
  return scene;
}

/// The cases of the last scene: fixed-step integrators over the steps, adaptive ones over the
/// tolerances.
void add_cases(const Sweep& sweep, const std::vector<BenchScene>& scenes,
               const std::vector<double>& steps, std::vector<BenchCase>& cases) {
  const double interval = scenes.back().grid.interval;
  for (const auto* info : sweep.integrators) {
    BenchCase c;
    c.scene = scenes.size() - 1;
    c.integrator = info->name;
    c.kind = info->kind;
    c.order = info->order;
    c.adaptive = info->adaptive;
    if (info->adaptive) {
      // Sampled at the instants of the fixed-step runs: dopri interpolates them (dense output),
      // its steps are its controller's whatever the output step.
      c.dt = interval;
      for (double tolerance : sweep.tolerances) {
        c.tolerance = tolerance;
        cases.push_back(c);
      }
    } else {
      for (double dt : steps) {
        c.dt = dt;
        cases.push_back(c);
      }
    }
  }
}

}  // namespace

/// Loads the scenes and lays out every case (no reference yet). Throws InputError.
void plan_bench(const BenchOptions& options, std::vector<BenchScene>& scenes,
                std::vector<BenchCase>& cases) {
  if (options.scenes.empty()) throw InputError("at least one SCENE file is required");
  const Sweep sweep = parse_sweep(options);
  std::set<std::string> labels;
  for (const std::filesystem::path& file : options.scenes) {
    SceneDescription description = load_scene(file);
    if (sweep.duration) description.duration = *sweep.duration;
    const std::vector<double> steps = scene_steps(sweep, description, file);
    const double interval = sampling_interval(sweep, steps, description);
    scenes.push_back(bench_scene(file, description, interval, labels));
    add_cases(sweep, scenes, steps, cases);
  }
}

const OutputFolderKind kBenchOutput{"bench", "report.md", "# tumble bench", "results.csv"};

void write_bench_folder(const BenchOutcome& outcome, const std::filesystem::path& tmp,
                        const std::filesystem::path& output) {
  try {
    write_results_csv(outcome, tmp / "results.csv");
    write_plots(outcome, tmp);
    write_report(outcome, tmp / "report.md");
  } catch (const WriteError& error) {
    throw output_write_error(error, tmp, output);
  }
}

}  // namespace tumble::app
