#pragma once
// A fixture for end-to-end tests of the `tumble` executable: a fresh temporary folder per test,
// scene files written into it, and ffprobe's view of a video.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "support/run_command.hpp"
#include "support/scene_builder.hpp"

namespace tumble::testing {

/// A needle (moments 0.001 : 1 : 1) spun fast about its axis with a wobble: with dt = 0.01,
/// explicit Euler blows up at step 241 (t = 2.41 s), while stable integrators get through.
inline nlohmann::json fast_needle_scene() {
  return SceneBuilder()
      .duration(3.0)
      .dt(0.01)
      .body(BodyBuilder("needle").principal({0.001, 1, 1}).mass(1.0).angular_velocity({10, 1, 0}))
      .json();
}

/// Each test gets its own empty folder (named after its suite), removed afterwards.
class CommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fresh_directory(::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name());
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  /// Writes `scene` as JSON into the folder and returns its path.
  std::string write_scene(const nlohmann::json& scene,
                          const std::string& name = "scene.json") const {
    std::ofstream(dir_ / name) << scene.dump(2);
    return path(name);
  }

  std::filesystem::path dir_;
};

}  // namespace tumble::testing
