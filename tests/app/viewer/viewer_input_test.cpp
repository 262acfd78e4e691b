#include "app/viewer/viewer_input.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
// tumble_app_lib links ImGui privately, so its include directory does not reach the tests.
#include <imgui/imgui.h>

#include <cstring>

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
