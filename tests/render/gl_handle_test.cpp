// GL object ownership: every name the renderer's internal types create is deleted exactly when
// its owner goes, moved-from owners delete nothing, and failed construction leaves nothing.
// These reach into render/src (internal headers) and check names with glIs* in the same context.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <ostream>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "gl_handle.hpp"
#include "gl_program.hpp"
#include "gpu_mesh.hpp"
#include "overlay_pass.hpp"
#include "render/offscreen_context.hpp"
#include "render/renderer.hpp"
#include "render_support.hpp"
#include "scene_passes.hpp"

namespace tumble::render::detail {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

constexpr int kContextWidth = 64;
constexpr int kContextHeight = 48;

/// How many names in 1..8191 are live objects for `is` (Mesa hands out small names).
int live(GLboolean (*is)(GLuint)) {
  int count = 0;
  for (GLuint name = 1; name < 8192; ++name) count += is(name) == GL_TRUE ? 1 : 0;
  return count;
}

/// Shaders or programs (`is`, with `status` their glGet*iv) that were never deleted: GL keeps
/// a deleted one that is still attached or in use, flagged with GL_DELETE_STATUS.
int undeleted(GLboolean (*is)(GLuint), void (*status)(GLuint, GLenum, GLint*)) {
  int count = 0;
  for (GLuint name = 1; name < 8192; ++name) {
    if (is(name) != GL_TRUE) continue;
    GLint deleted = GL_FALSE;
    status(name, GL_DELETE_STATUS, &deleted);
    count += deleted == GL_FALSE ? 1 : 0;
  }
  return count;
}

/// Live names of every kind, so one comparison checks them all.
struct LiveObjects {
  int buffers = live(glIsBuffer);
  int vertex_arrays = live(glIsVertexArray);
  int textures = live(glIsTexture);
  int framebuffers = live(glIsFramebuffer);
  int renderbuffers = live(glIsRenderbuffer);
  int shaders = undeleted(glIsShader, glGetShaderiv);
  int programs = undeleted(glIsProgram, glGetProgramiv);
  bool operator==(const LiveObjects&) const = default;
};

void PrintTo(const LiveObjects& o, std::ostream* out) {
  *out << "{buffers " << o.buffers << ", vertex arrays " << o.vertex_arrays << ", textures "
       << o.textures << ", framebuffers " << o.framebuffers << ", renderbuffers " << o.renderbuffers
       << ", shaders " << o.shaders << ", programs " << o.programs << "}";
}

constexpr const char* kVertex =
    "#version 330 core\nlayout(location = 0) in vec3 p;\nvoid main() { gl_Position = vec4(p, 1); "
    "}\n";
constexpr const char* kFragment =
    "#version 330 core\nout vec4 colour;\nvoid main() { colour = vec4(1); }\n";

TEST(GlHandle, DeletesItsObjectOnceAndMovedFromHandlesDeleteNothing) {
  OffscreenContext context(kContextWidth, kContextHeight, 1);
  GlBuffer first = GlBuffer::create();
  glBindBuffer(GL_ARRAY_BUFFER, first.get());  // a generated name is an object once bound
  const GLuint name = first.get();
  ASSERT_NE(name, 0u);
  EXPECT_EQ(glIsBuffer(name), GL_TRUE);

  GlBuffer second(std::move(first));
  EXPECT_EQ(first.get(), 0u);  // NOLINT(bugprone-use-after-move): moved-from holds nothing
  EXPECT_EQ(second.get(), name);
  first.reset();
  { GlBuffer gone(std::move(first)); }
  EXPECT_EQ(glIsBuffer(name), GL_TRUE);

  // Move assignment deletes what the target held.
  GlBuffer third = GlBuffer::create();
  glBindBuffer(GL_ARRAY_BUFFER, third.get());
  const GLuint replaced = third.get();
  third = std::move(second);
  EXPECT_EQ(glIsBuffer(replaced), GL_FALSE);
  EXPECT_EQ(glIsBuffer(name), GL_TRUE);
  EXPECT_EQ(third.get(), name);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  third.reset();
  EXPECT_EQ(glIsBuffer(name), GL_FALSE);
  EXPECT_EQ(third.get(), 0u);
}

TEST(GlHandle, EveryKindIsDeletedWithItsHandle) {
  OffscreenContext context(kContextWidth, kContextHeight, 1);
  const LiveObjects before;
  {
    const GlVertexArray vao = GlVertexArray::create();
    glBindVertexArray(vao.get());
    const GlTexture texture = GlTexture::create();
    glBindTexture(GL_TEXTURE_2D, texture.get());
    const GlFramebuffer fbo = GlFramebuffer::create();
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.get());
    const GlRenderbuffer rbo = GlRenderbuffer::create();
    glBindRenderbuffer(GL_RENDERBUFFER, rbo.get());
    const GlShader shader = GlShader::create(GLenum{GL_VERTEX_SHADER});
    const GlProgramName program = GlProgramName::create();
    const LiveObjects during;
    EXPECT_EQ(during.vertex_arrays, before.vertex_arrays + 1);
    EXPECT_EQ(during.textures, before.textures + 1);
    EXPECT_EQ(during.framebuffers, before.framebuffers + 1);
    EXPECT_EQ(during.renderbuffers, before.renderbuffers + 1);
    EXPECT_EQ(during.shaders, before.shaders + 1);
    EXPECT_EQ(during.programs, before.programs + 1);
    glBindVertexArray(0);
    glBindTexture(GL_TEXTURE_2D, 0);
    context.make_current();  // binds the context's own framebuffer again
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
  }
  EXPECT_EQ(LiveObjects(), before);
}

