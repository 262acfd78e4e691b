#pragma once
/// @file A note when a mesh's size suggests its file is not in the unit `--scale` (or a robot
/// file's mesh scale) assumed.

#include <optional>
#include <string>

#include <Eigen/Core>

#include "engine/mass/mesh_analysis.hpp"

namespace tumble::app {

/// A note for `report` (sizes in metres after `scale`) when its largest extent L suggests the
/// wrong unit, or nothing. Sizes between 1 mm and 10 m never get one. Beyond 10 m, and only
/// without a scale (every |factor| 1), each common unit whose factor brings L into 0.01..10 m
/// is named: millimetres (0.001), inches (0.0254), micrometres (1e-06), e.g. "size 111 m:
/// millimetres? --scale 0.001; inches? --scale 0.0254". Below 1 mm with a scale given, when
/// the file's own numbers span 0.01..10, it says the file may already be in metres ("size 0.2
/// mm: the file may already be in metres: leave out --scale"); below 1 mm without a scale,
/// only that the body is under a millimetre and --scale converts a file not in metres.
std::optional<std::string> unit_hint(const engine::MeshReport& report,
                                     const Eigen::Vector3d& scale);

/// The factor to metres of the first unit unit_hint names for a body too large to be in
/// metres (0.001 for 111 m), or nothing when it names none.
std::optional<double> likely_unit_factor(const engine::MeshReport& report,
                                         const Eigen::Vector3d& scale);

/// The name of the unit of `factor` as likely_unit_factor gives it ("millimetres").
std::string unit_name(double factor);

}  // namespace tumble::app
