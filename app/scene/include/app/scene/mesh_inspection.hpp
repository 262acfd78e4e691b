#pragma once
/// @file One mesh file's mass properties and checks, and the two ways they are reported: the
/// table people read and the JSON object scripts read.

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/geometry/triangle_mesh.hpp"
#include "engine/mass/mesh_analysis.hpp"

namespace tumble::app {

/// Imports and analyses one mesh file (throws tumble::InputError naming the file). With
/// `imported`, also hands back the mesh as read (file axes, before the analysis welds, drops
/// or flips anything), for drawing it without reading the file again.
engine::MeshReport inspect_file(const std::filesystem::path& file, const engine::MassOptions& mass,
                                engine::TriangleMesh* imported = nullptr);

/// The report as one JSON object (SI units; inertia about the centre of mass, file axes).
nlohmann::json report_to_json(const engine::MeshReport& report);

/// The report as a readable table.
std::string format_report(const engine::MeshReport& report);

}  // namespace tumble::app
