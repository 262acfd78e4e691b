#pragma once
/// @file The viewer's input, independent of any window system: key, mouse, text and file-drop
/// events, the keyboard shortcuts they trigger, their delivery to Dear ImGui, and `--script`
/// files of timed events (how the viewer is driven in tests, through the same path as a user).
///
/// The SDL window translates its events into these; a script's events are injected into the
/// same stream, so everything after translation is exercised by a scripted run.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <variant>
#include <vector>

struct ImGuiIO;

namespace tumble::app::viewer {

/// Keys the viewer or ImGui's text fields use.
enum class Key {
  kUnknown,
  kSpace,
  kEnter,
  kEscape,
  kTab,
  kBackspace,
  kDelete,
  kInsert,
  kLeft,
  kRight,
  kUp,
  kDown,
  kHome,
  kEnd,
  kPageUp,
  kPageDown,
  kMinus,   ///< also keypad minus
  kEquals,  ///< also keypad plus: "faster" on keyboards where + needs shift
  kF1,
  kA,
  kB,
  kC,
  kD,
  kE,
  kF,
  kG,
  kH,
  kI,
  kJ,
  kK,
  kL,
  kM,
  kN,
  kO,
  kP,
  kQ,
  kR,
  kS,
  kT,
  kU,
  kV,
  kW,
  kX,
  kY,
  kZ,
  k0,
  k1,
  k2,
  k3,
  k4,
  k5,
  k6,
  k7,
  k8,
  k9,
};

struct Modifiers {
  bool ctrl = false;
  bool shift = false;
  bool alt = false;
  friend bool operator==(const Modifiers&, const Modifiers&) = default;
};

struct KeyEvent {
  Key key = Key::kUnknown;
  bool down = true;
  Modifiers modifiers;
};
/// Typed text (UTF-8), for ImGui's text fields.
struct TextEvent {
  std::string text;
};
/// Pointer position in window pixels, origin at the top-left corner.
struct MouseMoveEvent {
  float x = 0.0f;
  float y = 0.0f;
};
/// button: 0 left, 1 right, 2 middle. Carries the position so a click needs no prior move.
struct MouseButtonEvent {
  int button = 0;
  bool down = true;
  float x = 0.0f;
  float y = 0.0f;
};
/// Wheel turned by `dy` notches (positive: away from the user, zoom in).
struct WheelEvent {
  float dy = 0.0f;
};
/// A file dropped on the window.
struct DropEvent {
  std::filesystem::path path;
};
/// The window was closed.
struct QuitEvent {};

using InputEvent = std::variant<KeyEvent, TextEvent, MouseMoveEvent, MouseButtonEvent, WheelEvent,
                                DropEvent, QuitEvent>;

/// What a keyboard shortcut asks the viewer to do.
enum class Shortcut {
  kTogglePause,   ///< Space (at the end of the run: from the start again)
  kStep,          ///< Right: one dt step (pauses first)
  kReset,         ///< Backspace: back to the initial state
  kSlower,        ///< -: halve the time scale
  kFaster,        ///< = or +: double the time scale
  kToggleHelp,    ///< F1
  kScreenshot,    ///< Ctrl+P
  kToggleRecord,  ///< Ctrl+R
  kOpen,          ///< Ctrl+O: focus the open-file field
  kQuit,          ///< Ctrl+Q or Escape (Escape closes the help first when it is shown)
};

/// The shortcut a key press triggers, if any (key releases trigger nothing). Ctrl-less letters
/// and digits trigger nothing, so they stay free for ImGui's text fields.
std::optional<Shortcut> shortcut_for(const KeyEvent& event, bool help_shown);

/// One line per shortcut, "Space  play / pause", for the help overlay.
std::vector<std::string> shortcut_help();

/// The key named `name` as scripts write it (case-insensitive): "space", "enter", "escape",
/// "tab", "backspace", "delete", "insert", "left", "right", "up", "down", "home", "end",
/// "pageup", "pagedown", "minus" or "-", "equals" or "=" or "plus" or "+", "f1", "a".."z",
/// "0".."9". Nothing for an unknown name.
std::optional<Key> key_from_name(const std::string& name);
/// The script name of `key` ("space", "f1", "p", ...).
std::string key_name(Key key);

/// Parses "ctrl+shift+p" style chords (modifiers ctrl, shift, alt, then one key name).
std::optional<KeyEvent> parse_key_chord(const std::string& text);

// --- Dear ImGui ------------------------------------------------------------------------------

/// Sets ImGui's key map (io.KeyMap) for the Key codes fed by feed_imgui. Call once per context.
void configure_imgui_keys(ImGuiIO& io);

/// Applies one event to ImGui's input state (io.MousePos, io.MouseDown, io.MouseWheel,
/// io.KeysDown, io.KeyCtrl/KeyShift/KeyAlt, io.AddInputCharacter*). Mouse button and key presses
/// are latched so a press and release within one frame still register as a click (or a key
/// stroke, as a script's `key enter` gives): call end_frame() after ImGui::NewFrame() to release
/// latched buttons and keys. Modifier changes that follow a latched key release wait with it.
class ImGuiInput {
 public:
  void feed(ImGuiIO& io, const InputEvent& event);
  /// Releases buttons and keys whose release arrived in the same frame as their press.
  void end_frame(ImGuiIO& io);

