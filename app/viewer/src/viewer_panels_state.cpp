// The viewer's "Initial state" panel section: the body, its angular velocity and orientation,
// principal-axis spin presets and, for a top, its tilt and spin.
#include "app/viewer/viewer_panels.hpp"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>

#include "app/viewer/viewer_initial_state.hpp"
#include "viewer_panels_common.hpp"

namespace tumble::app::viewer {
namespace {

/// Restarts the runs from `state` for `body`, or shows why it cannot.
void restart_from(Viewer& viewer, std::size_t body, const engine::BodyState& state) {
  try {
    viewer.session().set_initial_state(body, state);
  } catch (const std::exception& error) {
    viewer.notify(error.what(), true);
  }
}

/// The angular velocity (world or body frame) and yaw-pitch-roll fields, and their Apply.
void omega_and_orientation(Viewer& viewer, std::size_t body, VectorFrame& omega_frame,
                           std::array<double, 3>& omega_field, std::array<double, 3>& ypr_field) {
  int frame = omega_frame == VectorFrame::kBody ? 1 : 0;
  ImGui::RadioButton("world", &frame, 0);
  ImGui::SameLine();
  ImGui::RadioButton("body frame", &frame, 1);
  omega_frame = frame == 1 ? VectorFrame::kBody : VectorFrame::kWorld;
  ImGui::InputScalarN("w (rad/s)", ImGuiDataType_Double, omega_field.data(), 3, nullptr, nullptr,
                      "%.4g");
  ImGui::InputScalarN("yaw pitch roll", ImGuiDataType_Double, ypr_field.data(), 3, nullptr, nullptr,
                      "%.2f");
  if (!ImGui::Button("Apply (restart)##state")) return;
  const Session& session = viewer.session();
  const engine::BodyModel& model = session.compiled().bodies[body];
  engine::BodyState state = session.initial_state(body);
  const Eigen::Vector3d ypr(ypr_field[0], ypr_field[1], ypr_field[2]);
  const Eigen::Vector3d omega(omega_field[0], omega_field[1], omega_field[2]);
  if (!ypr.allFinite() || !omega.allFinite()) {
    viewer.notify("initial state: every value must be a finite number", true);
    return;
  }
  set_orientation_ypr_deg(model, state, ypr);
  set_initial_omega(model, state, omega, omega_frame);
  restart_from(viewer, body, state);
}

/// Presets: spin about a principal axis at `rate`, with a small perturbation.
void principal_spin_presets(Viewer& viewer, std::size_t body, double& rate) {
  ImGui::SetNextItemWidth(scaled(120.0f));
  ImGui::InputDouble("rate (rad/s)", &rate, 0.0, 0.0, "%.4g");
  static constexpr const char* kPresetNames[3] = {"axis 1 (min)", "axis 2 (mid)", "axis 3 (max)"};
  for (int axis = 0; axis < 3; ++axis) {
    if (axis > 0) ImGui::SameLine();
    if (!ImGui::Button(kPresetNames[axis])) continue;
    if (!(std::abs(rate) < 1e9)) {
      viewer.notify("rate: expected a finite number of rad/s", true);
    } else {
      const Session& session = viewer.session();
      engine::BodyState state = session.initial_state(body);
      preset_principal_spin(session.compiled().bodies[body], state, axis, rate,
                            kPresetPerturbation);
      restart_from(viewer, body, state);
    }
  }
  ImGui::TextColored(kDimColour, "spin about a principal axis, %g%% off it",
                     100.0 * kPresetPerturbation);
}

/// A top's tilt and spin, and their Apply.
void top_fields(Viewer& viewer, std::size_t body, double& tilt_deg, double& spin) {
  ImGui::SetNextItemWidth(scaled(120.0f));
  ImGui::InputDouble("tilt (deg)", &tilt_deg, 0.0, 0.0, "%.3g");
  ImGui::SetNextItemWidth(scaled(120.0f));
  ImGui::InputDouble("spin (rad/s)", &spin, 0.0, 0.0, "%.4g");
  if (!ImGui::Button("Apply top")) return;
  if (!std::isfinite(tilt_deg) || !std::isfinite(spin)) {
    viewer.notify("top: tilt and spin must be finite numbers", true);
    return;
  }
  const Session& session = viewer.session();
  engine::BodyState state = session.initial_state(body);
  set_top_pose(session.compiled().bodies[body], state, {tilt_deg, spin});
  restart_from(viewer, body, state);
}

}  // namespace

void Panels::initial_state_section(Viewer& viewer) {
  if (!ImGui::CollapsingHeader("Initial state")) return;
  const auto& bodies = viewer.session().compiled().bodies;
  if (bodies.size() > 1) body_combo("body", scaled(180.0f), bodies, viewer.selected_body);
  const std::size_t body = std::min(viewer.selected_body, bodies.size() - 1);
  omega_and_orientation(viewer, body, omega_frame_, omega_, ypr_deg_);
  principal_spin_presets(viewer, body, preset_rate_);
  if (is_top(bodies[body])) top_fields(viewer, body, tilt_deg_, spin_);
}

}  // namespace tumble::app::viewer
