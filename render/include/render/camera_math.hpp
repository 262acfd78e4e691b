#pragma once
// View and projection matrices of a render::Camera (OpenGL conventions: right-handed view space
// looking down -z, clip-space depth in [-1, 1]).

#include <Eigen/Core>

#include "render/draw_list.hpp"

namespace tumble::render {

/// World-to-view transform of a look-at camera.
Eigen::Matrix4f view_matrix(const Camera& camera);

/// Perspective projection for an image of the given aspect ratio (width / height).
Eigen::Matrix4f projection_matrix(const Camera& camera, float aspect);

/// Pixel coordinates (x right, y down, pixel centres at +0.5) of a world point, and its
/// clip-space w; a point behind the camera has w <= 0.
Eigen::Vector3f project_to_pixels(const Camera& camera, int width, int height,
                                  const Eigen::Vector3f& world);

}  // namespace tumble::render
