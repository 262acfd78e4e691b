#pragma once
// Where the video camera stands: automatic framing from a bound of the whole run, and the
// fixed, orbiting and following camera modes (private to the app's frame builder).

#include <Eigen/Core>
#include <limits>
#include <vector>

#include "app/scene/render_settings.hpp"
#include "engine/body/rigid_body.hpp"
#include "engine/geometry/triangle_mesh.hpp"
#include "render/draw_list.hpp"

namespace tumble::app::detail {

/// A ball in the world (m).
struct Sphere {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

/// A ball holding all of `spheres`: the centre of their bounding box, the radius reaching the
/// farthest one (not minimal, but within a factor sqrt(3) and stable).
Sphere enclosing_sphere(const std::vector<Sphere>& spheres);

/// The largest |w| a torque-free body reaches.
double largest_free_omega(const engine::BodyModel& body, const engine::BodyState& state);

/// Where a body and its drawn items go over the run.
struct MotionBound {
  std::vector<Sphere> spheres;  ///< together hold the body over the whole run
  Sphere body;                  ///< around the initial centre of mass (follow mode)
  double lowest = std::numeric_limits<double>::infinity();  ///< lowest body point, world z
};

/// Bounds the motion in closed form, with no simulation: a pivoted body stays within its reach
/// of the pivot, a body on a spring within the stretch its energy allows, a free body on its
/// straight or parabolic path (sampled). `geometry` is the body-frame mesh, `body_radius` its
/// bounding radius about the centre of mass, `reach` how far body and drawn items extend from
/// the centre of mass, `arrows` how far the drawn items extend from the rotation centre.
MotionBound motion_bound(const engine::BodyModel& body, const engine::BodyState& state,
                         const engine::TriangleMesh& geometry, double duration, double body_radius,
                         double reach, double arrows);

/// The camera's placement at time zero; camera_at() moves it along the run.
struct CameraRig {
  CameraSettings settings;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();   ///< looked-at point at t = 0
  Eigen::Vector3d offset = Eigen::Vector3d::UnitX();  ///< eye - target at t = 0
  double reach = 1.0;  ///< radius around the target that must stay visible (near/far planes)
};

/// Places the camera: explicit eye and target when given; otherwise the target is the centre
/// of `scene_bound` (follow mode: `follow_bound`, the followed body's ball around its centre
/// of mass) and the distance is the one at which that ball just fits the field of view, from
/// the azimuth and elevation. `aspect` is width / height.
CameraRig make_camera_rig(const CameraSettings& settings, const Sphere& scene_bound,
                          const Sphere& follow_bound, double aspect);

/// The camera at simulated `time`; `follow_position` is the followed body's centre of mass.
render::Camera camera_at(const CameraRig& rig, double time, const Eigen::Vector3d& follow_position);

}  // namespace tumble::app::detail
