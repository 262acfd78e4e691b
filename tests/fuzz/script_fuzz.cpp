// Fuzz target: the viewer's `--script` parser (app/viewer/src/viewer_script.cpp) on any text.
#include "app/viewer/viewer_input.hpp"
#include "base/errors.hpp"
#include "fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    tumble::app::viewer::parse_script(tumble::fuzz::as_text(data, size), "fuzz.script");
  } catch (const tumble::InputError&) {
    // A clean refusal.
  }
  return 0;
}
