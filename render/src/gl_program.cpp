#include "gl_program.hpp"

#include <stdexcept>
#include <utility>

namespace tumble::render::detail {

namespace {

std::string first_line(std::string log) {
  const auto end = log.find('\n');
  if (end != std::string::npos) log.resize(end);
  return log;
}

GlShader compile(std::string_view name, GLenum stage, std::string_view source) {
  GlShader shader = GlShader::create(stage);
  const GLchar* text = source.data();
  const auto length = static_cast<GLint>(source.size());
  glShaderSource(shader.get(), 1, &text, &length);
  glCompileShader(shader.get());
  GLint ok = GL_FALSE;
  glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[1024] = {};
    glGetShaderInfoLog(shader.get(), sizeof log, nullptr, log);
    throw std::runtime_error("renderer: shader '" + std::string(name) +
                             "' failed to compile: " + first_line(log));
  }
  return shader;
}

}  // namespace

GlProgram::GlProgram(std::string_view name, std::string_view vertex, std::string_view fragment,
                     std::string_view geometry) {
  // The shaders are deleted when they go out of scope; attached ones live on in the program.
  const GlShader vs = compile(name, GL_VERTEX_SHADER, vertex);
  const GlShader fs = compile(name, GL_FRAGMENT_SHADER, fragment);
  const GlShader gs = geometry.empty() ? GlShader() : compile(name, GL_GEOMETRY_SHADER, geometry);
  GlProgramName program = GlProgramName::create();
  glAttachShader(program.get(), vs.get());
  glAttachShader(program.get(), fs.get());
  if (gs) glAttachShader(program.get(), gs.get());
  glLinkProgram(program.get());
  GLint ok = GL_FALSE;
  glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[1024] = {};
    glGetProgramInfoLog(program.get(), sizeof log, nullptr, log);
    throw std::runtime_error("renderer: shader '" + std::string(name) +
                             "' failed to link: " + first_line(log));
  }
  program_ = std::move(program);
}

GLint GlProgram::uniform(const char* name) {
  const auto found = locations_.find(name);
  if (found != locations_.end()) return found->second;
  const GLint location = glGetUniformLocation(program_.get(), name);
  locations_.emplace(name, location);
  return location;
}

}  // namespace tumble::render::detail
