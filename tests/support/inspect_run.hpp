#pragma once
// `tumble inspect` run in the test's own process: its command line parsed as the executable
// parses it, run_inspect called with captured streams.

#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/commands/inspect_command.hpp"

namespace tumble::testing {

struct InspectRun {
  int status = -1;
  std::string out;
  std::string err;
};

/// `tumble inspect ARGS...`; a command-line error gives status 1 and CLI11's message.
inline InspectRun run_inspect_args(const std::vector<std::string>& args) {
  CLI::App cli;
  app::InspectOptions options;
  CLI::App& inspect = app::add_inspect_command(cli, options);
  std::vector<const char*> argv = {"tumble", "inspect"};
  for (const std::string& arg : args) argv.push_back(arg.c_str());
  InspectRun run;
  try {
    cli.parse(static_cast<int>(argv.size()), argv.data());
  } catch (const CLI::ParseError& error) {
    run.status = 1;
    run.err = error.what();
    return run;
  }
  if (!inspect.parsed()) return run;
  std::ostringstream out, err;
  run.status = app::run_inspect(options, out, err);
  run.out = out.str();
  run.err = err.str();
  return run;
}

}  // namespace tumble::testing
