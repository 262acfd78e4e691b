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

GLuint compile(std::string_view name, GLenum stage, std::string_view source) {
  const GLuint shader = glCreateShader(stage);
  const GLchar* text = source.data();
  const auto length = static_cast<GLint>(source.size());
  glShaderSource(shader, 1, &text, &length);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[1024] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw std::runtime_error("renderer: shader '" + std::string(name) +
                             "' failed to compile: " + first_line(log));
  }
  return shader;
}

}  // namespace

GlProgram::GlProgram(std::string_view name, std::string_view vertex, std::string_view fragment,
                     std::string_view geometry) {
  const GLuint vs = compile(name, GL_VERTEX_SHADER, vertex);
  const GLuint fs = compile(name, GL_FRAGMENT_SHADER, fragment);
  const GLuint gs = geometry.empty() ? 0 : compile(name, GL_GEOMETRY_SHADER, geometry);
  program_ = glCreateProgram();
  glAttachShader(program_, vs);
  glAttachShader(program_, fs);
  if (gs != 0) glAttachShader(program_, gs);
  glLinkProgram(program_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  if (gs != 0) glDeleteShader(gs);
  GLint ok = GL_FALSE;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[1024] = {};
    glGetProgramInfoLog(program_, sizeof log, nullptr, log);
    glDeleteProgram(program_);
    program_ = 0;
    throw std::runtime_error("renderer: shader '" + std::string(name) +
                             "' failed to link: " + first_line(log));
  }
}

GlProgram::~GlProgram() {
  if (program_ != 0) glDeleteProgram(program_);
}

GlProgram::GlProgram(GlProgram&& other) noexcept
    : program_(std::exchange(other.program_, 0)), locations_(std::move(other.locations_)) {}

GlProgram& GlProgram::operator=(GlProgram&& other) noexcept {
  if (this != &other) {
    if (program_ != 0) glDeleteProgram(program_);
    program_ = std::exchange(other.program_, 0);
    locations_ = std::move(other.locations_);
  }
  return *this;
}

GLint GlProgram::uniform(const char* name) {
  const auto found = locations_.find(name);
  if (found != locations_.end()) return found->second;
  const GLint location = glGetUniformLocation(program_, name);
  locations_.emplace(name, location);
  return location;
}

}  // namespace tumble::render::detail
