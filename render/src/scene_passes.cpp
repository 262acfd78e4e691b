#include "scene_passes.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "arrow_geometry.hpp"
#include "render/camera_math.hpp"
#include "shaders.hpp"

namespace tumble::render::detail {

namespace {

constexpr int kShadowMapSize = 1024;
constexpr float kOpaqueAlpha = 0.999f;

void set_colour(GlProgram& program, const Rgba& c) {
  glUniform4f(program.uniform("base_colour"), c.r, c.g, c.b, c.a);
}

void set_vector(GlProgram& program, const char* name, const Eigen::Vector3f& v) {
  glUniform3f(program.uniform(name), v.x(), v.y(), v.z());
}

void set_matrix(GlProgram& program, const char* name, const Eigen::Matrix4f& m) {
  glUniformMatrix4fv(program.uniform(name), 1, GL_FALSE, m.data());  // Eigen is column-major
}

/// World-to-clip matrix of an orthographic light looking along -`from` at a sphere.
Eigen::Matrix4f light_matrix(const Eigen::Vector3f& from, const Eigen::Vector3f& centre,
                             float radius) {
  Camera light;
  light.eye = centre + from * (2.0f * radius);
  light.target = centre;
  light.up = from.unitOrthogonal();
  Eigen::Matrix4f ortho = Eigen::Matrix4f::Identity();
  ortho(0, 0) = 1.0f / radius;
  ortho(1, 1) = 1.0f / radius;
  ortho(2, 2) = -2.0f / (4.0f * radius);  // view depth 0 .. 4r mapped to -1 .. 1
  ortho(2, 3) = -1.0f;
  return ortho * view_matrix(light);
}

}  // namespace

ScenePasses::ScenePasses(bool lod, bool reuse_static_layers, bool smooth_lines)
    : background_program_("background", shaders::kBackgroundVertex, shaders::kBackgroundFragment),
      mesh_program_("mesh", shaders::kMeshVertex, shaders::kMeshFragment),
      shadow_program_("shadow", shaders::kShadowVertex, shaders::kShadowFragment),
      ground_program_("ground", shaders::kGroundVertex,
                      std::string("#version 330 core\n") + shaders::kGroundFragmentBody),
      shadowed_ground_program_(
          "shadowed ground", shaders::kGroundVertex,
          std::string("#version 330 core\n#define SHADOWS 1\n") + shaders::kGroundFragmentBody),
      line_program_("polyline", shaders::kLineVertex, shaders::kLineFragment,
                    shaders::kLineGeometry),
      point_program_("points", shaders::kPointVertex, shaders::kPointFragment),
      cylinder_(upload_mesh(unit_cylinder(24))),
      cone_(upload_mesh(unit_cone(24))),
      lod_(lod),
      reuse_static_layers_(reuse_static_layers),
      smooth_lines_(smooth_lines) {
  // The background triangle needs a (any) vertex array bound in a core profile.
  empty_vao_ = GlVertexArray::create();

  // Ground: a unit square in plane coordinates, scaled and placed per frame.
  const float corners[] = {-1, -1, 1, -1, -1, 1, 1, 1};
  ground_vao_ = GlVertexArray::create();
  glBindVertexArray(ground_vao_.get());
  ground_buffer_ = GlBuffer::create();
  glBindBuffer(GL_ARRAY_BUFFER, ground_buffer_.get());
  glBufferData(GL_ARRAY_BUFFER, sizeof corners, corners, GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);

  // Streamed positions of polylines and points, refilled each frame.
  stream_vao_ = GlVertexArray::create();
  glBindVertexArray(stream_vao_.get());
  stream_buffer_ = GlBuffer::create();
  glBindBuffer(GL_ARRAY_BUFFER, stream_buffer_.get());
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindVertexArray(0);
}

void ScenePasses::draw(const DrawList& frame, std::vector<GpuMesh>& meshes,
                       OffscreenContext& context) {
  const int width = context.width();
  const int height = context.height();
  const Eigen::Matrix4f view = view_matrix(frame.camera);
  view_projection_ =
      projection_matrix(frame.camera, static_cast<float>(width) / static_cast<float>(height)) *
      view;
  near_plane_ = frame.camera.near_plane;
  collect_solids(frame, meshes, view, height);
  drawn_ = find_drawn_box(frame, width, height);

  // Shadow map from the key light, only when there is a ground to receive it.
  shadow_valid_ = false;
  if (frame.style.ground && frame.style.shadows && !solids_.empty()) {
    draw_shadow_map(frame);
    context.make_current();
  }

  // Opaque solids first, then the ground and the background, which only fill what is left
  // (llvmpipe skips depth-rejected pixels early), then lines, points and translucent solids.
  // With static layers, the background and the ground outside the shadow's patch come first,
  // from a stored copy; the solids then overwrite them where they are nearer, which leaves
  // the same pixels (the ground's rest is pushed back by its polygon offset either way).
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  const GroundPlacement ground = place_ground(frame);
  const bool static_layers_drawn = static_layers(frame, ground, context);
  if (!static_layers_drawn) glClear(GL_DEPTH_BUFFER_BIT);
  mesh_program_.use();
  const Eigen::Vector3f key = frame.style.key_light_from.normalized();
  const Eigen::Vector3f to_eye = (frame.camera.eye - frame.camera.target).normalized();
  const Eigen::Vector3f fill = (2.0f * key.dot(to_eye) * to_eye - key).normalized();
  set_vector(mesh_program_, "eye", frame.camera.eye);
  set_vector(mesh_program_, "key_direction", key);
  set_vector(mesh_program_, "fill_direction", fill);
  set_vector(mesh_program_, "sky_up", frame.style.ground_normal.normalized());
  draw_solids(false);
  if (frame.style.ground) {
    draw_ground_part(frame, ground, 0, height);
    if (!static_layers_drawn) draw_ground_part(frame, ground, 1, height);
  }
  if (!static_layers_drawn) draw_background(frame.style);
  draw_lines_and_points(frame, width, height);
  draw_solids(true);
  glBindVertexArray(0);
}

std::optional<PixelBox> ScenePasses::find_drawn_box(const DrawList& frame, int width,
                                                    int height) const {
  if (frame.style.ground) return std::nullopt;
  float low_x = std::numeric_limits<float>::infinity(), low_y = low_x;
  float high_x = -low_x, high_y = -low_x;
  // Grows the box by the pixel of clip-space point `clip`, `margin` pixels around it; false
  // when the point is not in front of the camera (then its projection is not bounded).
  const auto add = [&](const Eigen::Vector4f& clip, float margin) {
    if (!(clip.w() > 1e-6f)) return false;
    const float x = (0.5f * clip.x() / clip.w() + 0.5f) * static_cast<float>(width);
    const float y = (0.5f * clip.y() / clip.w() + 0.5f) * static_cast<float>(height);
    if (!std::isfinite(x) || !std::isfinite(y)) return false;
    low_x = std::min(low_x, x - margin);
    high_x = std::max(high_x, x + margin);
    low_y = std::min(low_y, y - margin);
    high_y = std::max(high_y, y + margin);
    return true;
  };
  // A solid lies in its mesh's box, placed by its model matrix; with the box's corners in
  // front of the camera, its projection lies within theirs (the projection of a convex set in
  // front of the camera is the hull of its corners' projections).
  for (const Solid& solid : solids_) {
    const Eigen::Matrix4f to_clip = view_projection_ * solid.model;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3f p =
          solid.mesh->box.corner(static_cast<Eigen::AlignedBox3f::CornerType>(corner));
      if (!add(to_clip * p.homogeneous(), 1.0f)) return std::nullopt;
    }
  }
  // Lines and points: their vertices, out by half their width and the smoothed edge (a
  // segment between two points in front of the camera projects between their projections).
  for (const Polyline& line : frame.polylines) {
    for (const Eigen::Vector3f& p : line.points) {
      if (!add(view_projection_ * p.homogeneous(), 0.5f * line.width_px + 2.0f)) {
        return std::nullopt;
      }
    }
  }
  for (const Points& points : frame.points) {
    for (const Eigen::Vector3f& p : points.positions) {
      if (!add(view_projection_ * p.homogeneous(), 0.5f * points.size_px + 2.0f)) {
        return std::nullopt;
      }
    }
  }
  if (!(low_x <= high_x)) return PixelBox{};  // nothing but the background
  // 8 pixels of background all round (the block scan looks one pixel past each block), then
  // out to whole 8-pixel blocks, so that the scan's blocks are the whole frame's.
  constexpr int kAlign = 8;
  const auto outward = [](float v, int limit, bool up) {
    const float grown = up ? std::ceil(v) + kAlign : std::floor(v) - kAlign;
    const int clamped = static_cast<int>(std::clamp(grown, 0.0f, static_cast<float>(limit)));
    return up ? std::min(limit, (clamped + kAlign - 1) / kAlign * kAlign)
              : clamped / kAlign * kAlign;
  };
  const PixelBox box{outward(low_x, width, false), outward(low_y, height, false),
                     outward(high_x, width, true), outward(high_y, height, true)};
  if (box.x0 >= box.x1 || box.y0 >= box.y1) return PixelBox{};
  return box;
}

