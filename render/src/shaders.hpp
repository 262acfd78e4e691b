#pragma once
// GLSL 3.30 sources of the scene passes (background, meshes, ground + shadow, lines, points).

namespace tumble::render::detail::shaders {

/// Full-screen triangle from gl_VertexID; t runs 0 at the top row to 1 at the bottom row.
inline constexpr const char* kBackgroundVertex = R"(#version 330 core
out float t;
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
  t = 0.5 - 0.5 * p.y;
  gl_Position = vec4(p, 1.0, 1.0);  // at the far plane: drawn last, only where nothing else is
})";

inline constexpr const char* kBackgroundFragment = R"(#version 330 core
in float t;
uniform vec4 top;
uniform vec4 bottom;
out vec4 colour;
void main() { colour = vec4(mix(top.rgb, bottom.rgb, t), 1.0); })";

inline constexpr const char* kMeshVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 model;
uniform mat3 normal_matrix;
uniform mat4 view_projection;
out vec3 world_position;
out vec3 world_normal;
void main() {
  vec4 world = model * vec4(position, 1.0);
  world_position = world.xyz;
  world_normal = normal_matrix * normal;
  gl_Position = view_projection * world;
})";

/// Key + fill Blinn-Phong with a hemisphere ambient; two-sided (inconsistent winding is fine).
inline constexpr const char* kMeshFragment = R"(#version 330 core
in vec3 world_position;
in vec3 world_normal;
uniform vec4 base_colour;
uniform vec3 eye;
uniform vec3 key_direction;
uniform vec3 fill_direction;
uniform vec3 sky_up;
out vec4 colour;
void main() {
  vec3 n = normalize(world_normal);
  if (!gl_FrontFacing) n = -n;
  vec3 v = normalize(eye - world_position);
  float key = max(dot(n, key_direction), 0.0);
  float fill = max(dot(n, fill_direction), 0.0);
  float hemisphere = 0.5 + 0.5 * dot(n, sky_up);
  vec3 h = normalize(key_direction + v);
  float specular = key > 0.0 ? 0.30 * pow(max(dot(n, h), 0.0), 40.0) : 0.0;
  vec3 lit = base_colour.rgb * (0.14 + 0.16 * hemisphere + 0.70 * key + 0.22 * fill);
  colour = vec4(lit + vec3(specular), base_colour.a);
})";

/// Depth-only pass from the key light.
inline constexpr const char* kShadowVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
uniform mat4 light_model_view_projection;
void main() { gl_Position = light_model_view_projection * vec4(position, 1.0); })";

inline constexpr const char* kShadowFragment = R"(#version 330 core
void main() {})";

/// A square of the ground plane (the whole ground, or just the patch a shadow can fall on).
inline constexpr const char* kGroundVertex = R"(#version 330 core
layout(location = 0) in vec2 corner;
uniform vec3 quad_centre;
uniform vec3 axis_u;
uniform vec3 axis_v;
uniform float quad_half_size;
uniform mat4 view_projection;
out vec3 world_position;
void main() {
  world_position = quad_centre + quad_half_size * (corner.x * axis_u + corner.y * axis_v);
  gl_Position = view_projection * vec4(world_position, 1.0);
})";

/// Lit ground fading into the background gradient towards its edge (opaque: blending is costly
/// on llvmpipe); 2x2 bilinear PCF taps (a 4x4-texel footprint) of the
/// key light's shadow map.
/// Compiled twice, with and without "#define SHADOWS" (llvmpipe runs both sides of a branch, so
/// a uniform switch would pay for the shadow taps even when shadows are off).
inline constexpr const char* kGroundFragmentBody = R"(
in vec3 world_position;
uniform vec3 ground_centre;
uniform float ground_half_size;
uniform vec4 base_colour;
uniform vec3 normal;
uniform vec3 key_direction;
uniform mat4 light_view_projection;
uniform sampler2DShadow shadow_map;
uniform float texel;
uniform vec4 background_top;
uniform vec4 background_bottom;
uniform float viewport_height;
out vec4 colour;
void main() {
  float lit = 1.0;
#ifdef SHADOWS
  {
    vec4 s = light_view_projection * vec4(world_position, 1.0);
    vec3 uvz = s.xyz / s.w * 0.5 + 0.5;
    if (all(greaterThan(uvz.xy, vec2(0.0))) && all(lessThan(uvz.xy, vec2(1.0)))) {
      float sum = 0.0;
      for (int i = 0; i < 4; ++i) {
        vec2 offset = vec2(float(i & 1), float(i >> 1)) * 2.0 - 1.0;
        sum += texture(shadow_map, vec3(uvz.xy + offset * 1.25 * texel, uvz.z));
      }
      lit = mix(0.45, 1.0, 0.25 * sum);
    }
  }
#endif
  float diffuse = max(dot(normal, key_direction), 0.0);
  vec3 c = base_colour.rgb * (0.55 + 0.45 * diffuse) * lit;
  float fade = 1.0 - smoothstep(0.55, 1.0, length(world_position - ground_centre) / ground_half_size);
  vec3 background = mix(background_bottom.rgb, background_top.rgb, gl_FragCoord.y / viewport_height);
  colour = vec4(mix(background, c, fade), 1.0);
})";

