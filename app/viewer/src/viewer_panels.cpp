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
#include "engine/input_error.hpp"
#include "engine/integrators.hpp"

namespace tumble::app::viewer {
namespace {

const ImVec4 kErrorColour{1.0f, 0.45f, 0.40f, 1.0f};
const ImVec4 kDimColour{0.70f, 0.70f, 0.70f, 1.0f};

/// Index of `name` in the integrator catalogue (0 when absent).
int catalog_index(const std::string& name) {
  const auto& catalog = engine::integrator_catalog();
  for (std::size_t i = 0; i < catalog.size(); ++i) {
    if (catalog[i].name == name) return static_cast<int>(i);
  }
  return 0;
}

/// One line of a plot.
struct Series {
  const char* name;
  const std::vector<float>* values;
  ImU32 colour;
};

/// Several series in one frame filling the panel's width, each decimated to a min/max pair per
/// two pixels (so a long history costs the same as a short one: llvmpipe pays per triangle),
/// with the latest values as a legend above it.
void plot(const std::vector<Series>& series, float height) {
  // Legend: the latest value of each series in its colour.
  for (std::size_t k = 0; k < series.size(); ++k) {
    if (k > 0) ImGui::SameLine();
    const std::vector<float>& values = *series[k].values;
    ImGui::PushStyleColor(ImGuiCol_Text, series[k].colour);
    ImGui::Text("%s %.3g", series[k].name, values.empty() ? 0.0 : double{values.back()});
    ImGui::PopStyleColor();
  }
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const float width = ImGui::GetContentRegionAvail().x;
  ImGui::Dummy(ImVec2(width, height));
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(origin, ImVec2(origin.x + width, origin.y + height),
                      ImGui::GetColorU32(ImGuiCol_FrameBg));

  // A common vertical range; a flat one is widened so a constant draws mid-height.
  float low = FLT_MAX;
  float high = -FLT_MAX;
  for (const Series& line : series) {
    for (float v : *line.values) {
      if (std::isfinite(v)) {
        low = std::min(low, v);
        high = std::max(high, v);
      }
    }
  }
  if (low > high) return;
  if (high - low < 1e-30f) {
    low -= 1.0f;
    high += 1.0f;
  }
  const int buckets = std::max(1, static_cast<int>(width / 2.0f));
  std::vector<ImVec2> points;
  for (const Series& line : series) {
    const std::vector<float>& values = *line.values;
    if (values.size() < 2) continue;
    points.clear();
    const auto to_screen = [&](double fraction, float v) {
      return ImVec2(origin.x + static_cast<float>(fraction) * width,
                    origin.y + height - 2.0f - (v - low) / (high - low) * (height - 4.0f));
    };
    const std::size_t n = values.size();
    if (n <= static_cast<std::size_t>(2 * buckets)) {
      for (std::size_t i = 0; i < n; ++i) {
        points.push_back(to_screen(static_cast<double>(i) / static_cast<double>(n - 1), values[i]));
      }
    } else {
      // Each bucket's minimum and maximum, in the order they occur.
      for (int b = 0; b < buckets; ++b) {
        const std::size_t first =
            n * static_cast<std::size_t>(b) / static_cast<std::size_t>(buckets);
        const std::size_t last =
            n * static_cast<std::size_t>(b + 1) / static_cast<std::size_t>(buckets);
        std::size_t lo = first;
        std::size_t hi = first;
        for (std::size_t i = first; i < last; ++i) {
          if (values[i] < values[lo]) lo = i;
          if (values[i] > values[hi]) hi = i;
        }
        for (std::size_t i : {std::min(lo, hi), std::max(lo, hi)}) {
          points.push_back(
              to_screen(static_cast<double>(i) / static_cast<double>(n - 1), values[i]));
        }
      }
    }
    draw->AddPolyline(points.data(), static_cast<int>(points.size()), line.colour, ImDrawFlags_None,
                      1.0f);
  }
}

}  // namespace

void Panels::draw(Viewer& viewer, const FrameStats& stats, int width, int height) {
  sync(viewer);
  const float panel_x = static_cast<float>(width) - kPanelWidth - 10.0f;
  ImGui::SetNextWindowPos(ImVec2(panel_x, 10.0f), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(kPanelWidth, static_cast<float>(height) - 20.0f),
                           ImGuiCond_Always);
  ImGui::Begin("tumble view", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  simulation_section(viewer, stats);
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

  notices_window(viewer, height);
  if (viewer.help_shown) help_window(viewer, width, height);
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
        "Nothing open. Open a scene (.json) or a mesh below, or drop a file on "
        "the window.");
    return;
  }
  ImGui::TextWrapped("%s", session.scene().name.c_str());
  ImGui::TextColored(kDimColour, "%s", viewer.file().string().c_str());
  if (!ImGui::CollapsingHeader("Simulation", ImGuiTreeNodeFlags_DefaultOpen)) return;

