// The viewer's panels: the main window and its "Simulation", "Integrator" and "Files" sections,
// the help and notices windows (the other sections are in viewer_panels_*.cpp).
#include "app/viewer/viewer_panels.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "app/viewer/viewer_initial_state.hpp"
#include "base/errors.hpp"
#include "engine/dynamics/integrators.hpp"
#include "viewer_panels_common.hpp"

namespace tumble::app::viewer {
namespace {

/// Index of `name` in the integrator catalogue (0 when absent).
int catalog_index(const std::string& name) {
  const auto& catalog = engine::integrator_catalog();
  for (std::size_t i = 0; i < catalog.size(); ++i) {
    if (catalog[i].name == name) return static_cast<int>(i);
  }
  return 0;
}

}  // namespace

void body_combo(const char* label, float width, const std::vector<engine::BodyModel>& bodies,
                std::size_t& chosen) {
  ImGui::SetNextItemWidth(width);
  if (ImGui::BeginCombo(label, bodies[chosen].name.c_str())) {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (ImGui::Selectable(bodies[i].name.c_str(), i == chosen)) chosen = i;
    }
    ImGui::EndCombo();
  }
}

PanelRect panel_rect(int width, int height, float font_px) {
  const float unit = font_px / render::kDefaultFontPx;
  const float margin = std::round(10.0f * unit);
  PanelRect rect;
  rect.width = std::floor(std::min(kPanelWidth * unit, kMaxPanelShare * static_cast<float>(width)));
  rect.x = static_cast<float>(width) - rect.width - margin;
  rect.y = margin;
  rect.height = std::max(static_cast<float>(height) - 2.0f * margin, 1.0f);
  return rect;
}