inline constexpr const char* kLineVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
uniform mat4 view_projection;
void main() { gl_Position = view_projection * vec4(position, 1.0); })";

/// Expands each segment into a screen-space quad of constant pixel width (with square caps
/// half a width long, which closes the joints of a polyline); clips at the near plane. The quad
/// is a pixel wider on each side than the line, and `across_px` (the distance from the centre
/// line, in pixels) lets the fragment shader give the edge pixels their coverage: a box filter
/// of the line's true width, so lines are anti-aliased by themselves (when anti-aliasing is on;
/// the image filter alone hardly softens a two-pixel line).
inline constexpr const char* kLineGeometry = R"(#version 330 core
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;
uniform vec2 viewport;
uniform float half_width;
out float across_px;
void main() {
  vec4 a = gl_in[0].gl_Position;
  vec4 b = gl_in[1].gl_Position;
  const float near_w = 1e-4;
  if (a.w < near_w && b.w < near_w) return;
  if (a.w < near_w) a = mix(a, b, (near_w - a.w) / (b.w - a.w));
  if (b.w < near_w) b = mix(b, a, (near_w - b.w) / (a.w - b.w));
  vec2 sa = a.xy / a.w * viewport * 0.5;
  vec2 sb = b.xy / b.w * viewport * 0.5;
  vec2 d = sb - sa;
  float len = length(d);
  vec2 dir = len > 1e-6 ? d / len : vec2(1.0, 0.0);
  float reach = half_width + 1.0;
  vec2 side = vec2(-dir.y, dir.x) * reach;
  vec2 cap = dir * half_width;
  vec2 to_ndc = 2.0 / viewport;
  across_px = reach;
  gl_Position = vec4((sa - cap + side) * to_ndc * a.w, a.z, a.w); EmitVertex();
  across_px = -reach;
  gl_Position = vec4((sa - cap - side) * to_ndc * a.w, a.z, a.w); EmitVertex();
  across_px = reach;
  gl_Position = vec4((sb + cap + side) * to_ndc * b.w, b.z, b.w); EmitVertex();
  across_px = -reach;
  gl_Position = vec4((sb + cap - side) * to_ndc * b.w, b.z, b.w); EmitVertex();
  EndPrimitive();
})";

/// A line's colour with its coverage of the pixel (see kLineGeometry) as alpha.
inline constexpr const char* kLineFragment = R"(#version 330 core
uniform vec4 base_colour;
uniform float half_width;
uniform float smooth_edges;  // 1: coverage; 0: aliased, as drawn without anti-aliasing
in float across_px;
out vec4 colour;
void main() {
  float inside = abs(across_px) <= half_width ? 1.0 : 0.0;
  float coverage = mix(inside, clamp(half_width + 0.5 - abs(across_px), 0.0, 1.0), smooth_edges);
  if (coverage <= 0.0) discard;
  colour = vec4(base_colour.rgb, base_colour.a * coverage);
})";

inline constexpr const char* kPointVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
uniform mat4 view_projection;
uniform float size;
void main() {
  gl_Position = view_projection * vec4(position, 1.0);
  gl_PointSize = size;
})";

/// Round dots with a one-pixel soft edge.
inline constexpr const char* kPointFragment = R"(#version 330 core
uniform vec4 base_colour;
uniform float size;
out vec4 colour;
void main() {
  float r = length(gl_PointCoord - vec2(0.5)) * size;
  float alpha = clamp(0.5 * size - r + 0.5, 0.0, 1.0);
  if (alpha <= 0.0) discard;
  colour = vec4(base_colour.rgb, base_colour.a * alpha);
})";

}  // namespace tumble::render::detail::shaders
