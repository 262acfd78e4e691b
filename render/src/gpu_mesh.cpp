#include "gpu_mesh.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace tumble::render::detail {

namespace {

void validate(const MeshData& mesh) {
  if (mesh.positions.empty() || mesh.indices.empty()) {
    throw std::invalid_argument("render mesh: no vertices or no triangles");
  }
  if (mesh.indices.size() % 3 != 0) {
    throw std::invalid_argument("render mesh: index count " + std::to_string(mesh.indices.size()) +
                                " is not a multiple of 3");
  }
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) {
    throw std::invalid_argument("render mesh: " + std::to_string(mesh.normals.size()) +
                                " normals for " + std::to_string(mesh.positions.size()) +
                                " vertices");
  }
  for (const std::uint32_t index : mesh.indices) {
    if (index >= mesh.positions.size()) {
      throw std::invalid_argument("render mesh: index " + std::to_string(index) +
                                  " out of range (" + std::to_string(mesh.positions.size()) +
                                  " vertices)");
    }
  }
}

}  // namespace

void GpuMesh::draw(std::size_t level) const {
  glBindVertexArray(vao.get());
  if (index_buffer && !levels.empty()) {
    const LodLevel& drawn = levels[std::min(level, levels.size() - 1)];
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(drawn.count), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(drawn.first * sizeof(std::uint32_t)));
  } else if (index_buffer) {
    glDrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, nullptr);
  } else {
    glDrawArrays(GL_TRIANGLES, 0, count);
  }
}

std::size_t GpuMesh::triangles(std::size_t level) const {
  if (levels.empty()) return static_cast<std::size_t>(count) / 3;
  return levels[std::min(level, levels.size() - 1)].count / 3;
}

void GpuMesh::refine_for(float pixels_per_unit) {
  if (!chain) return;
  const std::size_t built = chain->indices().size();
  if (chain->grow_for(pixels_per_unit)) {
    const std::vector<std::uint32_t>& indices = chain->indices();
    glBindVertexArray(vao.get());
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, index_buffer.get());
    if (indices.size() <= index_capacity) {
      glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLintptr>(built * sizeof(std::uint32_t)),
                      static_cast<GLsizeiptr>((indices.size() - built) * sizeof(std::uint32_t)),
                      indices.data() + built);
    } else {
      index_capacity = indices.size();
      glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                   static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)), indices.data(),
                   GL_STATIC_DRAW);
    }
    glBindVertexArray(0);
    levels = chain->levels();
  }
  if (chain->complete()) chain.reset();
}

GpuMesh upload_mesh(const MeshData& mesh, bool with_lod) {
  validate(mesh);
  GpuMesh gpu;
  gpu.closed = mesh.closed;

  // Interleave position + normal; flat shading duplicates each triangle's corners.
  std::vector<float> vertices;
  if (!mesh.normals.empty()) {
    vertices.reserve(6 * mesh.positions.size());
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      const Eigen::Vector3f n = mesh.normals[i].normalized();
      vertices.insert(vertices.end(), {mesh.positions[i].x(), mesh.positions[i].y(),
                                       mesh.positions[i].z(), n.x(), n.y(), n.z()});
    }
  } else {
    vertices.reserve(6 * mesh.indices.size());
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
      const Eigen::Vector3f& a = mesh.positions[mesh.indices[t]];
      const Eigen::Vector3f& b = mesh.positions[mesh.indices[t + 1]];
      const Eigen::Vector3f& c = mesh.positions[mesh.indices[t + 2]];
      const Eigen::Vector3f n = (b - a).cross(c - a).normalized();
      for (const Eigen::Vector3f* p : {&a, &b, &c}) {
        vertices.insert(vertices.end(), {p->x(), p->y(), p->z(), n.x(), n.y(), n.z()});
      }
    }
  }

  // Bounding sphere: centre of the axis-aligned box, radius to the farthest vertex.
  for (const auto& p : mesh.positions) gpu.box.extend(p);
  const Eigen::Vector3f centre = gpu.centre();
  for (const auto& p : mesh.positions) gpu.radius = std::max(gpu.radius, (p - centre).norm());

  gpu.vao = GlVertexArray::create();
  glBindVertexArray(gpu.vao.get());
  gpu.vertex_buffer = GlBuffer::create();
  glBindBuffer(GL_ARRAY_BUFFER, gpu.vertex_buffer.get());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)),
               vertices.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                        reinterpret_cast<const void*>(3 * sizeof(float)));
  if (!mesh.normals.empty()) {
    gpu.levels = {{0, mesh.indices.size(), 0.0f}};
    gpu.index_capacity = mesh.indices.size();
    if (with_lod && mesh.indices.size() / 3 > kLodMinTriangles) {
      std::vector<Eigen::Vector3f> unit_normals(mesh.normals.size());
      for (std::size_t i = 0; i < mesh.normals.size(); ++i) {
        unit_normals[i] = mesh.normals[i].normalized();
      }
      gpu.chain = std::make_unique<LodChain>(mesh.positions, std::move(unit_normals), mesh.indices);
      // The copies add at most a quarter, then halves of it: room for them all at once.
      gpu.index_capacity += mesh.indices.size() / 2 + 3;
    }
    gpu.index_buffer = GlBuffer::create();
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu.index_buffer.get());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(gpu.index_capacity * sizeof(std::uint32_t)), nullptr,
                 GL_STATIC_DRAW);
    glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, 0,
                    static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)),
                    mesh.indices.data());
    gpu.count = static_cast<GLsizei>(mesh.indices.size());
  } else {
    gpu.count = static_cast<GLsizei>(vertices.size() / 6);
  }
  glBindVertexArray(0);
  return gpu;
}

}  // namespace tumble::render::detail