void Panels::draw(Viewer& viewer, const FrameStats& stats, int width, int height) {
  sync(viewer);
  // At most 45 % of a small window's width; collapsible (click its title bar) to free the view.
  const PanelRect panel = panel_rect(width, height, ImGui::GetFontSize());
  ImGui::SetNextWindowPos(ImVec2(panel.x, panel.y), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(panel.width, panel.height), ImGuiCond_Always);
  ImGui::Begin("tumble view", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
  if (viewer.robot()) {
    robot_section(viewer);
  } else {
    simulation_section(viewer, stats);
  }
  if (!viewer.session().empty()) {
    integrator_section(viewer);
    initial_state_section(viewer);
    show_section(viewer);
    camera_section(viewer);
    inspector_section(viewer);
    plots_section(viewer);
  }
  files_section(viewer);
  ImGui::End();

  notices_window(viewer, panel, height);
  if (viewer.help_shown) help_window(viewer, panel, height);
}

void Panels::sync(const Viewer& viewer) {
  const Session& session = viewer.session();
  if (session.empty()) return;
  const std::size_t body = std::min(viewer.selected_body, session.compiled().bodies.size() - 1);
  if (session.generation() == generation_ && body == synced_body_ &&
      omega_frame_ == synced_frame_) {
    return;
  }
  if (session.generation() != generation_) {
    integrator_index_ = catalog_index(session.integrator());
    dt_ = session.dt();
  }
  generation_ = session.generation();
  synced_body_ = body;
  synced_frame_ = omega_frame_;
  const engine::BodyModel& model = session.compiled().bodies[body];
  const engine::BodyState& state = session.initial_state(body);
  const Eigen::Vector3d omega = initial_omega(model, state, omega_frame_);
  const Eigen::Vector3d ypr = orientation_ypr_deg(model, state);
  for (int a = 0; a < 3; ++a) {
    omega_[static_cast<std::size_t>(a)] = omega[a];
    ypr_deg_[static_cast<std::size_t>(a)] = ypr[a];
  }
  if (is_top(model)) {
    const TopPose pose = top_pose(model, state);
    tilt_deg_ = pose.tilt_deg;
    spin_ = pose.spin;
  }
  const double rate = omega.norm();
  if (rate > 0.0) preset_rate_ = rate;
}

void Panels::simulation_section(Viewer& viewer, const FrameStats& stats) {
  Session& session = viewer.session();
  if (session.empty()) {
    ImGui::TextWrapped(
        "Nothing open. Open a scene (.json), a mesh or a robot file (.urdf, .sdf, MJCF .xml) "
        "below, or drop a file on the window.");
    return;
  }
  ImGui::TextWrapped("%s", session.scene().name.c_str());
  ImGui::TextColored(kDimColour, "%s", viewer.file().string().c_str());
  if (!ImGui::CollapsingHeader("Simulation", ImGuiTreeNodeFlags_DefaultOpen)) return;

  if (ImGui::Button(session.paused() ? "Play" : "Pause", ImVec2(scaled(70.0f), 0.0f))) {
    viewer.apply(Shortcut::kTogglePause);
  }
  ImGui::SameLine();
  if (ImGui::Button("Step")) viewer.apply(Shortcut::kStep);
  ImGui::SameLine();
  if (ImGui::Button("Reset")) viewer.apply(Shortcut::kReset);
  ImGui::SameLine();
  if (ImGui::Button("-")) viewer.apply(Shortcut::kSlower);
  ImGui::SameLine();
  if (ImGui::Button("+")) viewer.apply(Shortcut::kFaster);

  ImGui::Text("t = %.3f s of %g s%s", session.time(), session.scene().duration,
              session.finished() ? " (end)" : "");
  ImGui::Text("time scale %gx, real-time factor %.2f", session.time_scale(),
              session.paused() ? 0.0 : session.real_time_factor());
  ImGui::Text("%.0f frames/s (%.1f ms a frame)", stats.frames_per_second, stats.frame_ms);
  if (const auto& blow_up = session.simulation().blow_up()) {
    ImGui::TextColored(kErrorColour, "blew up at t = %.4g s: %s", blow_up->time,
                       blow_up->reason.c_str());
  }
}

void Panels::integrator_section(Viewer& viewer) {
  Session& session = viewer.session();
  if (!ImGui::CollapsingHeader("Integrator", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const auto& catalog = engine::integrator_catalog();
  const std::string current = catalog[static_cast<std::size_t>(integrator_index_)].name;
  ImGui::SetNextItemWidth(scaled(180.0f));
  if (ImGui::BeginCombo("integrator", current.c_str())) {
    for (std::size_t i = 0; i < catalog.size(); ++i) {
      const bool selected = static_cast<int>(i) == integrator_index_;
      if (ImGui::Selectable(catalog[i].name.c_str(), selected)) {
        integrator_index_ = static_cast<int>(i);
      }
    }
    ImGui::EndCombo();
  }
  // dt from a list of round values, or typed.
  static constexpr double kStepChoices[] = {1e-4, 2e-4, 5e-4, 1e-3, 2e-3,
                                            5e-3, 1e-2, 2e-2, 5e-2, 0.1};
  ImGui::SetNextItemWidth(scaled(100.0f));
  ImGui::InputDouble("##dt", &dt_, 0.0, 0.0, "%.6g");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(scaled(72.0f));
  if (ImGui::BeginCombo("dt (s)", "list", ImGuiComboFlags_None)) {
    for (double choice : kStepChoices) {
      char label[32];
      std::snprintf(label, sizeof label, "%g", choice);
      if (ImGui::Selectable(label, choice == dt_)) dt_ = choice;
    }
    ImGui::EndCombo();
  }
  ImGui::Checkbox("beside the current runs", &beside_);
  if (ImGui::Button("Apply (restart)")) {
    const std::string name = catalog[static_cast<std::size_t>(integrator_index_)].name;
    if (auto error = session.set_integrator(name, dt_, beside_)) viewer.notify(*error, true);
  }
  if (session.run_count() > 1) {
    ImGui::SameLine();
    if (ImGui::Button("Only the first")) session.remove_beside_runs();
  }
  for (std::size_t k = 0; k < session.run_count(); ++k) {
    const std::string colour = k == 0 ? "solid" : beside_colour(k).name;
    ImGui::BulletText("%s: %s, dt = %g s", colour.c_str(), session.integrator(k).c_str(),
                      session.dt(k));
  }
}

void Panels::files_section(Viewer& viewer) {
  // Ctrl+O opens the section (DefaultOpen would only apply the first time it is drawn).
  const bool focus = viewer.open_requested;
  if (focus) ImGui::SetNextItemOpen(true);
  if (!ImGui::CollapsingHeader("Files")) return;
  if (focus) {
    ImGui::SetKeyboardFocusHere();
    viewer.open_requested = false;
  }
  const bool entered = ImGui::InputTextWithHint("##open", "scene.json, mesh or robot file",
                                                &open_path_, ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  if ((ImGui::Button("Open") || entered) && !open_path_.empty()) viewer.open(open_path_);

  if (viewer.recording()) {
    if (ImGui::Button("Stop recording")) viewer.stop_recording();
    ImGui::SameLine();
    ImGui::TextColored(kErrorColour, "REC %s", viewer.recording_path().string().c_str());
  } else {
    ImGui::InputTextWithHint("##record", "video.mp4, .webm, .gif or dir/ (empty: auto)",
                             &record_path_);
    ImGui::SameLine();
    if (ImGui::Button("Record")) viewer.start_recording(record_path_);
  }
  if (ImGui::Button("Screenshot (Ctrl+P)")) viewer.request_screenshot();
  ImGui::SameLine();
  if (ImGui::Button("Help (F1)")) viewer.help_shown = !viewer.help_shown;
}

void Panels::help_window(Viewer& viewer, const PanelRect& panel, int height) {
  // Centred in the view left of the panel; in a small window it scrolls rather than overflows.
  const float margin = panel.y;
  ImGui::SetNextWindowPos(ImVec2(0.5f * panel.x, 0.5f * static_cast<float>(height)),
                          ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSizeConstraints(
      ImVec2(0.0f, 0.0f), ImVec2(std::max(panel.x - 2.0f * margin, 1.0f), panel.height));
  ImGui::SetNextWindowBgAlpha(0.92f);
  bool open = true;
  ImGui::Begin(
      "Keys", &open,
      ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse);
  for (const std::string& line : shortcut_help()) ImGui::TextUnformatted(line.c_str());
  ImGui::Separator();
  ImGui::TextUnformatted("Mouse: drag to orbit, wheel to zoom (not over a panel).");
  ImGui::TextUnformatted("Drop a scene or mesh file on the window to open it.");
  ImGui::End();
  if (!open) viewer.help_shown = false;
}

void Panels::notices_window(Viewer& viewer, const PanelRect& panel, int height) {
  const auto& notices = viewer.notices();
  if (notices.empty()) return;
  // Bottom left, its lines wrapped before the control panel.
  const float margin = panel.y;
  ImGui::SetNextWindowPos(ImVec2(margin, static_cast<float>(height) - margin), ImGuiCond_Always,
                          ImVec2(0.0f, 1.0f));
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("notices", nullptr,
               ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_AlwaysAutoResize |
                   ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoFocusOnAppearing);
  ImGui::PushTextWrapPos(
      std::max(panel.x - 2.0f * margin - ImGui::GetStyle().WindowPadding.x, scaled(100.0f)));
  std::optional<std::size_t> dismissed;
  for (std::size_t i = 0; i < notices.size(); ++i) {
    const Notice& notice = notices[i];
    ImGui::PushID(static_cast<int>(i));
    if (notice.error) {
      ImGui::TextColored(kErrorColour, "error: %s", notice.text.c_str());
      ImGui::SameLine();
      if (ImGui::SmallButton("dismiss")) dismissed = i;
    } else {
      ImGui::TextUnformatted(notice.text.c_str());
    }
    ImGui::PopID();
  }
  ImGui::PopTextWrapPos();
  ImGui::End();
  if (dismissed) viewer.dismiss_notice(*dismissed);
}

}  // namespace tumble::app::viewer
