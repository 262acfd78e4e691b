// SDF (.sdf, .world): the links of every model, nested models too, with their stated
// <inertial> and their <collision> (or <visual>) geometry.
#include <cmath>
#include <numbers>
#include <string>

#include "app/robot/inertial_xml.hpp"
#include "app/robot/robot_model.hpp"
#include "base/errors.hpp"
#include "link_tree.hpp"
#include "sdf_frames.hpp"
#include "xml_values.hpp"

namespace tumble::app::robot {
namespace {

struct Context {
  const std::filesystem::path& file;
  const std::string& text;
  const ReadOptions& options;
};

/// The text of the child element `name`, or nothing when it is absent.
std::optional<std::string> child_text(const pugi::xml_node& node, const char* name) {
  const pugi::xml_node child = node.child(name);
  if (!child) return std::nullopt;
  return std::string(child.text().get());
}

/// The child's text; throws InputError "WHERE: <PARENT> has no <NAME>" when it is absent.
std::string required(const pugi::xml_node& node, const char* name, const std::string& where) {
  std::optional<std::string> text = child_text(node, name);
  if (!text) throw InputError(where + ": <" + node.name() + "> has no <" + name + ">");
  return *text;
}

/// The element's <pose> in the link's frame. Poses relative to another frame would need the
/// model's kinematics, so only those relative to the link itself (or to nothing, the default)
/// are read.
Eigen::Isometry3d link_pose(const pugi::xml_node& parent, const std::string& link_name,
                            const std::string& where) {
  const pugi::xml_node pose = parent.child("pose");
  const std::string relative_to = pose.attribute("relative_to").value();
  if (!relative_to.empty() && relative_to != link_name) {
    throw InputError(where + ": pose relative_to '" + relative_to +
                     "': only poses relative to the link itself are supported");
  }
  return sdf_pose_value(pose, where);
}

StatedInertial stated_inertial(const pugi::xml_node& inertial, const std::string& link_name,
                               const std::string& where, Link& link) {
  StatedInertial stated;
  const Eigen::Isometry3d frame = link_pose(inertial, link_name, where);
  stated.center_of_mass = frame.translation();
  if (const std::optional<std::string> mass = child_text(inertial, "mass")) {
    stated.mass = parse_number(*mass, where + ": mass");
  }
  const pugi::xml_node inertia = inertial.child("inertia");
  if (!inertia) return stated;
  double values[6] = {};
  const char* names[6] = {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"};
  for (int i = 0; i < 6; ++i) {
    const std::optional<std::string> text = child_text(inertia, names[i]);
    const bool diagonal = i == 0 || i == 3 || i == 5;
    if (!text && diagonal) {
      link.notes.push_back(std::string("the stated inertia has no ") + names[i]);
      return stated;
    }
    // SDF's products of inertia default to zero.
    values[i] = text ? parse_number(*text, where + ": inertia " + names[i]) : 0.0;
  }
  const Eigen::Matrix3d in_frame =
      inertia_matrix(values[0], values[1], values[2], values[3], values[4], values[5]);
  stated.inertia = frame.linear() * in_frame * frame.linear().transpose();
  return stated;
}

/// The shape of a <geometry>, or nothing for one that has no volume (plane, height map, ...),
/// which gets a note on the link.
std::optional<std::variant<engine::Shape, MeshGeometry>> geometry_shape(
    const pugi::xml_node& geometry, const std::string& where, const Context& context, Link& link,
    const std::string& what) {
  const pugi::xml_node shape = geometry.first_child();
  const std::string kind = shape ? shape.name() : "";
  const std::string at = where + ": " + kind;
  if (kind == "box")
    return engine::Box{parse_positive_vector(required(shape, "size", at), at + " size")};
  if (kind == "sphere")
    return engine::Sphere{parse_positive(required(shape, "radius", at), at + " radius")};
  if (kind == "ellipsoid") {
    return engine::Ellipsoid{parse_positive_vector(required(shape, "radii", at), at + " radii")};
  }
  if (kind == "cylinder" || kind == "capsule") {
    const double radius = parse_positive(required(shape, "radius", at), at + " radius");
    const double length = parse_positive(required(shape, "length", at), at + " length");
    if (kind == "cylinder") return engine::Cylinder{radius, length};
    return engine::Capsule{radius, length};
  }
  if (kind == "mesh") {
    std::string uri = required(shape, "uri", at);
    if (uri.starts_with("model://")) uri = "package://" + uri.substr(8);
    MeshGeometry out;
    out.file = resolve_mesh_path(uri, context.file.parent_path(), context.options.packages, where);
    if (const std::optional<std::string> scale = child_text(shape, "scale")) {
      const std::vector<double> s = parse_numbers(*scale, {3}, at + " scale");
      out.scale = Eigen::Vector3d(s[0], s[1], s[2]);
      if (out.scale.cwiseAbs().minCoeff() == 0.0) {
        throw InputError(at + " scale: a factor is zero ('" + *scale + "')");
      }
    }
    if (shape.child("submesh"))
      link.notes.push_back(what + ": <submesh> ignored: the whole mesh is used");
    return out;
  }
  if (kind.empty()) throw InputError(where + ": <geometry> is empty");
  link.notes.push_back(what + ": a " + kind + " has no volume of its own and is ignored");
  return std::nullopt;
}

Link read_link(const pugi::xml_node& node, const std::string& prefix, const Context& context) {
  Link link;
  const std::string file = context.file.string();
  const std::string local = node.attribute("name").value();
  if (local.empty()) {
    throw InputError(file + ": line " + std::to_string(line_of(context.text, node.offset_debug())) +
                     ": <link> has no name");
  }
  link.name = prefix + local;
  const std::string where = file + ": link '" + link.name + "'";
  const pugi::xml_node inertial = node.child("inertial");
  if (inertial && inertial.next_sibling("inertial")) {
    throw InputError(where + ": has more than one <inertial> element");
  }
  if (inertial) link.stated = stated_inertial(inertial, local, where + ": inertial", link);
  locate_inertial(link, context.text, node, inertial);
  const char* kind = context.options.from == GeometrySource::collision ? "collision" : "visual";
  std::size_t index = 0;
  for (const pugi::xml_node element : node.children(kind)) {
    const std::string name = element.attribute("name").value();
    Geometry geometry;
    geometry.where = "link '" + link.name + "' " + kind + " " +
                     (name.empty() ? std::to_string(index) : "'" + name + "'");
    ++index;
    const std::string at = file + ": " + geometry.where;
    const pugi::xml_node shape = element.child("geometry");
    if (!shape) throw InputError(at + ": has no <geometry>");
    geometry.pose = link_pose(element, local, at);
    auto read = geometry_shape(shape, at, context, link, geometry.where);
    if (!read) continue;
    geometry.shape = std::move(*read);
    link.geometries.push_back(std::move(geometry));
  }
  note_other_geometry(link, node, context.options.from);
  return link;
}

/// What the models of a file give: their links and the joints between them.
struct SdfModels {
  std::vector<Link> links;
  std::vector<JointEdge> joints;
};

/// The links of `model` and of the models nested in it, their names prefixed by `prefix`,
/// each link's frame `model_frame` times its pose in the model; the joints between them.
void read_model(const pugi::xml_node& model, const std::string& prefix,
                const Eigen::Isometry3d& model_frame, const Context& context, SdfModels& out) {
  const std::string where =
      context.file.string() + ": model '" + std::string(model.attribute("name").value()) + "'";
  const SdfModelFrames frames(model, model_frame, where);
  for (const pugi::xml_node child : model.children()) {
    const std::string name = child.name();
    if (name == "link") {
      out.links.push_back(read_link(child, prefix, context));
      out.links.back().frame = frames.resolve(child.attribute("name").value());
    }
    if (name == "model") {
      const pugi::xml_node pose = child.child("pose");
      if (!std::string(pose.attribute("relative_to").value()).empty()) {
        throw InputError(where + ": nested model '" + child.attribute("name").value() +
                         "': pose relative_to is not supported on a model's pose");
      }
      read_model(child, prefix + child.attribute("name").value() + "::",
                 model_frame * sdf_pose_value(pose, where), context, out);
    }
    if (name == "joint") {
      JointEdge joint;
      joint.name = prefix + child.attribute("name").value();
      const std::string parent = child.child("parent").text().get();
      // A joint to the world fixes a root; it is no edge of the tree.
      if (parent == "world") continue;
      joint.parent = prefix + parent;
      joint.child = prefix + child.child("child").text().get();
      out.joints.push_back(std::move(joint));
    }
  }
}

}  // namespace

Robot read_sdf(const std::filesystem::path& file, std::string text, const ReadOptions& options) {
  Robot robot;
  robot.format = RobotFormat::sdf;
  robot.file = file;
  robot.text = std::move(text);
  pugi::xml_document document;
  load_robot_document(document, robot.text, file);
  const pugi::xml_node root = document.child("sdf");
  if (!root) throw InputError(file.string() + ": not an SDF file: it has no <sdf> element");
  const Context context{file, robot.text, options};
  // A model file's links are named as the model scopes them ("link", "nested::link"); a
  // world's by their model too ("model::link"), as several models may share link names.
  // Frames: a model file's links in the model's frame; a world's in the world's frame.
  SdfModels models;
  for (const pugi::xml_node model : root.children("model")) {
    read_model(model, "", Eigen::Isometry3d::Identity(), context, models);
  }
  for (const pugi::xml_node world : root.children("world")) {
    for (const pugi::xml_node model : world.children("model")) {
      read_model(model, std::string(model.attribute("name").value()) + "::",
                 sdf_pose_value(model.child("pose"), file.string() + ": model '" +
                                                         model.attribute("name").value() + "'"),
                 context, models);
    }
  }
  robot.links = std::move(models.links);
  build_link_tree(robot.links, models.joints, file.string(), false);
  if (robot.links.empty()) throw InputError(file.string() + ": has no <model> with a <link>");
  return robot;
}

}  // namespace tumble::app::robot
