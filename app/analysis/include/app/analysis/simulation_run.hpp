#pragma once
/// @file A run of a scene without rendering, as `tumble simulate` makes it and the Python
/// module's tumble.simulate: the options over the scene, checked before anything runs; the
/// steps, with the recorded ones handed to a callback (the CSV writer, numpy arrays); each
/// body's invariants watched; a summary at the end.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/scene/scene.hpp"

namespace tumble::engine {
class Simulation;
}  // namespace tumble::engine

namespace tumble::app {

/// What a run was asked to do. Options given here override the scene.
struct SimulateOptions {
  std::filesystem::path scene;
  std::optional<std::string> integrator;
  std::optional<double> dt;
  std::optional<double> duration;
  std::optional<double> tolerance;           ///< relative tolerance of adaptive integrators
  std::optional<double> absolute_tolerance;  ///< their absolute tolerance
  std::optional<double> blowup_factor;
  std::optional<std::filesystem::path> csv;
  long long every = 1;  ///< record every Nth step (the first and the last always)
  bool json = false;
  bool list_integrators = false;
  bool allow_long = false;  ///< run beyond kMaxStepsWithoutAllowLong steps or kMaxCsvBytes of CSV
};

/// Runs longer than this many steps, or CSVs estimated larger than this many bytes, are refused
/// unless --allow-long is given (a mistyped --dt 1e-9 is 2e10 steps and 8 TB of CSV).
inline constexpr double kMaxStepsWithoutAllowLong = 1e9;
inline constexpr double kMaxCsvBytes = 10e9;
/// The estimated size of one CSV row (19 fields of up to 24 characters, a short body name).
inline constexpr double kCsvRowBytes = 400.0;

/// How one body's invariants fared over a run.
struct BodySummary {
  std::string name;
  bool energy_conserved = true;    ///< energy is an invariant of this body's equations
  bool momentum_conserved = true;  ///< |L| is an invariant (torque-free about the centre)
  double energy_drift_max = 0.0;   ///< max |E - E0| / |E0| (absolute when E0 = 0)
  double energy_drift_final = 0.0;
  double momentum_drift_max = 0.0;  ///< max | |L| - |L0| | / |L0| (absolute when L0 = 0)
  double momentum_drift_final = 0.0;
  std::optional<double> orientation_error;  ///< rad, against the exact solution (§4, §4b)
};

/// What a run did.
struct RunSummary {
  std::string scene;           ///< the scene's name
  std::filesystem::path file;  ///< the scene file
  std::string integrator;
  double dt = 0.0;
  double duration = 0.0;
  std::size_t steps = 0;        ///< steps completed
  std::size_t total_steps = 0;  ///< steps the duration needs
  double time = 0.0;            ///< simulated time reached, s
  double wall_seconds = 0.0;    ///< the stepping loop only
  std::optional<std::filesystem::path> csv;
  std::size_t csv_rows = 0;
  std::vector<BodySummary> bodies;
  std::optional<std::string> blow_up;  ///< the one-line message, when the run blew up
};

/// The summary as one JSON object (what `tumble simulate --json` prints).
nlohmann::json summary_to_json(const RunSummary& summary);

/// The integrators with their order and properties (`tumble simulate --list-integrators
/// --json`): name, order (-1: exact, 0: does not converge), adaptive, needs_torque_free,
/// properties.
nlohmann::json integrators_to_json();

/// Called with the simulation at every recorded step: the first, every `every`th, the last,
/// and after a blow-up the last good one.
using RecordStep = std::function<void(const engine::Simulation&)>;
/// Polled every 64 steps; true stops the run (Ctrl-C).
using StopRequested = std::function<bool()>;

/// One run of a scene. The constructor applies `options` over `scene` and checks them all
/// (tumble::InputError naming the option or the scene's field) before anything is read or run.
class SimulationRun {
 public:
  SimulationRun(const SimulateOptions& options, SceneDescription scene);

  /// The scene with the options applied (for the files it reads: scene_inputs).
  const SceneDescription& scene() const { return scene_; }

  /// Compiles the scene (imports its meshes) and steps to the end or the blow-up, calling
  /// `record` at the recorded steps. Returns false when `stop` asked it to stop (the summary
  /// is then incomplete). Throws tumble::InputError for a scene the integrator cannot take.
  bool run(const RecordStep& record, const StopRequested& stop);

  /// What the run did; `blow_up` is "blow-up: " and describe_blow_up's words.
  const RunSummary& summary() const { return summary_; }

 private:
  SimulateOptions options_;
  SceneDescription scene_;
  RunSummary summary_;
};

}  // namespace tumble::app
