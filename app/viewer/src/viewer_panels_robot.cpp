// The viewer's panel for a robot file: its links (differing ones marked), the legend, and the
// inspector of the selected link (both inertials and their differences).
#include <imgui.h>

#include <cstdio>
#include <string>

#include "app/video/robot_picture.hpp"
#include "app/viewer/viewer_panels.hpp"
#include "viewer_panels_common.hpp"

namespace tumble::app::viewer {
namespace {

ImVec4 imgui_colour(const render::Rgba& colour) {
  return ImVec4(colour.r, colour.g, colour.b, 1.0f);
}

}  // namespace

void Panels::robot_section(Viewer& viewer) {
  const RobotPicture& picture = *viewer.robot();
  ImGui::TextWrapped("%s", picture.report.robot.file.filename().string().c_str());
  ImGui::TextColored(kDimColour, "%s", viewer.file().string().c_str());
  char tolerance[32];
  std::snprintf(tolerance, sizeof tolerance, "%g", picture.tolerance);
  ImGui::TextColored(imgui_colour(kStatedBoxColour), "box: stated inertial (equal inertia)");
  ImGui::TextColored(imgui_colour(kComputedWireColour), "wire: computed (from %s)",
                     picture.report.source.c_str());
  ImGui::TextColored(imgui_colour(kDifferingBoxColour), "red box: differs by more than %s",
                     tolerance);

  if (ImGui::CollapsingHeader("Links", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::TextColored(kDimColour, "%zu links, %zu differing; click one here or in the view",
                       picture.links.size(), picture.differing());
    ImGui::BeginChild("links", ImVec2(0.0f, scaled(160.0f)), true);
    for (std::size_t i = 0; i < picture.links.size(); ++i) {
      const LinkPicture& link = picture.links[i];
      const std::string label =
          (link.differs ? "! " : "  ") + link.name + "##link" + std::to_string(i);
      if (link.differs) ImGui::PushStyleColor(ImGuiCol_Text, kErrorColour);
      if (ImGui::Selectable(label.c_str(), viewer.selected_link == i)) viewer.selected_link = i;
      if (link.differs) ImGui::PopStyleColor();
    }
    ImGui::EndChild();
  }

  if (!ImGui::CollapsingHeader("Inspector", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (!viewer.selected_link || *viewer.selected_link >= picture.links.size()) {
    ImGui::TextColored(kDimColour, "no link selected");
    return;
  }
  const std::string report = link_inspector_text(picture, *viewer.selected_link);
  ImGui::BeginChild("link report", ImVec2(0.0f, scaled(240.0f)), true,
                    ImGuiWindowFlags_HorizontalScrollbar);
  ImGui::TextUnformatted(report.c_str());
  ImGui::EndChild();
}

}  // namespace tumble::app::viewer
