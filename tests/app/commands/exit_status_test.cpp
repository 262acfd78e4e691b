// The one mapping from outcomes to exit statuses (app/support/exit_status.hpp), in itself and
// as every command applies it through the `tumble` executable.
#include "app/support/exit_status.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/run_command.hpp"
#include "support/scene_builder.hpp"

namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;
using tumble::app::kExitBlowUp;
using tumble::app::kExitInputError;
using tumble::app::kExitInternalError;
using tumble::app::kExitInterrupted;
using tumble::app::run_guarded;
using tumble::testing::run_command;
using tumble::testing::tumble_executable;

std::size_t line_count(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

TEST(RunGuarded, PassesTheBodysStatusThroughAndSaysNothing) {
  std::ostringstream err;
  EXPECT_EQ(run_guarded("simulate", err, [] { return kExitBlowUp; }), kExitBlowUp);
  EXPECT_EQ(run_guarded("simulate", err, [] { return 0; }), 0);
  EXPECT_EQ(err.str(), "");
}

TEST(RunGuarded, BadInputIsOneLineAndStatusOne) {
  std::ostringstream err;
  const int status = run_guarded(
      "inspect", err, []() -> int { throw tumble::InputError("part.stl: the surface is open"); });
  EXPECT_EQ(status, kExitInputError);
  EXPECT_EQ(err.str(), "tumble inspect: error: part.stl: the surface is open\n");
}

TEST(RunGuarded, AnyOtherExceptionIsAnInternalErrorNeverBadInput) {
  const std::vector<std::function<int()>> bugs = {
      []() -> int { throw std::logic_error("frames must not go back"); },
      []() -> int { throw std::invalid_argument("unknown mesh id 7"); },
      []() -> int { throw std::runtime_error("OSMesaMakeCurrent failed"); },
      []() -> int { throw std::bad_alloc(); },
  };
  for (const auto& bug : bugs) {
    std::ostringstream err;
    EXPECT_EQ(run_guarded("render", err, bug), kExitInternalError);
    EXPECT_THAT(err.str(), StartsWith("tumble render: internal error"));
    EXPECT_EQ(line_count(err.str()), 1u) << err.str();
  }
}

TEST(RunGuarded, AClaimOnTheFailureWinsAndOnlyOnFailure) {
  std::ostringstream err;
  int claims = 0;
  const auto interrupted = [&] {
    ++claims;
    err << "tumble render: interrupted by SIGINT\n";
    return kExitInterrupted;
  };
  EXPECT_EQ(run_guarded(
                "render", err, [] { return 0; }, interrupted),
            0);
  EXPECT_EQ(claims, 0);
  const int status = run_guarded(
      "render", err, []() -> int { throw tumble::InputError("ffmpeg failed"); }, interrupted);
  EXPECT_EQ(status, kExitInterrupted);
  EXPECT_EQ(err.str(), "tumble render: interrupted by SIGINT\n");
  // No claim (-1): the usual line.
  std::ostringstream plain;
  EXPECT_EQ(run_guarded(
                "render", plain, []() -> int { throw tumble::InputError("ffmpeg failed"); },
                [] { return -1; }),
            kExitInputError);
  EXPECT_EQ(plain.str(), "tumble render: error: ffmpeg failed\n");
}

// --- every command, through the executable ------------------------------------------------

class CommandExitStatus : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = tumble::testing::fresh_directory("CommandExitStatus");
    scene_ = (dir_ / "scene.json").string();
    tumble::testing::SceneBuilder()
        .duration(0.1)
        .dt(0.01)
        .body(tumble::testing::BodyBuilder().angular_velocity({0.1, 2.0, 0.1}))
        .write(scene_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  tumble::testing::CommandResult tumble(const std::string& arguments) const {
    return run_command(tumble_executable() + " " + arguments);
  }

  /// Status 1 and exactly one line on stderr that starts with `prefix` and holds `names`.
  void expect_bad_input(const std::string& arguments, const std::string& prefix,
                        const std::string& names) const {
    const auto result = tumble(arguments);
    EXPECT_EQ(result.status, kExitInputError) << arguments << "\n" << result.err;
    EXPECT_THAT(result.err, StartsWith(prefix)) << arguments;
    EXPECT_THAT(result.err, HasSubstr(names)) << arguments;
    EXPECT_EQ(line_count(result.err), 1u) << arguments << "\n" << result.err;
    EXPECT_EQ(result.out, "") << arguments;
  }

  std::string out(const std::string& name) const { return (dir_ / name).string(); }

  std::filesystem::path dir_;
  std::string scene_;
};

TEST_F(CommandExitStatus, UnknownOptionsAreOneLineAndStatusOneForEveryCommand) {
  // Each with its required arguments, so the unknown option is the only mistake.
  const std::vector<std::pair<std::string, std::string>> commands = {
      {"inspect", "/tmp/x.stl"},
      {"simulate", scene_},
      {"render", scene_ + " -o " + out("a.mp4")},
      {"compare", scene_ + " --integrators rk4,splitting -o " + out("a.mp4")},
      {"bench", scene_ + " -o " + out("b")},
      {"stability", "-o " + out("s")},
      {"inertials", out("robot.urdf")},
      {"view", ""}};
  for (const auto& [command, arguments] : commands) {
    expect_bad_input(command + " " + arguments + " --no-such-option",
                     "tumble " + command + ": error: ", "--no-such-option");
  }
}

TEST_F(CommandExitStatus, UnparsableValuesAreOneLineAndStatusOne) {
  expect_bad_input("inspect /tmp/x.stl --density abc", "tumble inspect: error: ", "--density");
  expect_bad_input("simulate " + scene_ + " --dt abc", "tumble simulate: error: ", "--dt");
  expect_bad_input("simulate " + scene_ + " --every nan", "tumble simulate: error: ", "--every");
  expect_bad_input("render " + scene_ + " -o " + out("a.mp4") + " --aa 4.5",
                   "tumble render: error: ", "--aa");
  expect_bad_input(
      "compare " + scene_ + " --integrators rk4,splitting -o " + out("a.mp4") + " --fps x",
      "tumble compare: error: ", "--fps");
  expect_bad_input("bench " + scene_ + " -o " + out("b") + " --repeat x",
                   "tumble bench: error: ", "--repeat");
  expect_bad_input("stability -o " + out("s") + " --dts 0.1,abc",
                   "tumble stability: error: ", "--dts");
  expect_bad_input("inertials " + out("r.urdf") + " --tolerance abc",
                   "tumble inertials: error: ", "--tolerance");
  expect_bad_input("view --dt abc", "tumble view: error: ", "--dt");
}

TEST_F(CommandExitStatus, MissingInputFilesAreOneLineNamingTheFile) {
  const std::string missing = out("missing.json");
  expect_bad_input("inspect " + out("missing.stl"), "tumble inspect: error: ", "missing.stl");
  expect_bad_input("simulate " + missing, "tumble simulate: error: ", missing);
  expect_bad_input("render " + missing + " -o " + out("a.mp4"), "tumble render: error: ", missing);
  expect_bad_input("compare " + missing + " --integrators rk4,splitting -o " + out("a.mp4"),
                   "tumble compare: error: ", missing);
  expect_bad_input("bench " + missing + " -o " + out("b"), "tumble bench: error: ", missing);
  expect_bad_input("stability " + missing + " -o " + out("s"),
                   "tumble stability: error: ", missing);
  expect_bad_input("inertials " + out("missing.urdf") + " -o " + out("o.urdf"),
                   "tumble inertials: error: ", "missing.urdf");
  // Nothing was written for any of them.
  EXPECT_EQ(tumble::testing::directory_entries(dir_), std::vector<std::string>{"scene.json"});
}

TEST_F(CommandExitStatus, HelpAndVersionExitZero) {
  const auto help = tumble("--help");
  EXPECT_EQ(help.status, 0);
  // Every command is listed by the one `tumble`, those that draw included.
  for (const char* command :
       {"inspect", "simulate", "render", "compare", "bench", "stability", "view", "inertials"}) {
    EXPECT_THAT(help.out, HasSubstr(std::string("\n  ") + command + " ")) << command;
  }
  const auto render_help = tumble("render --help");
  EXPECT_EQ(render_help.status, 0);
  EXPECT_THAT(render_help.out, HasSubstr("Usage: tumble render [OPTIONS] SCENE"));
  EXPECT_THAT(render_help.out, HasSubstr("--aa"));
  const auto version = tumble("--version");
  EXPECT_EQ(version.status, 0);
  EXPECT_THAT(version.out, StartsWith("tumble "));
  EXPECT_EQ(tumble("").status, kExitInputError);
}

TEST_F(CommandExitStatus, TheCommandsThatDrawNothingLoadNoGraphicsOrWindowLibraries) {
  // `tumble` itself: what it needs at start-up, read from its dynamic section.
  const auto needed = run_command("ldd " + tumble_executable());
  ASSERT_EQ(needed.status, 0) << needed.err;
  for (const char* library :
       {"libOSMesa", "libGL", "libLLVM", "libSDL2", "libpulse", "libX11", "libpng", "libimgui"}) {
    EXPECT_THAT(needed.out, ::testing::Not(HasSubstr(library))) << library;
  }
  // ... while tumble-draw, which it runs for render, compare and view, has the renderer.
  const auto drawing = run_command("ldd " + std::string(TUMBLE_BINARY_DIR) + "/app/tumble-draw");
  EXPECT_THAT(drawing.out, HasSubstr("libOSMesa"));
}

TEST_F(CommandExitStatus, AMissingDrawingExecutableIsAnInternalError) {
  // A copy of tumble without tumble-draw beside it: a broken installation, not bad input.
  const auto lonely = dir_ / "bin";
  std::filesystem::create_directories(lonely);
  std::filesystem::copy_file(tumble_executable(), lonely / "tumble");
  const auto result =
      run_command((lonely / "tumble").string() + " render " + scene_ + " -o " + out("a.mp4"));
  EXPECT_EQ(result.status, kExitInternalError) << result.err;
  EXPECT_THAT(result.err, HasSubstr("tumble render: internal error: cannot run"));
  EXPECT_THAT(result.err, HasSubstr("tumble-draw"));
  EXPECT_EQ(line_count(result.err), 1u);
  // The commands that draw nothing work without it.
  const auto simulate = run_command((lonely / "tumble").string() + " simulate " + scene_);
  EXPECT_EQ(simulate.status, 0) << simulate.err;
}

}  // namespace
