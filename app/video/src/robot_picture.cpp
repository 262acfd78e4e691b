// A robot file as a picture: loading (everything that can fail) and drawing.
#include "app/video/robot_picture.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <numbers>
#include <type_traits>
#include <utility>
#include <variant>

#include "base/errors.hpp"
#include "engine/geometry/primitive_meshes.hpp"
#include "engine/import/mesh_import.hpp"
#include "engine/mass/primitive_shapes.hpp"
#include "render/camera_math.hpp"

namespace tumble::app {
namespace {

using tumble::InputError;

/// Segments around a curved primitive's axis.
constexpr int kRobotShapeSegments = 32;
/// A box side the moments make zero is drawn this fraction of the longest.
constexpr double kFlatBoxFloor = 1e-3;

std::string lower_extension(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

/// One geometry as a mesh in the model frame: the link's frame, then the geometry's pose.
engine::TriangleMesh placed_geometry(const robot::Geometry& geometry,
                                     const Eigen::Isometry3d& link_frame) {
  engine::TriangleMesh mesh;
  Eigen::Matrix3d scale = Eigen::Matrix3d::Identity();
  if (const auto* shape = std::get_if<engine::Shape>(&geometry.shape)) {
    mesh = engine::tessellate(*shape, kRobotShapeSegments);
  } else {
    const auto& file = std::get<robot::MeshGeometry>(geometry.shape);
    mesh = engine::import_mesh(file.file);
    scale = file.scale.asDiagonal();
  }
  const Eigen::Isometry3d placement = link_frame * geometry.pose;
  engine::transform_mesh(mesh, placement.linear() * scale, placement.translation());
  return mesh;
}

/// The equal-inertia box of `properties` (link frame) placed in the model frame.
InertiaBox placed_box(const engine::MassProperties& properties,
                      const Eigen::Isometry3d& link_frame) {
  InertiaBox box = equal_inertia_box(properties);
  box.center = link_frame * box.center;
  box.axes = link_frame.linear() * box.axes;
  return box;
}

/// The stated inertial as mass properties, when it states a positive mass and an inertia.
std::optional<engine::MassProperties> stated_properties(
    const std::optional<robot::StatedInertial>& stated) {
  if (!stated || !stated->mass || !stated->inertia || !(*stated->mass > 0.0)) return std::nullopt;
  if (!stated->inertia->allFinite()) return std::nullopt;
  return engine::MassProperties{*stated->mass, stated->center_of_mass, *stated->inertia};
}

Eigen::Vector3d drawn_sides(const InertiaBox& box) {
  const double floor = std::max(kFlatBoxFloor * box.sides.maxCoeff(), 1e-9);
  return box.sides.cwiseMax(Eigen::Vector3d::Constant(floor));
}

/// The box's eight corners, corner i at (+-, +-, +-) half sides by the bits of i.
std::array<Eigen::Vector3f, 8> box_corners(const InertiaBox& box) {
  const Eigen::Vector3d half = 0.5 * drawn_sides(box);
  std::array<Eigen::Vector3f, 8> corners;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d unit((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0);
    corners[static_cast<std::size_t>(i)] =
        (box.center + box.axes * unit.cwiseProduct(half)).cast<float>();
  }
  return corners;
}

void extend(Eigen::AlignedBox3d& bounds, const InertiaBox& box) {
  for (const Eigen::Vector3f& corner : box_corners(box)) bounds.extend(corner.cast<double>());
}

render::MeshData flat_mesh_data(const engine::TriangleMesh& mesh) {
  render::MeshData data;
  data.positions.reserve(mesh.positions.size());
  for (const Eigen::Vector3d& p : mesh.positions) data.positions.push_back(p.cast<float>());
  data.indices.reserve(3 * mesh.triangles.size());
  for (const auto& triangle : mesh.triangles) {
    data.indices.insert(data.indices.end(), triangle.begin(), triangle.end());
  }
  return data;
}

/// Distance along the ray `origin` + t `direction` to triangle (a, b, c), if it is hit at
/// t > 0 (Moller and Trumbore, "Fast, minimum storage ray-triangle intersection", 1997).
std::optional<double> ray_hits_triangle(const Eigen::Vector3d& origin,
                                        const Eigen::Vector3d& direction, const Eigen::Vector3d& a,
                                        const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a;
  const Eigen::Vector3d ac = c - a;
  const Eigen::Vector3d p = direction.cross(ac);
  const double determinant = ab.dot(p);
  if (std::abs(determinant) < 1e-300) return std::nullopt;
  const Eigen::Vector3d s = origin - a;
  const double u = s.dot(p) / determinant;
  if (u < 0.0 || u > 1.0) return std::nullopt;
  const Eigen::Vector3d q = s.cross(ab);
  const double v = direction.dot(q) / determinant;
  if (v < 0.0 || u + v > 1.0) return std::nullopt;
  const double t = ac.dot(q) / determinant;
  if (!(t > 0.0)) return std::nullopt;
  return t;
}

std::string box_sides_text(const std::optional<InertiaBox>& box) {
  if (!box) return "-";
  char text[96];
  std::snprintf(text, sizeof text, "%.4g x %.4g x %.4g m", box->sides[0], box->sides[1],
                box->sides[2]);
  return text;
}

}  // namespace

std::optional<std::size_t> pick_link(const RobotPicture& picture, const render::Camera& camera,
                                     int width, int height, float x, float y) {
  // The pixel's ray: its points on the near and far planes, back through the projection.
  const Eigen::Matrix4f clip_from_world =
      render::projection_matrix(camera, static_cast<float>(width) / static_cast<float>(height)) *
      render::view_matrix(camera);
  const Eigen::Matrix4d world_from_clip = clip_from_world.cast<double>().inverse();
  const double ndc_x = 2.0 * x / width - 1.0;
  const double ndc_y = 1.0 - 2.0 * y / height;
  const auto unproject = [&](double ndc_z) {
    const Eigen::Vector4d point = world_from_clip * Eigen::Vector4d(ndc_x, ndc_y, ndc_z, 1.0);
    return Eigen::Vector3d(point.head<3>() / point.w());
  };
  const Eigen::Vector3d origin = unproject(-1.0);
  const Eigen::Vector3d direction = (unproject(1.0) - origin).normalized();
  std::optional<std::size_t> nearest;
  double nearest_t = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < picture.links.size(); ++i) {
    const engine::TriangleMesh& mesh = picture.links[i].geometry;
    for (const auto& triangle : mesh.triangles) {
      const auto t = ray_hits_triangle(origin, direction, mesh.positions[triangle[0]],
                                       mesh.positions[triangle[1]], mesh.positions[triangle[2]]);
      if (t && *t < nearest_t) {
        nearest_t = *t;
        nearest = i;
      }
    }
  }
  return nearest;
}

std::string link_inspector_text(const RobotPicture& picture, std::size_t index) {
  const LinkPicture& link = picture.links.at(index);
  std::string text = format_comparison(picture.report.robot, {picture.report.links.at(index)},
                                       picture.report.source, picture.tolerance, true);
  // The file's header line is the window's title already; the link's block and verdict stay.
  text.erase(0, text.find('\n') + 1);
  while (!text.empty() && text.front() == '\n') text.erase(0, 1);
  text += "\nequal-inertia box, stated:   " + box_sides_text(link.stated) +
          "\nequal-inertia box, computed: " + box_sides_text(link.computed) +
          "\ndrawn from: " + link.drawn_from + " geometry\n";
  return text;
}

std::size_t RobotPicture::differing() const {
  return static_cast<std::size_t>(std::count_if(
      links.begin(), links.end(), [](const LinkPicture& link) { return link.differs; }));
}

bool is_robot_file(const std::filesystem::path& file) {
  const std::string extension = lower_extension(file);
  if (extension == ".urdf" || extension == ".sdf" || extension == ".world") return true;
  if (extension != ".xml") return false;
  // MJCF: the first element (after the declaration and comments) is <mujoco>.
  std::ifstream in(file, std::ios::binary);
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head.find("<mujoco") != std::string::npos;
}

RobotPicture load_robot_picture(const std::filesystem::path& file,
                                const RobotPictureOptions& options) {
  robot::ReadOptions read;
  read.from = options.from;
  read.packages = package_paths(options.package_paths);
  RobotPicture picture{compute_inertials(file, read, {}), {}, options.tolerance, {}};
  if (picture.report.failed()) throw InputError(picture.report.errors().front());

  // The drawn geometry: visual, else the link's collision geometry.
  read.from = robot::GeometrySource::visual;
  const robot::Robot visual = robot::read_robot(file, read);
  read.from = robot::GeometrySource::collision;
  const robot::Robot collision = options.from == robot::GeometrySource::collision
                                     ? picture.report.robot
                                     : robot::read_robot(file, read);
  Eigen::AlignedBox3d stated_bounds;
  for (std::size_t i = 0; i < picture.report.links.size(); ++i) {
    const robot::Link& link = picture.report.robot.links[i];
    const LinkComparison& comparison = picture.report.links[i];
    LinkPicture out;
    out.name = link.name;
    out.drawn_from = "none";
    for (const auto* source : {&visual, &collision}) {
      if (i >= source->links.size() || source->links[i].geometries.empty()) continue;
      for (const robot::Geometry& geometry : source->links[i].geometries) {
        engine::append_mesh(out.geometry, placed_geometry(geometry, link.frame));
      }
      out.drawn_from = source == &visual ? "visual" : "collision";
      break;
    }
    for (const Eigen::Vector3d& p : out.geometry.positions) picture.bounds.extend(p);
    if (const auto stated = stated_properties(link.stated)) {
      out.stated = placed_box(*stated, link.frame);
      extend(stated_bounds, *out.stated);
    }
    if (comparison.result.computed) {
      out.computed = placed_box(*comparison.result.computed, link.frame);
      extend(picture.bounds, *out.computed);
    }
    out.differs = !within_tolerance(comparison, options.tolerance);
    picture.links.push_back(std::move(out));
  }
  // A stated box frames the picture only when nothing else can (a wrong one may be huge).
  if (picture.bounds.isEmpty()) picture.bounds = stated_bounds;
  return picture;
}

render::Camera robot_camera(const RobotPicture& picture, int width, int height) {
  render::Camera camera;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0.5;
  if (!picture.bounds.isEmpty()) {
    center = picture.bounds.center();
    radius = std::max(0.5 * picture.bounds.diagonal().norm(), 1e-6);
  }
  // The bounding sphere within the narrower of the two fields of view, with a margin.
  const double vertical = camera.vertical_fov_deg * std::numbers::pi / 180.0;
  const double aspect = static_cast<double>(width) / static_cast<double>(std::max(height, 1));
  const double horizontal = 2.0 * std::atan(std::tan(vertical / 2.0) * aspect);
  const double distance = 1.1 * radius / std::sin(std::min(vertical, horizontal) / 2.0);
  const Eigen::Vector3d direction = Eigen::Vector3d(1.0, -1.4, 0.8).normalized();
  camera.target = center.cast<float>();
  camera.eye = (center + distance * direction).cast<float>();
  camera.up = Eigen::Vector3f::UnitZ();
  camera.near_plane = static_cast<float>(std::max(distance - 2.0 * radius, distance * 1e-3));
  camera.far_plane = static_cast<float>(distance + 4.0 * radius);
  return camera;
}

std::vector<render::Polyline> wire_box(const InertiaBox& box, const render::Rgba& colour,
                                       float width_px) {
  const std::array<Eigen::Vector3f, 8> c = box_corners(box);
  std::vector<render::Polyline> lines;
  // The loops z- (corners 0,1,3,2) and z+ (4,5,7,6), then the struts joining them.
  lines.push_back({{c[0], c[1], c[3], c[2], c[0]}, colour, width_px});
  lines.push_back({{c[4], c[5], c[7], c[6], c[4]}, colour, width_px});
  for (std::size_t i = 0; i < 4; ++i) lines.push_back({{c[i], c[i + 4]}, colour, width_px});
  return lines;
}

RobotDrawing::RobotDrawing(const RobotPicture& picture, render::Renderer& renderer)
    : picture_(picture) {
  for (const LinkPicture& link : picture.links) {
    LinkMeshes meshes;
    if (!link.geometry.triangles.empty()) {
      meshes.geometry = renderer.upload(flat_mesh_data(link.geometry));
    }
    if (link.stated) {
      meshes.stated = renderer.upload(flat_mesh_data(engine::box_mesh(drawn_sides(*link.stated))));
      Eigen::Matrix4d pose = Eigen::Matrix4d::Identity();
      pose.topLeftCorner<3, 3>() = link.stated->axes;
      pose.topRightCorner<3, 1>() = link.stated->center;
      meshes.stated_pose = pose.cast<float>();
    }
    meshes_.push_back(meshes);
  }
}

render::DrawList RobotDrawing::frame(const render::Camera& camera,
                                     std::optional<std::size_t> selected, bool legend,
                                     float font_px) const {
  render::DrawList list;
  list.camera = camera;
  for (std::size_t i = 0; i < picture_.links.size(); ++i) {
    const LinkPicture& link = picture_.links[i];
    const LinkMeshes& meshes = meshes_[i];
    if (meshes.geometry) {
      list.meshes.push_back({*meshes.geometry, Eigen::Matrix4f::Identity(),
                             selected == i ? kSelectedLinkColour : kLinkColour});
    }
    if (meshes.stated) {
      list.meshes.push_back({*meshes.stated, meshes.stated_pose,
                             link.differs ? kDifferingBoxColour : kStatedBoxColour});
    }
    if (link.computed) {
      const float width = selected == i ? 3.0f : 2.0f;
      for (render::Polyline& line : wire_box(*link.computed, kComputedWireColour, width)) {
        list.polylines.push_back(std::move(line));
      }
    }
  }
  if (legend) {
    render::OverlayPanel panel;
    panel.title = picture_.report.robot.file.filename().string();
    panel.font_px = font_px;
    panel.width_px = 26.0f * font_px;
    char tolerance[32];
    std::snprintf(tolerance, sizeof tolerance, "%g", picture_.tolerance);
    panel.lines = {
        std::to_string(picture_.links.size()) + " links; inertia from " + picture_.report.source,
        "blue box: stated inertial (equal inertia)", "orange wire: computed inertial",
        "red box: differs by > " + std::string(tolerance) + " (" +
            std::to_string(picture_.differing()) + " of them)"};
    list.panels.push_back(std::move(panel));
  }
  return list;
}

}  // namespace tumble::app
