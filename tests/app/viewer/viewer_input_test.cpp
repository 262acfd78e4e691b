#include "app/viewer/viewer_input.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
// tumble_app_lib links ImGui privately, so its include directory does not reach the tests.
#include <imgui/imgui.h>

#include <cstring>
#include <fstream>

#include "engine/input_error.hpp"
#include "support/input_error.hpp"

namespace tumble::app::viewer {
namespace {

using ::testing::HasSubstr;

// --- Shortcuts, key names, chords ------------------------------------------------------------

std::optional<Shortcut> shortcut(Key key, Modifiers modifiers = {}, bool help_shown = false) {
  return shortcut_for(KeyEvent{key, true, modifiers}, help_shown);
}

constexpr Modifiers kCtrl{true, false, false};
constexpr Modifiers kShift{false, true, false};
constexpr Modifiers kAlt{false, false, true};

TEST(ViewerShortcuts, PlainKeys) {
  EXPECT_EQ(shortcut(Key::kSpace), Shortcut::kTogglePause);
  EXPECT_EQ(shortcut(Key::kRight), Shortcut::kStep);
  EXPECT_EQ(shortcut(Key::kBackspace), Shortcut::kReset);
  EXPECT_EQ(shortcut(Key::kMinus), Shortcut::kSlower);
  EXPECT_EQ(shortcut(Key::kEquals), Shortcut::kFaster);
  EXPECT_EQ(shortcut(Key::kEquals, kShift), Shortcut::kFaster);  // "+" on a US keyboard
  EXPECT_EQ(shortcut(Key::kF1), Shortcut::kToggleHelp);
}

TEST(ViewerShortcuts, CtrlChords) {
  EXPECT_EQ(shortcut(Key::kP, kCtrl), Shortcut::kScreenshot);
  EXPECT_EQ(shortcut(Key::kR, kCtrl), Shortcut::kToggleRecord);
  EXPECT_EQ(shortcut(Key::kO, kCtrl), Shortcut::kOpen);
  EXPECT_EQ(shortcut(Key::kQ, kCtrl), Shortcut::kQuit);
  // Other ctrl chords, and ctrl on the plain shortcut keys, do nothing.
  EXPECT_EQ(shortcut(Key::kA, kCtrl), std::nullopt);
  EXPECT_EQ(shortcut(Key::kSpace, kCtrl), std::nullopt);
  EXPECT_EQ(shortcut(Key::k1, kCtrl), std::nullopt);
}

TEST(ViewerShortcuts, EscapeClosesTheHelpBeforeQuitting) {
  EXPECT_EQ(shortcut(Key::kEscape, {}, true), Shortcut::kToggleHelp);
  EXPECT_EQ(shortcut(Key::kEscape, {}, false), Shortcut::kQuit);
}

TEST(ViewerShortcuts, PlainLettersAndDigitsAreLeftForTextFields) {
  for (int k = static_cast<int>(Key::kA); k <= static_cast<int>(Key::k9); ++k) {
    EXPECT_EQ(shortcut(static_cast<Key>(k)), std::nullopt) << key_name(static_cast<Key>(k));
    EXPECT_EQ(shortcut(static_cast<Key>(k), kShift), std::nullopt);
  }
  for (const Key key : {Key::kEnter, Key::kTab, Key::kLeft, Key::kUp, Key::kDown, Key::kDelete,
                        Key::kHome, Key::kEnd, Key::kUnknown}) {
    EXPECT_EQ(shortcut(key), std::nullopt) << key_name(key);
  }
}

TEST(ViewerShortcuts, ReleasesAndAltTriggerNothing) {
  EXPECT_EQ(shortcut_for(KeyEvent{Key::kSpace, false, {}}, false), std::nullopt);
  EXPECT_EQ(shortcut_for(KeyEvent{Key::kP, false, kCtrl}, false), std::nullopt);
  EXPECT_EQ(shortcut_for(KeyEvent{Key::kEscape, false, {}}, false), std::nullopt);
  EXPECT_EQ(shortcut(Key::kSpace, kAlt), std::nullopt);
  EXPECT_EQ(shortcut(Key::kQ, Modifiers{true, false, true}), std::nullopt);
}

TEST(ViewerShortcuts, HelpListsEveryShortcut) {
  const std::vector<std::string> help = shortcut_help();
  ASSERT_EQ(help.size(), 10u);
  EXPECT_THAT(help[0], HasSubstr("Space"));
  EXPECT_THAT(help[0], HasSubstr("play / pause"));
  std::string all;
  for (const std::string& line : help) all += line + "\n";
  for (const char* text : {"Right", "Backspace", "F1", "Ctrl+P", "Ctrl+R", "Ctrl+O", "Ctrl+Q",
                           "Escape", "screenshot", "recording", "quit", "reset"}) {
    EXPECT_THAT(all, HasSubstr(text));
  }
}

TEST(ViewerKeys, NameRoundTripForEveryKey) {
  for (int k = static_cast<int>(Key::kSpace); k <= static_cast<int>(Key::k9); ++k) {
    const Key key = static_cast<Key>(k);
    EXPECT_EQ(key_from_name(key_name(key)), key) << key_name(key);
  }
}

TEST(ViewerKeys, Names) {
  EXPECT_EQ(key_name(Key::kSpace), "space");
  EXPECT_EQ(key_name(Key::kPageDown), "pagedown");
  EXPECT_EQ(key_name(Key::kF1), "f1");
  EXPECT_EQ(key_name(Key::kP), "p");
  EXPECT_EQ(key_name(Key::k7), "7");
  EXPECT_EQ(key_name(Key::kMinus), "minus");
  EXPECT_EQ(key_name(Key::kEquals), "equals");
  EXPECT_EQ(key_name(Key::kUnknown), "unknown");
}

TEST(ViewerKeys, AliasesAndCase) {
  EXPECT_EQ(key_from_name("SPACE"), Key::kSpace);
  EXPECT_EQ(key_from_name("PageUp"), Key::kPageUp);
  EXPECT_EQ(key_from_name("F1"), Key::kF1);
  EXPECT_EQ(key_from_name("Z"), Key::kZ);
  EXPECT_EQ(key_from_name("0"), Key::k0);
  EXPECT_EQ(key_from_name("-"), Key::kMinus);
  EXPECT_EQ(key_from_name("="), Key::kEquals);
  EXPECT_EQ(key_from_name("plus"), Key::kEquals);
  EXPECT_EQ(key_from_name("+"), Key::kEquals);
}

TEST(ViewerKeys, UnknownNames) {
  for (const char* name : {"", "unknown", "shift", "ctrl", "f2", "aa", "spacebar", " a", "!"}) {
    EXPECT_EQ(key_from_name(name), std::nullopt) << '"' << name << '"';
  }
}

TEST(ViewerKeys, Chords) {
  const std::optional<KeyEvent> p = parse_key_chord("ctrl+shift+p");
  ASSERT_TRUE(p);
  EXPECT_EQ(p->key, Key::kP);
  EXPECT_TRUE(p->down);
  EXPECT_EQ(p->modifiers, (Modifiers{true, true, false}));

  const std::optional<KeyEvent> f1 = parse_key_chord("Alt+F1");
  ASSERT_TRUE(f1);
  EXPECT_EQ(f1->key, Key::kF1);
  EXPECT_EQ(f1->modifiers, kAlt);

  const std::optional<KeyEvent> space = parse_key_chord("space");
  ASSERT_TRUE(space);
  EXPECT_EQ(space->key, Key::kSpace);
  EXPECT_EQ(space->modifiers, Modifiers{});

  // "+" is both the separator and a key name.
  const std::optional<KeyEvent> plus = parse_key_chord("ctrl++");
  ASSERT_TRUE(plus);
  EXPECT_EQ(plus->key, Key::kEquals);
  EXPECT_EQ(plus->modifiers, kCtrl);
  EXPECT_EQ(parse_key_chord("+")->key, Key::kEquals);
}

TEST(ViewerKeys, BadChords) {
  for (const char* text : {"", "ctrl", "ctrl+", "shift+", "ctrl+foo", "p+ctrl", "meta+p"}) {
    EXPECT_EQ(parse_key_chord(text), std::nullopt) << '"' << text << '"';
  }
}

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
  EXPECT_EQ(as<KeyEvent>(steps[0]).modifiers, kCtrl);
  EXPECT_EQ(as<KeyEvent>(steps[1]).key, Key::kP);
  EXPECT_FALSE(as<KeyEvent>(steps[1]).down);
  EXPECT_EQ(as<KeyEvent>(steps[1]).modifiers, kCtrl);
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
  EXPECT_EQ(as<KeyEvent>(steps[0]).modifiers, kShift);
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
  EXPECT_THAT(error_of("1 jump"), HasSubstr("screenshot or quit), got \"jump\""));
  EXPECT_THAT(error_of("1 KEY space"), HasSubstr("got \"KEY\""));
  EXPECT_THAT(error_of("1   # only a time"),
              HasSubstr("run.txt:1: expected a verb (key, keydown, keyup, type, move, click, "
                        "press, release, drag, wheel, drop, screenshot or quit), got end of line"));
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

// --- Dear ImGui ------------------------------------------------------------------------------

/// A real ImGui context with a fixed 400x300 panel at the top-left corner of an 800x600 window.
class ViewerImGuiInput : public ::testing::Test {
 protected:
  void SetUp() override {
    context_ = ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(800.0f, 600.0f);
    unsigned char* pixels = nullptr;
    int width = 0;
    int height = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
    configure_imgui_keys(io);
  }
  void TearDown() override { ImGui::DestroyContext(context_); }

