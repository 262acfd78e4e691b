// `--script` files: timed input for the viewer, parsed into the same events the window produces.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <system_error>

#include "app/scene/render_settings.hpp"
#include "app/support/text_file.hpp"
#include "app/viewer/viewer_input.hpp"
#include "base/errors.hpp"

namespace tumble::app::viewer {
namespace {

using tumble::InputError;

/// A click's release follows its press by this long (s).
constexpr double kClickSeconds = 0.05;
/// A drag takes this long (s), in this many pointer moves.
constexpr double kDragSeconds = 0.2;
constexpr int kDragMoves = 10;

constexpr const char* kVerbs =
    "key, keydown, keyup, type, move, click, press, release, drag, wheel, drop, screenshot, "
    "resize or quit";

bool is_blank(char c) {
  return std::isspace(static_cast<unsigned char>(c)) != 0;
}

/// `text` without the comment: `#` at the start or after a blank (so `type C#` types "C#").
std::string without_comment(const std::string& text) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '#' && (i == 0 || is_blank(text[i - 1]))) return text.substr(0, i);
  }
  return text;
}

/// `text` as a finite number, if it is one in full.
std::optional<double> to_number(const std::string& text) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  if (error != std::errc() || stop != end) return std::nullopt;
  return value;
}

/// Reads one script line word by word; every error names the file and line.
class LineReader {
 public:
  LineReader(const std::filesystem::path& file, std::size_t number, std::string text)
      : file_(file), number_(number), text_(std::move(text)) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(file_.string() + ":" + std::to_string(number_) + ": " + what);
  }
  [[noreturn]] void fail(const std::string& expected, const std::optional<std::string>& got) const {
    fail("expected " + expected + ", got " + (got ? "\"" + *got + "\"" : "end of line"));
  }

  /// Whether only blanks remain.
  bool at_end() {
    skip_blanks();
    return position_ == text_.size();
  }

  /// The next blank-separated word, if any.
  std::optional<std::string> word() {
    if (at_end()) return std::nullopt;
    const std::size_t start = position_;
    while (position_ < text_.size() && !is_blank(text_[position_])) ++position_;
    return text_.substr(start, position_ - start);
  }

  /// The rest of the line without surrounding blanks; fails when it is empty.
  std::string rest(const std::string& expected) {
    if (at_end()) fail(expected, std::nullopt);
    std::size_t stop = text_.size();
    while (stop > position_ && is_blank(text_[stop - 1])) --stop;
    std::string value = text_.substr(position_, stop - position_);
    position_ = text_.size();
    return value;
  }

  /// The next word as a finite number; `name` says what it is (X, DY, ...).
  double number(const std::string& name) {
    const std::optional<std::string> text = word();
    const std::optional<double> value = text ? to_number(*text) : std::nullopt;
    if (!value || !std::isfinite(*value)) fail("a number for " + name, text);
    return *value;
  }

  /// The next word as a whole number of pixels from 1 to kMaxImageSide; `name` says which side.
  int pixels(const std::string& name) {
    const std::optional<std::string> text = word();
    const std::optional<double> value = text ? to_number(*text) : std::nullopt;
    if (!value || !(*value >= 1.0 && *value <= kMaxImageSide) || std::floor(*value) != *value) {
      fail("a whole number of pixels from 1 to " + std::to_string(kMaxImageSide) + " for " + name,
           text);
    }
    return static_cast<int>(*value);
  }

  /// The optional BUTTON word ending a mouse step (left when absent).
  int button() {
    const std::optional<std::string> text = word();
    if (!text || *text == "left") return 0;
    if (*text == "right") return 1;
    if (*text == "middle") return 2;
    fail("a button (left, right or middle)", text);
  }

  /// The next word as a key chord.
  KeyEvent chord() {
    const std::optional<std::string> text = word();
    const std::optional<KeyEvent> event = text ? parse_key_chord(*text) : std::nullopt;
    if (!event) fail("a key chord such as space or ctrl+p", text);
    return *event;
  }

  /// Fails when anything but blanks remains; `usage` is the verb's form.
  void finish(const std::string& usage) {
    if (!at_end()) fail("end of line after \"" + usage + "\"", word());
  }

 private:
  void skip_blanks() {
    while (position_ < text_.size() && is_blank(text_[position_])) ++position_;
  }

  const std::filesystem::path& file_;
  std::size_t number_;
  std::string text_;
  std::size_t position_ = 0;
};

void add_event(std::vector<ScriptStep>& steps, double at, InputEvent event) {
  steps.push_back({at, std::move(event)});
}

/// Keys: a stroke is press, release, then the modifiers let go.
void parse_key(LineReader& line, const std::string& verb, double time,
               std::vector<ScriptStep>& steps) {
  KeyEvent event = line.chord();
  line.finish(verb + " CHORD");
  if (verb != "keyup") add_event(steps, time, event);
  if (verb != "keydown") {
    event.down = false;
    add_event(steps, time, event);
  }
  if (verb == "key" && event.modifiers != Modifiers{}) {
    add_event(steps, time, KeyEvent{Key::kUnknown, false, Modifiers{}});
  }
}

/// Buttons: click is press and release 50 ms apart at one place.
void parse_button(LineReader& line, const std::string& verb, double time,
                  std::vector<ScriptStep>& steps) {
  const auto x = static_cast<float>(line.number("X"));
  const auto y = static_cast<float>(line.number("Y"));
  const int button = line.button();
  line.finish(verb + " X Y [BUTTON]");
  // The pointer gets there first, so ImGui knows what is under it when the button changes.
  add_event(steps, time, MouseMoveEvent{x, y});
  if (verb != "release") add_event(steps, time, MouseButtonEvent{button, true, x, y});
  if (verb != "press") {
    add_event(steps, verb == "click" ? time + kClickSeconds : time,
              MouseButtonEvent{button, false, x, y});
  }
}

