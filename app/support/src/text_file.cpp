#include "app/support/text_file.hpp"

#include <fstream>
#include <sstream>
#include <system_error>

#include "engine/input_error.hpp"

namespace tumble::app {

std::string read_text_file(const std::filesystem::path& file, const std::string& what) {
  using engine::InputError;
  std::error_code error;
  if (std::filesystem::is_directory(file, error)) {
    throw InputError(file.string() + ": is a directory, expected a " + what);
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot open the " + what);
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(file.string() + ": cannot read the " + what);
  return text.str();
}

}  // namespace tumble::app
