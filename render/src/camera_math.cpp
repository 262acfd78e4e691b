#include "render/camera_math.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace tumble::render {

Eigen::Matrix4f view_matrix(const Camera& camera) {
  const Eigen::Vector3f forward = (camera.target - camera.eye).normalized();
  Eigen::Vector3f side = forward.cross(camera.up);
  if (side.squaredNorm() < 1e-12f) side = forward.unitOrthogonal();  // up parallel to view
  side.normalize();
  const Eigen::Vector3f true_up = side.cross(forward);
  Eigen::Matrix4f view = Eigen::Matrix4f::Identity();
  view.block<1, 3>(0, 0) = side.transpose();
  view.block<1, 3>(1, 0) = true_up.transpose();
  view.block<1, 3>(2, 0) = -forward.transpose();
  view(0, 3) = -side.dot(camera.eye);
  view(1, 3) = -true_up.dot(camera.eye);
  view(2, 3) = forward.dot(camera.eye);
  return view;
}

Eigen::Matrix4f projection_matrix(const Camera& camera, float aspect) {
  const float fov = camera.vertical_fov_deg * std::numbers::pi_v<float> / 180.0f;
  const float focal = 1.0f / std::tan(0.5f * fov);
  const float n = camera.near_plane;
  const float f = camera.far_plane;
  Eigen::Matrix4f projection = Eigen::Matrix4f::Zero();
  projection(0, 0) = focal / aspect;
  projection(1, 1) = focal;
  projection(2, 2) = (f + n) / (n - f);
  projection(2, 3) = 2.0f * f * n / (n - f);
  projection(3, 2) = -1.0f;
  return projection;
}

Eigen::Vector3f project_to_pixels(const Camera& camera, int width, int height,
                                  const Eigen::Vector3f& world) {
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const Eigen::Vector4f clip =
      projection_matrix(camera, aspect) * view_matrix(camera) * world.homogeneous();
  const float w = clip.w();
  const float x_ndc = clip.x() / w;
  const float y_ndc = clip.y() / w;
  return {0.5f * (x_ndc + 1.0f) * static_cast<float>(width),
          0.5f * (1.0f - y_ndc) * static_cast<float>(height), w};
}

}  // namespace tumble::render
