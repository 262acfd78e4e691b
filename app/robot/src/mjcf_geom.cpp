// MJCF geoms and mesh assets.
#include "mjcf_geom.hpp"

#include <sstream>

#include "base/errors.hpp"
#include "engine/mass/primitive_shapes.hpp"

namespace tumble::app::robot::mjcf {
namespace {

std::size_t word_count(const std::string& text) {
  std::istringstream in(text);
  std::size_t count = 0;
  for (std::string word; in >> word;) ++count;
  return count;
}

/// How many size numbers a geom type needs (with fromto, the length comes from the points).
std::size_t needed_sizes(const std::string& type, bool fromto) {
  if (type == "sphere" || fromto) return 1;
  if (type == "capsule" || type == "cylinder") return 2;
  return 3;
}

/// A single number of an attribute, when given.
std::optional<double> number(const Attributes& a, const char* name, const Model& model,
                             const std::string& where) {
  const std::optional<std::string> value = a.get(name);
  if (!value) return std::nullopt;
  return parse_numbers(*value, 1, 1, model.source, a.node, where, name)[0];
}

/// The primitive of MuJoCo type `type` and half sizes `s` (fromto: `half` is the half length).
engine::Shape primitive(const std::string& type, const std::vector<double>& s,
                        std::optional<double> half) {
  if (type == "sphere") return engine::Sphere{s[0]};
  if (type == "capsule") return engine::Capsule{s[0], 2.0 * half.value_or(s[1])};
  if (type == "cylinder") return engine::Cylinder{s[0], 2.0 * half.value_or(s[1])};
  const Eigen::Vector3d halves =
      half ? Eigen::Vector3d(s[0], s[0], *half) : Eigen::Vector3d(s[0], s[1], s[2]);
  if (type == "box") return engine::Box{2.0 * halves};
  return engine::Ellipsoid{halves};
}

/// The shape of a primitive geom, and with fromto its frame too.
engine::Shape primitive_geom(const Attributes& a, const std::string& type, const Model& model,
                             const std::string& where, Eigen::Isometry3d& pose) {
  const pugi::xml_node node = a.node;
  if (a.get("mesh")) {
    model.source.fail(node, where + ": mesh: a " + type +
                                " geom with a mesh is fitted to it by MuJoCo, which tumble does "
                                "not do (make it type=\"mesh\")");
  }
  std::optional<double> half;
  if (const std::optional<std::string> fromto = a.get("fromto")) {
    if (type == "sphere") model.source.fail(node, where + ": fromto: a sphere takes no fromto");
    const std::vector<double> v = parse_numbers(*fromto, 6, 6, model.source, node, where, "fromto");
    const Eigen::Vector3d from(v[0], v[1], v[2]);
    const Eigen::Vector3d to(v[3], v[4], v[5]);
    if ((to - from).norm() == 0.0) {
      model.source.fail(node, where + ": fromto: its two points are the same");
    }
    half = 0.5 * (to - from).norm();
    pose.linear() = z_to(from - to);  // MuJoCo's geom z points from `to` to `from`
    pose.translation() = 0.5 * (from + to);
  }
  // The geom's own size numbers replace only the first ones of its class's.
  const Attributes inherited{pugi::xml_node(), a.inherited};
  const std::string size = merged_size(inherited.get("size").value_or(""),
                                       a.own("size") ? node.attribute("size").value() : "");
  const std::size_t needed = needed_sizes(type, half.has_value());
  if (word_count(size) < needed) {
    model.source.fail(node, where + ": size: a " + type + (half ? " with fromto" : "") + " takes " +
                                std::to_string(needed) + " numbers (MJCF half sizes), got " +
                                std::to_string(word_count(size)));
  }
  const std::vector<double> s = parse_numbers(size, needed, 3, model.source, node, where, "size");
  engine::Shape shape = primitive(type, s, half);
  try {
    engine::validate_shape(shape);
  } catch (const InputError& error) {
    model.source.fail(node, where + ": size: " + error.what());
  }
  return shape;
}

/// A <mesh>'s inertia attribute (MuJoCo 3): exact, convex, shell and legacy (MuJoCo's own
/// approximation, computed as MuJoCo does) are followed.
void read_mesh_inertia(const Attributes& a, const Model& model, const std::string& where,
                       MeshAsset& out) {
  const std::optional<std::string> value = a.get("inertia");
  if (!value) return;
  const std::optional<engine::InertiaMethod> method = engine::parse_inertia_method(*value);
  if (!method || *method == engine::InertiaMethod::automatic) {
    model.source.fail(
        a.node, where + ": inertia: expected convex, exact, legacy or shell, got '" + *value + "'");
  }
  out.inertia = method;
}

MeshGeometry mesh_geom(const Attributes& a, const Model& model, const std::string& where) {
  const std::optional<std::string> name = a.get("mesh");
  if (!name) model.source.fail(a.node, where + ": mesh: a mesh geom needs a mesh attribute");
  const auto it = model.meshes.find(*name);
  if (it == model.meshes.end()) {
    model.source.fail(a.node, where + ": mesh: no <mesh name=\"" + *name + "\"> in <asset>");
  }
  if (it->second.file.empty()) {
    model.source.fail(a.node, where + ": mesh '" + *name +
                                  "' gives its vertices inline, which tumble does not read "
                                  "(give it a file)");
  }
  std::optional<engine::InertiaMethod> inertia = it->second.inertia;
  if (const std::optional<std::string> shell = a.get("shellinertia")) {
    if (*shell != "true" && *shell != "false") {
      model.source.fail(a.node,
                        where + ": shellinertia: expected true or false, got '" + *shell + "'");
    }
    if (*shell == "true") inertia = engine::InertiaMethod::shell;
  }
  return MeshGeometry{it->second.file, it->second.scale, inertia};
}

/// The geom's frame from pos and its orientation (fromto sets it in primitive_geom instead).
Eigen::Isometry3d geom_pose(const Attributes& a, const Model& model, const std::string& where) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  if (const std::optional<std::string> pos = a.get("pos")) {
    const std::vector<double> p = parse_numbers(*pos, 3, 3, model.source, a.node, where, "pos");
    pose.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
  }
  if (auto rotation = orientation(a, model.compiler, model.source, where)) {
    pose.linear() = *rotation;
  }
  return pose;
}

}  // namespace

