// MJCF (MuJoCo) files: one link per body, in the file's order (MuJoCo's body ids from 1),
// its frame the nested bodies' poses composed from the world down.
#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <pugixml.hpp>

#include "app/robot/robot_model.hpp"
#include "base/errors.hpp"
#include "element_bytes.hpp"
#include "mjcf_geom.hpp"

namespace tumble::app::robot {
namespace {

using mjcf::Attributes;
using mjcf::Model;

/// Elements of MuJoCo 3 or of generated structure that make, move or repeat bodies and geoms
/// in ways tumble does not follow: refused rather than read wrong.
constexpr std::array<std::string_view, 5> kRefused = {"frame", "composite", "flexcomp", "replicate",
                                                      "attach"};

/// Throws at the first <include> anywhere below `node`.
void refuse_includes(pugi::xml_node node, const mjcf::Source& source) {
  for (const pugi::xml_node child : node.children()) {
    if (std::string_view(child.name()) == "include") {
      source.fail(child, "<include file=\"" + std::string(child.attribute("file").value()) +
                             "\">: included files are not read (put their contents into this "
                             "file, so that its inertials can be rewritten in place)");
    }
    refuse_includes(child, source);
  }
}

/// One <compiler>'s settings into `out` (its meshdir and assetdir as written).
void read_compiler_element(pugi::xml_node c, const mjcf::Source& source, mjcf::Compiler& out,
                           std::string& meshdir, std::string& assetdir) {
  if (const pugi::xml_attribute a = c.attribute("angle")) {
    const std::string value = a.value();
    if (value != "degree" && value != "radian") {
      source.fail(c, "compiler: angle: expected degree or radian, got '" + value + "'");
    }
    out.degrees = value == "degree";
  }
  if (const pugi::xml_attribute a = c.attribute("eulerseq")) {
    const std::string value = a.value();
    if (value.size() != 3 || value.find_first_not_of("xyzXYZ") != std::string::npos) {
      source.fail(c, "compiler: eulerseq: expected three of x, y, z, X, Y, Z, got '" + value + "'");
    }
    out.eulerseq = value;
  }
  if (const pugi::xml_attribute a = c.attribute("coordinate");
      a && std::string(a.value()) != "local") {
    source.fail(c, "compiler: coordinate: only local coordinates are read, got '" +
                       std::string(a.value()) + "'");
  }
  if (const pugi::xml_attribute a = c.attribute("inertiagrouprange")) {
    const std::vector<double> v =
        mjcf::parse_numbers(a.value(), 2, 2, source, c, "compiler", "inertiagrouprange");
    out.group_first = static_cast<int>(v[0]);
    out.group_last = static_cast<int>(v[1]);
  }
  if (const pugi::xml_attribute a = c.attribute("strippath")) {
    const std::string value = a.value();
    if (value != "true" && value != "false") {
      source.fail(c, "compiler: strippath: expected true or false, got '" + value + "'");
    }
    out.strippath = value == "true";
  }
  if (const pugi::xml_attribute a = c.attribute("inertiafromgeom")) {
    const std::string value = a.value();
    if (value != "true" && value != "false" && value != "auto") {
      source.fail(c,
                  "compiler: inertiafromgeom: expected true, false or auto, got '" + value + "'");
    }
    out.inertiafromgeom = value;
  }
  if (const pugi::xml_attribute a = c.attribute("meshdir")) meshdir = a.value();
  if (const pugi::xml_attribute a = c.attribute("assetdir")) assetdir = a.value();
}

/// The settings of all <compiler> elements (MuJoCo applies them before anything else).
mjcf::Compiler read_compiler(pugi::xml_node root, const mjcf::Source& source) {
  mjcf::Compiler out;
  std::string meshdir, assetdir;
  for (const pugi::xml_node c : root.children("compiler")) {
    read_compiler_element(c, source, out, meshdir, assetdir);
  }
  // meshdir wins over assetdir; both are relative to the model file's folder.
  const std::filesystem::path dir(meshdir.empty() ? assetdir : meshdir);
  out.meshdir = dir.is_absolute() ? dir : source.file.parent_path() / dir;
  return out;
}

/// The inertial element as the file states it, its rotation applied to the inertia.
StatedInertial read_inertial(pugi::xml_node node, const Model& model, const std::string& body) {
  const std::string where = body + ": inertial";
  const Attributes a{node, nullptr};
  const mjcf::Source& source = model.source;
  StatedInertial out;
  if (const auto pos = a.get("pos")) {
    const std::vector<double> p = mjcf::parse_numbers(*pos, 3, 3, source, node, where, "pos");
    out.center_of_mass = Eigen::Vector3d(p[0], p[1], p[2]);
  }
  if (const auto mass = a.get("mass")) {
    out.mass = mjcf::parse_numbers(*mass, 1, 1, source, node, where, "mass")[0];
  }
  const auto diagonal = a.get("diaginertia");
  const auto full = a.get("fullinertia");
  if (diagonal && full) {
    source.fail(node, where + ": diaginertia and fullinertia both give the inertia (give one)");
  }
  const std::optional<Eigen::Matrix3d> rotation =
      mjcf::orientation(a, model.compiler, source, where);
  if (full && rotation) {
    source.fail(node, where + ": fullinertia is in the body's axes: it takes no orientation");
  }
  if (diagonal) {
    const std::vector<double> d =
        mjcf::parse_numbers(*diagonal, 3, 3, source, node, where, "diaginertia");
    const Eigen::Matrix3d r = rotation.value_or(Eigen::Matrix3d::Identity());
    out.inertia = r * Eigen::Vector3d(d[0], d[1], d[2]).asDiagonal() * r.transpose();
  } else if (full) {
    const std::vector<double> f =
        mjcf::parse_numbers(*full, 6, 6, source, node, where, "fullinertia");
    Eigen::Matrix3d inertia;
    inertia << f[0], f[3], f[4], f[3], f[1], f[5], f[4], f[5], f[2];
    out.inertia = inertia;
  }
  return out;
}

/// Bodies, in the file's order (depth first, as MuJoCo numbers them).
struct Walk {
  const Model& model;
  const ReadOptions& options;
  Robot& robot;
  int next_id = 1;
};

/// Where a body's children are: the enclosing body's name (empty: the world) and frame.
struct Place {
  std::string parent;
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
};

void read_children(pugi::xml_node parent, const std::string& childclass, const Place& place,
                   Walk& walk);

/// The body's frame in its parent's: pos and an orientation (quat, axisangle, euler, xyaxes or
/// zaxis; bodies take no default class).
Eigen::Isometry3d body_pose(pugi::xml_node body, const Model& model, const std::string& where) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  const Attributes a{body, nullptr};
  if (const std::optional<std::string> pos = a.get("pos")) {
    const std::vector<double> p = mjcf::parse_numbers(*pos, 3, 3, model.source, body, where, "pos");
    pose.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
  }
  if (auto rotation = mjcf::orientation(a, model.compiler, model.source, where)) {
    pose.linear() = *rotation;
  }
  return pose;
}

/// The body's geoms of the kind asked for (or all, when it has none of that kind).
void read_geoms(pugi::xml_node body, const std::string& childclass, Walk& walk, Link& link) {
  std::vector<Geometry> colliding, visual;
  int index = 0;
  for (const pugi::xml_node geom : body.children("geom")) {
    const pugi::xml_attribute name = geom.attribute("name");
    const std::string where =
        "body '" + link.name + "' geom " +
        (name ? "'" + std::string(name.value()) + "'" : std::to_string(index));
    ++index;
    mjcf::GeomRead read = mjcf::read_geom(geom, childclass, walk.model, where);
    if (read.note) link.notes.push_back(*read.note);
    if (read.geometry) (read.collides ? colliding : visual).push_back(std::move(*read.geometry));
  }
  const bool want_collision = walk.options.from == GeometrySource::collision;
  std::vector<Geometry>& wanted = want_collision ? colliding : visual;
  std::vector<Geometry>& others = want_collision ? visual : colliding;
  if (wanted.empty() && !others.empty()) {
    link.notes.push_back(
        want_collision ? "no geom collides (contype and conaffinity 0): all its geoms are used"
                       : "no geom with mass is visual only (contype and conaffinity 0): all "
                         "its geoms are used");
    link.geometries = std::move(others);
  } else {
    link.geometries = std::move(wanted);
  }
}

/// The body as a link, then its child bodies.
void read_body(pugi::xml_node body, const std::string& inherited_class, const Place& place,
               Walk& walk) {
  const mjcf::Source& source = walk.model.source;
  const std::string childclass = body.attribute("childclass").as_string(inherited_class.c_str());
  Link link;
  const pugi::xml_attribute name = body.attribute("name");
  link.name = name ? name.value() : "body " + std::to_string(walk.next_id);
  ++walk.next_id;
  const std::string where = "body '" + link.name + "'";
  link.parent = place.parent;
  link.frame = place.frame * body_pose(body, walk.model, where);
  walk.model.defaults.get(childclass, body, source, where + ": childclass");
  read_geoms(body, childclass, walk, link);
  std::vector<pugi::xml_node> inertials;
  for (const pugi::xml_node inertial : body.children("inertial")) inertials.push_back(inertial);
  if (inertials.size() > 1) source.fail(inertials[1], where + ": has two inertial elements");
  const std::string& text = walk.robot.text;
  if (!inertials.empty()) {
    if (walk.model.compiler.inertiafromgeom == "true") {
      link.notes.push_back(
          "the compiler's inertiafromgeom=\"true\": MuJoCo ignores this "
          "<inertial> and uses the one computed from the geoms");
    }
    link.stated = read_inertial(inertials[0], walk.model, where);
    link.inertial_bytes =
        element_bytes(text, static_cast<std::size_t>(inertials[0].offset_debug())).whole;
  }
  const ElementBytes bytes = element_bytes(text, static_cast<std::size_t>(body.offset_debug()));
  link.insert_at = bytes.content_begin;
  link.child_indent = child_indent(text, bytes);
  const Place children{link.name, link.frame};
  walk.robot.links.push_back(std::move(link));
  read_children(body, childclass, children, walk);
}

/// The bodies among `parent`'s children (refusing what tumble would read wrong).
void read_children(pugi::xml_node parent, const std::string& childclass, const Place& place,
                   Walk& walk) {
  for (const pugi::xml_node child : parent.children()) {
    const std::string_view kind = child.name();
    if (std::find(kRefused.begin(), kRefused.end(), kind) != kRefused.end()) {
      walk.model.source.fail(child, "<" + std::string(kind) +
                                        ">: not read by tumble (it makes or moves bodies and "
                                        "geoms); expand it into plain bodies and geoms");
    }
    if (kind == "body") read_body(child, childclass, place, walk);
  }
}

}  // namespace

