// `tumble stability`: every case x integrator x dt, classified from the signed change of the
// invariants, written as a CSV, a markdown report and a heat map.
//
// Design: this file holds the options; the command's flow is app/analysis/stability_job.hpp.
#include "app/commands/stability_command.hpp"

#include <ostream>

#include <CLI/CLI.hpp>

#include "app/analysis/stability_job.hpp"
#include "app/support/exit_status.hpp"
#include "app/support/interrupt_guard.hpp"

namespace tumble::app {

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
      "Output folder DIR (written atomically: .DIR.tmp-PID renamed at the end); with --shard, "
      "the folder of the part");
  command.add_option_function<std::string>(
      "--shard", [&](const std::string& value) { options.shard = value; },
      "I/N: make only the I-th of N shards of the runs (I from 0; every N-th run of the sweep) "
      "and write -o DIR as a part: its rows and part.json, for tumble merge");
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
        if (options.list_suites) {
          list_stability_suites(out);
          return kExitDone;
        }
        const int status = write_stability(
            options, [&] { return guard.interrupted(); }, out, err);
        return status == kExitInterrupted ? interrupted() : status;
      },
      [&] { return guard.interrupted() ? interrupted() : -1; });
}

}  // namespace tumble::app
