// The viewer's keys: names, chords, shortcuts, and their delivery to Dear ImGui (1.86, whose
// input API is the array one: io.KeyMap indexes io.KeysDown, here by our Key codes).
#include "app/viewer/viewer_input.hpp"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <utility>

namespace tumble::app::viewer {
namespace {

/// The last Key code; letters and digits are contiguous runs ending before it.
constexpr Key kLastKey = Key::k9;

/// Key codes as indices into io.KeysDown and the latch arrays.
int key_index(Key key) {
  return static_cast<int>(key);
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

/// Names of the keys that are not letters or digits; the first name of a key is its own.
constexpr std::array<std::pair<const char*, Key>, 23> kNamedKeys = {{
    {"space", Key::kSpace},
    {"enter", Key::kEnter},
    {"escape", Key::kEscape},
    {"tab", Key::kTab},
    {"backspace", Key::kBackspace},
    {"delete", Key::kDelete},
    {"insert", Key::kInsert},
    {"left", Key::kLeft},
    {"right", Key::kRight},
    {"up", Key::kUp},
    {"down", Key::kDown},
    {"home", Key::kHome},
    {"end", Key::kEnd},
    {"pageup", Key::kPageUp},
    {"pagedown", Key::kPageDown},
    {"minus", Key::kMinus},
    {"-", Key::kMinus},
    {"equals", Key::kEquals},
    {"=", Key::kEquals},
    {"plus", Key::kEquals},
    {"+", Key::kEquals},
    {"f1", Key::kF1},
    {"unknown", Key::kUnknown},
}};

/// The help line of each shortcut, in the order the overlay lists them.
constexpr std::array<const char*, 10> kHelpLines = {
    "Space      play / pause",
    "Right      one step (pauses)",
    "Backspace  reset to the initial state",
    "-          half speed",
    "= or +     double speed",
    "F1         show / hide this help",
    "Ctrl+P     screenshot",
    "Ctrl+R     start / stop recording",
    "Ctrl+O     open a scene",
    "Ctrl+Q     quit (Escape also closes the help first)",
};

}  // namespace

std::optional<Shortcut> shortcut_for(const KeyEvent& event, bool help_shown) {
  if (!event.down || event.modifiers.alt) return std::nullopt;
  // Ctrl chords: the only shortcuts on letters.
  if (event.modifiers.ctrl) {
    switch (event.key) {
      case Key::kP:
        return Shortcut::kScreenshot;
      case Key::kR:
        return Shortcut::kToggleRecord;
      case Key::kO:
        return Shortcut::kOpen;
      case Key::kQ:
        return Shortcut::kQuit;
      default:
        return std::nullopt;
    }
  }
  // Plain keys (shift allowed: + is shift+= on many keyboards).
  switch (event.key) {
    case Key::kSpace:
      return Shortcut::kTogglePause;
    case Key::kRight:
      return Shortcut::kStep;
    case Key::kBackspace:
      return Shortcut::kReset;
    case Key::kMinus:
      return Shortcut::kSlower;
    case Key::kEquals:
      return Shortcut::kFaster;
    case Key::kF1:
      return Shortcut::kToggleHelp;
    case Key::kEscape:
      return help_shown ? Shortcut::kToggleHelp : Shortcut::kQuit;
    default:
      return std::nullopt;
  }
}

std::vector<std::string> shortcut_help() {
  return std::vector<std::string>(kHelpLines.begin(), kHelpLines.end());
}

std::optional<Key> key_from_name(const std::string& name) {
  const std::string wanted = lower(name);
  // Single letters and digits.
  if (wanted.size() == 1 && wanted[0] >= 'a' && wanted[0] <= 'z') {
    return static_cast<Key>(key_index(Key::kA) + (wanted[0] - 'a'));
  }
  if (wanted.size() == 1 && wanted[0] >= '0' && wanted[0] <= '9') {
    return static_cast<Key>(key_index(Key::k0) + (wanted[0] - '0'));
  }
  // Named keys ("unknown" is only an output name).
  for (const auto& [key_text, key] : kNamedKeys) {
    if (wanted == key_text && key != Key::kUnknown) return key;
  }
  return std::nullopt;
}

std::string key_name(Key key) {
  if (key_index(key) >= key_index(Key::kA) && key_index(key) <= key_index(Key::kZ)) {
    return std::string(1, static_cast<char>('a' + (key_index(key) - key_index(Key::kA))));
  }
  if (key_index(key) >= key_index(Key::k0) && key_index(key) <= key_index(Key::k9)) {
    return std::string(1, static_cast<char>('0' + (key_index(key) - key_index(Key::k0))));
  }
  for (const auto& [key_text, named] : kNamedKeys) {
    if (named == key) return key_text;
  }
  return "unknown";
}

std::optional<KeyEvent> parse_key_chord(const std::string& text) {
  KeyEvent event;
  std::string rest = lower(text);
  // Leading "MODIFIER+" prefixes; what remains is one key name (which may itself be "+").
  for (bool found = true; found;) {
    found = false;
    for (const auto& [prefix, flag] :
         {std::pair{"ctrl+", &Modifiers::ctrl}, std::pair{"shift+", &Modifiers::shift},
          std::pair{"alt+", &Modifiers::alt}}) {
      const std::string p = prefix;
      if (rest.size() > p.size() && rest.compare(0, p.size(), p) == 0) {
        event.modifiers.*flag = true;
        rest.erase(0, p.size());
        found = true;
      }
    }
  }
  const std::optional<Key> key = key_from_name(rest);
  if (!key) return std::nullopt;
  event.key = *key;
  return event;
}

void configure_imgui_keys(ImGuiIO& io) {
  static_assert(static_cast<int>(kLastKey) < 512, "Key codes index io.KeysDown[512]");
  const std::array<std::pair<ImGuiKey, Key>, ImGuiKey_COUNT> map = {{
      {ImGuiKey_Tab, Key::kTab},
      {ImGuiKey_LeftArrow, Key::kLeft},
      {ImGuiKey_RightArrow, Key::kRight},
      {ImGuiKey_UpArrow, Key::kUp},
      {ImGuiKey_DownArrow, Key::kDown},
      {ImGuiKey_PageUp, Key::kPageUp},
      {ImGuiKey_PageDown, Key::kPageDown},
      {ImGuiKey_Home, Key::kHome},
      {ImGuiKey_End, Key::kEnd},
      {ImGuiKey_Insert, Key::kInsert},
      {ImGuiKey_Delete, Key::kDelete},
      {ImGuiKey_Backspace, Key::kBackspace},
      {ImGuiKey_Space, Key::kSpace},
      {ImGuiKey_Enter, Key::kEnter},
      {ImGuiKey_Escape, Key::kEscape},
      {ImGuiKey_KeyPadEnter, Key::kEnter},
      {ImGuiKey_A, Key::kA},
      {ImGuiKey_C, Key::kC},
      {ImGuiKey_V, Key::kV},
      {ImGuiKey_X, Key::kX},
      {ImGuiKey_Y, Key::kY},
      {ImGuiKey_Z, Key::kZ},
  }};
  for (const auto& [imgui_key, key] : map) io.KeyMap[imgui_key] = key_index(key);
}

void ImGuiInput::feed(ImGuiIO& io, const InputEvent& event) {
  static_assert(static_cast<int>(kLastKey) < kKeySlots, "the key latch must hold every Key");
  const auto set_modifiers = [&](const Modifiers& modifiers) {
    // After a latched key release, modifier changes wait for it (ctrl+a stays ctrl+a).
    if (std::any_of(std::begin(key_pending_release_), std::end(key_pending_release_),
                    [](bool pending) { return pending; })) {
      pending_modifiers_ = modifiers;
      return;
    }
    io.KeyCtrl = modifiers.ctrl;
    io.KeyShift = modifiers.shift;
    io.KeyAlt = modifiers.alt;
  };

  // Keys: press, release now, or release at end_frame() when pressed in this frame.
  if (const auto* key = std::get_if<KeyEvent>(&event)) {
    const int index = key_index(key->key);
    if (key->key != Key::kUnknown) {
      if (key->down) {
        io.KeysDown[index] = true;
        key_pressed_[index] = true;
        key_pending_release_[index] = false;
      } else if (key_pressed_[index]) {
        key_pending_release_[index] = true;
      } else {
        io.KeysDown[index] = false;
      }
    }
    set_modifiers(key->modifiers);
    return;
  }
  // Text for the focused text field.
  if (const auto* text = std::get_if<TextEvent>(&event)) {
    io.AddInputCharactersUTF8(text->text.c_str());
    return;
  }
  // Pointer moves.
  if (const auto* move = std::get_if<MouseMoveEvent>(&event)) {
    io.MousePos = ImVec2(move->x, move->y);
    return;
  }
  // Buttons: same latch as keys.
  if (const auto* button = std::get_if<MouseButtonEvent>(&event)) {
    io.MousePos = ImVec2(button->x, button->y);
    if (button->button < 0 || button->button > 2) return;
    const int b = button->button;
    if (button->down) {
      io.MouseDown[b] = true;
      pressed_[b] = true;
      pending_release_[b] = false;
    } else if (pressed_[b]) {
      pending_release_[b] = true;
    } else {
      io.MouseDown[b] = false;
    }
    return;
  }
  // Wheel notches accumulate until the next frame.
  if (const auto* wheel = std::get_if<WheelEvent>(&event)) {
    io.MouseWheel += wheel->dy;
  }
}

void ImGuiInput::end_frame(ImGuiIO& io) {
  // Latched buttons and keys go up now that ImGui has seen them down for a frame.
  for (int b = 0; b < 3; ++b) {
    if (pending_release_[b]) io.MouseDown[b] = false;
    pending_release_[b] = false;
    pressed_[b] = false;
  }
  for (int k = 0; k < kKeySlots; ++k) {
    if (key_pending_release_[k]) io.KeysDown[k] = false;
    key_pending_release_[k] = false;
    key_pressed_[k] = false;
  }
  // Modifier changes that waited for them.
  if (pending_modifiers_) {
    io.KeyCtrl = pending_modifiers_->ctrl;
    io.KeyShift = pending_modifiers_->shift;
    io.KeyAlt = pending_modifiers_->alt;
    pending_modifiers_.reset();
  }
}

}  // namespace tumble::app::viewer
