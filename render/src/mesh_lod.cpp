// Simplified copies with meshoptimizer, which keeps a subset of the original vertices, so every
// level shares the full mesh's vertex buffer and normals. The first level (a quarter of the
// triangles) is one pass over the full mesh, the costliest of the chain: on meshes of 200,000
// triangles or more it clusters vertices on a grid (meshopt_simplifySloppy), about nine times
// cheaper than edge collapses. The other levels, and the first on smaller meshes, use the
// edge-collapse simplifier (meshopt_simplify: quadric error metrics after Garland & Heckbert,
// "Surface Simplification Using Quadric Error Metrics", SIGGRAPH 1997). Levels are made on
// demand (LodChain::grow_for): a frame asks for them only as far as its size needs, so a body
// drawn large never pays for its coarse copies.
//
// Error bound. Both simplifiers report a quadric error (Garland & Heckbert): the distance of
// the kept vertices from the planes of the triangles they replaced, relative to the mesh's
// extent (times meshopt_simplifyScale for mesh units); summed over the chain's steps (each level
// is simplified from the one before: triangle inequality). That figure misses what matters most
// for an outline on a smooth surface: every kept vertex is an original vertex, on the surface,
// while a long new triangle's interior cuts inside a curved surface. Against the analytic torus
// the test samples, its centroids lay up to 3x deeper than the quadric figure. So each level's
// error is also measured: the largest distance of a triangle's centroid and edge midpoints from
// the tangent planes at its corners (the vertex normals). On a sphere of radius R a triangle
// whose corners are a apart sags by about a^2 / (8R) at an edge midpoint, which is the
// midpoint's distance from the corner's tangent plane, and by about twice less than that plane
// distance at the centroid, so the measure bounds the sag. The level's error is the larger of
// the two; a silhouette point moves by at most it, hence by error * pixels-per-unit pixels.
#include "mesh_lod.hpp"

#include <meshoptimizer.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <utility>

namespace tumble::render::detail {

namespace {

/// Stop when a level would have fewer triangles than this, or shrank by less than a tenth.
constexpr std::size_t kCoarsestTriangles = 2000;
constexpr double kLeastShrink = 0.9;
/// The first simplified copy has a quarter of the triangles, and at least this many.
constexpr std::size_t kFirstTriangles = 10000;
/// Meshes of at least this many triangles get their first copy by clustering. Below it edge
/// collapses cost under about 0.1 s and bound the copy more tightly where parts lie close
/// together: on assimp's ManyEarthsNotJustOne.nff (ten spheres, 51,200 triangles) clustering's
/// first copy was bounded at 0.039 against 0.0067 by edge collapses.
constexpr std::size_t kClusterTriangles = 200000;

}  // namespace

float interior_deviation(const std::vector<Eigen::Vector3f>& positions,
                         const std::vector<Eigen::Vector3f>& normals, const std::uint32_t* indices,
                         std::size_t count) {
  float worst = 0.0f;
  for (std::size_t t = 0; t + 2 < count; t += 3) {
    const Eigen::Vector3f* p[3] = {&positions[indices[t]], &positions[indices[t + 1]],
                                   &positions[indices[t + 2]]};
    const Eigen::Vector3f* n[3] = {&normals[indices[t]], &normals[indices[t + 1]],
                                   &normals[indices[t + 2]]};
    const Eigen::Vector3f centroid = (*p[0] + *p[1] + *p[2]) / 3.0f;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3f& corner = *p[i];
      const Eigen::Vector3f& normal = *n[i];
      const Eigen::Vector3f next = 0.5f * (corner + *p[(i + 1) % 3]);
      const Eigen::Vector3f previous = 0.5f * (corner + *p[(i + 2) % 3]);
      worst =
          std::max({worst, std::abs(normal.dot(centroid - corner)),
                    std::abs(normal.dot(next - corner)), std::abs(normal.dot(previous - corner))});
    }
  }
  return worst;
}

