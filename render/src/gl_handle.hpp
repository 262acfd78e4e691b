#pragma once
// Move-only owners of OpenGL object names. Each handle deletes its object exactly once, when it
// is destroyed or reassigned; a moved-from handle holds 0 and deletes nothing. Deleting needs
// the context that created the object current, so owners of handles make their context current
// before they go (OffscreenContext, Renderer).

#include <stdexcept>
#include <string>
#include <utility>

#include "gl.hpp"

namespace tumble::render::detail {

template <typename Kind>
class GlHandle {
 public:
  GlHandle() = default;
  /// Takes ownership of an existing name (0 for none).
  explicit GlHandle(GLuint name) : name_(name) {}
  ~GlHandle() { reset(); }
  GlHandle(GlHandle&& other) noexcept : name_(std::exchange(other.name_, 0)) {}
  GlHandle& operator=(GlHandle&& other) noexcept {
    if (this != &other) {
      reset();
      name_ = std::exchange(other.name_, 0);
    }
    return *this;
  }
  GlHandle(const GlHandle&) = delete;
  GlHandle& operator=(const GlHandle&) = delete;

  /// A new object (glGen* / glCreate*); `arguments` are the shader stage for shaders. Throws
  /// std::runtime_error when GL hands back no name.
  template <typename... Arguments>
  static GlHandle create(Arguments... arguments) {
    GlHandle handle(Kind::create(arguments...));
    if (handle.name_ == 0) {
      throw std::runtime_error(std::string("renderer: ") + Kind::kCreator + " returned no name");
    }
    return handle;
  }

  GLuint get() const { return name_; }
  explicit operator bool() const { return name_ != 0; }

  /// Deletes the object now (if any).
  void reset() noexcept {
    if (name_ != 0) Kind::destroy(name_);
    name_ = 0;
  }

 private:
  GLuint name_ = 0;
};

namespace gl_kind {

struct Buffer {
  static constexpr const char* kCreator = "glGenBuffers";
  static GLuint create() {
    GLuint name = 0;
    glGenBuffers(1, &name);
    return name;
  }
  static void destroy(GLuint name) { glDeleteBuffers(1, &name); }
};

struct VertexArray {
  static constexpr const char* kCreator = "glGenVertexArrays";
  static GLuint create() {
    GLuint name = 0;
    glGenVertexArrays(1, &name);
    return name;
  }
  static void destroy(GLuint name) { glDeleteVertexArrays(1, &name); }
};

struct Texture {
  static constexpr const char* kCreator = "glGenTextures";
  static GLuint create() {
    GLuint name = 0;
    glGenTextures(1, &name);
    return name;
  }
  static void destroy(GLuint name) { glDeleteTextures(1, &name); }
};

struct Framebuffer {
  static constexpr const char* kCreator = "glGenFramebuffers";
  static GLuint create() {
    GLuint name = 0;
    glGenFramebuffers(1, &name);
    return name;
  }
  static void destroy(GLuint name) { glDeleteFramebuffers(1, &name); }
};

struct Renderbuffer {
  static constexpr const char* kCreator = "glGenRenderbuffers";
  static GLuint create() {
    GLuint name = 0;
    glGenRenderbuffers(1, &name);
    return name;
  }
  static void destroy(GLuint name) { glDeleteRenderbuffers(1, &name); }
};

struct Shader {
  static constexpr const char* kCreator = "glCreateShader";
  static GLuint create(GLenum stage) { return glCreateShader(stage); }
  static void destroy(GLuint name) { glDeleteShader(name); }
};

struct Program {
  static constexpr const char* kCreator = "glCreateProgram";
  static GLuint create() { return glCreateProgram(); }
  static void destroy(GLuint name) { glDeleteProgram(name); }
};

}  // namespace gl_kind

using GlBuffer = GlHandle<gl_kind::Buffer>;
using GlVertexArray = GlHandle<gl_kind::VertexArray>;
using GlTexture = GlHandle<gl_kind::Texture>;
using GlFramebuffer = GlHandle<gl_kind::Framebuffer>;
using GlRenderbuffer = GlHandle<gl_kind::Renderbuffer>;
using GlShader = GlHandle<gl_kind::Shader>;
using GlProgramName = GlHandle<gl_kind::Program>;

}  // namespace tumble::render::detail
