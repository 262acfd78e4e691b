#pragma once
/// @file A robot file as a picture (`tumble view ROBOT`, `tumble render ROBOT -o robot.png`):
/// each link's geometry in the zero configuration, its stated inertial as a translucent box of
/// equal inertia and its computed one as a wire box, links whose two inertials differ beyond
/// the tolerance highlighted.
///
/// Design note
/// - Loading (load_robot_picture) does everything that can fail: reading the file twice (the
///   drawn geometry, and the geometry `tumble inertials` computes from), importing the meshes,
///   computing the inertials. Drawing (RobotDrawing) only uploads and places what was loaded,
///   so a viewer that fails to open a robot keeps what it showed.
/// - Links are drawn from their visual geometry, or from their collision geometry when they
///   have no visual; the computed inertial follows `from` (collision by default), as
///   `tumble inertials` computes it, so "differs" here is `tumble inertials --check`'s verdict
///   at the same tolerance.
/// - The link geometry is translucent, so that the boxes inside it show; a link's boxes are
///   placed by Link::frame (the zero configuration) like its geometry.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "app/robot/inertials_report.hpp"
#include "app/video/inertia_box.hpp"
#include "engine/geometry/triangle_mesh.hpp"
#include "render/draw_list.hpp"
#include "render/renderer.hpp"

namespace tumble::app {

/// What a robot picture is made from.
struct RobotPictureOptions {
  /// The geometry the computed inertials come from (as `tumble inertials --from`).
  robot::GeometrySource from = robot::GeometrySource::collision;
  /// `--package-path NAME=DIR` values.
  std::vector<std::string> package_paths;
  /// Relative difference beyond which a link is highlighted (`tumble inertials --tolerance`).
  double tolerance = 1e-3;
};

/// One link as drawn.
struct LinkPicture {
  std::string name;
  /// The link's geometry in the model frame (zero configuration), its parts appended.
  engine::TriangleMesh geometry;
  /// "visual", "collision" (a link without visual geometry), or "none".
  std::string drawn_from;
  /// The equal-inertia boxes in the model frame, where the inertial exists.
  std::optional<InertiaBox> stated;
  std::optional<InertiaBox> computed;
  /// The stated and computed inertials differ beyond the tolerance (or the stated one is
  /// missing or impossible while the link has geometry).
  bool differs = false;
};

/// A robot file loaded for drawing.
struct RobotPicture {
  /// The comparison `tumble inertials` makes (its robot read with `from`'s geometry).
  InertialsReport report;
  std::vector<LinkPicture> links;  ///< in report.links' order
  double tolerance = 1e-3;
  /// Bounds of everything drawn, model frame (empty for a robot with nothing to draw).
  Eigen::AlignedBox3d bounds;
  std::size_t differing() const;
};

/// Whether `file` is a robot description by its name: .urdf, .sdf, .world, or an .xml whose
/// first element is <mujoco> (MJCF).
bool is_robot_file(const std::filesystem::path& file);

/// Reads and computes everything a picture of `file` needs. Throws InputError, one line
/// naming the file: unreadable or malformed, a mesh missing or unreadable, or a link whose
/// inertial cannot be computed (the first such link, as `tumble inertials` says it).
RobotPicture load_robot_picture(const std::filesystem::path& file,
                                const RobotPictureOptions& options);

/// Colours of the picture (also the legend's).
inline constexpr render::Rgba kLinkColour{0.62f, 0.64f, 0.68f, 0.30f};
inline constexpr render::Rgba kSelectedLinkColour{0.95f, 0.85f, 0.30f, 0.45f};
inline constexpr render::Rgba kStatedBoxColour{0.20f, 0.45f, 0.95f, 0.45f};
inline constexpr render::Rgba kDifferingBoxColour{0.90f, 0.12f, 0.12f, 0.50f};
inline constexpr render::Rgba kComputedWireColour{0.98f, 0.55f, 0.05f, 1.0f};

/// The camera framing the whole robot in a `width` x `height` image, seen from the front
/// right and above (z up).
render::Camera robot_camera(const RobotPicture& picture, int width, int height);

/// The link whose geometry is the first hit along the ray through pixel (`x`, `y`) of a
/// `width` x `height` image seen by `camera` (pixels from the top-left), if any.
std::optional<std::size_t> pick_link(const RobotPicture& picture, const render::Camera& camera,
                                     int width, int height, float x, float y);

/// The inspector's text for link `index`: its stated and computed inertials (mass, centre of
/// mass, principal moments, the equal-inertia boxes' sides) and their relative differences, as
/// `tumble inertials` measures them, with the verdict at the picture's tolerance.
std::string link_inspector_text(const RobotPicture& picture, std::size_t index);

/// A picture's meshes uploaded into a renderer, and the draw list that shows them.
class RobotDrawing {
 public:
  /// Uploads the links' geometry and the boxes into `renderer`, which must outlive this.
  RobotDrawing(const RobotPicture& picture, render::Renderer& renderer);

  /// The picture seen by `camera`, link `selected` (if any) highlighted, with a legend panel
  /// in the top-left corner unless `legend` is false.
  render::DrawList frame(const render::Camera& camera, std::optional<std::size_t> selected,
                         bool legend, float font_px = 13.0f) const;

 private:
  struct LinkMeshes {
    std::optional<render::MeshId> geometry;
    std::optional<render::MeshId> stated;
    Eigen::Matrix4f stated_pose = Eigen::Matrix4f::Identity();
  };
  const RobotPicture& picture_;
  std::vector<LinkMeshes> meshes_;
};

/// The twelve edges of `box` as polylines (a wire box): two closed loops and four struts.
std::vector<render::Polyline> wire_box(const InertiaBox& box, const render::Rgba& colour,
                                       float width_px);

}  // namespace tumble::app
