#pragma once
/// @file The heat map of `tumble stability`: one panel per case (rows integrators, columns
/// dt), cells coloured by outcome, drawn by gnuplot through a temporary script.

#include <filesystem>
#include <string>
#include <vector>

#include "app/analysis/stability_classes.hpp"

namespace tumble::app {

/// One case's matrix.
struct HeatMapPanel {
  std::string title;
  std::string x_label;                               ///< e.g. "|w| dt"
  std::vector<std::string> columns;                  ///< the dt labels
  std::vector<std::string> rows;                     ///< the integrators, top to bottom
  std::vector<std::vector<StabilityOutcome>> cells;  ///< [row][column]
};

/// The gnuplot script that draws `panels` to `png` and `svg` (exposed for tests).
std::string heat_map_script(const std::vector<HeatMapPanel>& panels,
                            const std::filesystem::path& png, const std::filesystem::path& svg);

/// Writes the script beside `png`, runs gnuplot on it and removes it. Throws tumble::InputError
/// with gnuplot's first error line when gnuplot fails or is missing, WriteError naming the file
/// when the script or a picture could not be written whole (a full disk).
void draw_heat_map(const std::vector<HeatMapPanel>& panels, const std::filesystem::path& png,
                   const std::filesystem::path& svg);

}  // namespace tumble::app
