// The `tumble` command line: one executable, one subcommand per job.
#include <iostream>

#include <CLI/CLI.hpp>

#include "app/commands/bench_command.hpp"
#include "app/commands/compare_command.hpp"
#include "app/commands/inspect_command.hpp"
#include "app/commands/render_command.hpp"
#include "app/commands/simulate_command.hpp"
#include "app/commands/stability_command.hpp"
#include "app/commands/view_command.hpp"
#include "app/commands/exit_status.hpp"

int main(int argc, char** argv) {
  CLI::App cli{"tumble: rigid bodies with mass properties from real meshes: inspect, simulate, "
               "render, compare, view"};
  cli.require_subcommand(1);
  cli.set_version_flag("--version", "tumble 0.1.0");

  tumble::app::InspectOptions inspect_options;
  CLI::App& inspect = tumble::app::add_inspect_command(cli, inspect_options);
  tumble::app::SimulateOptions simulate_options;
  CLI::App& simulate = tumble::app::add_simulate_command(cli, simulate_options);
  tumble::app::RenderOptions render_options;
  CLI::App& render = tumble::app::add_render_command(cli, render_options);
  tumble::app::CompareOptions compare_options;
  CLI::App& compare = tumble::app::add_compare_command(cli, compare_options);
  tumble::app::BenchOptions bench_options;
  CLI::App& bench = tumble::app::add_bench_command(cli, bench_options);
  tumble::app::StabilityOptions stability_options;
  CLI::App& stability = tumble::app::add_stability_command(cli, stability_options);
  tumble::app::ViewOptions view_options;
  CLI::App& view = tumble::app::add_view_command(cli, view_options);

  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    // --help and --version are "errors" that exit 0; every real one is bad input (status 1).
    return cli.exit(error) == 0 ? tumble::app::kExitDone : tumble::app::kExitInputError;
  }

  if (inspect.parsed()) return tumble::app::run_inspect(inspect_options, std::cout, std::cerr);
  if (simulate.parsed()) return tumble::app::run_simulate(simulate_options, std::cout, std::cerr);
  if (render.parsed()) return tumble::app::run_render(render_options, std::cout, std::cerr);
  if (compare.parsed()) return tumble::app::run_compare(compare_options, std::cout, std::cerr);
  if (bench.parsed()) return tumble::app::run_bench(bench_options, std::cout, std::cerr);
  if (stability.parsed()) {
    return tumble::app::run_stability(stability_options, std::cout, std::cerr);
  }
  if (view.parsed()) return tumble::app::run_view(view_options, std::cout, std::cerr);
  return tumble::app::kExitDone;
}
