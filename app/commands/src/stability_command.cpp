// `tumble stability`: every case x integrator x dt, classified from the signed change of the
// invariants, written as a CSV, a markdown report and a heat map.
//
// Design: this file holds the options and the command's flow (cases, the sweep, the output
// folder, the summary); a run is app/analysis/stability_runner.hpp, the outputs are
// app/analysis/stability_report.hpp.
#include "app/commands/stability_command.hpp"

#include <algorithm>
#include <cstddef>
#include <ostream>

#include <CLI/CLI.hpp>

#include "app/analysis/gnuplot.hpp"
#include "app/analysis/stability_plot.hpp"
#include "app/analysis/stability_report.hpp"
#include "app/analysis/stability_runner.hpp"
#include "app/analysis/stability_suite.hpp"
#include "app/commands/exit_status.hpp"
#include "app/scene/option_lists.hpp"
#include "app/support/file_write.hpp"
#include "app/support/interrupt_guard.hpp"
#include "app/support/output_folder.hpp"
#include "engine/input_error.hpp"
#include "engine/integrators.hpp"

namespace tumble::app {
namespace {

using engine::InputError;
namespace fs = std::filesystem;

/// The integrators --integrators names (each name checked), or every one.
std::vector<engine::IntegratorInfo> parse_integrators(const std::optional<std::string>& text) {
  if (!text) return engine::integrator_catalog();
  std::vector<engine::IntegratorInfo> chosen;
  for (const engine::IntegratorInfo* info : parse_integrator_list(*text, "--integrators")) {
    chosen.push_back(*info);
  }
  return chosen;
}

/// The cases to run: the suite's (filtered by --cases), then the scene files.
std::vector<StabilityCase> gather_cases(const StabilityOptions& options, std::string& suite_name) {
  std::optional<std::vector<double>> dts;
  if (options.dts) dts = parse_positive_list(*options.dts, "--dts");
  std::vector<StabilityCase> cases;
  const bool use_suite = options.suite || options.cases || options.scenes.empty();
  if (use_suite) {
    StabilitySuite suite = stability_suite(options.suite.value_or("standard"));
    suite_name = suite.name;
    if (options.cases) {
      for (const std::string& name : split_option_list(*options.cases, "--cases")) {
        const auto found = std::find_if(suite.cases.begin(), suite.cases.end(),
                                        [&](const StabilityCase& c) { return c.name == name; });
        if (found == suite.cases.end()) {
          std::string names;
          for (const StabilityCase& c : suite.cases) names += (names.empty() ? "" : ", ") + c.name;
          throw InputError("--cases: no case '" + name + "' in suite '" + suite.name +
                           "'; expected one of: " + names);
        }
        cases.push_back(*found);
      }
    } else {
      cases = std::move(suite.cases);
    }
  }
  for (const fs::path& scene : options.scenes) cases.push_back(scene_case(scene, dts));
  return cases;
}

/// Writes the CSV, the markdown report and the heat map into the temporary folder `temporary`;
/// a failed write is named by its final name in `output` (nothing is written there).
void write_outputs(const std::string& suite, const std::vector<StabilityCase>& cases,
                   const std::vector<engine::IntegratorInfo>& integrators,
                   const std::vector<StabilityRun>& runs, const fs::path& temporary,
                   const fs::path& output) {
  try {
    write_text_file(temporary / "stability.csv", stability_csv(suite, cases, runs));
    write_text_file(temporary / "stability.md",
                    stability_markdown(suite, cases, integrators, runs));
    draw_heat_map(stability_heat_map(cases, integrators, runs), temporary / "stability.png",
                  temporary / "stability.svg");
  } catch (const WriteError& error) {
    throw output_write_error(error, temporary, output);
  }
}

/// A stability output: stability.md under its title (and the suite), beside stability.csv.
const OutputFolderKind kStabilityOutput{"stability", "stability.md", "# tumble stability",
                                        "stability.csv"};

int list_suites(std::ostream& out) {
  for (const SuiteListing& suite : stability_suite_listing()) {
    out << suite.name << "  " << suite.description << "\n";
  }
  return 0;
}

/// Runs every case under every integrator at each of its dts, in the order the outputs read
/// them (stability_report.hpp), with one progress line per case on `err`. Stops early, with
/// the runs so far, when `guard` caught a signal.
std::vector<StabilityRun> run_sweep(const std::vector<StabilityCase>& cases,
                                    const std::vector<engine::IntegratorInfo>& integrators,
                                    const InterruptGuard& guard, std::ostream& err) {
  std::vector<StabilityRun> runs;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const StabilityCase& c = cases[k];
    err << "tumble stability: [" << k + 1 << "/" << cases.size() << "] " << c.name << ": "
        << integrators.size() * c.dts.size() << " runs\n"
        << std::flush;
    if (guard.interrupted()) return runs;
    const StabilityReference reference = stability_reference(c);
    for (const engine::IntegratorInfo& info : integrators) {
      for (const double dt : c.dts) {
        if (guard.interrupted()) return runs;
        StabilityRun run =
            run_stability_case(c, info, dt, reference, [&guard] { return guard.interrupted(); });
        if (run.stopped) return runs;  // within the run: it is left out, as are the rest
        runs.push_back(std::move(run));
      }
    }
  }
  return runs;
}

/// The counts of each outcome, and where the outputs went.
void print_summary(const std::vector<StabilityRun>& runs, std::size_t case_count,
                   const fs::path& output, std::ostream& out) {
  std::size_t counts[kStabilityOutcomeCount] = {};
  for (const StabilityRun& r : runs) ++counts[static_cast<int>(r.outcome)];
  out << "tumble stability: " << runs.size() << " runs over " << case_count << " cases: ";
  for (int o = 0; o < kStabilityOutcomeCount; ++o) {
    out << (o ? ", " : "") << counts[o] << " " << outcome_name(static_cast<StabilityOutcome>(o));
  }
  out << "\n  wrote " << (output / "stability.csv").string() << ", stability.md, stability.png, "
      << "stability.svg\n";
}

int stability(const StabilityOptions& options, const InterruptGuard& guard, std::ostream& out,
              std::ostream& err) {
  // Options, cases and the output folder are checked before any run.
  if (!options.output) throw InputError("-o DIR is required (or --list-suites)");
  const std::vector<engine::IntegratorInfo> integrators = parse_integrators(options.integrators);
  std::string suite;
  const std::vector<StabilityCase> cases = gather_cases(options, suite);
  if (!gnuplot_available()) throw InputError("gnuplot is not installed (needed for the heat map)");
  const fs::path output = *options.output;
  const fs::path temporary = start_output_folder(output, kStabilityOutput);
  try {
    const std::vector<StabilityRun> runs = run_sweep(cases, integrators, guard, err);
    if (guard.interrupted()) {
      std::error_code ignored;
      fs::remove_all(temporary, ignored);
      return kExitInterrupted;
    }

    // The outputs, then the folder into place.
    write_outputs(suite, cases, integrators, runs, temporary, output);
    if (guard.interrupted()) {
      std::error_code ignored;
      fs::remove_all(temporary, ignored);
      return kExitInterrupted;
    }
    finish_output_folder(temporary, output);
    print_summary(runs, cases.size(), output, out);
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(temporary, ignored);
    throw;
  }
  return 0;
}

}  // namespace

