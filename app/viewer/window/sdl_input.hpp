#pragma once
/// @file SDL's events as the viewer's input (viewer_input.hpp), for `tumble view`'s window.

#include <vector>

#include "app/viewer/viewer_input.hpp"

namespace tumble::app {

/// The window's events since the last call, as the viewer's input: keys, text, pointer, wheel,
/// dropped files and quit; the rest are dropped.
std::vector<viewer::InputEvent> window_events();

}  // namespace tumble::app
