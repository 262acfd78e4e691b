#include "arrow_geometry.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace tumble::render::detail {

namespace {

/// Adds a flat disc at height z facing `normal_z` (+1 up, -1 down).
void add_cap(MeshData& mesh, int segments, float z, float normal_z) {
  const auto centre = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.emplace_back(0.0f, 0.0f, z);
  mesh.normals.emplace_back(0.0f, 0.0f, normal_z);
  for (int i = 0; i < segments; ++i) {
    const float angle =
        2.0f * std::numbers::pi_v<float> * static_cast<float>(i) / static_cast<float>(segments);
    mesh.positions.emplace_back(std::cos(angle), std::sin(angle), z);
    mesh.normals.emplace_back(0.0f, 0.0f, normal_z);
  }
  for (int i = 0; i < segments; ++i) {
    const auto a = centre + 1 + static_cast<std::uint32_t>(i);
    const auto b = centre + 1 + static_cast<std::uint32_t>((i + 1) % segments);
    if (normal_z > 0) {
      mesh.indices.insert(mesh.indices.end(), {centre, a, b});
    } else {
      mesh.indices.insert(mesh.indices.end(), {centre, b, a});
    }
  }
}

/// Adds the side of a (possibly tapered) tube from radius r0 at z=0 to r1 at z=1.
void add_side(MeshData& mesh, int segments, float r0, float r1) {
  const auto first = static_cast<std::uint32_t>(mesh.positions.size());
  // Side normal of a frustum: radial component 1, axial component (r0 - r1).
  const float axial = r0 - r1;
  for (int i = 0; i <= segments; ++i) {
    const float angle =
        2.0f * std::numbers::pi_v<float> * static_cast<float>(i) / static_cast<float>(segments);
    const float c = std::cos(angle);
    const float s = std::sin(angle);
    const Eigen::Vector3f normal = Eigen::Vector3f(c, s, axial).normalized();
    mesh.positions.emplace_back(r0 * c, r0 * s, 0.0f);
    mesh.normals.push_back(normal);
    mesh.positions.emplace_back(r1 * c, r1 * s, 1.0f);
    mesh.normals.push_back(normal);
  }
  for (int i = 0; i < segments; ++i) {
    const auto a = first + 2 * static_cast<std::uint32_t>(i);
    mesh.indices.insert(mesh.indices.end(), {a, a + 2, a + 1, a + 1, a + 2, a + 3});
  }
}

}  // namespace

MeshData unit_cylinder(int segments) {
  MeshData mesh;
  add_side(mesh, segments, 1.0f, 1.0f);
  add_cap(mesh, segments, 0.0f, -1.0f);
  add_cap(mesh, segments, 1.0f, 1.0f);
  mesh.closed = true;  // outward by construction (tests/render/arrow_geometry_test.cpp)
  return mesh;
}

MeshData unit_cone(int segments) {
  MeshData mesh;
  add_side(mesh, segments, 1.0f, 0.0f);
  add_cap(mesh, segments, 0.0f, -1.0f);
  mesh.closed = true;
  return mesh;
}

bool arrow_transforms(const Arrow& arrow, ArrowTransforms& out) {
  const Eigen::Vector3f axis = arrow.to - arrow.from;
  const float length = axis.norm();
  if (!(length > 0.0f) || !std::isfinite(length)) return false;
  const Eigen::Vector3f direction = axis / length;
  const float shaft_radius = 0.5f * arrow.thickness;
  const float head_length = std::min(4.5f * arrow.thickness, 0.4f * length);
  const float head_radius = 1.6f * arrow.thickness;

  // Rotation taking +z to the arrow's direction.
  const Eigen::Matrix3f rotation =
      Eigen::Quaternionf::FromTwoVectors(Eigen::Vector3f::UnitZ(), direction).toRotationMatrix();
  Eigen::Matrix4f shaft = Eigen::Matrix4f::Identity();
  shaft.block<3, 3>(0, 0) =
      rotation * Eigen::Vector3f(shaft_radius, shaft_radius, length - head_length).asDiagonal();
  shaft.block<3, 1>(0, 3) = arrow.from;
  Eigen::Matrix4f head = Eigen::Matrix4f::Identity();
  head.block<3, 3>(0, 0) =
      rotation * Eigen::Vector3f(head_radius, head_radius, head_length).asDiagonal();
  head.block<3, 1>(0, 3) = arrow.from + direction * (length - head_length);
  out = {shaft, head};
  return true;
}

}  // namespace tumble::render::detail
