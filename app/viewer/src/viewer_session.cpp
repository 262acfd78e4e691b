#include "app/viewer/viewer_session.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <utility>

#include "app/support/printf_number.hpp"
#include "app/viewer/viewer_initial_state.hpp"
#include "base/errors.hpp"
#include "engine/dynamics/integrators.hpp"
#include "render/overlay_layout.hpp"

namespace tumble::app::viewer {
namespace {

using tumble::InputError;

constexpr float kBesideAlpha = 0.55f;
constexpr std::array<RunColour, kMaxRuns - 1> kBesidePalette = {
    {{"green", {0.15f, 0.75f, 0.25f, kBesideAlpha}},
     {"magenta", {0.85f, 0.20f, 0.75f, kBesideAlpha}},
     {"cyan", {0.10f, 0.75f, 0.85f, kBesideAlpha}}}};
constexpr double kMinTimeScale = 1.0 / 64.0;
constexpr double kMaxTimeScale = 64.0;
/// Simulated time the runs may fall behind the clock before the debt is dropped (s of wall
/// time): a long stall (a dragged window, a slow step) does not make the physics race after.
constexpr double kMaxLagWall = 0.25;
constexpr double kTrailSeconds = 3.0;

/// Keeps the newest `length` values.
void trim(std::vector<float>& values, std::size_t length) {
  if (values.size() > length)
    values.erase(values.begin(), values.end() - static_cast<long>(length));
}

/// A point fixed in each body to trail when the scene names none: the mesh vertex farthest
/// from the centre of mass, or a corner of the equivalent box.
std::vector<TrailSettings> default_trails(const CompiledScene& compiled) {
  std::vector<TrailSettings> trails;
  for (std::size_t i = 0; i < compiled.bodies.size(); ++i) {
    TrailSettings trail;
    trail.body = i;
    trail.seconds = kTrailSeconds;
    if (i < compiled.geometry.size() && compiled.geometry[i] &&
        !compiled.geometry[i]->positions.empty()) {
      for (const Eigen::Vector3d& p : compiled.geometry[i]->positions) {
        if (p.squaredNorm() > trail.point.squaredNorm()) trail.point = p;
      }
    } else {
      const engine::BodyModel& body = compiled.bodies[i];
      const Eigen::Vector3d half = 0.5 * equivalent_box_size(body.mass, body.moments);
      trail.point = body.principal_to_body * half;
    }
    trails.push_back(trail);
  }
  return trails;
}

}  // namespace

SceneDescription mesh_scene(const std::filesystem::path& mesh, bool allow_overlap) {
  SceneDescription scene;
  scene.file = mesh;
  scene.name = mesh.filename().string();
  scene.duration = 60.0;
  scene.dt = 1e-3;
  scene.integrator = "rk4";
  BodyDescription body;
  body.name = mesh.stem().string().empty() ? "body" : mesh.stem().string();
  body.mesh = mesh;
  body.density = 1000.0;
  body.overlap = allow_overlap ? engine::OverlapMode::kSum : engine::OverlapMode::kUnion;
  scene.bodies.push_back(body);
  return scene;
}

RunColour beside_colour(std::size_t index) {
  return kBesidePalette[(index - 1) % kBesidePalette.size()];
}

Session::Session(render::Renderer& renderer)
    : renderer_(renderer), mesh_mark_(renderer.mesh_count()) {}

Session::~Session() {
  runs_.clear();
  renderer_.release_meshes(mesh_mark_);
}

std::optional<std::string> Session::open(const std::filesystem::path& file,
                                         const RunChoice& choice) {
  try {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    const bool is_scene = extension == ".json";
    if (!is_scene && !std::filesystem::exists(file)) return file.string() + ": no such file";
    // A mesh opened on its own spins about its intermediate axis, ready to flip.
    SceneDescription scene = is_scene ? load_scene(file) : mesh_scene(file, choice.allow_overlap);
    if (choice.integrator) override_integrator(scene, *choice.integrator);
    if (choice.dt) {
      scene.dt = positive_option(*choice.dt, "--dt");
      if (auto problem = step_problem(scene.dt, scene.duration)) return "--dt: " + *problem;
    }
    return open_compiled(scene, !is_scene);
  } catch (const InputError& error) {
    return error.what();
  } catch (const std::exception& error) {
    return file.string() + ": " + error.what();
  }
}

void Session::close() {
  runs_.clear();
  renderer_.release_meshes(mesh_mark_);
  history_ = {};
  ++generation_;
}

std::optional<std::string> Session::open_compiled(const SceneDescription& scene,
                                                  bool spin_about_intermediate) {
  // Everything is built aside first, so a failure leaves the open scene as it was.
  CompiledScene compiled;
  RenderSettings settings;
  try {
    compiled = compile_scene(scene, /*keep_geometry=*/true);
    std::vector<std::string> names;
    for (const BodyDescription& body : scene.bodies) names.push_back(body.name);
    settings = parse_render_settings(scene.render ? *scene.render : nlohmann::json::object(),
                                     scene.file.string(), names);
    if (spin_about_intermediate) {
      preset_principal_spin(compiled.bodies[0], compiled.initial[0], 1, kMeshSpinRate,
                            kPresetPerturbation);
    }
  } catch (const InputError& error) {
    return error.what();
  } catch (const std::exception& error) {
    return scene.file.string() + ": " + error.what();
  }

  // Swap in the new scene, keeping the old one to fall back to.
  SceneDescription old_scene = std::exchange(scene_, scene);
  CompiledScene old_compiled = std::exchange(compiled_, std::move(compiled));
  RenderSettings old_settings = std::exchange(render_settings_, settings);
  std::vector<TrailSettings> old_trails = default_trails_;
  const std::vector<RunSpec> old_runs = specs();
  const ShowSettings old_show = show_;
  const bool old_show_trails = show_trails_;
  const std::size_t old_plotted_body = std::exchange(plotted_body_, 0);
  show_ = settings.show;
  show_trails_ = !settings.show.trails.empty();
  default_trails_ = settings.show.trails.empty() ? default_trails(compiled_) : settings.show.trails;
  try {
    rebuild({{scene.integrator, scene.dt}});
  } catch (const std::exception& error) {
    // rebuild() refuses before it touches the runs, so the old ones keep going as they were.
    scene_ = std::move(old_scene);
    compiled_ = std::move(old_compiled);
    render_settings_ = old_settings;
    default_trails_ = old_trails;
    show_ = old_show;
    show_trails_ = old_show_trails;
    plotted_body_ = old_plotted_body;
    if (runs_.empty() && !old_runs.empty()) rebuild(old_runs);
    return scene.file.string() + ": " + error.what();
  }
  return std::nullopt;
}

std::vector<Session::RunSpec> Session::specs() const {
  std::vector<RunSpec> out;
  for (const Run& run : runs_) out.push_back({run.integrator, run.dt});
  return out;
}

void Session::rebuild(const std::vector<RunSpec>& specs) {
  // Simulations first: the only part that can refuse (an integrator that cannot take a body),
  // and nothing has changed yet when it does.
  std::vector<Run> runs;
  for (const RunSpec& spec : specs) {
    engine::SimulationSettings run_settings = compiled_.settings;
    run_settings.integrator = engine::integrator_from_name(spec.integrator).value();
    run_settings.dt = spec.dt;
    Run run;
    run.integrator = spec.integrator;
    run.dt = spec.dt;
    run.simulation =
        std::make_unique<engine::Simulation>(compiled_.bodies, compiled_.initial, run_settings);
    runs.push_back(std::move(run));
  }

  // Then the drawing: the old runs' meshes go before the new ones are uploaded.
  runs_.clear();
  renderer_.release_meshes(mesh_mark_);
  RenderSettings builder_settings = render_settings_;
  // The window's size, not the scene's video size: the camera's aspect and the overlay's
  // placement follow what is drawn.
  builder_settings.width = renderer_.width();
  builder_settings.height = renderer_.height();
  builder_settings.font_scale = font_scale();
  // Everything the toggles can show is prepared, so that they work at any time without a
  // rebuild: the paths' histories (cheap) and the inertia ellipsoid's mesh. (The paths are
  // kept unscaled, so they follow the w arrow's scale, which the ellipsoid changes.)
  builder_settings.show.herpolhode = true;
  builder_settings.show.polhode = true;
  builder_settings.show.inertia_ellipsoid = true;
  builder_settings.show.trails = default_trails_;
  // Runs beside the first draw only their bodies: they keep no paths.
  RenderSettings beside_settings = builder_settings;
  beside_settings.show.herpolhode = beside_settings.show.polhode = false;
  beside_settings.show.trails.clear();
  for (std::size_t k = 0; k < runs.size(); ++k) {
    runs[k].builder = std::make_unique<FrameBuilder>(
        scene_, compiled_, k == 0 ? builder_settings : beside_settings, renderer_);
    runs[k].builder->observe(*runs[k].simulation);
  }
  runs_ = std::move(runs);
  if (!runs_.empty())
    scene_camera_ = runs_.front().builder->build(*runs_.front().simulation).camera;

  // Clock and plots start again.
  ++generation_;
  target_time_ = 0.0;
  rate_wall_ = 0.0;
  rate_start_ = 0.0;
  history_ = History{};
  drift_ = InvariantDrift(compiled_.bodies, compiled_.initial);
  record_history();
}

double Session::font_scale() const {
  return font_scale_ ? *font_scale_ : render_settings_.font_scale;
}

void Session::set_font_scale(std::optional<double> scale) {
  font_scale_ = scale;
  refit_frames();
}

void Session::refit_frames() {
  for (Run& run : runs_)
    run.builder->set_frame(renderer_.width(), renderer_.height(), font_scale());
}

void Session::set_time_scale(double scale) {
  if (!std::isfinite(scale)) return;
  time_scale_ = std::clamp(scale, kMinTimeScale, kMaxTimeScale);
}

void Session::advance(double wall_seconds, std::chrono::steady_clock::duration budget) {
  if (runs_.empty()) return;
  wall_seconds = std::max(wall_seconds, 0.0);
  if (!paused_ && !finished()) {
    // The target moves with the clock alone: a step that ends past it (by at most half a
    // step) is not carried into the next target, so nothing adds up over many frames.
    const double now = time();
    target_time_ += wall_seconds * time_scale_;
    target_time_ = std::min(target_time_, now + (kMaxLagWall + wall_seconds) * time_scale_);
    step_runs_to(target_time_, std::chrono::steady_clock::now() + budget);
    if (finished()) paused_ = true;
  }

  // Real-time factor over windows of about a second.
  rate_wall_ += wall_seconds;
  if (rate_wall_ >= 1.0) {
    real_time_factor_ = (time() - rate_start_) / rate_wall_;
    rate_wall_ = 0.0;
    rate_start_ = time();
  }
}

void Session::step_runs_to(double time_point, std::chrono::steady_clock::time_point deadline) {
  bool stepped = false;
  for (Run& run : runs_) {
    engine::Simulation& simulation = *run.simulation;
    std::size_t count = 0;
    // A step is taken when it ends at or before the target (half a step of slack for rounding).
    while (!simulation.finished() && simulation.time() + 0.5 * run.dt <= time_point) {
      simulation.step();
      stepped = true;
      if (++count % 32 == 0 && std::chrono::steady_clock::now() > deadline) break;
    }
    run.builder->observe(simulation);
  }
  if (stepped) record_history();
}

void Session::step() {
  if (runs_.empty()) return;
  paused_ = true;
  const double before = time();
  if (finished()) return;
  const double target = before + runs_.front().dt;
  step_runs_to(target, std::chrono::steady_clock::time_point::max());
  target_time_ = time();
}

void Session::reset() {
  if (runs_.empty()) return;
  rebuild(specs());
}

double Session::time() const {
  return runs_.empty() ? 0.0 : runs_.front().simulation->time();
}

bool Session::finished() const {
  return !runs_.empty() && runs_.front().simulation->finished();
}

const engine::Simulation& Session::simulation(std::size_t run) const {
  return *runs_.at(run).simulation;
}
const std::string& Session::integrator(std::size_t run) const {
  return runs_.at(run).integrator;
}
double Session::dt(std::size_t run) const {
  return runs_.at(run).dt;
}

std::optional<std::string> Session::set_integrator(const std::string& integrator, double dt,
                                                   bool beside) {
  if (runs_.empty()) return std::string("nothing is open");
  if (!engine::integrator_from_name(integrator)) {
    return "integrator: unknown \"" + integrator + "\" (expected one of " + integrator_names() +
           ")";
  }
  if (!(dt > 0.0) || !std::isfinite(dt)) return "dt: expected a positive number of seconds";
  if (auto problem = step_problem(dt, scene_.duration)) return "dt: " + *problem;
  if (beside && runs_.size() >= kMaxRuns) {
    return "at most " + std::to_string(kMaxRuns) + " runs side by side";
  }

  std::vector<RunSpec> runs;
  if (beside) runs = specs();
  runs.push_back({integrator, dt});
  try {
    rebuild(runs);
  } catch (const std::exception& error) {
    return error.what();  // refused before anything changed
  }
  return std::nullopt;
}

void Session::remove_beside_runs() {
  if (runs_.size() <= 1) return;
  runs_.resize(1);
}

const engine::BodyState& Session::initial_state(std::size_t body) const {
  return compiled_.initial.at(body);
}

void Session::set_initial_state(std::size_t body, const engine::BodyState& state) {
  const engine::BodyState old = compiled_.initial.at(body);
  compiled_.initial.at(body) = state;
  try {
    rebuild(specs());
  } catch (const std::exception&) {
    compiled_.initial.at(body) = old;
    throw;
  }
}

double Session::reach() const {
  return runs_.empty() ? 1.0 : runs_.front().builder->reach();
}

render::DrawList Session::frame(const render::Camera& camera) {
  if (runs_.empty()) {
    render::DrawList empty;
    empty.camera = camera;
    return empty;
  }
  ShowSettings show = show_;
  show.trails = show_trails_ ? default_trails_ : std::vector<TrailSettings>{};
  render::DrawList list = runs_.front().builder->build(*runs_.front().simulation, show);
  list.camera = camera;
  if (runs_.size() == 1) return list;

  // Runs beside the first: their bodies, translucent, in their colours, and a legend.
  // The legend at the bottom left, its text and size following the frame as the overlay's do.
  render::OverlayPanel legend;
  legend.title = "runs";
  legend.font_px = render::overlay_font_px(renderer_.width(), renderer_.height(), font_scale());
  const float unit = legend.font_px / render::kDefaultFontPx;
  legend.width_px = std::min(300.0f * unit, 0.5f * static_cast<float>(renderer_.width()));
  legend.position_px = Eigen::Vector2f(
      12.0f * unit, std::max(0.0f, static_cast<float>(renderer_.height()) - 140.0f * unit));
  legend.lines.push_back("solid: " + runs_.front().integrator +
                         ", dt = " + printf_number(runs_.front().dt, "%g") + " s");
  ShowSettings bodies_only;
  bodies_only.bodies = show_.bodies;
  bodies_only.angular_velocity = false;
  bodies_only.angular_momentum = false;
  bodies_only.overlay = false;
  for (std::size_t k = 1; k < runs_.size(); ++k) {
    const RunColour colour = beside_colour(k);
    for (render::MeshInstance mesh :
         runs_[k].builder->build(*runs_[k].simulation, bodies_only).meshes) {
      mesh.colour = colour.colour;
      list.meshes.push_back(mesh);
    }
    std::string line = std::string(colour.name) + ": " + runs_[k].integrator +
                       ", dt = " + printf_number(runs_[k].dt, "%g") + " s";
    if (const auto& blow_up = runs_[k].simulation->blow_up()) {
      line += printf_number(blow_up->time, " (blew up at t = %.4g s)");
    }
    legend.lines.push_back(std::move(line));
  }
  list.panels.push_back(std::move(legend));
  return list;
}

void Session::set_plotted_body(std::size_t body) {
  if (body >= compiled_.bodies.size() || body == plotted_body_) return;
  plotted_body_ = body;
  history_ = History{};
  record_history();
}

void Session::record_history() {
  if (runs_.empty()) return;
  const engine::Simulation& simulation = *runs_.front().simulation;
  const InvariantDrift::Values drift = drift_(simulation.bodies(), simulation.states());
  history_.time.push_back(static_cast<float>(simulation.time()));
  history_.energy_drift.push_back(static_cast<float>(drift.energy));
  history_.momentum_drift.push_back(static_cast<float>(drift.momentum));
  const std::size_t body = std::min(plotted_body_, simulation.bodies().size() - 1);
  const Eigen::Vector3d omega =
      initial_omega(simulation.bodies()[body], simulation.states()[body], VectorFrame::kBody);
  for (int a = 0; a < 3; ++a) history_.omega[a].push_back(static_cast<float>(omega[a]));

  // Drop the oldest samples in chunks (amortised constant time per sample).
  if (history_.time.size() > kHistoryLength + kHistoryLength / 4) {
    trim(history_.time, kHistoryLength);
    trim(history_.energy_drift, kHistoryLength);
    trim(history_.momentum_drift, kHistoryLength);
    for (auto& values : history_.omega) trim(values, kHistoryLength);
  }
}

}  // namespace tumble::app::viewer
