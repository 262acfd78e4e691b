// Which reader a robot file goes to.
#include "app/robot/robot_model.hpp"

#include <cctype>

#include "app/support/text_file.hpp"
#include "base/errors.hpp"

namespace tumble::app::robot {
namespace {

/// The name of the first element of an XML text (after the declaration, comments and
/// processing instructions), or "" when there is none.
std::string root_element_name(const std::string& text) {
  std::size_t at = 0;
  while ((at = text.find('<', at)) != std::string::npos) {
    if (text.compare(at, 4, "<!--") == 0) {
      at = text.find("-->", at);
      if (at == std::string::npos) return "";
    } else if (text.compare(at, 2, "<?") == 0 || text.compare(at, 2, "<!") == 0) {
      at = text.find('>', at);
      if (at == std::string::npos) return "";
    } else {
      std::size_t end = at + 1;
      while (end < text.size() && text[end] != '>' && text[end] != '/' &&
             !std::isspace(static_cast<unsigned char>(text[end]))) {
        ++end;
      }
      return text.substr(at + 1, end - at - 1);
    }
  }
  return "";
}

}  // namespace

Robot read_robot(const std::filesystem::path& file, const ReadOptions& options) {
  std::string text = read_text_file(file, "robot file");
  const std::string root = root_element_name(text);
  if (root == "robot") return read_urdf(file, std::move(text), options);
  if (root == "sdf") return read_sdf(file, std::move(text), options);
  if (root == "mujoco") return read_mjcf(file, std::move(text), options);
  throw InputError(file.string() + ": not a robot description: its root element is " +
                   (root.empty() ? std::string("missing") : "<" + root + ">") +
                   " (expected <robot> for URDF, <sdf> for SDF or <mujoco> for MJCF)");
}

}  // namespace tumble::app::robot