CLI::App& add_stability_command(CLI::App& cli, StabilityOptions& options) {
  CLI::App& command =
      *cli.add_subcommand("stability",
                          "Stiff and extreme cases over every integrator and a dt sweep: CSV, "
                          "markdown matrices and a heat map");
  command.add_option_function<std::string>(
      "--suite", [&](const std::string& value) { options.suite = value; },
      "Built-in suite (default standard; see --list-suites)");
  command.add_option_function<std::string>(
      "--integrators", [&](const std::string& value) { options.integrators = value; },
      "Comma-separated integrators (default: all)");
  command.add_option_function<std::string>(
      "--dts", [&](const std::string& value) { options.dts = value; },
      "Comma-separated time steps in s for the SCENE cases (default: the scene's dt x 1, 2, 4, 8)");
  command.add_option_function<std::string>(
      "--cases", [&](const std::string& value) { options.cases = value; },
      "Comma-separated built-in cases of the suite (default: all)");
  command.add_option_function<std::vector<std::string>>(
      "SCENE",
      [&](const std::vector<std::string>& values) {
        for (const std::string& value : values) options.scenes.emplace_back(value);
      },
      "Scene files added as cases (alone: only they run, unless --suite or --cases is given)");
  command.add_option_function<std::string>(
      "-o,--output", [&](const std::string& value) { options.output = value; },
      "Output folder DIR (written atomically: .DIR.tmp-PID renamed at the end)");
  command.add_flag("--list-suites", options.list_suites, "List the built-in suites, then exit");
  return command;
}

int run_stability(const StabilityOptions& options, std::ostream& out, std::ostream& err) {
  const InterruptGuard guard;
  const std::string output = options.output ? options.output->string() : "";
  const auto interrupted = [&] {
    guard.report(err, "stability", output);
    return kExitInterrupted;
  };
  return run_guarded(
      "stability", err,
      [&] {
        if (options.list_suites) return list_suites(out);
        const int status = stability(options, guard, out, err);
        return status == kExitInterrupted ? interrupted() : status;
      },
      [&] { return guard.interrupted() ? interrupted() : -1; });
}

}  // namespace tumble::app
