#pragma once
/// @file What `tumble stability` is asked to do: the suite and its cases, scene files as cases,
/// the integrators and steps, the output folder and the shard.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tumble::app {

/// What `tumble stability` was asked to do.
struct StabilityOptions {
  std::optional<std::string> suite;        ///< default "standard" (none when only scenes are given)
  std::optional<std::string> integrators;  ///< comma-separated names; default all
  std::optional<std::string> dts;          ///< comma-separated seconds, for scene cases
  std::optional<std::string> cases;        ///< comma-separated built-in case names
  std::vector<std::filesystem::path> scenes;
  std::optional<std::filesystem::path> output;
  std::optional<std::string> shard;  ///< "I/N": only that shard's runs, written as a part
  bool list_suites = false;
};

}  // namespace tumble::app
