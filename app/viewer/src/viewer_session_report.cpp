// What the viewer's inspector shows of a body: its mass-property report, or its given inertia.
#include <sstream>

#include "app/scene/mesh_inspection.hpp"
#include "app/support/printf_number.hpp"
#include "app/viewer/viewer_session.hpp"

namespace tumble::app::viewer {

std::string Session::inspector_text(std::size_t body) const {
  if (body >= compiled_.bodies.size()) return {};
  if (body < compiled_.reports.size() && compiled_.reports[body]) {
    return format_report(*compiled_.reports[body]);
  }
  const engine::BodyModel& model = compiled_.bodies[body];
  std::ostringstream text;
  text << model.name << ": inertia given in the scene\n"
       << "mass              " << printf_number(model.mass, "%.6g") << " kg\n"
       << "principal moments " << printf_number(model.moments[0], "%.6g") << ", "
       << printf_number(model.moments[1], "%.6g") << ", " << printf_number(model.moments[2], "%.6g")
       << " kg m^2" << (model.pivoted ? " (about the pivot)" : "") << "\n";
  return text.str();
}

std::vector<std::string> Session::inspector_warnings(std::size_t body) const {
  if (body < compiled_.reports.size() && compiled_.reports[body]) {
    return compiled_.reports[body]->warnings;
  }
  return {};
}

}  // namespace tumble::app::viewer
