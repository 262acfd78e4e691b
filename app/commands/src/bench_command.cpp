// `tumble bench`: options, validation, the output directory and the run of every case.
#include "app/commands/bench_command.hpp"

#include "app/scene/option_lists.hpp"
#include "app/support/interrupt_guard.hpp"
#include "app/support/output_folder.hpp"
#include "app/support/printf_number.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <ostream>
#include <set>
#include <sstream>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "app/commands/exit_status.hpp"

#include "app/analysis/bench_report.hpp"
#include "app/analysis/bench_runner.hpp"
#include "app/analysis/gnuplot.hpp"
#include "app/scene/scene.hpp"
#include "app/support/progress_bar.hpp"
#include "engine/input_error.hpp"
#include "engine/integrators.hpp"

namespace tumble::app {
namespace {

using engine::InputError;

/// A whole number in [minimum, ...] or an error naming the option.
long long parse_count(const std::string& text, const char* option, long long minimum) {
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

/// The steps of one scene: the given steps, or the default factors of the scene's dt that fit.
std::vector<double> scene_steps(const Sweep& sweep, const SceneDescription& description,
                                const std::filesystem::path& file) {
  std::vector<double> steps;
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

/// Loads the scenes and lays out every case (no reference yet). Throws InputError.
void plan(const BenchOptions& options, std::vector<BenchScene>& scenes,
          std::vector<BenchCase>& cases) {
  if (options.scenes.empty()) throw InputError("at least one SCENE file is required");
  if (options.output.empty()) throw InputError("-o DIR is required");
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

/// A bench output: report.md under its title, beside results.csv.
const OutputFolderKind kBenchOutput{"bench", "report.md", "# tumble bench", "results.csv"};

std::string case_line(const BenchScene& scene, const BenchCase& c, const CaseResult& r) {
  std::string line = scene.label + " " + c.integrator + " " +
                     (c.tolerance ? "tol " + printf_number(*c.tolerance, "%.3g")
                                  : "dt " + printf_number(c.dt, "%.4g")) +
                     ": " + printf_number(r.median_seconds, "%.3g") + " s, ";
  if (r.blow_up_time) return line + "blew up at t = " + printf_number(*r.blow_up_time) + " s";
  return line + "orientation error " + printf_number(r.errors.orientation_final, "%.2e") + " rad";
}

/// Thrown out of a run that caught SIGINT or SIGTERM, to remove its outputs on the way out.
struct Interrupted {};

int bench(const BenchOptions& options, const InterruptGuard& guard, std::ostream& out,
          std::ostream& err) {
  // Everything the user typed is checked before any output is created, the cheap checks
  // before the scenes' meshes are read.
  BenchOutcome outcome;
  outcome.repeat = static_cast<int>(parse_count(options.repeat.value_or("3"), "--repeat", 1));
  const auto jobs = static_cast<std::size_t>(parse_count(options.jobs.value_or("1"), "--jobs", 1));
  if (!gnuplot_available()) throw InputError("gnuplot is not installed (needed for the plots)");
  plan(options, outcome.scenes, outcome.cases);
  const std::filesystem::path tmp = start_output_folder(options.output, kBenchOutput);

  try {
    // References, once per scene.
    for (BenchScene& scene : outcome.scenes) {
      try {
        scene.reference = make_reference(scene.bodies, scene.initial, scene.grid);
      } catch (const InputError& error) {
        throw InputError(scene.file.string() + ": " + error.what());
      }
      if (guard.interrupted()) throw Interrupted{};
    }

    // The cases, one line (or a bar on a terminal) each.
    const std::vector<int> cores = available_cores();
    outcome.cores_available = cores.size();
    outcome.workers = std::clamp<std::size_t>(jobs, 1, cores.size());
    outcome.cores_used.assign(cores.begin(), cores.begin() + static_cast<long>(outcome.workers));
    const bool tty = ProgressBar::on_terminal(err);
    ProgressBar bar(err, outcome.cases.size(), "runs", tty);
    const std::size_t total = outcome.cases.size();
    outcome.results = run_cases(
        outcome.scenes, outcome.cases, outcome.repeat, outcome.workers,
        [&](std::size_t i, const CaseResult& r, std::size_t finished) {
          if (tty) {
            bar.update(finished);
          } else {
            err << "tumble bench: [" << finished << "/" << total << "] "
                << case_line(outcome.scenes[outcome.cases[i].scene], outcome.cases[i], r) << "\n";
          }
        },
        [&] { return guard.interrupted(); });
    bar.clear();
    if (guard.interrupted()) throw Interrupted{};

    // Outputs, then the directory into place; a failed write names the file by its final name.
    try {
      write_results_csv(outcome, tmp / "results.csv");
      write_plots(outcome, tmp);
      write_report(outcome, tmp / "report.md");
    } catch (const WriteError& error) {
      throw output_write_error(error, tmp, options.output);
    }
    if (guard.interrupted()) throw Interrupted{};
    finish_output_folder(tmp, options.output);
  } catch (const Interrupted&) {
    std::error_code ignored;
    std::filesystem::remove_all(tmp, ignored);
    return kExitInterrupted;
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove_all(tmp, ignored);
    throw;
  }
  out << "tumble bench: " << outcome.cases.size() << " runs on " << outcome.workers
      << " core(s); wrote " << (options.output / "report.md").string() << "\n";
  return 0;
}

}  // namespace

CLI::App& add_bench_command(CLI::App& cli, BenchOptions& options) {
  CLI::App& bench = *cli.add_subcommand(
      "bench", "Error against run time for each integrator: results.csv, plots, report.md");
  bench.add_option_function<std::vector<std::string>>(
      "SCENE",
      [&](const std::vector<std::string>& values) {
        options.scenes.assign(values.begin(), values.end());
      },
      "Scene files (JSON)");
  bench.add_option_function<std::string>(
      "--integrators", [&](const std::string& v) { options.integrators = v; },
      "Comma-separated integrators (default: all but exact)");
  bench.add_option_function<std::string>(
      "--dts", [&](const std::string& v) { options.dts = v; },
      "Comma-separated steps in s for fixed-step integrators, each dividing the largest "
      "(default: the scene's dt times 4, 2, 1, 1/2, 1/4)");
  bench.add_option_function<std::string>(
      "--tolerances", [&](const std::string& v) { options.tolerances = v; },
      "Comma-separated tolerances for adaptive integrators (default 1e-4,1e-6,...,1e-12)");
  bench.add_option_function<std::string>(
      "--duration", [&](const std::string& v) { options.duration = v; },
      "Simulated time T in s (default: the scene's)");
  bench.add_option_function<std::string>(
      "--repeat", [&](const std::string& v) { options.repeat = v; },
      "Timed runs per case after the measured warm-up run; their median, min and max are kept "
      "(default 3)");
  bench.add_option_function<std::string>(
      "--jobs", [&](const std::string& v) { options.jobs = v; },
      "Cases run in parallel, one pinned core each, capped at the cores (default 1)");
  bench.add_option_function<std::string>(
      "-o,--output", [&](const std::string& v) { options.output = v; },
      "Output directory DIR (written atomically; an existing one must be empty or a previous "
      "bench output)");
  return bench;
}

int run_bench(const BenchOptions& options, std::ostream& out, std::ostream& err) {
  const InterruptGuard guard;
  const auto interrupted = [&] {
    guard.report(err, "bench", options.output.string());
    return kExitInterrupted;
  };
  return run_guarded(
      "bench", err,
      [&] {
        const int status = bench(options, guard, out, err);
        return status == kExitInterrupted ? interrupted() : status;
      },
      [&] { return guard.interrupted() ? interrupted() : -1; });
}

}  // namespace tumble::app