TEST(GlHandle, CreatingWithoutAContextThrows) {
  // OSMesa has no current context on a fresh thread: GL hands back no name.
  std::string message;
  std::thread([&] {
    try {
      GlBuffer::create();
    } catch (const std::runtime_error& error) {
      message = error.what();
    }
  }).join();
  EXPECT_THAT(message, HasSubstr("glGenBuffers returned no name"));
}

TEST(GpuMesh, ManyMeshesLeaveNoBufferOrVertexArrayBehind) {
  OffscreenContext context(kContextWidth, kContextHeight, 1);
  const LiveObjects before;
  MeshData smooth = testing::box_mesh({0.5f, 0.4f, 0.3f});
  smooth.normals.assign(smooth.positions.begin(), smooth.positions.end());
  const MeshData flat = testing::box_mesh({0.2f, 0.3f, 0.4f});
  std::vector<GLuint> vaos;
  std::vector<GLuint> buffers;
  {
    std::vector<GpuMesh> meshes;
    for (int i = 0; i < 50; ++i) {
      meshes.push_back(upload_mesh(i % 2 == 0 ? smooth : flat));  // reallocations move them
      const GpuMesh& mesh = meshes.back();
      vaos.push_back(mesh.vao.get());
      buffers.push_back(mesh.vertex_buffer.get());
      EXPECT_EQ(static_cast<bool>(mesh.index_buffer), i % 2 == 0);
      if (mesh.index_buffer) buffers.push_back(mesh.index_buffer.get());
    }
    const LiveObjects during;
    EXPECT_EQ(during.vertex_arrays, before.vertex_arrays + 50);
    EXPECT_EQ(during.buffers, before.buffers + 75);
    for (const GLuint vao : vaos) EXPECT_EQ(glIsVertexArray(vao), GL_TRUE) << vao;
    for (const GLuint buffer : buffers) EXPECT_EQ(glIsBuffer(buffer), GL_TRUE) << buffer;

    // A moved-from mesh owns nothing; its new owner keeps the objects alive.
    GpuMesh moved = std::move(meshes.front());
    EXPECT_FALSE(meshes.front().vao);  // NOLINT(bugprone-use-after-move)
    meshes.erase(meshes.begin());
    EXPECT_EQ(glIsVertexArray(moved.vao.get()), GL_TRUE);
  }
  for (const GLuint vao : vaos) EXPECT_EQ(glIsVertexArray(vao), GL_FALSE) << vao;
  for (const GLuint buffer : buffers) EXPECT_EQ(glIsBuffer(buffer), GL_FALSE) << buffer;
  EXPECT_EQ(LiveObjects(), before);
}