  /// Feeds `events`, then runs one frame with `ui` inside the panel.
  template <class Ui>
  void frame(const std::vector<InputEvent>& events, Ui&& ui) {
    ImGuiIO& io = ImGui::GetIO();
    for (const InputEvent& event : events) input_.feed(io, event);
    io.DeltaTime = 1.0f / 60.0f;
    ImGui::NewFrame();
    ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f));
    ImGui::SetNextWindowSize(ImVec2(400.0f, 300.0f));
    ImGui::Begin("panel", nullptr,
                 ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove |
                     ImGuiWindowFlags_NoSavedSettings);
    ui();
    ImGui::End();
    ImGui::EndFrame();
    input_.end_frame(io);
  }

  /// A 100x40 button at the panel's top-left content corner (window padding 8 px):
  /// its centre is (58, 28). Returns how often it reported a click over the frames run.
  int button_clicks(const std::vector<std::vector<InputEvent>>& frames) {
    int clicks = 0;
    for (const auto& events : frames) {
      frame(events, [&] { clicks += ImGui::Button("Go", ImVec2(100.0f, 40.0f)) ? 1 : 0; });
    }
    return clicks;
  }

  ImGuiContext* context_ = nullptr;
  ImGuiInput input_;
};

TEST_F(ViewerImGuiInput, KeyMapPointsAtKeyCodes) {
  const ImGuiIO& io = ImGui::GetIO();
  EXPECT_EQ(io.KeyMap[ImGuiKey_Tab], static_cast<int>(Key::kTab));
  EXPECT_EQ(io.KeyMap[ImGuiKey_Backspace], static_cast<int>(Key::kBackspace));
  EXPECT_EQ(io.KeyMap[ImGuiKey_Enter], static_cast<int>(Key::kEnter));
  EXPECT_EQ(io.KeyMap[ImGuiKey_KeyPadEnter], static_cast<int>(Key::kEnter));
  EXPECT_EQ(io.KeyMap[ImGuiKey_A], static_cast<int>(Key::kA));
  EXPECT_EQ(io.KeyMap[ImGuiKey_Z], static_cast<int>(Key::kZ));
}

