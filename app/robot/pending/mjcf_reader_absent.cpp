// read_mjcf until the MJCF reader (src/mjcf_reader.cpp) is in: MJCF files are refused.
#include "app/robot/robot_model.hpp"
#include "tumble/errors.hpp"

namespace tumble::app::robot {

Robot read_mjcf(const std::filesystem::path& file, std::string, const ReadOptions&) {
  throw InputError(file.string() + ": MJCF files are not read yet");
}

}  // namespace tumble::app::robot
