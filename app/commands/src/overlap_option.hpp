#pragma once
/// @file `--overlap union|sum|refuse` and its old alias `--allow-overlap`, as inspect and
/// inertials take them (engine::OverlapMode).

#include <string>

#include <CLI/CLI.hpp>

#include "engine/mass/mesh_analysis.hpp"

namespace tumble::app {

/// Adds --overlap and --allow-overlap (the same as --overlap sum) to `command`, into `mode`.
inline void add_overlap_options(CLI::App& command, engine::OverlapMode& mode) {
  command
      .add_option_function<std::string>(
          "--overlap",
          [&mode](const std::string& name) { mode = *engine::overlap_mode_named(name); },
          "Parts that overlap, nest facing the same way or repeat: union (the solid is their "
          "exact union; a warning states the shared volume; default), sum (each part counted "
          "whole, the shared volume twice; a warning), refuse (an error naming the parts)")
      ->check(CLI::IsMember({"union", "sum", "refuse"}))
      ->option_text("union|sum|refuse");
  command.add_flag_callback(
      "--allow-overlap", [&mode] { mode = engine::OverlapMode::kSum; },
      "The same as --overlap sum (kept for older scripts)");
}

}  // namespace tumble::app