TEST_F(ViewerImGuiInput, ClickWithinOneFramePressesAButton) {
  const std::vector<InputEvent> click = {MouseButtonEvent{0, true, 58.0f, 28.0f},
                                         MouseButtonEvent{0, false, 58.0f, 28.0f}};
  // Two settling frames, the click's frame, then frames for the release to register.
  EXPECT_EQ(button_clicks({{}, {}, click, {}, {}}), 1);
  EXPECT_FALSE(ImGui::GetIO().MouseDown[0]);
}

TEST_F(ViewerImGuiInput, PressAndReleaseInSeparateFramesPressAButton) {
  EXPECT_EQ(button_clicks({{},
                           {},
                           {MouseButtonEvent{0, true, 58.0f, 28.0f}},
                           {MouseButtonEvent{0, false, 58.0f, 28.0f}},
                           {}}),
            1);
}

TEST_F(ViewerImGuiInput, ClickBesideTheButtonMissesIt) {
  const std::vector<InputEvent> click = {MouseButtonEvent{0, true, 200.0f, 28.0f},
                                         MouseButtonEvent{0, false, 200.0f, 28.0f}};
  EXPECT_EQ(button_clicks({{}, {}, click, {}, {}}), 0);
}

TEST_F(ViewerImGuiInput, LatchHoldsTheButtonForOneFrame) {
  ImGuiIO& io = ImGui::GetIO();
  // A release in the frame of its press keeps the button down until end_frame().
  input_.feed(io, MouseButtonEvent{1, true, 3.0f, 4.0f});
  input_.feed(io, MouseButtonEvent{1, false, 3.0f, 4.0f});
  EXPECT_TRUE(io.MouseDown[1]);
  EXPECT_EQ(io.MousePos.x, 3.0f);
  EXPECT_EQ(io.MousePos.y, 4.0f);
  input_.end_frame(io);
  EXPECT_FALSE(io.MouseDown[1]);
  // A release in a later frame applies at once.
  input_.feed(io, MouseButtonEvent{2, true, 0.0f, 0.0f});
  input_.end_frame(io);
  EXPECT_TRUE(io.MouseDown[2]);
  input_.feed(io, MouseButtonEvent{2, false, 0.0f, 0.0f});
  EXPECT_FALSE(io.MouseDown[2]);
}

