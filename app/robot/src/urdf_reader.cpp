// URDF: each <link>'s stated <inertial> and its <collision> (or <visual>) geometry, and its
// frame in the zero configuration from the <joint> tree.
#include <string>
#include <utility>
#include <vector>

#include "app/robot/inertial_xml.hpp"
#include "app/robot/robot_model.hpp"
#include "base/errors.hpp"
#include "link_tree.hpp"
#include "xml_values.hpp"

namespace tumble::app::robot {
namespace {

/// What the reader of one file knows: the file, for messages, and how to resolve meshes.
struct UrdfContext {
  const std::filesystem::path& file;
  const ReadOptions& options;
};

/// The attribute's value, or `fallback` when it is absent.
std::string attribute_or(const pugi::xml_node& node, const char* name, const char* fallback) {
  const pugi::xml_attribute attribute = node.attribute(name);
  return attribute ? attribute.value() : fallback;
}

/// The attribute's value; throws InputError "WHERE: <ELEMENT> has no NAME" when absent.
std::string required_attribute(const pugi::xml_node& node, const char* name,
                               const std::string& where) {
  const pugi::xml_attribute attribute = node.attribute(name);
  if (!attribute) {
    throw InputError(where + ": <" + node.name() + "> has no " + name + " attribute");
  }
  return attribute.value();
}

/// An <origin xyz="..." rpy="..."/> (absent: the identity).
Eigen::Isometry3d origin_pose(const pugi::xml_node& parent, const std::string& where) {
  const pugi::xml_node origin = parent.child("origin");
  if (!origin) return Eigen::Isometry3d::Identity();
  const std::vector<double> xyz =
      parse_numbers(attribute_or(origin, "xyz", "0 0 0"), {3}, where + ": origin xyz");
  const std::vector<double> rpy =
      parse_numbers(attribute_or(origin, "rpy", "0 0 0"), {3}, where + ": origin rpy");
  return pose_from({xyz[0], xyz[1], xyz[2]}, rotation_from_rpy({rpy[0], rpy[1], rpy[2]}));
}

/// The <inertial> as written; missing values stay unset (the command flags them).
StatedInertial stated_inertial(const pugi::xml_node& inertial, const std::string& where,
                               Link& link) {
  StatedInertial stated;
  const Eigen::Isometry3d frame = origin_pose(inertial, where);
  stated.center_of_mass = frame.translation();
  const pugi::xml_node mass = inertial.child("mass");
  if (mass && mass.attribute("value")) {
    stated.mass = parse_number(mass.attribute("value").value(), where + ": mass value");
  }
  const pugi::xml_node inertia = inertial.child("inertia");
  if (!inertia) return stated;
  double values[6] = {};
  const char* names[6] = {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"};
  for (int i = 0; i < 6; ++i) {
    const pugi::xml_attribute attribute = inertia.attribute(names[i]);
    if (!attribute) {
      link.notes.push_back(std::string("the stated inertia has no ") + names[i]);
      return stated;
    }
    values[i] = parse_number(attribute.value(), where + ": inertia " + names[i]);
  }
  const Eigen::Matrix3d in_frame =
      inertia_matrix(values[0], values[1], values[2], values[3], values[4], values[5]);
  // Given in the inertial frame (rotated by rpy): I_link = R I R^T.
  stated.inertia = frame.linear() * in_frame * frame.linear().transpose();
  return stated;
}

/// The shape of a <geometry> element.
std::variant<engine::Shape, MeshGeometry> geometry_shape(const pugi::xml_node& geometry,
                                                         const std::string& where,
                                                         const UrdfContext& context) {
  if (const pugi::xml_node box = geometry.child("box")) {
    return engine::Box{
        parse_positive_vector(required_attribute(box, "size", where), where + ": box size")};
  }
  if (const pugi::xml_node sphere = geometry.child("sphere")) {
    return engine::Sphere{
        parse_positive(required_attribute(sphere, "radius", where), where + ": sphere radius")};
  }
  for (const char* kind : {"cylinder", "capsule"}) {
    const pugi::xml_node node = geometry.child(kind);
    if (!node) continue;
    const double radius =
        parse_positive(required_attribute(node, "radius", where), where + ": " + kind + " radius");
    const double length =
        parse_positive(required_attribute(node, "length", where), where + ": " + kind + " length");
    if (std::string(kind) == "cylinder") return engine::Cylinder{radius, length};
    return engine::Capsule{radius, length};
  }
  if (const pugi::xml_node mesh = geometry.child("mesh")) {
    MeshGeometry out;
    out.file = resolve_mesh_path(required_attribute(mesh, "filename", where),
                                 context.file.parent_path(), context.options.packages, where);
    if (const pugi::xml_attribute scale = mesh.attribute("scale")) {
      const std::vector<double> s = parse_numbers(scale.value(), {1, 3}, where + ": mesh scale");
      out.scale =
          s.size() == 1 ? Eigen::Vector3d::Constant(s[0]) : Eigen::Vector3d(s[0], s[1], s[2]);
      if (out.scale.cwiseAbs().minCoeff() == 0.0) {
        throw InputError(where + ": mesh scale: a factor is zero ('" + scale.value() + "')");
      }
    }
    return out;
  }
  throw InputError(where + ": <geometry> has no box, cylinder, sphere, capsule or mesh");
}

Link read_urdf_link(const pugi::xml_node& node, const std::string& text,
                    const UrdfContext& context) {
  Link link;
  const std::string file = context.file.string();
  link.name = required_attribute(
      node, "name", file + ": line " + std::to_string(line_of(text, node.offset_debug())));
  const std::string where = file + ": link '" + link.name + "'";
  const pugi::xml_node inertial = node.child("inertial");
  if (inertial && inertial.next_sibling("inertial")) {
    throw InputError(where + ": has more than one <inertial> element");
  }
  if (inertial) link.stated = stated_inertial(inertial, where + ": inertial", link);
  locate_inertial(link, text, node, inertial);
  const char* kind = context.options.from == GeometrySource::collision ? "collision" : "visual";
  std::size_t index = 0;
  for (const pugi::xml_node element : node.children(kind)) {
    Geometry geometry;
    geometry.where = "link '" + link.name + "' " + kind + " " + std::to_string(index++);
    const std::string at = file + ": " + geometry.where;
    const pugi::xml_node shape = element.child("geometry");
    if (!shape) throw InputError(at + ": has no <geometry>");
    geometry.pose = origin_pose(element, at);
    geometry.shape = geometry_shape(shape, at, context);
    link.geometries.push_back(std::move(geometry));
  }
  note_other_geometry(link, node, context.options.from);
  return link;
}

/// The <joint> elements as tree edges: parent and child links, and the joint's <origin> (the
/// child's frame in the parent's; every kind of joint at zero adds nothing to it).
std::vector<JointEdge> read_urdf_joints(const pugi::xml_node& root, const std::string& text,
                                        const UrdfContext& context) {
  std::vector<JointEdge> joints;
  const std::string file = context.file.string();
  for (const pugi::xml_node node : root.children("joint")) {
    JointEdge joint;
    joint.name = required_attribute(
        node, "name", file + ": line " + std::to_string(line_of(text, node.offset_debug())));
    const std::string where = file + ": joint '" + joint.name + "'";
    for (const auto& [element, out] :
         {std::pair{"parent", &joint.parent}, std::pair{"child", &joint.child}}) {
      const pugi::xml_node link = node.child(element);
      if (!link) throw InputError(where + ": has no <" + element + "> element");
      *out = required_attribute(link, "link", where);
    }
    joint.origin = origin_pose(node, where);
    joints.push_back(std::move(joint));
  }
  return joints;
}

}  // namespace

Robot read_urdf(const std::filesystem::path& file, std::string text, const ReadOptions& options) {
  Robot robot;
  robot.format = RobotFormat::urdf;
  robot.file = file;
  robot.text = std::move(text);
  pugi::xml_document document;
  load_robot_document(document, robot.text, file);
  const pugi::xml_node root = document.child("robot");
  if (!root) throw InputError(file.string() + ": not a URDF file: it has no <robot> element");
  const UrdfContext context{file, options};
  for (const pugi::xml_node node : root.children("link")) {
    robot.links.push_back(read_urdf_link(node, robot.text, context));
  }
  build_link_tree(robot.links, read_urdf_joints(root, robot.text, context), file.string(), true);
  return robot;
}

}  // namespace tumble::app::robot
