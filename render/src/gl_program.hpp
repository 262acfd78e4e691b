#pragma once
// A linked GLSL program with cached uniform locations; compile/link errors throw one line.

#include <string>
#include <string_view>
#include <unordered_map>

#include "gl.hpp"

namespace tumble::render::detail {

class GlProgram {
 public:
  GlProgram() = default;
  /// Compiles and links; `geometry` may be empty. Throws std::runtime_error naming `name`.
  GlProgram(std::string_view name, std::string_view vertex, std::string_view fragment,
            std::string_view geometry = {});
  ~GlProgram();
  GlProgram(GlProgram&& other) noexcept;
  GlProgram& operator=(GlProgram&& other) noexcept;
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;

  void use() const { glUseProgram(program_); }
  /// Location of a uniform (-1 if absent; cached).
  GLint uniform(const char* name);

 private:
  GLuint program_ = 0;
  std::unordered_map<std::string, GLint> locations_;
};

}  // namespace tumble::render::detail