 private:
  static constexpr int kKeySlots = 64;       ///< > the largest Key code
  bool pressed_[3] = {false, false, false};  ///< pressed since the last end_frame()
  bool pending_release_[3] = {false, false, false};
  bool key_pressed_[kKeySlots] = {};
  bool key_pending_release_[kKeySlots] = {};
  std::optional<Modifiers> pending_modifiers_;
};

// --- Scripts ----------------------------------------------------------------------------------

/// A request a script makes that is not user input.
struct ScreenshotRequest {
  std::filesystem::path path;  ///< PNG; relative paths are against the working directory
};

/// A script's request to resize the window (as a user dragging its border would; the window
/// system then reports the new size as for any resize).
struct ResizeRequest {
  int width = 0;  ///< pixels, 1 to 8192
  int height = 0;
};

/// One timed step of a script.
struct ScriptStep {
  double time = 0.0;  ///< seconds of wall-clock time since the viewer started
  std::variant<InputEvent, ScreenshotRequest, ResizeRequest> action;
};

/// Parses a script. One step per line, `TIME VERB ARGS...`, times in seconds, non-decreasing;
/// `#` starts a comment; blank lines are skipped. Verbs:
///   key CHORD            press and release (e.g. `key space`, `key ctrl+p`)
///   keydown CHORD / keyup CHORD
///   type TEXT            the rest of the line as typed text
///   move X Y             pointer to window pixel (X, Y)
///   click X Y [BUTTON]   move there and press at TIME, release 50 ms later (BUTTON: left,
///                        right, middle)
///   press X Y [BUTTON] / release X Y [BUTTON]   move there, then the button
///   drag X1 Y1 X2 Y2 [BUTTON]   move to X1 Y1, press, ten moves over 0.2 s, release
///   wheel DY             wheel notches (positive zooms in)
///   drop PATH            a file dropped on the window (rest of the line)
///   screenshot PATH      writes what the window shows to PATH (PNG; rest of the line)
///   resize W H           asks for a W x H window (whole pixels, 1 to 8192)
///   quit                 closes the viewer
/// Steps are returned sorted by time (stable). Throws tumble::InputError naming `file`, the
/// line number and what was expected, e.g. `run.txt:3: expected a number for X, got "a"`.
std::vector<ScriptStep> parse_script(const std::string& text, const std::filesystem::path& file);

/// Reads and parses a script file (throws tumble::InputError naming the file when unreadable).
std::vector<ScriptStep> load_script(const std::filesystem::path& file);

/// Hands out a script's steps as the clock passes their times.
class ScriptPlayer {
 public:
  explicit ScriptPlayer(std::vector<ScriptStep> steps);
  /// The steps whose time is <= `now` that were not handed out yet, in order. A mouse button
  /// change is handed out alone, in a call of its own: the steps before it (the pointer's
  /// move) reach ImGui a frame earlier, so it knows what is under the pointer, as with a real
  /// mouse.
  std::vector<ScriptStep> due(double now);
  bool finished() const { return next_ == steps_.size(); }

 private:
  std::vector<ScriptStep> steps_;
  std::size_t next_ = 0;
};

}  // namespace tumble::app::viewer
