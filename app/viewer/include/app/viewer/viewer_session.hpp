#pragma once
/// @file What the viewer runs: one scene (or a mesh made into one), one or more runs of it with
/// different integrators, the clock that steps them, and the draw list of the current state.
///
/// Design note
/// - The same FrameBuilder as `tumble render` turns a run into a draw list, so a frame of the
///   viewer is a frame of a render with the same toggles; only the camera is the user's.
/// - The simulation follows the wall clock, not the frame rate: advance() is told how much real
///   time passed and steps every run to (real time x time scale), so slow drawing gives fewer
///   frames, never slower physics. Stepping has a budget per call; when stepping itself cannot
///   keep up, the real-time factor shown drops below the time scale.
/// - Runs beside the first ("compare beside") restart with it and are drawn as translucent
///   copies in their own colours, as `tumble compare --layout overlay` draws them.
/// - Errors (bad scene, bad mesh, an integrator that cannot take a body) come back as one-line
///   messages and leave what was open untouched.

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/frame/frame_builder.hpp"
#include "app/scene/render_settings.hpp"
#include "app/scene/scene.hpp"
#include "app/viewer/viewer_camera.hpp"
#include "engine/simulation/simulation.hpp"
#include "render/draw_list.hpp"
#include "render/renderer.hpp"

namespace tumble::app::viewer {

/// Angular speed (rad/s) a mesh opened on its own is spun at, about its intermediate axis.
inline constexpr double kMeshSpinRate = 6.0;
/// Relative perturbation of the spin presets (about each of the other two axes).
inline constexpr double kPresetPerturbation = 0.01;
/// Most runs side by side.
inline constexpr std::size_t kMaxRuns = 4;

/// A scene for a mesh opened on its own: one body of density 1000 kg/m^3 at the origin (spun
/// about its intermediate axis after compiling, see Session::open), rk4 at dt = 1 ms for 60 s.
SceneDescription mesh_scene(const std::filesystem::path& mesh, bool allow_overlap = false);

/// The draw-list colour and the legend's name of run `index` beside the first.
struct RunColour {
  const char* name;
  render::Rgba colour;
};
RunColour beside_colour(std::size_t index);

/// Recent values of the first run, for the live plots (oldest first).
struct History {
  std::vector<float> time;            ///< s
  std::vector<float> energy_drift;    ///< (E - E0) / |E0|
  std::vector<float> momentum_drift;  ///< (|L| - |L0|) / |L0|
  std::vector<float> omega[3];        ///< w of the selected body in its body frame, rad/s
};

/// An integrator and step to open a scene with instead of its own.
struct RunChoice {
  std::optional<std::string> integrator;
  std::optional<double> dt;
  bool allow_overlap = false;  ///< for a mesh opened on its own (engine::MassOptions)
};

class Session {
 public:
  /// Samples kept in History: when it passes 5/4 of this, the oldest are dropped down to it.
  static constexpr std::size_t kHistoryLength = 1200;

  /// Draws with `renderer`, which must outlive the session; meshes are uploaded into it.
  explicit Session(render::Renderer& renderer);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  /// Opens a scene (.json) or a mesh (any other file), paused or not as before, at t = 0 with
  /// the scene's integrator and dt, or those of `choice` (the command line's --integrator and
  /// --dt). On failure returns the one-line message and keeps what was open.
  std::optional<std::string> open(const std::filesystem::path& file, const RunChoice& choice = {});

  bool empty() const { return runs_.empty(); }
  /// Closes the scene: the runs end and their meshes are released (the viewer then shows
  /// something else, such as a robot file); empty() is then true.
  void close();
  /// Changes each time the runs restart (open, reset, integrator or initial state changed), so
  /// panels know when to refresh what they show.
  std::size_t generation() const { return generation_; }
  const SceneDescription& scene() const { return scene_; }
  const CompiledScene& compiled() const { return compiled_; }

  // --- Clock ---------------------------------------------------------------------------------
  bool paused() const { return paused_; }
  void set_paused(bool paused) { paused_ = paused; }
  /// Simulated seconds per real second, kept within [1/64, 64].
  double time_scale() const { return time_scale_; }
  void set_time_scale(double scale);
  /// Real time passed: steps every run towards (simulated time + wall_seconds x time scale),
  /// unless paused, spending at most `budget` on stepping. Pauses at the end of the scene.
  void advance(double wall_seconds,
               std::chrono::steady_clock::duration budget = std::chrono::milliseconds(12));
  /// One step of the first run's dt (every run to that time); pauses.
  void step();
  /// Every run back to t = 0 (the current initial state), history cleared.
  void reset();
  /// Simulated time of the first run (s).
  double time() const;
  /// The first run reached the scene's duration.
  bool finished() const;
  /// Simulated seconds per real second over the last second of advance() calls.
  double real_time_factor() const { return real_time_factor_; }

