// Display level of detail: the simplified copies' error bounds against the analytic surface the
// mesh samples, the level rule, and images drawn from them against the full mesh's.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "mesh_lod.hpp"
#include "render/renderer.hpp"
#include "render_support.hpp"
#include "support/torus_mesh.hpp"

namespace tumble::render {
namespace {

constexpr float kMajor = 0.6f;
constexpr float kMinor = 0.25f;

MeshData torus(int rings, int sides) {
  return tumble::testing::torus_mesh(rings, sides, kMajor, kMinor);
}

/// Distance from a point to the analytic torus surface.
float torus_distance(const Eigen::Vector3f& p) {
  const float ring = std::hypot(p.x(), p.y()) - kMajor;
  return std::abs(std::hypot(ring, p.z()) - kMinor);
}

TEST(LodChain, EachLevelShrinksAndStaysWithinItsErrorOfTheSurface) {
  const MeshData mesh = torus(300, 150);  // 90,000 triangles
  std::vector<std::uint32_t> indices;
  const std::vector<detail::LodLevel> levels =
      detail::build_lod_chain(mesh.positions, mesh.normals, mesh.indices, indices);
  ASSERT_GE(levels.size(), 3u);
  EXPECT_EQ(levels[0].count, mesh.indices.size());
  EXPECT_EQ(levels[0].error, 0.0f);
  // The full mesh's own distance to the torus: the sag of its chords (the coarser direction).
  const float sag = kMinor * (1.0f - std::cos(std::numbers::pi_v<float> / 150.0f)) +
                    (kMajor + kMinor) * (1.0f - std::cos(std::numbers::pi_v<float> / 300.0f));
  for (std::size_t k = 1; k < levels.size(); ++k) {
    SCOPED_TRACE(k);
    EXPECT_LE(levels[k].count, levels[k - 1].count * (k == 1 ? 3 : 6) / 10);
    EXPECT_GE(levels[k].error, levels[k - 1].error);
    EXPECT_EQ(levels[k].first, levels[k - 1].first + levels[k - 1].count);
    // The triangles' centres lie within the level's error (plus the full mesh's sag) of the
    // surface: an oracle independent of the simplifier's own bookkeeping.
    float worst = 0.0f;
    for (std::size_t t = levels[k].first; t < levels[k].first + levels[k].count; t += 3) {
      const Eigen::Vector3f centre = (mesh.positions[indices[t]] + mesh.positions[indices[t + 1]] +
                                      mesh.positions[indices[t + 2]]) /
                                     3.0f;
      worst = std::max(worst, torus_distance(centre));
    }
    EXPECT_LE(worst, levels[k].error + sag + 1e-5f)
        << "ratio " << worst / (levels[k].error + sag) << " tris " << levels[k].count / 3;
  }
  // Small meshes are left whole.
  const MeshData small = torus(40, 40);
  EXPECT_EQ(detail::build_lod_chain(small.positions, small.normals, small.indices, indices).size(),
            1u);
}

TEST(LodChain, GrowsOnlyAsFarAsAFrameNeedsAndPicksAsTheWholeChainWould) {
  const MeshData mesh = torus(300, 150);
  std::vector<std::uint32_t> indices;
  const std::vector<detail::LodLevel> whole =
      detail::build_lod_chain(mesh.positions, mesh.normals, mesh.indices, indices);
  ASSERT_GE(whole.size(), 4u);
  for (const float pixels_per_unit : {1.0f, 30.0f, 100.0f, 300.0f, 1000.0f, 1e5f}) {
    SCOPED_TRACE(pixels_per_unit);
    detail::LodChain chain(mesh.positions, mesh.normals, mesh.indices);
    EXPECT_EQ(chain.levels().size(), 1u);  // nothing is made before a frame asks
    chain.grow_for(pixels_per_unit);
    const std::vector<detail::LodLevel>& built = chain.levels();
    const std::size_t picked = detail::pick_lod_level(whole, pixels_per_unit);
    EXPECT_EQ(detail::pick_lod_level(built, pixels_per_unit), picked);
    // One level past the one picked (to know it is too coarse), unless the chain ran out.
    EXPECT_EQ(built.size(), std::min(picked + 2, whole.size()));
    for (std::size_t k = 0; k < built.size(); ++k) {
      EXPECT_EQ(built[k].count, whole[k].count);
      EXPECT_EQ(built[k].error, whole[k].error);
    }
    // Asking again for the same size makes nothing more.
    EXPECT_FALSE(chain.grow_for(pixels_per_unit));
  }
  detail::LodChain chain(mesh.positions, mesh.normals, mesh.indices);
  EXPECT_FALSE(chain.grow_for(std::nanf("")));
  EXPECT_FALSE(chain.grow_for(0.0f));
  EXPECT_EQ(chain.levels().size(), 1u);
}

/// A cube of side 1 whose faces are n x n grids, each face with its own corner copies (flat
/// normals, split at the edges as shaded_mesh_data splits creases).
MeshData gridded_cube(int n) {
  MeshData mesh;
  for (int axis = 0; axis < 3; ++axis) {
    for (const float side : {-0.5f, 0.5f}) {
      Eigen::Vector3f normal = Eigen::Vector3f::Zero();
      normal[axis] = side > 0 ? 1.0f : -1.0f;
      const int u = (axis + 1) % 3;
      const int v = (axis + 2) % 3;
      const auto base = static_cast<std::uint32_t>(mesh.positions.size());
      for (int i = 0; i <= n; ++i) {
        for (int j = 0; j <= n; ++j) {
          Eigen::Vector3f p;
          p[axis] = side;
          p[u] = -0.5f + static_cast<float>(i) / static_cast<float>(n);
          p[v] = -0.5f + static_cast<float>(j) / static_cast<float>(n);
          mesh.positions.push_back(p);
          mesh.normals.push_back(normal);
        }
      }
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          const auto at = [&](int a, int b) {
            return base + static_cast<std::uint32_t>(a * (n + 1) + b);
          };
          std::uint32_t q[4] = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
          if (side < 0) std::swap(q[1], q[3]);
          mesh.indices.insert(mesh.indices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
        }
      }
    }
  }
  return mesh;
}

TEST(LodChain, CornersOnACreaseKeepTheNormalOfTheirOwnFace) {
  // The first level clusters vertices by position, where the copies of an edge vertex (one
  // per face) coincide; each corner must come back with its own face's copy, or the faces
  // along the cube's edges would be shaded as if bent by 90 degrees.
  const MeshData mesh = gridded_cube(130);  // 202,800 triangles: clustered
  detail::LodChain chain(mesh.positions, mesh.normals, mesh.indices);
  ASSERT_TRUE(chain.grow());
  const detail::LodLevel& first = chain.levels()[1];
  EXPECT_LE(first.count, mesh.indices.size() * 3 / 10);
  const std::vector<std::uint32_t>& indices = chain.indices();
  std::size_t folded = 0;  // corners whose normal is off their triangle's own by over 45 deg
  for (std::size_t t = first.first; t < first.first + first.count; t += 3) {
    const Eigen::Vector3f& a = mesh.positions[indices[t]];
    const Eigen::Vector3f face =
        (mesh.positions[indices[t + 1]] - a).cross(mesh.positions[indices[t + 2]] - a);
    if (face.norm() < 1e-9f) continue;
    for (std::size_t c = t; c < t + 3; ++c) {
      folded += mesh.normals[indices[c]].dot(face.normalized()) <
                std::cos(0.25f * std::numbers::pi_v<float>);
    }
  }
  EXPECT_EQ(folded, 0u);
  // The cube keeps its size: its error bound is far under its side.
  EXPECT_LT(first.error, 0.05f);
}

TEST(LodChain, PicksTheCoarsestLevelUnderAPixel) {
  const std::vector<detail::LodLevel> levels{
      {0, 300, 0.0f}, {300, 150, 0.001f}, {450, 75, 0.004f}, {525, 36, 0.02f}};
  EXPECT_EQ(detail::pick_lod_level(levels, 100.0f), 2u);   // 0.4 px; the next 2 px
  EXPECT_EQ(detail::pick_lod_level(levels, 1000.0f), 0u);  // even the first is 1 px
  EXPECT_EQ(detail::pick_lod_level(levels, 10.0f), 3u);
  EXPECT_EQ(detail::pick_lod_level(levels, std::nanf("")), 0u);
  EXPECT_EQ(detail::pick_lod_level(levels, 0.0f), 0u);
}

DrawList torus_frame(MeshId mesh, float distance) {
  DrawList frame;
  frame.camera.eye = distance * Eigen::Vector3f(0.45f, -0.75f, 0.5f).normalized();
  frame.camera.target = Eigen::Vector3f::Zero();
  const Eigen::Affine3f pose(Eigen::AngleAxisf(0.4f, Eigen::Vector3f(1, 2, 3).normalized()));
  frame.meshes.push_back({mesh, pose.matrix(), {0.85f, 0.55f, 0.25f, 1.0f}});
  return frame;
}

/// Pixels that differ from the empty frame: the body's mask.
std::vector<bool> body_mask(const Image& frame, const Image& empty) {
  std::vector<bool> mask(static_cast<std::size_t>(frame.width * frame.height));
  for (int y = 0; y < frame.height; ++y) {
    for (int x = 0; x < frame.width; ++x) {
      mask[static_cast<std::size_t>(y * frame.width + x)] =
          testing::pixel_difference(frame, empty, x, y) > 4;
    }
  }
  return mask;
}

struct Comparison {
  std::size_t mask_xor = 0;
  std::size_t outline = 0;  ///< mask pixels of the full image with a 4-neighbour outside it
  std::size_t body = 0;
  std::size_t differing = 0;  ///< pixels off by more than 8 levels in a channel
};

Comparison compare(const Image& lod, const Image& full, const Image& empty) {
  const std::vector<bool> a = body_mask(lod, empty);
  const std::vector<bool> b = body_mask(full, empty);
  Comparison result;
  const int w = full.width;
  for (int y = 1; y + 1 < full.height; ++y) {
    for (int x = 1; x + 1 < w; ++x) {
      const auto i = static_cast<std::size_t>(y * w + x);
      result.mask_xor += a[i] != b[i];
      result.body += b[i];
      result.outline += b[i] && (!b[i - 1] || !b[i + 1] || !b[i - static_cast<std::size_t>(w)] ||
                                 !b[i + static_cast<std::size_t>(w)]);
      result.differing += testing::pixel_difference(lod, full, x, y) > 8;
    }
  }
  return result;
}

class LodImages : public ::testing::TestWithParam<std::pair<int, int>> {};

TEST_P(LodImages, AgreeWithTheFullMeshWithinAPixelOfOutline) {
  const auto [width, height] = GetParam();
  const MeshData mesh = torus(500, 250);  // 250,000 triangles
  Image empty, full, reduced;
  std::size_t full_triangles = 0;
  std::size_t reduced_triangles = 0;
  for (const bool lod : {false, true}) {
    Renderer renderer(RendererOptions{width, height, 1, lod});
    const MeshId id = renderer.upload(mesh);
    const DrawList frame = torus_frame(id, 3.2f);
    renderer.render(frame, lod ? reduced : full);
    (lod ? reduced_triangles : full_triangles) = renderer.last_frame_triangles();
    if (!lod) {
      DrawList nothing;
      nothing.camera = frame.camera;
      renderer.render(nothing, empty);
    }
  }
  EXPECT_EQ(full_triangles, mesh.indices.size() / 3);
  // The level drawn is much coarser: this frame cannot pass by drawing the full mesh.
  EXPECT_LE(reduced_triangles, full_triangles / 4);
  const Comparison c = compare(reduced, full, empty);
  RecordProperty("mask_xor", static_cast<int>(c.mask_xor));
  RecordProperty("outline", static_cast<int>(c.outline));
  RecordProperty("differing", static_cast<int>(c.differing));
  RecordProperty("body", static_cast<int>(c.body));
  RecordProperty("lod_triangles", static_cast<int>(reduced_triangles));
  ASSERT_GT(c.body, 1000u);
  // Outline error under a pixel: the masks differ by at most the outline's length (measured:
  // about a twentieth of it), and shading differences are rare.
  EXPECT_LE(c.mask_xor, c.outline);
  EXPECT_LT(static_cast<double>(c.differing), 0.01 * static_cast<double>(c.body));
}

INSTANTIATE_TEST_SUITE_P(Sizes, LodImages,
                         ::testing::Values(std::pair{1280, 720}, std::pair{480, 270}));

TEST(LodImages, ASmallChainOutgrowingItsFirstRoomStillDrawsRight) {
  // 25,000 triangles: the first copy keeps 10,000 (more than a quarter), so the chain outgrows
  // the room the index buffer was given at upload and is uploaded again whole.
  const MeshData mesh = torus(125, 100);
  Image empty, full, reduced;
  std::size_t reduced_triangles = 0;
  for (const bool lod : {false, true}) {
    Renderer renderer(RendererOptions{320, 180, 1, lod});
    const MeshId id = renderer.upload(mesh);
    // Near first (the first copy only), then far (the whole chain).
    Image near;
    renderer.render(torus_frame(id, 3.2f), near);
    const DrawList frame = torus_frame(id, 12.0f);
    renderer.render(frame, lod ? reduced : full);
    if (lod) reduced_triangles = renderer.last_frame_triangles();
    if (!lod) {
      DrawList nothing;
      nothing.camera = frame.camera;
      renderer.render(nothing, empty);
    }
  }
  EXPECT_LE(reduced_triangles, mesh.indices.size() / 3 / 4);
  const Comparison c = compare(reduced, full, empty);
  ASSERT_GT(c.body, 100u);
  EXPECT_LE(c.mask_xor, c.outline);
}

TEST(LodImages, CloserBodiesDrawFinerLevels) {
  const MeshData mesh = torus(500, 250);
  Renderer renderer(RendererOptions{640, 360, 1, true});
  const MeshId id = renderer.upload(mesh);
  std::vector<std::size_t> drawn;
  for (const float distance : {1.0f, 3.0f, 10.0f, 40.0f}) {
    Image image;
    renderer.render(torus_frame(id, distance), image);
    drawn.push_back(renderer.last_frame_triangles());
  }
  // Never finer farther away, and the near and far ends differ a lot.
  for (std::size_t i = 1; i < drawn.size(); ++i) EXPECT_LE(drawn[i], drawn[i - 1]) << i;
  EXPECT_GT(drawn.front(), 8 * drawn.back());
  EXPECT_LT(drawn.back(), 10000u);
}

}  // namespace
}  // namespace tumble::render
