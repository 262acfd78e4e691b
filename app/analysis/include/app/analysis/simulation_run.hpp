#pragma once
/// @file A scene run without rendering (`tumble simulate` as library calls): the options over the
/// scene, the run with its invariants watched, the trajectory it records, the CSV it writes and
/// the summary of how well the invariants held.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "app/scene/scene.hpp"
#include "engine/body/rigid_body.hpp"

namespace tumble::app {

/// What `tumble simulate` was asked to do. Options given here override the scene.
struct SimulateOptions {
  std::filesystem::path scene;
  std::optional<std::string> integrator;
  std::optional<double> dt;
  std::optional<double> duration;
  std::optional<double> tolerance;           ///< relative tolerance of adaptive integrators
  std::optional<double> absolute_tolerance;  ///< their absolute tolerance
  std::optional<double> blowup_factor;
  std::optional<std::filesystem::path> csv;
  long long every = 1;  ///< write every Nth step (the first and the last always)
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

/// The summary as one JSON object.
nlohmann::json summary_to_json(const RunSummary& summary);

/// The summary as readable text.
std::string format_summary(const RunSummary& summary);

/// One body at one recorded time, as the trajectory CSV gives it: position, orientation of the
/// user's body frame, velocity, world angular velocity, angular momentum and energy.
struct BodySample {
  Eigen::Vector3d position;
  Eigen::Quaterniond orientation;
  Eigen::Vector3d velocity;
  Eigen::Vector3d angular_velocity;
  Eigen::Vector3d angular_momentum;
  double energy = 0.0;
};

/// A run's recorded trajectory: the states at the times the CSV would hold (the first, every
/// `every`th step, the last; after a blow-up the last good one), and the run's summary.
struct Trajectory {
  std::vector<engine::BodyModel> bodies;
  std::vector<double> times;
  std::vector<std::vector<engine::BodyState>> states;  ///< states[k][i]: body i at times[k]
  std::vector<std::filesystem::path> inputs;           ///< the scene and the meshes it read
  RunSummary summary;

  /// Body `body` at recorded time `k`.
  BodySample sample(std::size_t k, std::size_t body) const;
};

/// Loads `options.scene`, applies the options over it, checks them (InputError naming the file
/// or option) and runs it to the end or a blow-up (summary.blow_up says which), recording the
/// trajectory in memory (options.csv is not written; see write_trajectory_csv). `interrupted`,
/// when given, is asked every 64 steps; when it says so the run stops where it is.
Trajectory run_simulation(const SimulateOptions& options,
                          const std::function<bool()>& interrupted = {});

/// As above, for a scene already loaded (`options.scene` is then not read: a scene given as
/// data, as the Python module's dicts are).
Trajectory run_simulation(const SimulateOptions& options, SceneDescription scene,
                          const std::function<bool()>& interrupted = {});

/// Writes `trajectory` to `path` (atomically) byte for byte as `tumble simulate --csv` writes
/// the same run.
void write_trajectory_csv(const Trajectory& trajectory, const std::filesystem::path& path);

/// `tumble simulate`'s run: as run_simulation, but streaming the rows into options.csv (its
/// temporary created before the run, renamed into place at the end) instead of memory. Fills
/// `summary`; returns 0, kExitBlowUp (the one line on `err`) or kExitInterrupted (nothing
/// written).
int simulate_scene(const SimulateOptions& options, const std::function<bool()>& interrupted,
                   RunSummary& summary, std::ostream& err);

/// The integrators: a table, or with `as_json` a JSON array of {name, order, adaptive,
/// needs_torque_free, properties}.
void list_integrators(bool as_json, std::ostream& out);

/// The integrators as `tumble simulate --list-integrators --json` lists them.
nlohmann::json integrators_to_json();

/// The summary as one JSON object.
nlohmann::json summary_to_json(const RunSummary& summary);

/// The summary as readable text.
std::string format_summary(const RunSummary& summary);

}  // namespace tumble::app