void read_mesh_assets(pugi::xml_node root, Model& model) {
  for (const pugi::xml_node asset : root.children("asset")) {
    for (const pugi::xml_node mesh : asset.children("mesh")) {
      const std::string class_name = mesh.attribute("class").as_string("main");
      const DefaultClass& cls = model.defaults.get(class_name, mesh, model.source, "<mesh>");
      const Attributes a{mesh, &cls.mesh};
      std::string file = a.get("file").value_or("");
      if (model.compiler.strippath) file = std::filesystem::path(file).filename().string();
      const std::string name = a.get("name").value_or(std::filesystem::path(file).stem().string());
      const std::string where = "mesh '" + name + "'";
      if (name.empty()) model.source.fail(mesh, "<mesh>: a mesh needs a name or a file");
      if (model.meshes.count(name)) model.source.fail(mesh, where + ": defined twice");
      MeshAsset out;
      if (!file.empty()) {
        try {
          out.file = resolve_mesh_path(file, model.compiler.meshdir, *model.packages, where);
        } catch (const InputError& error) {
          model.source.fail(mesh, error.what());
        }
      }
      if (const std::optional<std::string> scale = a.get("scale")) {
        const std::vector<double> v =
            parse_numbers(*scale, 3, 3, model.source, mesh, where, "scale");
        out.scale = Eigen::Vector3d(v[0], v[1], v[2]);
      }
      read_mesh_inertia(a, model, where, out);
      model.meshes[name] = out;
    }
  }
}

GeomRead read_geom(pugi::xml_node node, const std::string& class_name, const Model& model,
                   const std::string& where) {
  const std::string own_class = node.attribute("class").as_string(class_name.c_str());
  const Attributes a{node, &model.defaults.get(own_class, node, model.source, where).geom};
  GeomRead out;
  const double contype = number(a, "contype", model, where).value_or(1.0);
  const double conaffinity = number(a, "conaffinity", model, where).value_or(1.0);
  out.collides = contype != 0.0 || conaffinity != 0.0;
  const std::string type = a.get("type").value_or(a.get("mesh") ? "mesh" : "sphere");
  if (type == "plane" || type == "hfield" || type == "sdf") {
    out.note = where + " is a " + type + ": ignored (it has no volume)";
    return out;
  }
  if (type != "sphere" && type != "capsule" && type != "ellipsoid" && type != "cylinder" &&
      type != "box" && type != "mesh") {
    model.source.fail(node, where + ": type: unknown geom type '" + type + "'");
  }
  const double group = number(a, "group", model, where).value_or(0.0);
  if (group < model.compiler.group_first || group > model.compiler.group_last) {
    out.note = where + " is in group " + a.get("group").value_or("") +
               ", outside the compiler's inertiagrouprange: it adds no mass (as in MuJoCo)";
    return out;
  }
  Geometry geometry;
  geometry.where = where;
  geometry.mass = number(a, "mass", model, where);
  if (!geometry.mass) geometry.density = number(a, "density", model, where);
  for (const std::optional<double>& v : {geometry.mass, geometry.density}) {
    if (v && *v < 0.0)
      model.source.fail(node, where + ": a geom's mass and density cannot be negative");
    if (v && *v == 0.0) {
      out.note = where + " has zero mass or density: it adds no mass (as in MuJoCo)";
      return out;
    }
  }
  geometry.pose = geom_pose(a, model, where);
  if (type == "mesh") {
    if (a.get("fromto")) model.source.fail(node, where + ": fromto: a mesh geom takes no fromto");
    geometry.shape = mesh_geom(a, model, where);
  } else {
    geometry.shape = primitive_geom(a, type, model, where, geometry.pose);
  }
  out.geometry = std::move(geometry);
  return out;
}

}  // namespace tumble::app::robot::mjcf
