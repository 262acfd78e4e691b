#include "output_paths.hpp"

#include <stdexcept>
#include <system_error>

#include "base/errors.hpp"

namespace tumble::render::detail {

std::filesystem::path output_directory(const std::filesystem::path& target) {
  const std::filesystem::path parent = target.parent_path();
  return parent.empty() ? std::filesystem::path(".") : parent;
}

void require_output_directory(const std::filesystem::path& target) {
  const std::filesystem::path directory = output_directory(target);
  std::error_code error;
  if (!std::filesystem::is_directory(directory, error)) {
    throw InputError("cannot write '" + target.string() + "': directory '" + directory.string() +
                     "' does not exist");
  }
}

}  // namespace tumble::render::detail
