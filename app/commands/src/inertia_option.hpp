#pragma once
// The --inertia option inspect and inertials share.

#include <CLI/CLI.hpp>

#include "engine/mass/inertia_method.hpp"

namespace tumble::app {

/// Adds `--inertia exact|convex|shell|legacy|auto` to `command`, writing the choice into `method`.
void add_inertia_option(CLI::App& command, engine::InertiaMethod& method);

}  // namespace tumble::app