void ScenePasses::collect_solids(const DrawList& frame, std::vector<GpuMesh>& meshes,
                                 const Eigen::Matrix4f& view, int height) {
  solids_.clear();
  triangles_ = 0;
  for (const MeshInstance& instance : frame.meshes) {
    if (instance.mesh.value >= meshes.size() || !meshes[instance.mesh.value].vao) {
      throw std::invalid_argument("renderer: unknown mesh id " +
                                  std::to_string(instance.mesh.value));
    }
    solids_.push_back(
        {&meshes[instance.mesh.value], instance.pose, instance.colour, 0.0f, 0, 1.0f});
  }
  for (const Arrow& arrow : frame.arrows) {
    ArrowTransforms placed;
    if (!arrow_transforms(arrow, placed)) continue;
    solids_.push_back({&cylinder_, placed.shaft, arrow.colour, 0.0f, 0, 1.0f});
    solids_.push_back({&cone_, placed.head, arrow.colour, 0.0f, 0, 1.0f});
  }

  // View depth of each solid's centre, and a sphere bounding the whole scene.
  Eigen::AlignedBox3f box;
  std::vector<std::pair<Eigen::Vector3f, float>> spheres;
  for (Solid& solid : solids_) {
    const Eigen::Vector3f centre = (solid.model * solid.mesh->centre().homogeneous()).head<3>();
    const float scale = solid.model.block<3, 3>(0, 0).colwise().norm().maxCoeff();
    solid.view_depth = -(view * centre.homogeneous()).z();
    solid.scale = scale;
    spheres.emplace_back(centre, solid.mesh->radius * scale);
    box.extend(centre);
    // Level of detail: pixels per world unit at the mesh's nearest point (perspective:
    // height / (2 tan(fov / 2) depth)), the coarsest level under a pixel there.
    if (lod_ && (solid.mesh->levels.size() > 1 || solid.mesh->chain)) {
      const float nearest =
          std::max(solid.view_depth - solid.mesh->radius * scale, frame.camera.near_plane);
      const float half_fov = 0.5f * frame.camera.vertical_fov_deg * 3.14159265f / 180.0f;
      const float pixels_per_unit =
          static_cast<float>(height) / (2.0f * std::tan(half_fov) * nearest) * scale;
      solid.mesh->refine_for(pixels_per_unit);
      solid.level = pick_lod_level(solid.mesh->levels, pixels_per_unit);
    }
  }
  scene_centre_ = box.isEmpty() ? Eigen::Vector3f::Zero() : Eigen::Vector3f(box.center());
  scene_radius_ = 0.0f;
  for (const auto& [centre, radius] : spheres) {
    scene_radius_ = std::max(scene_radius_, (centre - scene_centre_).norm() + radius);
  }
}

