#pragma once
/// @file What the URDF and SDF readers share: the document read with byte offsets, numbers
/// read strictly (so that "1 2" where three are expected, or "nan", is an error naming the
/// element), poses, and where a link's inertial element is or goes.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <pugixml.hpp>

#include "app/robot/robot_model.hpp"

namespace tumble::app::robot {

/// Parses `text` (the robot file's bytes, kept unchanged) into `document` as UTF-8, so that
/// offset_debug() is a byte offset into `text`. Throws InputError "FILE: line N: XML error:
/// WHAT".
void load_robot_document(pugi::xml_document& document, const std::string& text,
                         const std::filesystem::path& file);

/// The finite numbers of a whitespace-separated list; `count` of them, or any count in
/// `counts` ("expected 1 or 3 numbers"). Throws InputError "WHERE: expected ..., got 'TEXT'".
std::vector<double> parse_numbers(const std::string& text, const std::vector<std::size_t>& counts,
                                  const std::string& where);

/// One finite number. Throws InputError "WHERE: expected a number, got 'TEXT'".
double parse_number(const std::string& text, const std::string& where);

/// One positive finite number (a size). Throws InputError "WHERE: expected a positive number,
/// got 'TEXT'".
double parse_positive(const std::string& text, const std::string& where);

/// Three positive finite numbers (box sizes, ellipsoid radii).
Eigen::Vector3d parse_positive_vector(const std::string& text, const std::string& where);

/// The pose of translation `xyz` and rotation `rotation`.
Eigen::Isometry3d pose_from(const Eigen::Vector3d& xyz, const Eigen::Matrix3d& rotation);

/// The symmetric inertia tensor of its six elements.
Eigen::Matrix3d inertia_matrix(double ixx, double ixy, double ixz, double iyy, double iyz,
                               double izz);

/// Fills `link`'s insert_at and child_indent from its element, and its inertial_bytes from its
/// inertial element when it has one.
void locate_inertial(Link& link, const std::string& text, const pugi::xml_node& link_node,
                     const pugi::xml_node& inertial_node);

/// Adds a note to a link that has none of the geometry asked for (`kind`, "collision" or
/// "visual") but has the other kind, naming the option that would use it.
void note_other_geometry(Link& link, const pugi::xml_node& link_node, GeometrySource from);

/// The 1-based line of byte `offset` of `text`, for messages.
std::size_t line_of(const std::string& text, std::size_t offset);

}  // namespace tumble::app::robot