namespace {

/// The first level, by vertex clustering (meshopt_simplifySloppy: the vertices of each cell of a
/// uniform grid merge into the one with the least quadric error), about nine times cheaper than
/// edge collapses over the full mesh (0.05 s against 0.45 s on a million triangles). Clustering by
/// position alone would join the copies of a vertex that sit on a crease (one per normal), so it
/// runs on the positions' unique vertices and each corner then takes back the copy whose normal
/// lies closest to its triangle's. Returns the count of `out`'s indices, and the error in mesh
/// units.
std::size_t cluster_first_level(const std::vector<Eigen::Vector3f>& positions,
                                const std::vector<Eigen::Vector3f>& normals,
                                std::span<const std::uint32_t> full, std::size_t target,
                                std::vector<std::uint32_t>& out, float& error) {
  const std::size_t n = positions.size();
  std::vector<std::uint32_t> unique(n);
  const std::size_t distinct = meshopt_generateVertexRemap(unique.data(), nullptr, n,
                                                           positions.data(), n, sizeof(float) * 3);
  // The copies of each distinct position, the first one first (it stands for them all).
  std::vector<std::uint32_t> start(distinct + 1, 0), copies(n);
  for (std::size_t v = 0; v < n; ++v) ++start[unique[v] + 1];
  for (std::size_t u = 0; u < distinct; ++u) start[u + 1] += start[u];
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::size_t v = 0; v < n; ++v) copies[fill[unique[v]]++] = static_cast<std::uint32_t>(v);

  std::vector<std::uint32_t> shadow(full.size());
  for (std::size_t i = 0; i < full.size(); ++i) shadow[i] = copies[start[unique[full[i]]]];
  out.resize(full.size());
  const std::size_t made =
      meshopt_simplifySloppy(out.data(), shadow.data(), shadow.size(), positions.front().data(), n,
                             sizeof(float) * 3, target, std::numeric_limits<float>::max(), &error);
  error *= meshopt_simplifyScale(positions.front().data(), n, sizeof(float) * 3);  // mesh units
  for (std::size_t t = 0; t + 2 < made; t += 3) {
    const Eigen::Vector3f& a = positions[out[t]];
    const Eigen::Vector3f face = (positions[out[t + 1]] - a).cross(positions[out[t + 2]] - a);
    for (std::size_t c = t; c < t + 3; ++c) {
      const std::uint32_t u = unique[out[c]];
      float best = -std::numeric_limits<float>::infinity();
      for (std::uint32_t k = start[u]; k < start[u + 1]; ++k) {
        const float along = normals[copies[k]].dot(face);
        if (along > best) {
          best = along;
          out[c] = copies[k];
        }
      }
    }
  }
  return made;
}

/// Simplifies `source` toward `target` indices by edge collapses, over the vertices it uses
/// only, renumbered in their order: meshopt_simplify's cost grows with the vertex count it is
/// given as well as with the indices, so given the full mesh's vertices every level cost about
/// as much as the first (on a 1M-triangle torus 300 ms a level, against 26 ms for a
/// 31,000-triangle level given its own 16,000 vertices). Returns the count of `out`'s indices
/// (into `positions`), and the step's error in mesh units.
std::size_t collapse_edges(const std::vector<Eigen::Vector3f>& positions,
                           std::span<const std::uint32_t> source, std::size_t target,
                           std::vector<std::uint32_t>& out, float& error) {
  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> compact(positions.size(), kUnused), original;
  for (const std::uint32_t v : source) compact[v] = 0;
  std::vector<Eigen::Vector3f> kept;
  for (std::size_t v = 0; v < positions.size(); ++v) {
    if (compact[v] == kUnused) continue;
    compact[v] = static_cast<std::uint32_t>(original.size());
    original.push_back(static_cast<std::uint32_t>(v));
    kept.push_back(positions[v]);
  }
  std::vector<std::uint32_t> renumbered(source.size());
  for (std::size_t i = 0; i < source.size(); ++i) renumbered[i] = compact[source[i]];
  out.resize(source.size());
  float relative = 0.0f;
  const std::size_t made = meshopt_simplify(
      out.data(), renumbered.data(), renumbered.size(), kept.front().data(), kept.size(),
      sizeof(Eigen::Vector3f), target, std::numeric_limits<float>::max(), 0, &relative);
  for (std::size_t i = 0; i < made; ++i) out[i] = original[out[i]];
  error =
      relative * meshopt_simplifyScale(kept.front().data(), kept.size(), sizeof(Eigen::Vector3f));
  return made;
}

}  // namespace

