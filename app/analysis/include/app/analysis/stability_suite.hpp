#pragma once
/// @file The built-in cases of `tumble stability` (engine/PHYSICS.md §7), built directly as engine
/// bodies, and user scene files turned into extra cases.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "engine/body/rigid_body.hpp"

namespace tumble::app {

/// One stability case: bodies, a horizon and the time steps to sweep.
struct StabilityCase {
  std::string name;
  std::string description;
  std::vector<engine::BodyModel> bodies;
  std::vector<engine::BodyState> initial;
  double duration = 1.0;    ///< s
  std::vector<double> dts;  ///< s, swept in this order
  /// The dimensionless step the matrix columns show: `rate_label` = rate * dt (rate in 1/s,
  /// e.g. |w| or wn). rate = 0 shows dt itself in seconds.
  std::string rate_label = "dt";
  double rate = 0.0;
  /// When not empty, only these integrators run; the others are skipped with `skip_note`.
  std::vector<std::string> only_integrators;
  std::string skip_note;
  /// The energy that relative energy changes are divided by, J (absent: |E0|).
  std::optional<double> energy_scale;
  double blowup_factor = 10.0;      ///< see engine::SimulationSettings
  double tolerance = 1e-10;         ///< dopri's relative tolerance in the sweep
  double absolute_tolerance = 0.0;  ///< dopri's absolute tolerance in the sweep
  std::optional<std::string> note;  ///< shown under the case's matrix
};

/// A named list of cases.
struct StabilitySuite {
  std::string name;
  std::string description;
  std::vector<StabilityCase> cases;
};

/// The built-in suites' names with one line each, in the order --list-suites shows them.
struct SuiteListing {
  std::string name;
  std::string description;
};
std::vector<SuiteListing> stability_suite_listing();

/// The built-in suite `name`. Throws tumble::InputError ("--suite: unknown suite ...").
StabilitySuite stability_suite(const std::string& name);

/// A scene file as a case: its bodies, its duration, and `dts` or the scene's dt x {1, 2, 4, 8}.
/// Throws tumble::InputError naming the file.
StabilityCase scene_case(const std::filesystem::path& file,
                         const std::optional<std::vector<double>>& dts);

}  // namespace tumble::app
