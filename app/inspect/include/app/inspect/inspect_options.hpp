#pragma once
/// @file What `tumble inspect` is asked to do: the files, the mass options, the output format,
/// the batch options and the shard.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "app/robot/inertial_xml.hpp"
#include "engine/mass/mesh_analysis.hpp"

namespace tumble::app {

/// How the reports are printed: the table; one JSON document (an object, or an array for a
/// batch); JSON lines (one object per file as it finishes); an inertial element of a URDF,
/// SDF or MJCF file.
enum class InspectFormat { text, json, jsonl, urdf, sdf, mjcf };

/// What `tumble inspect` was asked to do.
struct InspectOptions {
  /// Mesh files, directories (the mesh files directly inside, or below with `recursive`) and
  /// `@LIST` files (one path a line, relative to the list's folder).
  std::vector<std::filesystem::path> files;
  engine::MassOptions mass;
  InspectFormat format = InspectFormat::text;
  /// The frame of the XML formats' inertia: the mesh file's axes or the principal axes.
  robot::InertialFrame frame = robot::InertialFrame::mesh;
  bool recursive = false;     ///< directories: descend into sub-directories
  unsigned jobs = 1;          ///< files inspected at once; 0: one per core
  bool format_given = false;  ///< --format, --json or --jsonl was given
  /// -o FILE: the output written there (atomically) instead of on stdout.
  std::optional<std::filesystem::path> output;
  /// "I/N": only every N-th file of the list from the I-th, written to -o FILE.jsonl as a part.
  std::optional<std::string> shard;
};

/// `--scale`'s value: one factor ("0.001", every axis) or three ("1,2,-1"), each finite and
/// non-zero. Throws InputError "--scale: expected one factor or three (sx,sy,sz), got ...".
Eigen::Vector3d parse_scale_factors(const std::string& text);

}  // namespace tumble::app
