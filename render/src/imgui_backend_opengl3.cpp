// Dear ImGui's OpenGL3 renderer backend, compiled from the source Debian ships
// (libimgui-dev) with GL prototypes from libOSMesa instead of the gl3w loader, which looks for
// libGL and fails on OSMesa.
#include "gl.hpp"
#define IMGUI_IMPL_OPENGL_LOADER_CUSTOM
#include TUMBLE_IMGUI_OPENGL3_SOURCE
