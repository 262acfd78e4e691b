// `tumble compare`: the options; the job is app/video/compare_job.hpp.
#include "app/commands/compare_command.hpp"

#include <ostream>

#include <CLI/CLI.hpp>

#include "app/support/exit_status.hpp"
#include "app/support/interrupt_guard.hpp"
#include "app/support/printf_number.hpp"
#include "app/support/progress_bar.hpp"
#include "command_line.hpp"
#include "engine/simulation/reference_motion.hpp"
#include "video_options_cli.hpp"

namespace tumble::app {

CLI::App& add_compare_command(CLI::App& cli, CompareOptions& options) {
  CLI::App& compare = *cli.add_subcommand(kCompareSummary.name, kCompareSummary.summary);
  compare.footer(
      "Every run uses the same dt and the same frame times as tumble render. grid: one panel "
      "per integrator, same camera, each with its energy and |L| drift plots. overlay: every "
      "run in its own translucent colour over a grey ghost of the reference (exact for "
      "torque-free scenes and heavy symmetric tops, otherwise dopri at tolerance " +
      printf_number(engine::kReferenceTolerance, "%g") +
      "). A run that blows up holds its "
      "last good state and says when. Exit status: 0 done, 1 bad scene/option/output or ffmpeg "
      "failure, 3 some run blew up (the output is still complete), 130 interrupted (nothing "
      "written).");
  add_video_options(
      compare, options,
      "Size WxH of the whole frame in pixels (default 1280x720; even for .mp4/.webm)");
  compare
      .add_option_function<std::string>(
          "--integrators", [&](const std::string& value) { options.integrators = value; },
          "Integrators to compare, comma-separated, at least two (see tumble simulate "
          "--list-integrators)")
      ->required()
      ->type_name("A,B,...");
  compare
      .add_option_function<std::string>(
          "--layout", [&](const std::string& value) { options.layout = value; },
          "grid (one panel per integrator, the default) or overlay (one view, one colour each)")
      ->type_name("grid|overlay");
  compare
      .add_option_function<double>(
          "--dt", [&](double value) { options.dt = value; },
          "Time step H in seconds of every run (default: the scene's)")
      ->type_name("H");
  return compare;
}

int run_compare(const CompareOptions& options, std::ostream& out, std::ostream& err) {
  const bool progress = !options.quiet && ProgressBar::on_terminal(err);
  const InterruptGuard guard;
  // An interruption under way wins over the error it caused (ffmpeg shares the terminal's
  // SIGINT and may fail first).
  const auto report = [&] {
    guard.report(err, "compare", options.output.string());
    return kExitInterrupted;
  };
  const auto interrupted = [&] { return guard.interrupted() ? report() : -1; };
  return run_guarded(
      "compare", err,
      [&] {
        const int status = write_comparison(
            options, [&] { return guard.interrupted(); }, out, err, progress);
        return status == kExitInterrupted ? report() : status;
      },
      interrupted);
}

}  // namespace tumble::app