  // --- Runs ----------------------------------------------------------------------------------
  std::size_t run_count() const { return runs_.size(); }
  const engine::Simulation& simulation(std::size_t run = 0) const;
  const std::string& integrator(std::size_t run = 0) const;
  double dt(std::size_t run = 0) const;
  /// Restarts from t = 0 with `integrator` at `dt`: replacing the runs, or, with `beside`,
  /// adding a run next to them (at most kMaxRuns). Returns the error and changes nothing when
  /// the name is unknown, dt is not positive and finite or too small, or the integrator cannot
  /// take a body.
  std::optional<std::string> set_integrator(const std::string& integrator, double dt, bool beside);
  /// Keeps only the first run (restarting nothing; the others' meshes are released at the
  /// next restart).
  void remove_beside_runs();

  // --- Initial state -------------------------------------------------------------------------
  /// The initial state of `body` (what reset() returns to).
  const engine::BodyState& initial_state(std::size_t body) const;
  /// Replaces the initial state of `body` and restarts every run from it. Throws InputError
  /// (and keeps the old state) when an integrator cannot take the new state.
  void set_initial_state(std::size_t body, const engine::BodyState& state);

  // --- Drawing -------------------------------------------------------------------------------
  /// Text size of the overlays relative to the frame's own: the one set_font_scale() gave (the
  /// command line's --font-scale), else the open scene's `render.font_scale` (1 without one).
  double font_scale() const;
  /// Overrides the scene's text scale (nullopt: back to it); the caller checks the range.
  void set_font_scale(std::optional<double> scale);
  /// Lays the next frames out for the renderer's size now (after Renderer::resize): the
  /// overlay, the runs' legend and the arrows' fit follow; nothing restarts.
  void refit_frames();

  /// What is drawn (the scene's `render.show`, then the user's toggles). `trails` switches
  /// the scene's trails, or one per body when the scene has none.
  ShowSettings& show() { return show_; }
  bool& show_trails() { return show_trails_; }
  /// The camera a render of the scene starts with, and the radius of the motion around it.
  const render::Camera& scene_camera() const { return scene_camera_; }
  double reach() const;
  /// The draw list of the current state seen by `camera`, showing what show() says (every
  /// toggle at once: the builders are made with everything prepared).
  render::DrawList frame(const render::Camera& camera);

  /// Body whose w the live plots show.
  std::size_t plotted_body() const { return plotted_body_; }
  void set_plotted_body(std::size_t body);
  const History& history() const { return history_; }

  /// The mass-property report of `body` as `tumble inspect` prints it, or for a body with
  /// given inertia its mass and moments.
  std::string inspector_text(std::size_t body) const;
  /// The mesh report's warnings for `body` (none for given inertia).
  std::vector<std::string> inspector_warnings(std::size_t body) const;

 private:
  struct RunSpec {
    std::string integrator;
    double dt = 0.0;
  };
  struct Run {
    std::string integrator;
    double dt = 0.0;
    std::unique_ptr<engine::Simulation> simulation;
    std::unique_ptr<FrameBuilder> builder;
  };

  std::optional<std::string> open_compiled(const SceneDescription& scene,
                                           bool spin_about_intermediate);
  std::vector<RunSpec> specs() const;
  /// Replaces the runs with new ones from the initial states, clock and history restarted.
  /// Throws InputError, changing nothing, when an integrator cannot take a body.
  void rebuild(const std::vector<RunSpec>& specs);
  void record_history();
  void step_runs_to(double time, std::chrono::steady_clock::time_point deadline);

  render::Renderer& renderer_;
  std::size_t mesh_mark_ = 0;  ///< renderer meshes before the session's own
  SceneDescription scene_;
  CompiledScene compiled_;
  RenderSettings render_settings_;
  std::vector<TrailSettings> default_trails_;
  std::vector<Run> runs_;
  ShowSettings show_;
  bool show_trails_ = false;
  std::optional<double> font_scale_;  ///< --font-scale, over the scene's
  render::Camera scene_camera_;

  bool paused_ = false;
  double time_scale_ = 1.0;
  double target_time_ = 0.0;
  double real_time_factor_ = 0.0;
  double rate_wall_ = 0.0;   ///< wall seconds in the current real-time-factor window
  double rate_start_ = 0.0;  ///< simulated time at its start

  std::size_t generation_ = 0;
  std::size_t plotted_body_ = 0;
  History history_;
  InvariantDrift drift_;
};

}  // namespace tumble::app::viewer
