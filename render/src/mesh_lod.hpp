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
/// referencing the same vertices, built one level at a time and only as far as frames need
/// them. A mesh of at most kLodMinTriangles triangles (or without normals) has level 0 only.
/// `normals` are the vertices' unit normals (the bound measures how far each simplified
/// triangle's interior leaves the tangent planes at its corners).
class LodChain {
 public:
  LodChain(std::vector<Eigen::Vector3f> positions, std::vector<Eigen::Vector3f> normals,
           const std::vector<std::uint32_t>& full);

  const std::vector<LodLevel>& levels() const { return levels_; }
  /// The concatenation of the levels' indices built so far.
  const std::vector<std::uint32_t>& indices() const { return indices_; }
  /// No further level will be made.
  bool complete() const { return complete_; }
  /// Makes the next level; false (and complete() from then on) when there is none.
  bool grow();
  /// Grows until the coarsest level built is not under `max_error_px` at `pixels_per_unit`
  /// (or the chain is complete), so that pick_lod_level over the levels built chooses what it
  /// would over the whole chain. Returns whether a level was added.
  bool grow_for(float pixels_per_unit, float max_error_px = 1.0f);

 private:
  std::vector<Eigen::Vector3f> positions_;
  std::vector<Eigen::Vector3f> normals_;
  std::vector<LodLevel> levels_;
  std::vector<std::uint32_t> indices_;
  std::vector<std::uint32_t> previous_;  ///< the coarsest copy's indices (none yet: empty)
  float quadric_error_ = 0.0f;           ///< meshoptimizer's errors summed along the chain
  bool complete_ = false;
};

/// The whole chain at once (every level LodChain would make); `indices` receives the
/// concatenation.
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