void ScenePasses::draw_shadow_map(const DrawList& frame) {
  if (!shadow_fbo_) {
    // Depth texture with hardware comparison (sampler2DShadow, bilinear PCF per tap).
    GlTexture texture = GlTexture::create();
    glBindTexture(GL_TEXTURE_2D, texture.get());
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, kShadowMapSize, kShadowMapSize, 0,
                 GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    GlFramebuffer framebuffer = GlFramebuffer::create();
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.get());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, texture.get(), 0);
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
    shadow_texture_ = std::move(texture);
    shadow_fbo_ = std::move(framebuffer);
  }
  const float radius = std::max(scene_radius_, 1e-3f);
  light_view_projection_ =
      light_matrix(frame.style.key_light_from.normalized(), scene_centre_, radius);

  glBindFramebuffer(GL_FRAMEBUFFER, shadow_fbo_.get());
  glViewport(0, 0, kShadowMapSize, kShadowMapSize);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glClear(GL_DEPTH_BUFFER_BIT);
  shadow_program_.use();
  const GLint mvp = shadow_program_.uniform("light_model_view_projection");
  // The shadow map's texels span 2 radius / kShadowMapSize: a coarser level is as good there.
  const float texels_per_unit = static_cast<float>(kShadowMapSize) / (2.0f * radius);
  for (const Solid& solid : solids_) {
    const Eigen::Matrix4f matrix = light_view_projection_ * solid.model;
    if (lod_) solid.mesh->refine_for(texels_per_unit * solid.scale);
    glUniformMatrix4fv(mvp, 1, GL_FALSE, matrix.data());
    const std::size_t level =
        lod_ ? std::max(solid.level,
                        pick_lod_level(solid.mesh->levels, texels_per_unit * solid.scale))
             : 0;
    solid.mesh->draw(level);
  }
  shadow_valid_ = true;
}

