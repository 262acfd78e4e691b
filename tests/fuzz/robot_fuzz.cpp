// Fuzz target: robot descriptions (URDF, SDF, MJCF) from text. The reader its root element
// picks, then each link's inertial from its geometry when every mesh it names is one of the
// small meshes in tests/fuzz/meshes (meshes anywhere else are not read, so the fuzzer cannot
// wander into the machine's files), then the rewrite with those inertials, which must read
// back (same links, the new inertials stated): a rewrite that breaks the file is a bug. The
// whole robot's total in its zero configuration (link frames from joints, poses, nested
// bodies) must be finite.
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "app/robot/link_inertial.hpp"
#include "app/robot/rewrite.hpp"
#include "app/robot/robot_model.hpp"
#include "app/robot/robot_total.hpp"
#include "base/errors.hpp"
#include "fuzz_target.hpp"

namespace {

using namespace tumble::app::robot;

const std::filesystem::path kMeshDir = TUMBLE_FUZZ_MESH_DIR;

/// True when every mesh of `link` is a file directly in kMeshDir.
bool meshes_are_ours(const Link& link) {
  for (const Geometry& geometry : link.geometries) {
    const auto* mesh = std::get_if<MeshGeometry>(&geometry.shape);
    if (mesh == nullptr) continue;
    std::error_code error;
    const auto file = std::filesystem::weakly_canonical(mesh->file, error);
    if (error || file.parent_path() != std::filesystem::weakly_canonical(kMeshDir) ||
        !std::filesystem::is_regular_file(file, error)) {
      return false;
    }
  }
  return true;
}

Robot read(const std::string& text) {
  const std::filesystem::path file = kMeshDir / "fuzz.robot";
  ReadOptions options;
  options.packages = {{"fuzz", kMeshDir}};
  if (text.find("<mujoco") != std::string::npos) return read_mjcf(file, text, options);
  if (text.find("<sdf") != std::string::npos) return read_sdf(file, text, options);
  return read_urdf(file, text, options);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = tumble::fuzz::as_text(data, size);
  Robot robot;
  try {
    robot = read(text);
  } catch (const tumble::InputError&) {
    return 0;  // a clean refusal
  }
  std::vector<std::optional<tumble::engine::MassProperties>> inertials(robot.links.size());
  for (std::size_t i = 0; i < robot.links.size(); ++i) {
    if (!meshes_are_ours(robot.links[i])) continue;
    inertials[i] = compute_link_inertial(robot.links[i], {}).computed;
  }
  // The zero configuration's total: finite whenever some link has a mass.
  if (const auto total = robot_total(robot.links, inertials)) {
    if (!std::isfinite(total->properties.mass) || !total->properties.inertia.allFinite()) {
      throw std::logic_error("the whole robot's total is not finite");
    }
  }
  std::string rewritten;
  try {
    rewritten = rewritten_text(robot, inertials, InertialFrame::mesh);
  } catch (const tumble::InputError&) {
    return 0;  // a link that can take no inertial, named
  }
  const Robot again = read(rewritten);
  if (again.links.size() != robot.links.size()) {
    throw std::logic_error("the rewritten robot has a different number of links");
  }
  for (std::size_t i = 0; i < robot.links.size(); ++i) {
    if (inertials[i] && !(again.links[i].stated && again.links[i].stated->mass)) {
      throw std::logic_error("link " + robot.links[i].name + " lost its new inertial");
    }
  }
  return 0;
}
