// `tumble view` in a build without the windowed viewer (TUMBLE_VIEWER off or SDL2 missing).
#include <ostream>

#include "app/viewer/view_options.hpp"

namespace tumble::app {

bool viewer_available() {
  return false;
}

int run_viewer_window(const ViewOptions&, std::ostream&, std::ostream& err) {
  err << "tumble view: this build has no viewer (install libsdl2-dev and configure with "
         "-DTUMBLE_VIEWER=ON)\n";
  return 1;
}

}  // namespace tumble::app