/// Drag: press at the start, evenly spaced moves to the end, release there.
void parse_drag(LineReader& line, double time, std::vector<ScriptStep>& steps) {
  const double x1 = line.number("X1");
  const double y1 = line.number("Y1");
  const double x2 = line.number("X2");
  const double y2 = line.number("Y2");
  const int button = line.button();
  line.finish("drag X1 Y1 X2 Y2 [BUTTON]");
  add_event(steps, time, MouseMoveEvent{static_cast<float>(x1), static_cast<float>(y1)});
  add_event(steps, time,
            MouseButtonEvent{button, true, static_cast<float>(x1), static_cast<float>(y1)});
  for (int i = 1; i <= kDragMoves; ++i) {
    const double f = static_cast<double>(i) / kDragMoves;
    add_event(steps, time + f * kDragSeconds,
              MouseMoveEvent{static_cast<float>(x1 + f * (x2 - x1)),
                             static_cast<float>(y1 + f * (y2 - y1))});
  }
  add_event(steps, time + kDragSeconds,
            MouseButtonEvent{button, false, static_cast<float>(x2), static_cast<float>(y2)});
}

/// Appends the steps of one line (`time` and verb already read).
void parse_action(LineReader& line, const std::string& verb, double time,
                  std::vector<ScriptStep>& steps) {
  if (verb == "key" || verb == "keydown" || verb == "keyup") {
    parse_key(line, verb, time, steps);
    return;
  }
  // Text, dropped files and screenshots take the rest of the line.
  if (verb == "type") {
    add_event(steps, time, TextEvent{line.rest("text for type")});
    return;
  }
  if (verb == "drop") {
    add_event(steps, time, DropEvent{line.rest("a path for drop")});
    return;
  }
  if (verb == "screenshot") {
    steps.push_back({time, ScreenshotRequest{line.rest("a path for screenshot")}});
    return;
  }
  // Pointer and wheel.
  if (verb == "move") {
    const double x = line.number("X");
    const double y = line.number("Y");
    line.finish("move X Y");
    add_event(steps, time, MouseMoveEvent{static_cast<float>(x), static_cast<float>(y)});
    return;
  }
  if (verb == "wheel") {
    const double dy = line.number("DY");
    line.finish("wheel DY");
    add_event(steps, time, WheelEvent{static_cast<float>(dy)});
    return;
  }
  if (verb == "click" || verb == "press" || verb == "release") {
    parse_button(line, verb, time, steps);
    return;
  }
  if (verb == "drag") {
    parse_drag(line, time, steps);
    return;
  }
  if (verb == "resize") {
    const int width = line.pixels("W");
    const int height = line.pixels("H");
    line.finish("resize W H");
    steps.push_back({time, ResizeRequest{width, height}});
    return;
  }
  if (verb == "quit") {
    line.finish("quit");
    add_event(steps, time, QuitEvent{});
    return;
  }
  line.fail(std::string("a verb (") + kVerbs + ")", verb);
}

bool is_button_step(const ScriptStep& step) {
  const auto* event = std::get_if<InputEvent>(&step.action);
  return event != nullptr && std::holds_alternative<MouseButtonEvent>(*event);
}

}  // namespace

std::vector<ScriptStep> parse_script(const std::string& text, const std::filesystem::path& file) {
  std::vector<ScriptStep> steps;
  std::istringstream in(text);
  double previous_time = 0.0;
  std::size_t number = 0;
  for (std::string raw; std::getline(in, raw);) {
    LineReader line(file, ++number, without_comment(raw));
    if (line.at_end()) continue;

    // The time: a finite, non-negative number of seconds, never before the previous line's.
    const std::optional<std::string> time_text = line.word();
    const std::optional<double> time = to_number(*time_text);
    if (!time) line.fail("a time in seconds", time_text);
    if (!std::isfinite(*time)) line.fail("a finite time in seconds", time_text);
    if (*time < 0.0) line.fail("a time >= 0 seconds", time_text);
    if (*time < previous_time) {
      std::ostringstream expected;
      expected << "a time >= " << previous_time << " (times must not decrease)";
      line.fail(expected.str(), time_text);
    }
    previous_time = *time;

    // The verb and its arguments.
    const std::optional<std::string> verb = line.word();
    if (!verb) line.fail(std::string("a verb (") + kVerbs + ")", std::nullopt);
    parse_action(line, *verb, *time, steps);
  }
  // Expanded steps (a click's release, a drag's moves) may fall after later lines.
  std::stable_sort(steps.begin(), steps.end(),
                   [](const ScriptStep& a, const ScriptStep& b) { return a.time < b.time; });
  return steps;
}

std::vector<ScriptStep> load_script(const std::filesystem::path& file) {
  return parse_script(read_text_file(file, "script"), file);
}

ScriptPlayer::ScriptPlayer(std::vector<ScriptStep> steps) : steps_(std::move(steps)) {}

std::vector<ScriptStep> ScriptPlayer::due(double now) {
  std::vector<ScriptStep> out;
  // Hand out due steps; a button change gets a frame of its own, so ImGui has seen the pointer
  // where it is (from the steps before) when the button goes down or up.
  while (next_ < steps_.size() && steps_[next_].time <= now) {
    if (is_button_step(steps_[next_]) && !out.empty()) break;
    out.push_back(steps_[next_++]);
    if (is_button_step(out.back())) break;
  }
  return out;
}

}  // namespace tumble::app::viewer
