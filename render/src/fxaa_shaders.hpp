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
// runs on 4x4-pixel blocks holding a pixel that passes this test (fxaa_blocks.hpp, on the CPU),
// drawn as rectangles.

namespace tumble::render::detail::shaders {

/// The edge blocks' rectangles (fxaa_blocks.hpp), two triangles each, in pixels.
inline constexpr const char* kEdgeBlockVertex = R"(#version 400 core
layout(location = 0) in vec2 pixel;
uniform vec2 texel;  // 1 / image size
void main() {
  gl_Position = vec4(pixel * texel * 2.0 - 1.0, 0.0, 1.0);
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