void ScenePasses::draw_background(const SceneStyle& style) {
  glDepthMask(GL_FALSE);
  background_program_.use();
  glUniform4f(background_program_.uniform("top"), style.background_top.r, style.background_top.g,
              style.background_top.b, 1.0f);
  glUniform4f(background_program_.uniform("bottom"), style.background_bottom.r,
              style.background_bottom.g, style.background_bottom.b, 1.0f);
  glBindVertexArray(empty_vao_.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthMask(GL_TRUE);
}

ScenePasses::GroundPlacement ScenePasses::place_ground(const DrawList& frame) const {
  const SceneStyle& style = frame.style;
  GroundPlacement placed;
  const Eigen::Vector3f normal = style.ground_normal.normalized();
  // Centred under the camera's target, large enough to fade out well beyond the scene.
  const Eigen::Vector3f target = frame.camera.target;
  placed.centre = target - normal * (normal.dot(target) - style.ground_height);
  placed.half_size = 4.0f * std::max((frame.camera.eye - target).norm(), scene_radius_);
  placed.axis_u = normal.unitOrthogonal();
  placed.axis_v = normal.cross(placed.axis_u);

  // Shadow taps are costly on llvmpipe: only the patch of ground a shadow can reach (the scene's
  // bounding sphere swept along the light) uses the shadowed program; the rest of the ground is
  // drawn without, pushed back by a polygon offset so it does not overwrite the patch.
  const Eigen::Vector3f key = style.key_light_from.normalized();
  const float cos_light = normal.dot(key);
  placed.patch = shadow_valid_ && cos_light > 0.1f;
  placed.patch_centre =
      scene_centre_ - key * (normal.dot(scene_centre_) - style.ground_height) / cos_light;
  placed.patch_half_size = 1.1f * scene_radius_ / std::max(cos_light, 0.1f);
  return placed;
}

void ScenePasses::draw_ground_part(const DrawList& frame, const GroundPlacement& ground, int part,
                                   int height) {
  if (part == 0 && !ground.patch) return;
  const SceneStyle& style = frame.style;
  const bool shadowed = part == 0 || (shadow_valid_ && !ground.patch);
  GlProgram& program = shadowed ? shadowed_ground_program_ : ground_program_;
  glBindVertexArray(ground_vao_.get());
  program.use();
  set_vector(program, "quad_centre", part == 0 ? ground.patch_centre : ground.centre);
  glUniform1f(program.uniform("quad_half_size"),
              part == 0 ? ground.patch_half_size : ground.half_size);
  set_vector(program, "ground_centre", ground.centre);
  glUniform1f(program.uniform("ground_half_size"), ground.half_size);
  set_vector(program, "axis_u", ground.axis_u);
  set_vector(program, "axis_v", ground.axis_v);
  set_matrix(program, "view_projection", view_projection_);
  set_colour(program, style.ground_colour);
  set_vector(program, "normal", style.ground_normal.normalized());
  set_vector(program, "key_direction", style.key_light_from.normalized());
  if (shadowed) {
    set_matrix(program, "light_view_projection", light_view_projection_);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, shadow_texture_.get());
    glUniform1i(program.uniform("shadow_map"), 0);
    glUniform1f(program.uniform("texel"), 1.0f / kShadowMapSize);
  }
  const Rgba& top = style.background_top;
  const Rgba& bottom = style.background_bottom;
  glUniform4f(program.uniform("background_top"), top.r, top.g, top.b, 1.0f);
  glUniform4f(program.uniform("background_bottom"), bottom.r, bottom.g, bottom.b, 1.0f);
  glUniform1f(program.uniform("viewport_height"), static_cast<float>(height));
  if (part == 1 && ground.patch) {
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 4.0f);
  }
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  glDisable(GL_POLYGON_OFFSET_FILL);
}

