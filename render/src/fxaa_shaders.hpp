#pragma once
// GLSL 4.00 sources (textureGather) of the post-process anti-aliasing filter (fxaa_pass.cpp).
//
// The idea is Lottes' "FXAA" (NVIDIA white paper, 2009; the low-cost variant of FXAA 3, with
// green standing in for luma as FXAA 3.11 allows): find edges from the luma of a pixel and its
// neighbours (here the four sides and two diagonals, from two gathers), and where the contrast
// is high, average the image along the edge's direction (perpendicular to the luma gradient).
// Two taps a third of the way along the edge give a narrow blend (A); two more at half the
// span widen it (B), and B is kept only when its luma stays within the neighbourhood's range
// (otherwise it has crossed onto another surface). Pixels below the contrast threshold are
// discarded: the output already holds the scene there (a plain copy, which llvmpipe does as a
// memcpy), so flat regions and the gentle background gradient stay bit for bit. The filter only
// runs on 8x8-pixel blocks found to hold an edge (kEdgeBlocksFragment, kEdgeBlockPoints).

namespace tumble::render::detail::shaders {

/// Full-screen triangle from gl_VertexID (the fragment shader works from gl_FragCoord).
inline constexpr const char* kFxaaVertex = R"(#version 330 core
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
  gl_Position = vec4(p, 0.0, 1.0);
})";

/// Edge blocks: one fragment per 8x8-pixel block of the image writes 1 when the block or its
/// one-pixel rim (10x10 pixels, 25 gathers of green) has contrast above the filter's absolute
/// floor, else 0.
inline constexpr const char* kEdgeBlocksFragment = R"(#version 400 core
uniform sampler2D scene;
uniform vec2 texel;
out vec4 edge;
void main() {
  vec2 corner = (floor(gl_FragCoord.xy) * 8.0) * texel;  // lower-left corner of the block
  float lo = 1.0;
  float hi = 0.0;
  for (int j = 0; j < 5; ++j) {
    for (int i = 0; i < 5; ++i) {
      vec4 g = textureGather(scene, corner + vec2(2 * i, 2 * j) * texel, 1);
      lo = min(lo, min(min(g.x, g.y), min(g.z, g.w)));
      hi = max(hi, max(max(g.x, g.y), max(g.z, g.w)));
    }
  }
  // No pixel of the block can pass the filter's test when the range is below both the floor
  // and the relative threshold of the block's darkest pixel (no neighbourhood is darker).
  edge = vec4(hi - lo >= max(0.0312, 0.125 * lo) ? 1.0 : 0.0);
})";

/// The filter runs only on edge blocks: one 8x8-pixel point per block, moved outside the clip
/// volume (culled) when the block is flat. (llvmpipe runs a fragment shader in full for every
/// covered pixel, discarded or not, so the work is saved by not covering the flat ones.)
inline constexpr const char* kEdgeBlockPoints = R"(#version 400 core
uniform sampler2D blocks;  // kEdgeBlocksFragment's output
uniform vec2 texel;        // 1 / image size
void main() {
  int columns = textureSize(blocks, 0).x;
  ivec2 block = ivec2(gl_VertexID % columns, gl_VertexID / columns);
  vec2 centre = (vec2(block) * 8.0 + 4.0) * texel * 2.0 - 1.0;
  bool edge = texelFetch(blocks, block, 0).r > 0.0;
  gl_Position = edge ? vec4(centre, 0.0, 1.0) : vec4(-2.0, -2.0, 0.0, 1.0);
  gl_PointSize = 8.0;
})";

inline constexpr const char* kFxaaFragment = R"(#version 400 core
uniform sampler2D scene;  // bilinear, clamped to the edge
uniform vec2 texel;       // 1 / image size
out vec4 colour;

const float kEdgeThreshold = 0.125;     // contrast relative to the brightest neighbour
const float kEdgeThresholdMin = 0.0312; // absolute floor (dark regions)
const float kReduceMul = 1.0 / 8.0;     // keeps the direction finite on faint edges
const float kReduceMin = 1.0 / 128.0;
const float kSpanMax = 8.0;             // longest blend, in pixels

float luma(vec3 c) { return dot(c, vec3(0.299, 0.587, 0.114)); }

void main() {
  vec2 uv = gl_FragCoord.xy * texel;  // the pixel's centre
  // Green as luma, two gathers: the 2x2 blocks above-right and below-left of the pixel give the
  // pixel (m), its four neighbours (n, e, s, w) and two diagonals (ne, sw).
  vec4 upper = textureGather(scene, uv + 0.5 * texel, 1);  // (n, ne, e, m)
  vec4 lower = textureGather(scene, uv - 0.5 * texel, 1);  // (w, m, s, sw)
  float m = upper.w;
  float lo = min(min(min(upper.x, upper.y), min(upper.z, m)), min(min(lower.x, lower.z), lower.w));
  float hi = max(max(max(upper.x, upper.y), max(upper.z, m)), max(max(lower.x, lower.z), lower.w));
  // Below the contrast threshold the output keeps the scene's pixel (copied there first).
  if (hi - lo < max(kEdgeThresholdMin, hi * kEdgeThreshold)) discard;

  // Edge tangent: the luma gradient (central differences, plus the diagonal) turned by 90 degrees.
  float diagonal = 0.5 * (upper.y - lower.w);
  vec2 gradient = vec2(upper.z - lower.x + diagonal, upper.x - lower.z + diagonal);
  vec2 along = vec2(-gradient.y, gradient.x);
  float reduce = max((upper.x + upper.z + lower.x + lower.z) * (0.25 * kReduceMul), kReduceMin);
  float scale = 1.0 / (min(abs(along.x), abs(along.y)) + reduce);
  along = clamp(along * scale, vec2(-kSpanMax), vec2(kSpanMax)) * texel;

  vec3 a = 0.5 * (texture(scene, uv - along * (1.0 / 6.0)).rgb +
                  texture(scene, uv + along * (1.0 / 6.0)).rgb);
  vec3 b = 0.5 * a + 0.25 * (texture(scene, uv - along * 0.5).rgb +
                             texture(scene, uv + along * 0.5).rgb);
  colour = vec4((b.g < lo || b.g > hi) ? a : b, 1.0);
})";

}  // namespace tumble::render::detail::shaders