TEST(GpuMesh, RejectedMeshCreatesNothing) {
  OffscreenContext context(kContextWidth, kContextHeight, 1);
  const LiveObjects before;
  MeshData mesh = testing::box_mesh({0.5f, 0.5f, 0.5f});
  mesh.indices.pop_back();
  EXPECT_THAT([&] { upload_mesh(mesh); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("is not a multiple of 3")));
  EXPECT_EQ(LiveObjects(), before);
}

TEST(GlProgram, LinkedProgramGoesWithItsOwnerAndLeavesNoShader) {
  OffscreenContext context(kContextWidth, kContextHeight, 1);
  const LiveObjects before;
  GLuint name = 0;
  {
    GlProgram program("test", kVertex, kFragment);
    name = program.name();
    EXPECT_EQ(glIsProgram(name), GL_TRUE);
    // The shaders are deleted once linked (attached, so flagged; they go with the program).
    GlProgram moved(std::move(program));
    EXPECT_EQ(program.name(), 0u);  // NOLINT(bugprone-use-after-move)
    EXPECT_EQ(moved.name(), name);
  }
  EXPECT_EQ(glIsProgram(name), GL_FALSE);
  EXPECT_EQ(LiveObjects(), before);
}

TEST(GlProgram, CompileAndLinkFailuresLeaveNoShaderOrProgram) {
  OffscreenContext context(kContextWidth, kContextHeight, 1);
  const LiveObjects before;
  // The fragment shader fails after the vertex shader compiled: that one must go too.
  EXPECT_THAT([] { GlProgram("broken", kVertex, "#version 330 core\nvoid main() { oops; }\n"); },
              ThrowsMessage<std::runtime_error>(HasSubstr("shader 'broken' failed to compile")));
  EXPECT_EQ(LiveObjects(), before);
  // Declared, never defined: compiles, fails to link.
  const char* unlinked =
      "#version 330 core\nout vec4 colour;\nvec4 helper();\nvoid main() { colour = helper(); }\n";
  EXPECT_THAT([&] { GlProgram("unlinked", kVertex, unlinked); },
              ThrowsMessage<std::runtime_error>(HasSubstr("shader 'unlinked' failed to link")));
  EXPECT_EQ(LiveObjects(), before);
}

/// A frame that uses every object of the scene passes: a mesh, an arrow, a polyline and
/// points, and a ground with a shadow (the lazily made shadow framebuffer and texture).
DrawList busy_frame(MeshId mesh) {
  DrawList frame;
  frame.camera.eye = {3.0f, -4.0f, 2.5f};
  frame.style.ground = true;
  frame.style.ground_height = -1.0f;
  frame.meshes.push_back({mesh, Eigen::Matrix4f::Identity(), {0.8f, 0.5f, 0.2f, 1.0f}});
  Arrow arrow;
  arrow.to = {1.0f, 0.5f, 0.0f};
  frame.arrows.push_back(arrow);
  Polyline line;
  line.points = {Eigen::Vector3f(0, 0, 0), Eigen::Vector3f(0, 1, 0), Eigen::Vector3f(1, 1, 0)};
  frame.polylines.push_back(line);
  Points points;
  points.positions = {Eigen::Vector3f(0, 0, 1)};
  frame.points.push_back(points);
  return frame;
}

