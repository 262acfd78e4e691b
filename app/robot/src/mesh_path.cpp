// Where the mesh paths of robot files lead (apart from read_robot, so that one reader links
// without the others).
#include <cstdlib>
#include <sstream>

#include "app/robot/robot_model.hpp"
#include "base/errors.hpp"

namespace tumble::app::robot {

std::filesystem::path resolve_mesh_path(const std::string& uri, const std::filesystem::path& base,
                                        const PackagePaths& packages, const std::string& where) {
  static const std::string kPackage = "package://";
  static const std::string kFile = "file://";
  if (uri.empty()) throw InputError(where + ": the mesh has no file name");
  if (uri.compare(0, kFile.size(), kFile) == 0) return uri.substr(kFile.size());
  if (uri.compare(0, kPackage.size(), kPackage) != 0) {
    if (uri.find("://") != std::string::npos) {
      throw InputError(where + ": mesh '" + uri +
                       "': only file paths, file:// and package:// URIs are read");
    }
    const std::filesystem::path path(uri);
    return path.is_absolute() ? path : base / path;
  }
  const std::string rest = uri.substr(kPackage.size());
  const std::size_t slash = rest.find('/');
  const std::string name = rest.substr(0, slash);
  const std::string inside = slash == std::string::npos ? "" : rest.substr(slash + 1);
  for (const auto& [package, folder] : packages) {
    if (package == name) return folder / inside;
  }
  // ROS_PACKAGE_PATH: folders separated by ':', each a package (named by its folder) or a
  // folder of packages.
  if (const char* ros = std::getenv("ROS_PACKAGE_PATH")) {
    std::stringstream entries(ros);
    std::string entry;
    while (std::getline(entries, entry, ':')) {
      if (entry.empty()) continue;
      std::filesystem::path folder(entry);
      if (!folder.has_filename()) folder = folder.parent_path();  // "/opt/pkg/" names pkg too
      std::error_code error;
      if (folder.filename() == name && std::filesystem::is_directory(folder, error)) {
        return folder / inside;
      }
      if (std::filesystem::is_directory(folder / name, error)) return folder / name / inside;
    }
  }
  throw InputError(where + ": mesh '" + uri + "': package '" + name +
                   "' is not known (give --package-path " + name +
                   "=DIR, or set ROS_PACKAGE_PATH)");
}

}  // namespace tumble::app::robot
