// SDL's events as the viewer's input.
#include "sdl_input.hpp"

#include <SDL.h>

#include <optional>

namespace tumble::app {
namespace {

using viewer::InputEvent;
using viewer::Key;

/// SDL's key code as the viewer's Key.
Key key_from_sdl(SDL_Keycode code) {
  if (code >= SDLK_a && code <= SDLK_z) {
    return static_cast<Key>(static_cast<int>(Key::kA) + static_cast<int>(code - SDLK_a));
  }
  if (code >= SDLK_0 && code <= SDLK_9) {
    return static_cast<Key>(static_cast<int>(Key::k0) + static_cast<int>(code - SDLK_0));
  }
  switch (code) {
    case SDLK_SPACE:
      return Key::kSpace;
    case SDLK_RETURN:
      return Key::kEnter;
    case SDLK_KP_ENTER:
      return Key::kEnter;
    case SDLK_ESCAPE:
      return Key::kEscape;
    case SDLK_TAB:
      return Key::kTab;
    case SDLK_BACKSPACE:
      return Key::kBackspace;
    case SDLK_DELETE:
      return Key::kDelete;
    case SDLK_INSERT:
      return Key::kInsert;
    case SDLK_LEFT:
      return Key::kLeft;
    case SDLK_RIGHT:
      return Key::kRight;
    case SDLK_UP:
      return Key::kUp;
    case SDLK_DOWN:
      return Key::kDown;
    case SDLK_HOME:
      return Key::kHome;
    case SDLK_END:
      return Key::kEnd;
    case SDLK_PAGEUP:
      return Key::kPageUp;
    case SDLK_PAGEDOWN:
      return Key::kPageDown;
    case SDLK_MINUS:
      return Key::kMinus;
    case SDLK_KP_MINUS:
      return Key::kMinus;
    case SDLK_EQUALS:
      return Key::kEquals;
    case SDLK_PLUS:
      return Key::kEquals;
    case SDLK_KP_PLUS:
      return Key::kEquals;
    case SDLK_F1:
      return Key::kF1;
    default:
      return Key::kUnknown;
  }
}

/// One SDL event as the viewer's input, if it is one.
std::optional<InputEvent> translate(const SDL_Event& event) {
  switch (event.type) {
    case SDL_QUIT:
      return viewer::QuitEvent{};
    case SDL_KEYDOWN:
    case SDL_KEYUP: {
      viewer::KeyEvent key;
      key.key = key_from_sdl(event.key.keysym.sym);
      key.down = event.type == SDL_KEYDOWN;
      const Uint16 mod = event.key.keysym.mod;
      key.modifiers = {(mod & KMOD_CTRL) != 0, (mod & KMOD_SHIFT) != 0, (mod & KMOD_ALT) != 0};
      return key;
    }
    case SDL_TEXTINPUT:
      return viewer::TextEvent{event.text.text};
    case SDL_MOUSEMOTION:
      return viewer::MouseMoveEvent{static_cast<float>(event.motion.x),
                                    static_cast<float>(event.motion.y)};
    case SDL_MOUSEBUTTONDOWN:
    case SDL_MOUSEBUTTONUP: {
      int button = -1;
      if (event.button.button == SDL_BUTTON_LEFT) button = 0;
      if (event.button.button == SDL_BUTTON_RIGHT) button = 1;
      if (event.button.button == SDL_BUTTON_MIDDLE) button = 2;
      if (button < 0) return std::nullopt;
      return viewer::MouseButtonEvent{button, event.type == SDL_MOUSEBUTTONDOWN,
                                      static_cast<float>(event.button.x),
                                      static_cast<float>(event.button.y)};
    }
    case SDL_MOUSEWHEEL: {
      float dy = static_cast<float>(event.wheel.y);
      if (event.wheel.direction == SDL_MOUSEWHEEL_FLIPPED) dy = -dy;
      return viewer::WheelEvent{dy};
    }
    default:
      return std::nullopt;
  }
}

}  // namespace

std::vector<InputEvent> window_events() {
  std::vector<InputEvent> events;
  SDL_Event event;
  while (SDL_PollEvent(&event) != 0) {
    if (event.type == SDL_DROPFILE) {
      events.push_back(viewer::DropEvent{event.drop.file});
      SDL_free(event.drop.file);
    } else if (auto input = translate(event)) {
      events.push_back(*input);
    }
  }
  return events;
}

}  // namespace tumble::app
