// The viewer's "Show" and "Camera" panel sections.
#include "app/viewer/viewer_panels.hpp"

#include <imgui.h>

#include "viewer_panels_common.hpp"

namespace tumble::app::viewer {

void Panels::show_section(Viewer& viewer) {
  Session& session = viewer.session();
  if (!ImGui::CollapsingHeader("Show")) return;
  ShowSettings& show = session.show();
  ImGui::Checkbox("bodies", &show.bodies);
  ImGui::SameLine(scaled(180.0f));
  ImGui::Checkbox("ground", &show.ground);
  ImGui::Checkbox("body axes", &show.body_axes);
  ImGui::SameLine(scaled(180.0f));
  ImGui::Checkbox("principal axes", &show.principal_axes);
  ImGui::Checkbox("w arrow", &show.angular_velocity);
  ImGui::SameLine(scaled(180.0f));
  ImGui::Checkbox("L arrow", &show.angular_momentum);
  ImGui::Checkbox("trails", &session.show_trails());
  ImGui::SameLine(scaled(180.0f));
  ImGui::Checkbox("inertia ellipsoid", &show.inertia_ellipsoid);
  ImGui::Checkbox("polhode", &show.polhode);
  ImGui::SameLine(scaled(180.0f));
  ImGui::Checkbox("herpolhode", &show.herpolhode);
  ImGui::Checkbox("overlay and plots", &show.overlay);
}

void Panels::camera_section(Viewer& viewer) {
  if (!ImGui::CollapsingHeader("Camera")) return;
  const auto& bodies = viewer.session().compiled().bodies;
  ImGui::Checkbox("follow", &viewer.follow);
  if (bodies.size() > 1) {
    ImGui::SameLine();
    body_combo("##follow", scaled(160.0f), bodies, viewer.follow_body);
  }
  if (ImGui::Button("Reset camera")) viewer.reset_camera();
  const OrbitCamera& camera = viewer.camera();
  ImGui::TextColored(kDimColour, "azimuth %.0f, elevation %.0f deg, distance %.3g m",
                     camera.azimuth_deg(), camera.elevation_deg(), camera.distance());
  ImGui::TextColored(kDimColour, "drag to orbit, wheel to zoom");
}

}  // namespace tumble::app::viewer
