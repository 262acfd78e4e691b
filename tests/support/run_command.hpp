#pragma once
// Runs a shell command and captures its exit status, stdout and stderr (for end-to-end tests of
// the `tumble` executable).

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace tumble::testing {

struct CommandResult {
  int status = -1;
  std::string out;
  std::string err;
};

inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Names of the entries of `dir`, sorted (to check what a command left behind).
inline std::vector<std::string> directory_entries(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

/// A fresh, empty directory under the system's temporary directory, unique per test.
inline std::filesystem::path fresh_directory(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("tumble_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// Runs `command` through the shell with stdout and stderr captured to files (a folder of
/// their own for each call, so that threads may run commands at once).
inline CommandResult run_command(const std::string& command) {
  static std::atomic<unsigned> calls{0};
  const auto dir = fresh_directory("cmd" + std::to_string(calls++));
  const auto out = dir / "out.txt";
  const auto err = dir / "err.txt";
  const std::string full = command + " >'" + out.string() + "' 2>'" + err.string() + "' </dev/null";
  const int raw = std::system(full.c_str());
  CommandResult result;
  result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  result.out = read_text(out);
  result.err = read_text(err);
  std::filesystem::remove_all(dir);
  return result;
}

/// The `tumble` executable of this build.
inline std::string tumble_executable() {
  return std::string(TUMBLE_BINARY_DIR) + "/app/tumble";
}

/// "codec,width,height,frames" of a video's first stream, as ffprobe counts them.
inline std::string probe_video(const std::filesystem::path& file) {
  const auto result = run_command(
      "ffprobe -v error -select_streams v:0 -count_frames -show_entries "
      "stream=codec_name,width,height,nb_read_frames -of csv=p=0 '" +
      file.string() + "'");
  EXPECT_EQ(result.status, 0) << result.err;
  std::string text = result.out;
  while (!text.empty() && (text.back() == '\n' || text.back() == ',')) text.pop_back();
  return text;
}

}  // namespace tumble::testing