TEST_F(ViewerImGuiInput, MovesAndWheel) {
  ImGuiIO& io = ImGui::GetIO();
  input_.feed(io, MouseMoveEvent{120.0f, 45.5f});
  EXPECT_EQ(io.MousePos.x, 120.0f);
  EXPECT_EQ(io.MousePos.y, 45.5f);
  input_.feed(io, WheelEvent{1.0f});
  input_.feed(io, WheelEvent{0.5f});
  EXPECT_EQ(io.MouseWheel, 1.5f);
}

TEST_F(ViewerImGuiInput, ModifiersFollowKeyEvents) {
  ImGuiIO& io = ImGui::GetIO();
  input_.feed(io, KeyEvent{Key::kUnknown, true, Modifiers{true, false, true}});
  EXPECT_TRUE(io.KeyCtrl);
  EXPECT_FALSE(io.KeyShift);
  EXPECT_TRUE(io.KeyAlt);
  frame({}, [] {});
  EXPECT_EQ(io.KeyMods, ImGuiKeyModFlags_Ctrl | ImGuiKeyModFlags_Alt);
  input_.feed(io, KeyEvent{Key::kUnknown, false, kShift});
  EXPECT_FALSE(io.KeyCtrl);
  EXPECT_TRUE(io.KeyShift);
  EXPECT_FALSE(io.KeyAlt);
}

TEST_F(ViewerImGuiInput, KeyStrokeWithinOneFrameIsSeen) {
  ImGuiIO& io = ImGui::GetIO();
  bool pressed = false;
  frame({KeyEvent{Key::kEnter, true, {}}, KeyEvent{Key::kEnter, false, {}}},
        [&] { pressed = ImGui::IsKeyPressed(static_cast<int>(Key::kEnter)); });
  EXPECT_TRUE(pressed);
  EXPECT_FALSE(io.KeysDown[static_cast<int>(Key::kEnter)]);
  frame({}, [&] { pressed = ImGui::IsKeyPressed(static_cast<int>(Key::kEnter)); });
  EXPECT_FALSE(pressed);
}

TEST_F(ViewerImGuiInput, TypingEditsATextField) {
  char text[64] = "";
  bool entered = false;
  const auto field = [&] {
    if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
    entered |= ImGui::InputText("name", text, sizeof text, ImGuiInputTextFlags_EnterReturnsTrue);
  };
  const auto keys = [](const std::string& chord) {
    std::vector<InputEvent> events;
    for (const ScriptStep& step : parse_script("0 key " + chord, "keys")) {
      events.push_back(std::get<InputEvent>(step.action));
    }
    return events;
  };
  frame({}, field);
  frame({}, field);
  frame({TextEvent{"hello"}}, field);
  frame({}, field);
  EXPECT_STREQ(text, "hello");
  // Script strokes arrive within one frame: the latch lets ImGui see them.
  frame(keys("backspace"), field);
  frame({}, field);
  EXPECT_STREQ(text, "hell");
  // Ctrl+A selects all (ctrl must still be held when ImGui sees the A), typing replaces it.
  frame(keys("ctrl+a"), field);
  EXPECT_FALSE(ImGui::GetIO().KeyCtrl);
  frame({TextEvent{"\xc3\xa9t\xc3\xa9"}}, field);  // "été": UTF-8 reaches the field
  frame({}, field);
  EXPECT_STREQ(text, "\xc3\xa9t\xc3\xa9");
  EXPECT_FALSE(entered);
  frame(keys("enter"), field);
  EXPECT_TRUE(entered);
}

}  // namespace
}  // namespace tumble::app::viewer
