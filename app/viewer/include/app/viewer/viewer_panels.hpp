#pragma once
/// @file The viewer's Dear ImGui panels: simulation control, integrator and dt, the initial
/// state, what is shown, the camera, the body inspector, live plots, files and recording, the
/// help overlay and notices. Drawn into the current ImGui frame; every change goes through
/// Viewer and Session, whose effects the tests check without a window.

#include <array>
#include <cstddef>
#include <string>

#include "app/scene/scene.hpp"
#include "app/viewer/viewer.hpp"

namespace tumble::app::viewer {

/// Frame timing the window measures, shown in the panel.
struct FrameStats {
  double frames_per_second = 0.0;
  double frame_ms = 0.0;  ///< drawing and showing one frame
};

/// Width (pixels) of the control panel on the right of the window, with 13 px text (it scales
/// with the text).
inline constexpr float kPanelWidth = 360.0f;
/// The control panel never takes more of the window's width than this.
inline constexpr float kMaxPanelShare = 0.45f;

/// Where the control panel goes in a window, in pixels from its top-left.
struct PanelRect {
  float x = 0.0f;
  float y = 0.0f;
  float width = 0.0f;
  float height = 0.0f;
};

/// The control panel of a `width` x `height` window whose text is `font_px` high: on the right,
/// kPanelWidth x font_px / 13 wide but at most kMaxPanelShare of the width, as tall as the
/// window less a margin of 10 px x font_px / 13 (whole pixels) above and below, that margin
/// from the right edge.
PanelRect panel_rect(int width, int height, float font_px);

class Panels {
 public:
  /// Draws every panel for `viewer` into the current ImGui frame (between ImGui::NewFrame and
  /// ImGui::Render), `width` x `height` pixels; sizes follow the frame's font
  /// (ImGui::GetFontSize(), which the window sets from render::overlay_font_px).
  void draw(Viewer& viewer, const FrameStats& stats, int width, int height);

 private:
  void simulation_section(Viewer& viewer, const FrameStats& stats);
  void integrator_section(Viewer& viewer);
  void initial_state_section(Viewer& viewer);
  void show_section(Viewer& viewer);
  void camera_section(Viewer& viewer);
  void inspector_section(Viewer& viewer);
  void plots_section(Viewer& viewer);
  void files_section(Viewer& viewer);
  /// A robot file: its links, the legend and the selected link's inertials.
  void robot_section(Viewer& viewer);
  void help_window(Viewer& viewer, const PanelRect& panel, int height);
  void notices_window(Viewer& viewer, const PanelRect& panel, int height);
  /// Refreshes the edit fields from the session when its runs restarted or the body changed.
  void sync(const Viewer& viewer);

  // Edit fields, kept between frames.
  std::size_t generation_ = static_cast<std::size_t>(-1);
  std::size_t synced_body_ = static_cast<std::size_t>(-1);
  int integrator_index_ = 0;
  double dt_ = 0.01;
  bool beside_ = false;
  VectorFrame omega_frame_ = VectorFrame::kBody;
  VectorFrame synced_frame_ = VectorFrame::kBody;
  std::array<double, 3> omega_{};
  std::array<double, 3> ypr_deg_{};
  double tilt_deg_ = 0.0;
  double spin_ = 0.0;
  double preset_rate_ = 6.0;
  std::string open_path_;
  std::string record_path_;
  // The inspector's report, formatted once per scene and body rather than every frame.
  std::size_t report_generation_ = static_cast<std::size_t>(-1);
  std::size_t report_body_ = static_cast<std::size_t>(-1);
  std::string report_;
};

}  // namespace tumble::app::viewer
