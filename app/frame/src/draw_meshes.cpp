#include "draw_meshes.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>
#include <vector>

#include "app/frame/frame_builder.hpp"
#include "engine/geometry/mesh_topology.hpp"
#include "engine/geometry/primitive_meshes.hpp"

namespace tumble::app {

Eigen::Vector3d equivalent_box_size(double mass, const Eigen::Vector3d& moments) {
  const double trace = moments.sum();
  Eigen::Vector3d size;
  for (int i = 0; i < 3; ++i) {
    // I_j + I_k - I_i = m s_i^2 / 6 for the box of sides s.
    size[i] = std::sqrt(std::max(0.0, 6.0 * (trace - 2.0 * moments[i]) / mass));
  }
  const double floor = 1e-3 * size.maxCoeff();
  return size.cwiseMax(Eigen::Vector3d::Constant(floor));
}

namespace detail {

render::MeshData shaded_mesh_data(const engine::TriangleMesh& mesh, double crease_angle_deg) {
  const double cos_crease = std::cos(crease_angle_deg * std::numbers::pi / 180.0);

  // Area-weighted and unit face normals, and the triangles around each vertex: those of vertex
  // v are around[start[v]] to around[start[v + 1]], in ascending order (one array for all, as
  // a counting sort: a vector per vertex cost a million-triangle mesh two million allocations).
  const std::size_t faces = mesh.triangles.size(), vertices = mesh.positions.size();
  std::vector<Eigen::Vector3d> face_normals(faces);
  std::vector<Eigen::Vector3d> unit_normals(faces);
  std::vector<std::uint32_t> start(vertices + 1, 0);
  for (std::size_t f = 0; f < faces; ++f) {
    const auto& t = mesh.triangles[f];
    const Eigen::Vector3d& a = mesh.positions[t[0]];
    face_normals[f] = (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a);
    unit_normals[f] = face_normals[f].normalized();
    for (std::uint32_t v : t) ++start[v + 1];
  }
  for (std::size_t v = 0; v < vertices; ++v) start[v + 1] += start[v];
  std::vector<std::uint32_t> around(3 * faces), cursor(start.begin(), start.end() - 1);
  for (std::size_t f = 0; f < faces; ++f) {
    for (std::uint32_t v : mesh.triangles[f]) around[cursor[v]++] = static_cast<std::uint32_t>(f);
  }

  // Each corner's normal averages the faces within the crease angle of its own; corners of a
  // vertex with the same normal share one output vertex (all of them on a smooth surface), so
  // the mesh stays connected for the renderer's simplifier and its vertex cache.
  render::MeshData out;
  out.indices.reserve(3 * faces);
  out.positions.reserve(vertices);
  out.normals.reserve(vertices);
  constexpr std::uint32_t kNone = 0xffffffffu;
  std::vector<std::uint32_t> first_out(vertices, kNone);
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> more_out;  // crease vertices
  for (std::size_t f = 0; f < faces; ++f) {
    for (std::uint32_t v : mesh.triangles[f]) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (std::uint32_t i = start[v]; i < start[v + 1]; ++i) {
        const std::uint32_t g = around[i];
        if (unit_normals[g].dot(unit_normals[f]) >= cos_crease) sum += face_normals[g];
      }
      const Eigen::Vector3f normal =
          (sum.squaredNorm() > 0.0 ? sum.normalized() : unit_normals[f]).cast<float>();
      std::uint32_t index = first_out[v];
      if (index != kNone && out.normals[index] != normal) {
        index = kNone;
        for (std::uint32_t other : more_out[v]) {
          if (out.normals[other] == normal) index = other;
        }
      }
      if (index == kNone) {
        index = static_cast<std::uint32_t>(out.positions.size());
        (first_out[v] == kNone ? first_out[v] : more_out[v].emplace_back()) = index;
        out.positions.push_back(mesh.positions[v].cast<float>());
        out.normals.push_back(normal);
      }
      out.indices.push_back(index);
    }
  }
  out.closed = engine::bounds_outward_solids(mesh);
  return out;
}

render::MeshData ellipsoid_mesh_data(const Eigen::Vector3d& radii) {
  const engine::TriangleMesh mesh = engine::ellipsoid_mesh(radii, 48, 24);
  render::MeshData out;
  const Eigen::Vector3d inverse_squared = radii.cwiseProduct(radii).cwiseInverse();
  for (const Eigen::Vector3d& p : mesh.positions) {
    out.positions.push_back(p.cast<float>());
    // The gradient of sum (x_i / r_i)^2.
    out.normals.push_back(p.cwiseProduct(inverse_squared).normalized().cast<float>());
  }
  for (const auto& t : mesh.triangles) out.indices.insert(out.indices.end(), t.begin(), t.end());
  out.closed = engine::bounds_outward_solids(mesh);
  return out;
}

double bounding_radius(const engine::TriangleMesh& mesh) {
  double radius = 0.0;
  for (const Eigen::Vector3d& p : mesh.positions) radius = std::max(radius, p.norm());
  return radius;
}

}  // namespace detail
}  // namespace tumble::app
