#pragma once
// Display level of detail: simplified index buffers of one mesh, each with a bound on how far
// its surface lies from the full mesh's, so a frame can draw the coarsest copy whose error is
// under a pixel at the size the mesh is drawn (render/renderer.hpp, design note).

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace tumble::render::detail {

/// Meshes with at most this many triangles are always drawn whole.
inline constexpr std::size_t kLodMinTriangles = 20000;

/// One level: a range of the concatenated index buffer and its geometric error.
struct LodLevel {
  std::size_t first = 0;  ///< first index of the level in the concatenated buffer
  std::size_t count = 0;  ///< indices (three per triangle)
  float error = 0.0f;     ///< bound on the distance to the full surface, mesh units
};

/// The full mesh (level 0, error 0) followed by simplified copies, the first with a quarter
/// of its triangles (at least 10,000), the others each about half the one before, all
/// referencing the same vertices. `indices` receives the
/// concatenation. A mesh of at most kLodMinTriangles triangles gets level 0 only.
/// `normals` are the vertices' unit normals (the bound measures how far each simplified
/// triangle's interior leaves the tangent planes at its corners).
std::vector<LodLevel> build_lod_chain(const std::vector<Eigen::Vector3f>& positions,
                                      const std::vector<Eigen::Vector3f>& normals,
                                      const std::vector<std::uint32_t>& full,
                                      std::vector<std::uint32_t>& indices);

/// The largest distance of a triangle's centroid and edge midpoints from the tangent planes
/// of its corners (through each corner, normal to its vertex normal), over `indices`.
float interior_deviation(const std::vector<Eigen::Vector3f>& positions,
                         const std::vector<Eigen::Vector3f>& normals, const std::uint32_t* indices,
                         std::size_t count);

/// The coarsest level whose error, drawn at `pixels_per_unit` pixels per mesh unit, stays
/// under `max_error_px` pixels (the levels' errors grow with their index). 0 when
/// `pixels_per_unit` is not finite and positive.
std::size_t pick_lod_level(const std::vector<LodLevel>& levels, float pixels_per_unit,
                           float max_error_px = 1.0f);

}  // namespace tumble::render::detail