void ScenePasses::draw_solids(bool translucent) {
  // Translucent solids: back to front, without depth writes, back faces before front faces.
  std::vector<const Solid*> selected;
  for (const Solid& solid : solids_) {
    if ((solid.colour.a < kOpaqueAlpha) == translucent) selected.push_back(&solid);
  }
  if (selected.empty()) return;
  if (translucent) {
    std::sort(selected.begin(), selected.end(),
              [](const Solid* a, const Solid* b) { return a->view_depth > b->view_depth; });
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    glEnable(GL_CULL_FACE);
  }
  mesh_program_.use();
  set_matrix(mesh_program_, "view_projection", view_projection_);
  const GLint model = mesh_program_.uniform("model");
  const GLint normal_matrix = mesh_program_.uniform("normal_matrix");
  for (const Solid* solid : selected) {
    glUniformMatrix4fv(model, 1, GL_FALSE, solid->model.data());
    const Eigen::Matrix3f normals = solid->model.block<3, 3>(0, 0).inverse().transpose();
    glUniformMatrix3fv(normal_matrix, 1, GL_FALSE, normals.data());
    set_colour(mesh_program_, solid->colour);
    if (!translucent) {
      // A closed mesh's back faces lie behind its front faces seen from outside it, unless the
      // near plane cuts it open: culled when its bounding sphere lies wholly beyond the near
      // plane. A mirroring pose turns the winding around.
      if (solid->mesh->closed &&
          solid->view_depth - solid->mesh->radius * solid->scale > near_plane_) {
        glEnable(GL_CULL_FACE);
        glCullFace(solid->model.block<3, 3>(0, 0).determinant() > 0.0f ? GL_BACK : GL_FRONT);
      } else {
        glDisable(GL_CULL_FACE);
      }
    } else {
      glCullFace(GL_FRONT);
      solid->mesh->draw(solid->level);
      glCullFace(GL_BACK);
      triangles_ += solid->mesh->triangles(solid->level);
    }
    solid->mesh->draw(solid->level);
    triangles_ += solid->mesh->triangles(solid->level);
  }
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
}

void ScenePasses::draw_lines_and_points(const DrawList& frame, int width, int height) {
  if (frame.polylines.empty() && frame.points.empty()) return;
  // Stream every vertex of this frame's polylines and points into one buffer.
  stream_.clear();
  for (const Polyline& line : frame.polylines) {
    for (const auto& p : line.points) stream_.insert(stream_.end(), {p.x(), p.y(), p.z()});
  }
  for (const Points& points : frame.points) {
    for (const auto& p : points.positions) stream_.insert(stream_.end(), {p.x(), p.y(), p.z()});
  }
  glBindVertexArray(stream_vao_.get());
  glBindBuffer(GL_ARRAY_BUFFER, stream_buffer_.get());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(stream_.size() * sizeof(float)),
               stream_.data(), GL_STREAM_DRAW);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);

  // Polylines: one line strip each, widened in the geometry shader.
  GLint first = 0;
  line_program_.use();
  set_matrix(line_program_, "view_projection", view_projection_);
  glUniform2f(line_program_.uniform("viewport"), static_cast<float>(width),
              static_cast<float>(height));
  glUniform1f(line_program_.uniform("smooth_edges"), smooth_lines_ ? 1.0f : 0.0f);
  for (const Polyline& line : frame.polylines) {
    const auto count = static_cast<GLsizei>(line.points.size());
    if (count >= 2) {
      glUniform1f(line_program_.uniform("half_width"), 0.5f * line.width_px);
      set_colour(line_program_, line.colour);
      glDrawArrays(GL_LINE_STRIP, first, count);
    }
    first += count;
  }

  // Points: round sprites.
  glEnable(GL_PROGRAM_POINT_SIZE);
  point_program_.use();
  set_matrix(point_program_, "view_projection", view_projection_);
  for (const Points& points : frame.points) {
    const auto count = static_cast<GLsizei>(points.positions.size());
    glUniform1f(point_program_.uniform("size"), points.size_px);
    set_colour(point_program_, points.colour);
    if (count > 0) glDrawArrays(GL_POINTS, first, count);
    first += count;
  }
  glDisable(GL_PROGRAM_POINT_SIZE);
  glDisable(GL_BLEND);
}

}  // namespace tumble::render::detail
