#pragma once
/// @file What `tumble bench` is asked to do: scenes, the sweep of integrators, steps and
/// tolerances, the repeats, the workers, the output folder and the shard.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tumble::app {

/// What `tumble bench` was asked to do (lists and numbers as typed; run_bench checks them).
struct BenchOptions {
  std::vector<std::filesystem::path> scenes;
  std::optional<std::string> integrators;  ///< comma-separated names
  std::optional<std::string> dts;          ///< comma-separated steps, s (fixed-step integrators)
  std::optional<std::string> tolerances;   ///< comma-separated tolerances (adaptive ones)
  std::optional<std::string> duration;     ///< s
  std::optional<std::string> repeat;       ///< timed runs per case (default 3)
  std::optional<std::string> jobs;         ///< worker threads, capped at the cores (default 1)
  std::optional<std::string> shard;        ///< "I/N": only that shard's cases, written as a part
  std::filesystem::path output;
};

/// Default step factors around the scene's dt, and default tolerances of adaptive integrators.
inline constexpr double kDefaultStepFactors[] = {4.0, 2.0, 1.0, 0.5, 0.25};
inline constexpr double kDefaultTolerances[] = {1e-4, 1e-6, 1e-8, 1e-10, 1e-12};

}  // namespace tumble::app