TEST(ScenePasses, ManyPassesLeaveNoGlObjectBehind) {
  OffscreenContext context(kContextWidth, kContextHeight, 1);
  const LiveObjects before;
  std::vector<GpuMesh> meshes;
  meshes.push_back(upload_mesh(testing::box_mesh({0.5f, 0.4f, 0.3f})));
  const DrawList frame = busy_frame(MeshId{0});
  for (int i = 0; i < 5; ++i) {
    ScenePasses passes;
    passes.draw(frame, meshes, context);
    passes.draw(frame, meshes, context);  // the same camera again: the static layers are stored
    if (i == 0) {
      const LiveObjects during;
      EXPECT_EQ(during.textures, before.textures + 1);  // the shadow map
      // Its framebuffer, and the context's stored copy of the static layers (colour and depth).
      EXPECT_EQ(during.framebuffers, before.framebuffers + 2);
      EXPECT_EQ(during.renderbuffers, before.renderbuffers + 2);
      EXPECT_EQ(during.programs, before.programs + 7);
      EXPECT_GT(during.buffers, before.buffers + 4);
    }
    context.make_current();
  }
  meshes.clear();
  // Mesa keeps the last program used alive (flagged for deletion) as the context's active
  // program; it is deleted, only not yet freed.
  EXPECT_LE(live(glIsProgram), before.programs + 1);
  // The context keeps its one stored copy of the static layers (made once, however many passes
  // stored into it) until it goes or is resized.
  LiveObjects expected = before;
  expected.framebuffers += 1;
  expected.renderbuffers += 2;
  EXPECT_EQ(LiveObjects(), expected);
  context.resize(kContextWidth + 2, kContextHeight);  // drops the stored copy
  context.make_current();
  EXPECT_EQ(LiveObjects(), before);
}

TEST(OverlayPass, ManyOverlaysLeaveNoGlObjectBehind) {
  OffscreenContext context(kContextWidth, kContextHeight, 1);
  const LiveObjects before;
  DrawList frame;
  Label label;
  label.text = "label";
  label.screen_px = {4.0f, 4.0f};
  frame.labels.push_back(label);
  OverlayPanel panel;
  panel.title = "panel";
  panel.lines = {"a line"};
  frame.panels.push_back(panel);
  for (int i = 0; i < 3; ++i) {
    OverlayPass overlay;  // the ImGui backend's program, buffers and font texture
    overlay.draw(frame, kContextWidth, kContextHeight);
    if (i == 0) {
      const LiveObjects during;
      EXPECT_EQ(during.programs, before.programs + 1);
      EXPECT_EQ(during.textures, before.textures + 1);
    }
  }
  glUseProgram(0);
  EXPECT_LE(live(glIsProgram), before.programs + 1);  // Mesa's active program, see above
  EXPECT_EQ(LiveObjects(), before);
}

TEST(OffscreenContext, HoldsOneFramebufferPerTargetAndNoFailedAttempt) {
  for (const int samples : {1, 4, 64}) {
    OffscreenContext context(kContextWidth, kContextHeight, samples);
    const LiveObjects objects;
    const bool resolved = context.samples() > 1;
    EXPECT_EQ(objects.framebuffers, resolved ? 2 : 1) << samples;
    EXPECT_EQ(objects.renderbuffers, resolved ? 3 : 2) << samples;
  }
}

TEST(OffscreenContext, InvalidSizeIsTheCallersMistake) {
  EXPECT_THAT([] { OffscreenContext(0, 10, 1); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("invalid image size 0x10")));
  EXPECT_THAT([] { OffscreenContext(64, 20000, 1); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("invalid image size 64x20000")));
}

TEST(Renderer, ReleasedMeshesAndDestroyedRenderersLeaveNoObject) {
  for (int round = 0; round < 3; ++round) {
    Renderer renderer({kContextWidth, kContextHeight, 1});
    LiveObjects before;
    renderer.with_context([&] { before = LiveObjects(); });
    for (int i = 0; i < 20; ++i) renderer.upload(testing::box_mesh({0.3f, 0.3f, 0.3f}));
    LiveObjects during;
    renderer.with_context([&] { during = LiveObjects(); });
    EXPECT_EQ(during.vertex_arrays, before.vertex_arrays + 20);
    EXPECT_EQ(during.buffers, before.buffers + 20);
    renderer.release_meshes(5);
    LiveObjects after;
    renderer.with_context([&] { after = LiveObjects(); });
    EXPECT_EQ(after.vertex_arrays, before.vertex_arrays + 5);
    EXPECT_EQ(after.buffers, before.buffers + 5);
    renderer.release_meshes(0);
    renderer.with_context([&] { after = LiveObjects(); });
    EXPECT_EQ(after, before);
  }
}

}  // namespace
}  // namespace tumble::render::detail
