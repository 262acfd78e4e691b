#pragma once
/// @file MJCF geoms and mesh assets as geometries: MuJoCo's half sizes turned into tumble's
/// shapes, the geom's frame from pos and an orientation or from fromto, and its own density or
/// mass.

#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include <Eigen/Core>
#include <pugixml.hpp>

#include "app/robot/robot_model.hpp"
#include "mjcf_defaults.hpp"
#include "mjcf_xml.hpp"

namespace tumble::app::robot::mjcf {

/// A <mesh> of <asset>: its file (resolved through meshdir) and scale. `file` is empty when
/// the mesh gives its vertices inline, which tumble does not read.
struct MeshAsset {
  std::filesystem::path file;
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  /// inertia="exact|convex|shell|legacy" (MuJoCo 3); unset when not given.
  std::optional<engine::InertiaMethod> inertia;
};

/// The model as far as geoms need it.
struct Model {
  Source source;
  Compiler compiler;
  Defaults defaults;
  std::map<std::string, MeshAsset, std::less<>> meshes;
  const PackagePaths* packages = nullptr;
};

/// Reads the <mesh> elements of every <asset> into `model.meshes` (a mesh's name defaults to
/// its file's name without folder and extension).
void read_mesh_assets(pugi::xml_node root, Model& model);

/// What one geom is.
struct GeomRead {
  /// Unset when the geom adds no mass (a plane, a height field, zero density or mass, a group
  /// outside inertiagrouprange): `note` then says why.
  std::optional<Geometry> geometry;
  std::optional<std::string> note;
  bool collides = true;  ///< contype or conaffinity non-zero
};

/// Reads the geom `node` of default class `class_name` (its childclass, unless the geom
/// names its own class). `where` names it ("body 'arm' geom 0"). Throws InputError "FILE:
/// line N: WHERE: ATTRIBUTE: ..." on bad or missing values.
GeomRead read_geom(pugi::xml_node node, const std::string& class_name, const Model& model,
                   const std::string& where);

}  // namespace tumble::app::robot::mjcf
