// `--script` files: parsing every verb into the viewer's input events, the errors naming file
// and line, and the player handing steps out as the clock passes them.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "app/viewer/viewer_input.hpp"
#include "support/input_error.hpp"

namespace tumble::app::viewer {
namespace {

using ::testing::HasSubstr;

constexpr Modifiers kScriptCtrl{true, false, false};
constexpr Modifiers kScriptShift{false, true, false};

// --- Scripts ---------------------------------------------------------------------------------

std::vector<ScriptStep> parse(const std::string& text) {
  return parse_script(text, "run.txt");
}

/// The message of the InputError that parsing `text` throws (a failure if it does not).
std::string error_of(const std::string& text) {
  return testing::input_error_of([&] { parse(text); }, text);
}

const InputEvent& event_of(const ScriptStep& step) {
  return std::get<InputEvent>(step.action);
}
template <class Event>
const Event& as(const ScriptStep& step) {
  return std::get<Event>(event_of(step));
}

TEST(ViewerScript, KeyStrokeIsPressReleaseAndModifiersUp) {
  const auto steps = parse("1.5 key ctrl+p\n");
  ASSERT_EQ(steps.size(), 3u);
  for (const ScriptStep& step : steps) EXPECT_EQ(step.time, 1.5);
  EXPECT_EQ(as<KeyEvent>(steps[0]).key, Key::kP);
  EXPECT_TRUE(as<KeyEvent>(steps[0]).down);
  EXPECT_EQ(as<KeyEvent>(steps[0]).modifiers, kScriptCtrl);
  EXPECT_EQ(as<KeyEvent>(steps[1]).key, Key::kP);
  EXPECT_FALSE(as<KeyEvent>(steps[1]).down);
  EXPECT_EQ(as<KeyEvent>(steps[1]).modifiers, kScriptCtrl);
  // The modifiers let go, as a window reports the release of Ctrl itself.
  EXPECT_EQ(as<KeyEvent>(steps[2]).key, Key::kUnknown);
  EXPECT_FALSE(as<KeyEvent>(steps[2]).down);
  EXPECT_EQ(as<KeyEvent>(steps[2]).modifiers, Modifiers{});

  const auto plain = parse("0 key space");
  ASSERT_EQ(plain.size(), 2u);
  EXPECT_TRUE(as<KeyEvent>(plain[0]).down);
  EXPECT_FALSE(as<KeyEvent>(plain[1]).down);
}

TEST(ViewerScript, KeyDownAndUp) {
  const auto steps = parse("0.25 keydown shift+right\n0.5 keyup shift+right\n");
  ASSERT_EQ(steps.size(), 2u);
  EXPECT_EQ(steps[0].time, 0.25);
  EXPECT_EQ(as<KeyEvent>(steps[0]).key, Key::kRight);
  EXPECT_TRUE(as<KeyEvent>(steps[0]).down);
  EXPECT_EQ(as<KeyEvent>(steps[0]).modifiers, kScriptShift);
  EXPECT_EQ(steps[1].time, 0.5);
  EXPECT_FALSE(as<KeyEvent>(steps[1]).down);
}

TEST(ViewerScript, TypeTakesTheRestOfTheLine) {
  const auto steps = parse("2 type  hello world  # a comment\n3 type C#\n");
  ASSERT_EQ(steps.size(), 2u);
  EXPECT_EQ(as<TextEvent>(steps[0]).text, "hello world");
  EXPECT_EQ(as<TextEvent>(steps[1]).text, "C#");
}

TEST(ViewerScript, MoveWheelDropScreenshotQuit) {
  const auto steps = parse(
      "0 move 12.5 -3\n"
      "0.1 wheel -2\n"
      "0.2 drop scenes/my scene.json\n"
      "0.3 screenshot out/shot 1.png\r\n"
      "4 quit\n");
  ASSERT_EQ(steps.size(), 5u);
  EXPECT_EQ(as<MouseMoveEvent>(steps[0]).x, 12.5f);
  EXPECT_EQ(as<MouseMoveEvent>(steps[0]).y, -3.0f);
  EXPECT_EQ(steps[1].time, 0.1);
  EXPECT_EQ(as<WheelEvent>(steps[1]).dy, -2.0f);
  EXPECT_EQ(as<DropEvent>(steps[2]).path, std::filesystem::path("scenes/my scene.json"));
  EXPECT_EQ(std::get<ScreenshotRequest>(steps[3].action).path,
            std::filesystem::path("out/shot 1.png"));
  EXPECT_EQ(steps[4].time, 4.0);
  EXPECT_TRUE(std::holds_alternative<QuitEvent>(event_of(steps[4])));
}

TEST(ViewerScript, ResizeAsksForAWindowSize) {
  const auto steps = parse("0.5 resize 480 270\n1e0 resize 8192 1\n");
  ASSERT_EQ(steps.size(), 2u);
  EXPECT_EQ(steps[0].time, 0.5);
  EXPECT_EQ(std::get<ResizeRequest>(steps[0].action).width, 480);
  EXPECT_EQ(std::get<ResizeRequest>(steps[0].action).height, 270);
  EXPECT_EQ(std::get<ResizeRequest>(steps[1].action).width, 8192);
  EXPECT_EQ(std::get<ResizeRequest>(steps[1].action).height, 1);
  const std::string expected = "run.txt:1: expected a whole number of pixels from 1 to 8192 for ";
  EXPECT_THAT(error_of("0 resize 0 270"), HasSubstr(expected + "W, got \"0\""));
  EXPECT_THAT(error_of("0 resize 480 270.5"), HasSubstr(expected + "H, got \"270.5\""));
  EXPECT_THAT(error_of("0 resize 8193 270"), HasSubstr(expected + "W, got \"8193\""));
  EXPECT_THAT(error_of("0 resize 480"), HasSubstr(expected + "H, got end of line"));
  EXPECT_THAT(error_of("0 resize 480 270 90"),
              HasSubstr("run.txt:1: expected end of line after \"resize W H\", got \"90\""));
}

TEST(ViewerScript, PressAndReleaseWithButtons) {
  const auto steps = parse(
      "1 press 10 20\n1 release 10 20 left\n2 press 1 2 right\n"
      "2 release 3 4 middle\n");
  // Each button change is preceded by a move of the pointer to its place.
  ASSERT_EQ(steps.size(), 8u);
  EXPECT_EQ(as<MouseMoveEvent>(steps[0]).x, 10.0f);
  EXPECT_EQ(as<MouseMoveEvent>(steps[0]).y, 20.0f);
  const MouseButtonEvent& press = as<MouseButtonEvent>(steps[1]);
  EXPECT_EQ(press.button, 0);
  EXPECT_TRUE(press.down);
  EXPECT_EQ(press.x, 10.0f);
  EXPECT_EQ(press.y, 20.0f);
  EXPECT_FALSE(as<MouseButtonEvent>(steps[3]).down);
  EXPECT_EQ(as<MouseButtonEvent>(steps[5]).button, 1);
  EXPECT_EQ(as<MouseMoveEvent>(steps[6]).x, 3.0f);
  EXPECT_EQ(as<MouseButtonEvent>(steps[7]).button, 2);
  EXPECT_EQ(as<MouseButtonEvent>(steps[7]).x, 3.0f);
}

TEST(ViewerScript, ClickReleasesFiftyMillisecondsLater) {
  const auto steps = parse("1 click 10 20 right\n");
  ASSERT_EQ(steps.size(), 3u);
  EXPECT_EQ(steps[0].time, 1.0);
  EXPECT_EQ(as<MouseMoveEvent>(steps[0]).x, 10.0f);
  EXPECT_EQ(steps[1].time, 1.0);
  EXPECT_EQ(as<MouseButtonEvent>(steps[1]).button, 1);
  EXPECT_TRUE(as<MouseButtonEvent>(steps[1]).down);
  EXPECT_NEAR(steps[2].time, 1.05, 1e-12);
  EXPECT_FALSE(as<MouseButtonEvent>(steps[2]).down);
  EXPECT_EQ(as<MouseButtonEvent>(steps[2]).x, 10.0f);
  EXPECT_EQ(as<MouseButtonEvent>(steps[2]).y, 20.0f);
}

TEST(ViewerScript, DragIsMovePressTenMovesAndRelease) {
  const auto steps = parse("0.5 drag 0 0 100 50\n");
  ASSERT_EQ(steps.size(), 13u);
  EXPECT_EQ(steps[0].time, 0.5);
  EXPECT_EQ(as<MouseMoveEvent>(steps[0]).x, 0.0f);
  EXPECT_EQ(steps[1].time, 0.5);
  EXPECT_TRUE(as<MouseButtonEvent>(steps[1]).down);
  EXPECT_EQ(as<MouseButtonEvent>(steps[1]).x, 0.0f);
  for (int i = 1; i <= 10; ++i) {
    EXPECT_NEAR(steps[i + 1].time, 0.5 + 0.02 * i, 1e-12);
    EXPECT_FLOAT_EQ(as<MouseMoveEvent>(steps[i + 1]).x, 10.0f * static_cast<float>(i));
    EXPECT_FLOAT_EQ(as<MouseMoveEvent>(steps[i + 1]).y, 5.0f * static_cast<float>(i));
  }
  EXPECT_NEAR(steps[12].time, 0.7, 1e-12);
  const MouseButtonEvent& release = as<MouseButtonEvent>(steps[12]);
  EXPECT_FALSE(release.down);
  EXPECT_EQ(release.button, 0);
  EXPECT_EQ(release.x, 100.0f);
  EXPECT_EQ(release.y, 50.0f);
}

TEST(ViewerScript, ExpandedStepsAreSortedByTime) {
  // The click's release (at 0.05) comes after the key stroke at 0.01.
  const auto steps = parse("0 click 5 5\n0.01 key space\n0.05 wheel 1\n");
  ASSERT_EQ(steps.size(), 6u);
  EXPECT_TRUE(std::holds_alternative<MouseMoveEvent>(event_of(steps[0])));
  EXPECT_TRUE(as<MouseButtonEvent>(steps[1]).down);
  EXPECT_EQ(as<KeyEvent>(steps[2]).key, Key::kSpace);
  EXPECT_EQ(as<KeyEvent>(steps[3]).key, Key::kSpace);
  // Equal times keep the file's order: the release (line 1) before the wheel (line 3).
  EXPECT_FALSE(as<MouseButtonEvent>(steps[4]).down);
  EXPECT_EQ(as<WheelEvent>(steps[5]).dy, 1.0f);
}

TEST(ViewerScript, CommentsBlankLinesAndEqualTimes) {
  const auto steps = parse(
      "# a script\n"
      "\n"
      "   \t\n"
      "1 key a   # first\n"
      "1 key b\n"
      "  # indented comment\n");
  ASSERT_EQ(steps.size(), 4u);
  EXPECT_EQ(as<KeyEvent>(steps[0]).key, Key::kA);
  EXPECT_EQ(as<KeyEvent>(steps[2]).key, Key::kB);
  EXPECT_TRUE(parse("").empty());
}

TEST(ViewerScript, BadTimes) {
  EXPECT_THAT(error_of("soon key space"),
              HasSubstr("run.txt:1: expected a time in seconds, got \"soon\""));
  EXPECT_THAT(error_of("\n-1 key space"),
              HasSubstr("run.txt:2: expected a time >= 0 seconds, got \"-1\""));
  EXPECT_THAT(error_of("inf key space"),
              HasSubstr("run.txt:1: expected a finite time in seconds, got \"inf\""));
  EXPECT_THAT(error_of("nan quit"), HasSubstr("run.txt:1: expected a finite time"));
  EXPECT_THAT(error_of("1s quit"), HasSubstr("run.txt:1: expected a time in seconds, got \"1s\""));
  EXPECT_THAT(error_of("2 key a\n# c\n1.5 key b\n"),
              HasSubstr("run.txt:3: expected a time >= 2 (times must not decrease), got \"1.5\""));
}

TEST(ViewerScript, BadVerbs) {
  EXPECT_THAT(error_of("1 jump"), HasSubstr("run.txt:1: expected a verb (key, keydown,"));
  EXPECT_THAT(error_of("1 jump"), HasSubstr("screenshot, resize or quit), got \"jump\""));
  EXPECT_THAT(error_of("1 KEY space"), HasSubstr("got \"KEY\""));
  EXPECT_THAT(
      error_of("1   # only a time"),
      HasSubstr("run.txt:1: expected a verb (key, keydown, keyup, type, move, click, "
                "press, release, drag, wheel, drop, screenshot, resize or quit), got end of line"));
}

TEST(ViewerScript, BadKeys) {
  EXPECT_THAT(error_of("0 key spacebar"),
              HasSubstr("run.txt:1: expected a key chord such as space or ctrl+p, got "
                        "\"spacebar\""));
  EXPECT_THAT(error_of("0 keydown ctrl+"), HasSubstr("got \"ctrl+\""));
  EXPECT_THAT(error_of("0 keyup"), HasSubstr("run.txt:1: expected a key chord such as space or "
                                             "ctrl+p, got end of line"));
  EXPECT_THAT(error_of("0 key a b"),
              HasSubstr("run.txt:1: expected end of line after \"key CHORD\", got \"b\""));
}

TEST(ViewerScript, BadNumbers) {
  EXPECT_THAT(error_of("0 move a 1"), HasSubstr("run.txt:1: expected a number for X, got \"a\""));
  EXPECT_THAT(error_of("0 move 1"),
              HasSubstr("run.txt:1: expected a number for Y, got end of line"));
  EXPECT_THAT(error_of("0 move 1 inf"), HasSubstr("expected a number for Y, got \"inf\""));
  EXPECT_THAT(error_of("0 move 1 2 3"),
              HasSubstr("run.txt:1: expected end of line after \"move X Y\", got \"3\""));
  EXPECT_THAT(error_of("0 wheel"),
              HasSubstr("run.txt:1: expected a number for DY, got end of line"));
  EXPECT_THAT(error_of("0 wheel 1 2"),
              HasSubstr("expected end of line after \"wheel DY\", got \"2\""));
  EXPECT_THAT(error_of("0 drag 0 0 10"),
              HasSubstr("run.txt:1: expected a number for Y2, got end of line"));
  EXPECT_THAT(error_of("0 click 1 2 left 4"),
              HasSubstr("expected end of line after \"click X Y [BUTTON]\", got \"4\""));
  EXPECT_THAT(error_of("0 quit now"),
              HasSubstr("run.txt:1: expected end of line after \"quit\", got \"now\""));
}

TEST(ViewerScript, BadButtons) {
  EXPECT_THAT(error_of("0 click 1 2 up"),
              HasSubstr("run.txt:1: expected a button (left, right or middle), got \"up\""));
  EXPECT_THAT(error_of("0 press 1 2 Left"), HasSubstr("got \"Left\""));
  EXPECT_THAT(error_of("0 drag 0 0 1 1 4"),
              HasSubstr("expected a button (left, right or middle), got \"4\""));
}

TEST(ViewerScript, MissingRestOfLine) {
  EXPECT_THAT(error_of("0 drop"),
              HasSubstr("run.txt:1: expected a path for drop, got end of line"));
  EXPECT_THAT(error_of("0 screenshot   # later"),
              HasSubstr("run.txt:1: expected a path for screenshot, got end of line"));
  EXPECT_THAT(error_of("0 type "), HasSubstr("run.txt:1: expected text for type, got end of line"));
}

TEST(ViewerScript, LoadsAFile) {
  const std::filesystem::path file =
      std::filesystem::path(::testing::TempDir()) / "viewer_input_test_script.txt";
  {
    std::ofstream out(file);
    out << "0 move 1 2\n0.5 quit\n";
  }
  const auto steps = load_script(file);
  ASSERT_EQ(steps.size(), 2u);
  EXPECT_EQ(steps[1].time, 0.5);
  {
    std::ofstream out(file);
    out << "0 quit\nx quit\n";
  }
  EXPECT_THAT(testing::input_error_of([&] { load_script(file); }),
              HasSubstr(file.string() + ":2: expected a time in seconds"));
  std::filesystem::remove(file);
}

TEST(ViewerScript, MissingFileNamesIt) {
  EXPECT_THAT(testing::input_error_of([] { load_script("/nonexistent/run.txt"); }),
              HasSubstr("/nonexistent/run.txt: cannot open the script"));
  EXPECT_THAT(testing::input_error_of([] { load_script(::testing::TempDir()); }),
              HasSubstr(": is a directory, expected a script"));
}

// --- Beyond the single verbs -----------------------------------------------------------------

TEST(ViewerScript, KeyDownOfAChordLeavesTheModifiersHeld) {
  const auto steps = parse("0 keydown ctrl+shift+p\n");
  ASSERT_EQ(steps.size(), 1u);  // no release and no modifiers-up event
  EXPECT_TRUE(as<KeyEvent>(steps[0]).down);
  EXPECT_EQ(as<KeyEvent>(steps[0]).modifiers, (Modifiers{true, true, false}));
  const auto up = parse("0 keyup ctrl+p\n");
  ASSERT_EQ(up.size(), 1u);
  EXPECT_FALSE(as<KeyEvent>(up[0]).down);
  EXPECT_EQ(as<KeyEvent>(up[0]).modifiers, kScriptCtrl);
}

TEST(ViewerScript, DragWithAnotherButtonUsesItForPressAndRelease) {
  const auto steps = parse("1 drag 10 10 20 30 middle\n");
  ASSERT_EQ(steps.size(), 13u);
  EXPECT_EQ(as<MouseButtonEvent>(steps[1]).button, 2);
  EXPECT_EQ(as<MouseButtonEvent>(steps[12]).button, 2);
  EXPECT_FLOAT_EQ(as<MouseMoveEvent>(steps[6]).x, 15.0f);  // halfway: move 5 of 10
  EXPECT_FLOAT_EQ(as<MouseMoveEvent>(steps[6]).y, 20.0f);
  EXPECT_NEAR(steps[6].time, 1.1, 1e-12);
}

TEST(ViewerScript, TimesMayUseExponentsAndFractions) {
  const auto steps = parse("1e-1 wheel 1\n0.25 wheel 2\n2.5E0 quit\n");
  ASSERT_EQ(steps.size(), 3u);
  EXPECT_EQ(steps[0].time, 0.1);
  EXPECT_EQ(steps[1].time, 0.25);
  EXPECT_EQ(steps[2].time, 2.5);
}

TEST(ViewerScript, OrderIsCheckedOnTheLinesTimesNotOnExpandedSteps) {
  // The drag's release lands at 0.7, after the key at 0.6: still a valid script.
  const auto steps = parse("0.5 drag 0 0 1 1\n0.6 key space\n");
  ASSERT_EQ(steps.size(), 15u);
  // Move, press, five moves to 0.6, the stroke at 0.6 (after the equal-time move of the
  // earlier line), five moves to 0.7 and the release.
  EXPECT_NEAR(steps[6].time, 0.6, 1e-12);
  EXPECT_TRUE(std::holds_alternative<MouseMoveEvent>(event_of(steps[6])));
  EXPECT_EQ(as<KeyEvent>(steps[7]).key, Key::kSpace);
  EXPECT_EQ(as<KeyEvent>(steps[8]).key, Key::kSpace);
  EXPECT_NEAR(steps[9].time, 0.62, 1e-12);
  EXPECT_FALSE(as<MouseButtonEvent>(steps[14]).down);
  for (std::size_t i = 1; i < steps.size(); ++i) EXPECT_LE(steps[i - 1].time, steps[i].time);
}

TEST(ViewerScript, ZeroIsAValidFirstTimeAndTimesMayRepeat) {
  const auto steps = parse("0 wheel 1\n0 wheel 2\n0 wheel 3\n");
  ASSERT_EQ(steps.size(), 3u);
  EXPECT_EQ(as<WheelEvent>(steps[2]).dy, 3.0f);
}

TEST(ViewerScript, LineNumbersCountBlankAndCommentLines) {
  EXPECT_THAT(error_of("# header\n\n0 key space\n   \n# more\n1 move 1\n"),
              HasSubstr("run.txt:6: expected a number for Y, got end of line"));
  EXPECT_THAT(error_of("0 quit\r\n1 quit\r\n2 bogus\r\n"), HasSubstr("run.txt:3: expected a verb"));
}

TEST(ViewerScript, TheDecreasingTimeNamesThePreviousLinesTime) {
  EXPECT_THAT(
      error_of("0.5 key a\n0.75 key b\n0.7 key c\n"),
      HasSubstr("run.txt:3: expected a time >= 0.75 (times must not decrease), got \"0.7\""));
  // Only the latest time counts: 1 then 3 then 2 fails at line 3, not 1 then 0.5 at line 2.
  EXPECT_THAT(error_of("1 quit\n3 quit\n2 quit\n"), HasSubstr("run.txt:3: expected a time >= 3"));
}

TEST(ViewerScript, AHashInsideAWordIsNoComment) {
  EXPECT_THAT(error_of("0 key a#b"),
              HasSubstr("run.txt:1: expected a key chord such as space or ctrl+p, got \"a#b\""));
  const auto steps = parse("0 drop my#file.stl # dropped\n");
  ASSERT_EQ(steps.size(), 1u);
  EXPECT_EQ(as<DropEvent>(steps[0]).path, std::filesystem::path("my#file.stl"));
}

TEST(ViewerScript, NumbersMustBePlainDecimals) {
  EXPECT_THAT(error_of("+1 quit"), HasSubstr("run.txt:1: expected a time in seconds, got \"+1\""));
  EXPECT_THAT(error_of("0x10 quit"), HasSubstr("got \"0x10\""));
  EXPECT_THAT(error_of("0 move 1,5 2"), HasSubstr("expected a number for X, got \"1,5\""));
  EXPECT_THAT(error_of("0 wheel 1e999"), HasSubstr("expected a number for DY, got \"1e999\""));
}

TEST(ViewerScript, TheFileNameInMessagesIsTheOneGiven) {
  EXPECT_THAT(testing::input_error_of([] { parse_script("0 hop", "scripts/demo.txt"); }),
              HasSubstr("scripts/demo.txt:1: expected a verb"));
}

// --- ScriptPlayer ----------------------------------------------------------------------------

TEST(ViewerScriptPlayer, HandsOutStepsAsTimePasses) {
  ScriptPlayer player(parse("0 move 1 1\n0.5 wheel 1\n0.5 wheel 2\n1 quit\n"));
  EXPECT_FALSE(player.finished());
  const auto first = player.due(0.1);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<MouseMoveEvent>(event_of(first[0])));
  EXPECT_TRUE(player.due(0.49).empty());
  const auto second = player.due(0.75);
  ASSERT_EQ(second.size(), 2u);
  EXPECT_EQ(as<WheelEvent>(second[0]).dy, 1.0f);
  EXPECT_EQ(as<WheelEvent>(second[1]).dy, 2.0f);
  EXPECT_FALSE(player.finished());
  EXPECT_EQ(player.due(1.0).size(), 1u);
  EXPECT_TRUE(player.finished());
  EXPECT_TRUE(player.due(100.0).empty());
}

TEST(ViewerScriptPlayer, EachButtonChangeGetsItsOwnCall) {
  ScriptPlayer player(
      parse("0 wheel 1\n0 press 5 5\n0 release 5 5\n0 key space\n"
            "0 screenshot a.png\n"));
  // Steps before a button change come first (with press's move); the button alone after.
  const auto first = player.due(1.0);
  ASSERT_EQ(first.size(), 2u);
  EXPECT_TRUE(std::holds_alternative<WheelEvent>(event_of(first[0])));
  EXPECT_TRUE(std::holds_alternative<MouseMoveEvent>(event_of(first[1])));
  const auto press = player.due(1.0);
  ASSERT_EQ(press.size(), 1u);
  EXPECT_TRUE(as<MouseButtonEvent>(press[0]).down);
  const auto move = player.due(1.0);  // the release's move
  ASSERT_EQ(move.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<MouseMoveEvent>(event_of(move[0])));
  const auto release = player.due(1.0);
  ASSERT_EQ(release.size(), 1u);
  EXPECT_FALSE(as<MouseButtonEvent>(release[0]).down);
  const auto rest = player.due(1.0);
  ASSERT_EQ(rest.size(), 3u);
  EXPECT_TRUE(as<KeyEvent>(rest[0]).down);
  EXPECT_FALSE(as<KeyEvent>(rest[1]).down);
  EXPECT_EQ(std::get<ScreenshotRequest>(rest[2].action).path, "a.png");
  EXPECT_TRUE(player.finished());
}

TEST(ViewerScriptPlayer, LateClickStillSplitsPressAndRelease) {
  ScriptPlayer player(parse("0 click 1 1\n"));
  // All are due by t = 3, but ImGui must see the move, the press and the release in frames
  // of their own.
  EXPECT_TRUE(std::holds_alternative<MouseMoveEvent>(event_of(player.due(3.0).at(0))));
  EXPECT_EQ(player.due(3.0).size(), 1u);
  EXPECT_FALSE(player.finished());
  const auto release = player.due(3.0);
  ASSERT_EQ(release.size(), 1u);
  EXPECT_FALSE(as<MouseButtonEvent>(release[0]).down);
  EXPECT_TRUE(player.finished());
}

}  // namespace
}  // namespace tumble::app::viewer