LodChain::LodChain(std::vector<Eigen::Vector3f> positions, std::vector<Eigen::Vector3f> normals,
                   const std::vector<std::uint32_t>& full)
    : positions_(std::move(positions)),
      normals_(std::move(normals)),
      levels_{{0, full.size(), 0.0f}},
      indices_(full.begin(), full.end()) {
  static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "packed positions");
  complete_ = full.size() / 3 <= kLodMinTriangles || positions_.empty() ||
              normals_.size() != positions_.size();
  if (complete_) {
    positions_ = {};
    normals_ = {};
    return;
  }
}

bool LodChain::grow() {
  if (complete_) return false;
  // The first copy goes from the full mesh straight down to a quarter (one pass over the big
  // mesh; by clustering on the biggest), the others halve the one before by edge collapses.
  // The source is the coarsest level so far: the full mesh, at the front of indices_, at first.
  const bool first = levels_.size() == 1;
  const std::span<const std::uint32_t> source =
      first ? std::span<const std::uint32_t>(indices_.data(), levels_.front().count)
            : std::span<const std::uint32_t>(previous_);
  const std::size_t target =
      first ? std::max(source.size() / 3 / 4, kFirstTriangles) * 3 : (source.size() / 3 / 2) * 3;
  std::vector<std::uint32_t> next;
  std::size_t made = 0;
  float step_error = 0.0f;
  if (target / 3 >= kCoarsestTriangles && target < source.size()) {
    if (first && source.size() / 3 >= kClusterTriangles) {
      made = cluster_first_level(positions_, normals_, source, target, next, step_error);
    } else {
      made = collapse_edges(positions_, source, target, next, step_error);
    }
  }
  if (made == 0 || static_cast<double>(made) > kLeastShrink * static_cast<double>(source.size())) {
    complete_ = true;  // nothing more to make: let the copies go
    positions_ = {};
    normals_ = {};
    previous_ = {};
    return false;
  }
  quadric_error_ += step_error;
  const float measured = interior_deviation(positions_, normals_, next.data(), made);
  levels_.push_back(
      {indices_.size(), made, std::max({quadric_error_, measured, levels_.back().error})});
  indices_.insert(indices_.end(), next.begin(), next.begin() + static_cast<std::ptrdiff_t>(made));
  next.resize(made);
  previous_ = std::move(next);
  return true;
}

bool LodChain::grow_for(float pixels_per_unit, float max_error_px) {
  bool grew = false;
  if (!(pixels_per_unit > 0.0f) || !std::isfinite(pixels_per_unit)) return false;
  while (!complete_ && levels_.back().error * pixels_per_unit < max_error_px) grew |= grow();
  return grew;
}

std::vector<LodLevel> build_lod_chain(const std::vector<Eigen::Vector3f>& positions,
                                      const std::vector<Eigen::Vector3f>& normals,
                                      const std::vector<std::uint32_t>& full,
                                      std::vector<std::uint32_t>& indices) {
  LodChain chain(positions, normals, full);
  while (chain.grow()) {
  }
  indices = chain.indices();
  return chain.levels();
}

std::size_t pick_lod_level(const std::vector<LodLevel>& levels, float pixels_per_unit,
                           float max_error_px) {
  if (!(pixels_per_unit > 0.0f) || !std::isfinite(pixels_per_unit)) return 0;
  std::size_t chosen = 0;
  for (std::size_t i = 1; i < levels.size(); ++i) {
    if (levels[i].error * pixels_per_unit < max_error_px) chosen = i;
  }
  return chosen;
}

}  // namespace tumble::render::detail
