// `tumble-draw`: the commands of `tumble` that draw (render, compare, view), which `tumble`
// hands over to (command_line.hpp). Run directly it works the same.
#include <iostream>

#include <CLI/CLI.hpp>

#include "app/commands/compare_command.hpp"
#include "app/commands/render_command.hpp"
#include "app/commands/view_command.hpp"
#include "app/support/exit_status.hpp"
#include "command_line.hpp"

int main(int argc, char** argv) {
  tumble::app::prepare_process();
  CLI::App cli;
  tumble::app::configure_top_level(cli);
  tumble::app::RenderOptions render_options;
  CLI::App& render = tumble::app::add_render_command(cli, render_options);
  tumble::app::CompareOptions compare_options;
  CLI::App& compare = tumble::app::add_compare_command(cli, compare_options);
  tumble::app::ViewOptions view_options;
  CLI::App& view = tumble::app::add_view_command(cli, view_options);
  tumble::app::name_manual_pages(cli);

  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return cli.exit(error) == 0 ? tumble::app::kExitDone : tumble::app::kExitInputError;
  }
  if (render.parsed()) return tumble::app::run_render(render_options, std::cout, std::cerr);
  if (compare.parsed()) return tumble::app::run_compare(compare_options, std::cout, std::cerr);
  if (view.parsed()) return tumble::app::run_view(view_options, std::cout, std::cerr);
  return tumble::app::kExitInputError;
}