Robot read_mjcf(const std::filesystem::path& file, std::string text, const ReadOptions& options) {
  Robot robot;
  robot.format = RobotFormat::mjcf;
  robot.file = file;
  robot.text = std::move(text);
  const mjcf::Source source{file, &robot.text};
  pugi::xml_document document;
  const pugi::xml_parse_result parsed = document.load_buffer(
      robot.text.data(), robot.text.size(), pugi::parse_default, pugi::encoding_utf8);
  if (!parsed) {
    const auto end =
        robot.text.begin() +
        std::min<std::ptrdiff_t>(parsed.offset, static_cast<std::ptrdiff_t>(robot.text.size()));
    throw InputError(file.string() + ": line " +
                     std::to_string(std::count(robot.text.begin(), end, '\n') + 1) +
                     ": XML error: " + parsed.description());
  }
  const pugi::xml_node root = document.document_element();
  if (std::string_view(root.name()) != "mujoco") {
    source.fail(root,
                "not MJCF: the root element is <" + std::string(root.name()) + ">, not <mujoco>");
  }
  refuse_includes(root, source);
  Model model{
      source, read_compiler(root, source), mjcf::Defaults(root, source), {}, &options.packages};
  mjcf::read_mesh_assets(root, model);
  Walk walk{model, options, robot};
  for (const pugi::xml_node world : root.children("worldbody"))
    read_children(world, "main", Place{}, walk);
  return robot;
}

}  // namespace tumble::app::robot
