#pragma once
// A linked GLSL program with cached uniform locations; compile/link errors throw one line.

#include <string>
#include <string_view>
#include <unordered_map>

#include "gl_handle.hpp"

namespace tumble::render::detail {

class GlProgram {
 public:
  GlProgram() = default;
  /// Compiles and links; `geometry` may be empty. Throws std::runtime_error naming `name`
  /// (every shader and program made on the way is deleted). Move-only: the program is deleted
  /// with the last owner, which needs the context current.
  GlProgram(std::string_view name, std::string_view vertex, std::string_view fragment,
            std::string_view geometry = {});

  void use() const { glUseProgram(program_.get()); }
  GLuint name() const { return program_.get(); }
  /// Location of a uniform (-1 if absent; cached).
  GLint uniform(const char* name);

 private:
  GlProgramName program_;
  std::unordered_map<std::string, GLint> locations_;
};

}  // namespace tumble::render::detail
