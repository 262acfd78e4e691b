// `tumble`: the command line. This executable holds the commands that draw nothing; for render,
// compare and view it becomes tumble-draw (command_line.hpp says why).
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/commands/bench_command.hpp"
#include "app/commands/farm_command.hpp"
#include "app/commands/inertials_command.hpp"
#include "app/commands/inspect_command.hpp"
#include "app/commands/merge_command.hpp"
#include "app/commands/simulate_command.hpp"
#include "app/commands/stability_command.hpp"
#include "app/support/exit_status.hpp"
#include "base/process.hpp"
#include "command_line.hpp"

namespace {

using tumble::app::CommandSummary;

/// tumble-draw beside this executable.
std::filesystem::path drawing_executable() {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  return (error ? std::filesystem::path(".") : self.parent_path()) / "tumble-draw";
}

/// Replaces this process with tumble-draw, given the same arguments; returns only on failure.
/// Its heap takes transparent huge pages: a big mesh's display copies and levels of detail are
/// hundreds of MB of fresh memory (a 1M-triangle render's start-up faulted 44,000 times and took
/// 1.45 s; with huge pages 10,000 times and 0.92 s). ffmpeg, started by it, inherits the setting.
int run_drawing_command(char** argv) {
  const std::filesystem::path executable = drawing_executable();
  std::vector<char*> environment = tumble::environment_with_huge_pages();
  ::execve(executable.c_str(), argv, environment.data());
  std::cerr << "tumble " << argv[1] << ": internal error: cannot run " << executable.string()
            << ": " << std::strerror(errno) << " (it is built beside tumble)\n";
  return tumble::app::kExitInternalError;
}

/// A drawing command in the help's list; never parsed here (main hands it over first).
void add_placeholder(CLI::App& cli, const CommandSummary& command) {
  cli.add_subcommand(command.name, command.summary)->allow_extras()->prefix_command();
}

}  // namespace

int main(int argc, char** argv) {
  tumble::app::prepare_process();
  if (argc > 1 && tumble::app::is_drawing_command(argv[1])) return run_drawing_command(argv);

  CLI::App cli;
  tumble::app::configure_top_level(cli);
  tumble::app::InspectOptions inspect_options;
  CLI::App& inspect = tumble::app::add_inspect_command(cli, inspect_options);
  tumble::app::SimulateOptions simulate_options;
  CLI::App& simulate = tumble::app::add_simulate_command(cli, simulate_options);
  add_placeholder(cli, tumble::app::kRenderSummary);
  add_placeholder(cli, tumble::app::kCompareSummary);
  tumble::app::BenchOptions bench_options;
  CLI::App& bench = tumble::app::add_bench_command(cli, bench_options);
  tumble::app::StabilityOptions stability_options;
  CLI::App& stability = tumble::app::add_stability_command(cli, stability_options);
  add_placeholder(cli, tumble::app::kViewSummary);
  tumble::app::InertialsOptions inertials_options;
  CLI::App& inertials = tumble::app::add_inertials_command(cli, inertials_options);
  tumble::app::MergeOptions merge_options;
  CLI::App& merge = tumble::app::add_merge_command(cli, merge_options);
  tumble::app::FarmOptions farm_options;
  CLI::App& farm = tumble::app::add_farm_command(cli, farm_options);
  tumble::app::name_manual_pages(cli);

  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    // --help and --version are "errors" that exit 0; every real one is bad input (status 1).
    return cli.exit(error) == 0 ? tumble::app::kExitDone : tumble::app::kExitInputError;
  }
  if (inspect.parsed()) return tumble::app::run_inspect(inspect_options, std::cout, std::cerr);
  if (simulate.parsed()) return tumble::app::run_simulate(simulate_options, std::cout, std::cerr);
  if (inertials.parsed()) {
    return tumble::app::run_inertials(inertials_options, std::cout, std::cerr);
  }
  if (merge.parsed()) return tumble::app::run_merge(merge_options, std::cout, std::cerr);
  if (bench.parsed()) return tumble::app::run_bench(bench_options, std::cout, std::cerr);
  if (stability.parsed()) {
    return tumble::app::run_stability(stability_options, std::cout, std::cerr);
  }
  if (farm.parsed()) return tumble::app::run_farm(farm_options, std::cout, std::cerr);
  // A drawing command after an option (`tumble --x render`) reaches here: CLI11 has already
  // refused the unknown option, so this is only a safeguard.
  std::cerr << "tumble: error: the command must come first\n";
  return tumble::app::kExitInputError;
}