  if (ImGui::Button(session.paused() ? "Play" : "Pause", ImVec2(70, 0))) {
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
  ImGui::SetNextItemWidth(180.0f);
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
  ImGui::SetNextItemWidth(100.0f);
  ImGui::InputDouble("##dt", &dt_, 0.0, 0.0, "%.6g");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(72.0f);
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

void Panels::initial_state_section(Viewer& viewer) {
  Session& session = viewer.session();
  if (!ImGui::CollapsingHeader("Initial state")) return;
  const auto& bodies = session.compiled().bodies;
  if (bodies.size() > 1) {
    ImGui::SetNextItemWidth(180.0f);
    if (ImGui::BeginCombo("body", bodies[viewer.selected_body].name.c_str())) {
      for (std::size_t i = 0; i < bodies.size(); ++i) {
        if (ImGui::Selectable(bodies[i].name.c_str(), i == viewer.selected_body)) {
          viewer.selected_body = i;
        }
      }
      ImGui::EndCombo();
    }
  }
  const std::size_t body = std::min(viewer.selected_body, bodies.size() - 1);
  const engine::BodyModel& model = bodies[body];

  // Angular velocity and orientation.
  int frame = omega_frame_ == VectorFrame::kBody ? 1 : 0;
  ImGui::RadioButton("world", &frame, 0);
  ImGui::SameLine();
  ImGui::RadioButton("body frame", &frame, 1);
  omega_frame_ = frame == 1 ? VectorFrame::kBody : VectorFrame::kWorld;
  ImGui::InputScalarN("w (rad/s)", ImGuiDataType_Double, omega_.data(), 3, nullptr, nullptr,
                      "%.4g");
  ImGui::InputScalarN("yaw pitch roll", ImGuiDataType_Double, ypr_deg_.data(), 3, nullptr, nullptr,
                      "%.2f");
  const auto apply = [&](const engine::BodyState& state) {
    try {
      session.set_initial_state(body, state);
    } catch (const std::exception& error) {
      viewer.notify(error.what(), true);
    }
  };
  if (ImGui::Button("Apply (restart)##state")) {
    engine::BodyState state = session.initial_state(body);
    const Eigen::Vector3d ypr(ypr_deg_[0], ypr_deg_[1], ypr_deg_[2]);
    const Eigen::Vector3d omega(omega_[0], omega_[1], omega_[2]);
    if (!ypr.allFinite() || !omega.allFinite()) {
      viewer.notify("initial state: every value must be a finite number", true);
    } else {
      set_orientation_ypr_deg(model, state, ypr);
      set_initial_omega(model, state, omega, omega_frame_);
      apply(state);
    }
  }

  // Presets: spin about a principal axis with a small perturbation.
  ImGui::SetNextItemWidth(120.0f);
  ImGui::InputDouble("rate (rad/s)", &preset_rate_, 0.0, 0.0, "%.4g");
  static constexpr const char* kPresetNames[3] = {"axis 1 (min)", "axis 2 (mid)", "axis 3 (max)"};
  for (int axis = 0; axis < 3; ++axis) {
    if (axis > 0) ImGui::SameLine();
    if (ImGui::Button(kPresetNames[axis])) {
      if (!(std::abs(preset_rate_) < 1e9)) {
        viewer.notify("rate: expected a finite number of rad/s", true);
      } else {
        engine::BodyState state = session.initial_state(body);
        preset_principal_spin(model, state, axis, preset_rate_, kPresetPerturbation);
        apply(state);
      }
    }
  }
  ImGui::TextColored(kDimColour, "spin about a principal axis, %g%% off it",
                     100.0 * kPresetPerturbation);

  // A top: tilt and spin.
  if (is_top(model)) {
    ImGui::SetNextItemWidth(120.0f);
    ImGui::InputDouble("tilt (deg)", &tilt_deg_, 0.0, 0.0, "%.3g");
    ImGui::SetNextItemWidth(120.0f);
    ImGui::InputDouble("spin (rad/s)", &spin_, 0.0, 0.0, "%.4g");
    if (ImGui::Button("Apply top")) {
      if (!std::isfinite(tilt_deg_) || !std::isfinite(spin_)) {
        viewer.notify("top: tilt and spin must be finite numbers", true);
      } else {
        engine::BodyState state = session.initial_state(body);
        set_top_pose(model, state, {tilt_deg_, spin_});
        apply(state);
      }
    }
  }
}

void Panels::show_section(Viewer& viewer) {
  Session& session = viewer.session();
  if (!ImGui::CollapsingHeader("Show")) return;
  ShowSettings& show = session.show();
  ImGui::Checkbox("bodies", &show.bodies);
  ImGui::SameLine(180.0f);
  ImGui::Checkbox("ground", &show.ground);
  ImGui::Checkbox("body axes", &show.body_axes);
  ImGui::SameLine(180.0f);
  ImGui::Checkbox("principal axes", &show.principal_axes);
  ImGui::Checkbox("w arrow", &show.angular_velocity);
  ImGui::SameLine(180.0f);
  ImGui::Checkbox("L arrow", &show.angular_momentum);
  ImGui::Checkbox("trails", &session.show_trails());
  ImGui::SameLine(180.0f);
  ImGui::Checkbox("inertia ellipsoid", &show.inertia_ellipsoid);
  ImGui::Checkbox("polhode", &show.polhode);
  ImGui::SameLine(180.0f);
  ImGui::Checkbox("herpolhode", &show.herpolhode);
  ImGui::Checkbox("overlay and plots", &show.overlay);
}

void Panels::camera_section(Viewer& viewer) {
  if (!ImGui::CollapsingHeader("Camera")) return;
  const auto& bodies = viewer.session().compiled().bodies;
  ImGui::Checkbox("follow", &viewer.follow);
  if (bodies.size() > 1) {
    ImGui::SameLine();
    ImGui::SetNextItemWidth(160.0f);
    if (ImGui::BeginCombo("##follow", bodies[viewer.follow_body].name.c_str())) {
      for (std::size_t i = 0; i < bodies.size(); ++i) {
        if (ImGui::Selectable(bodies[i].name.c_str(), i == viewer.follow_body)) {
          viewer.follow_body = i;
        }
      }
      ImGui::EndCombo();
    }
  }
  if (ImGui::Button("Reset camera")) viewer.reset_camera();
  const OrbitCamera& camera = viewer.camera();
  ImGui::TextColored(kDimColour, "azimuth %.0f, elevation %.0f deg, distance %.3g m",
                     camera.azimuth_deg(), camera.elevation_deg(), camera.distance());
  ImGui::TextColored(kDimColour, "drag to orbit, wheel to zoom");
}

void Panels::inspector_section(Viewer& viewer) {
  const Session& session = viewer.session();
  if (!ImGui::CollapsingHeader("Inspector")) return;
  const auto& bodies = session.compiled().bodies;
  const std::size_t body = std::min(viewer.selected_body, bodies.size() - 1);
  ImGui::TextColored(kDimColour, "body: %s (choose it under Initial state)",
                     bodies[body].name.c_str());
  for (const std::string& warning : session.inspector_warnings(body)) {
    ImGui::TextColored(kErrorColour, "warning: %s", warning.c_str());
  }
  if (report_generation_ != session.generation() || report_body_ != body) {
    report_ = session.inspector_text(body);
    report_generation_ = session.generation();
    report_body_ = body;
  }
  const std::string& report = report_;
  ImGui::BeginChild("report", ImVec2(0, 220), true, ImGuiWindowFlags_HorizontalScrollbar);
  ImGui::TextUnformatted(report.c_str());
  ImGui::EndChild();
}

void Panels::plots_section(Viewer& viewer) {
  Session& session = viewer.session();
  if (!ImGui::CollapsingHeader("Plots", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const History& history = session.history();
  ImGui::TextColored(kDimColour, "relative drift of the invariants");
  plot({{"energy", &history.energy_drift, IM_COL32(250, 200, 60, 255)},
        {"|L|", &history.momentum_drift, IM_COL32(200, 140, 255, 255)}},
       60.0f);
  const auto& bodies = session.compiled().bodies;
  ImGui::TextColored(kDimColour, "w of %s in its body frame (rad/s)",
                     bodies[std::min(session.plotted_body(), bodies.size() - 1)].name.c_str());
  plot({{"x", &history.omega[0], IM_COL32(240, 90, 80, 255)},
        {"y", &history.omega[1], IM_COL32(100, 220, 100, 255)},
        {"z", &history.omega[2], IM_COL32(100, 150, 255, 255)}},
       80.0f);
  if (viewer.selected_body != session.plotted_body())
    session.set_plotted_body(viewer.selected_body);
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
  const bool entered = ImGui::InputTextWithHint("##open", "scene.json or mesh file", &open_path_,
                                                ImGuiInputTextFlags_EnterReturnsTrue);
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

void Panels::help_window(Viewer& viewer, int width, int height) {
  ImGui::SetNextWindowPos(ImVec2(0.5f * static_cast<float>(width) - kPanelWidth / 2.0f,
                                 0.5f * static_cast<float>(height)),
                          ImGuiCond_Always, ImVec2(0.5f, 0.5f));
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

void Panels::notices_window(Viewer& viewer, int height) {
  const auto& notices = viewer.notices();
  if (notices.empty()) return;
  ImGui::SetNextWindowPos(ImVec2(10.0f, static_cast<float>(height) - 10.0f), ImGuiCond_Always,
                          ImVec2(0.0f, 1.0f));
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("notices", nullptr,
               ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_AlwaysAutoResize |
                   ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoFocusOnAppearing);
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
  ImGui::End();
  if (dismissed) viewer.dismiss_notice(*dismissed);
}

}  // namespace tumble::app::viewer
