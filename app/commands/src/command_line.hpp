#pragma once
/// @file What the two executables behind the one `tumble` command share: the top-level
/// command line, and the names and summaries of the commands that draw.
///
/// `tumble` itself holds the commands that draw nothing (inspect, simulate, bench, stability):
/// it never loads the GL, SDL or audio libraries. For render, compare and view it replaces
/// itself with `tumble-draw`, the executable beside it that holds those three
/// (docs/architecture.md), so to the user there is one command with one help text.

#include <malloc.h>

#include <csignal>
#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

namespace tumble::app {

/// What both executables set first, before any command runs.
///
/// A file size limit (ulimit -f): past it a write must fail with EFBIG, an error the outputs
/// report and clean up after, rather than kill the process with SIGXFSZ mid-file.
///
/// The heap: a large mesh's passes (reading, welding, the checks, the display copies) each
/// allocate and free blocks of megabytes. By default glibc maps each such block fresh and
/// unmaps it when freed, so the next pass's blocks fault in their pages again; here blocks
/// under 32 MiB come from the heap, which grows 64 MiB at a time and keeps what is freed for
/// the next pass, and every thread allocates from that one heap (a thread's own arena would
/// fault in fresh pages for what the main heap holds free). `tumble inspect` of a
/// 1M-triangle STL then takes a third of the page faults and a third less time with the
/// overlap checks (docs/performance.md, "Overlap checks"). Set here, in the executables only:
/// the libraries and the Python module leave a host process's heap as it is.
inline void prepare_process() {
  std::signal(SIGXFSZ, SIG_IGN);
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TOP_PAD, 64 << 20);
  mallopt(M_ARENA_MAX, 1);
}

/// A subcommand's name and its one-line summary (the help's command list).
struct CommandSummary {
  const char* name;
  const char* summary;
};

inline constexpr CommandSummary kRenderSummary{
    "render",
    "Render a scene off-screen to a video (.mp4, .webm, .gif) or PNG frames (DIR/), or a robot "
    "file's links and inertials to one PNG"};
inline constexpr CommandSummary kCompareSummary{
    "compare",
    "Render one scene with several integrators side by side (grid) or on top of each other "
    "(overlay) into one video or PNG frames"};
inline constexpr CommandSummary kViewSummary{
    "view",
    "Interactive viewer: play a scene or a mesh, inspect it, switch integrators, record; see a "
    "robot file's stated and computed inertials"};

/// The commands `tumble-draw` runs, in the order the help lists them.
inline constexpr CommandSummary kDrawingCommands[] = {kRenderSummary, kCompareSummary,
                                                      kViewSummary};

/// Whether `name` is one of kDrawingCommands.
inline bool is_drawing_command(std::string_view name) {
  for (const CommandSummary& command : kDrawingCommands) {
    if (name == command.name) return true;
  }
  return false;
}

/// A command-line error as one line, "tumble COMMAND: error: WHAT (see tumble COMMAND --help)",
/// like every other error tumble reports.
inline std::string one_line_failure(const CLI::App* cli, const CLI::Error& error) {
  std::string command = "tumble";
  for (const CLI::App* subcommand : cli->get_subcommands()) command += " " + subcommand->get_name();
  std::string what = error.what();
  for (char& c : what) {
    if (c == '\n') c = ' ';
  }
  return command + ": error: " + what + " (see " + command + " --help)\n";
}

/// The top-level command line both executables start from: named "tumble", one subcommand
/// required, --version, errors in one line.
inline void configure_top_level(CLI::App& cli) {
  cli.failure_message(one_line_failure);
  cli.name("tumble");
  cli.description(
      "tumble: rigid bodies with mass properties from real meshes: inspect, simulate, render, "
      "compare, bench, stability, view");
  cli.require_subcommand(1);
  cli.set_version_flag("--version", "tumble " TUMBLE_VERSION);
}

/// Ends every command's help with the page of the manual that holds it: "Manual:
/// docs/inspect.md" (after the footer the command has).
inline void name_manual_pages(CLI::App& cli) {
  for (CLI::App* command : cli.get_subcommands({})) {
    const std::string footer = command->get_footer();
    command->footer((footer.empty() ? "" : footer + "\n\n") + "Manual: docs/" +
                    command->get_name() + ".md");
  }
}

}  // namespace tumble::app
