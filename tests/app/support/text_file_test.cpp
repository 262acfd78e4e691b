// read_text_file: whole files named by the user, with errors that name them.
#include "app/support/text_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/input_error.hpp"
#include "support/run_command.hpp"

namespace tumble::app {
namespace {

namespace fs = std::filesystem;
using testing::input_error_of;

class TextFileTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::fresh_directory("TextFileTest"); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(TextFileTest, ReadsEveryByteUnchanged) {
  std::string bytes = "line one\r\nline two\n";
  bytes += '\0';
  bytes += "after a NUL\xff";
  {
    std::ofstream out(dir_ / "scene.json", std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  EXPECT_EQ(read_text_file(dir_ / "scene.json", "scene file"), bytes);
}

TEST_F(TextFileTest, AnEmptyFileIsEmptyText) {
  { std::ofstream(dir_ / "empty.txt"); }
  EXPECT_EQ(read_text_file(dir_ / "empty.txt", "script"), "");
}

TEST_F(TextFileTest, AMissingFileNamesItAndWhatWasExpected) {
  const fs::path file = dir_ / "nope.json";
  EXPECT_EQ(input_error_of([&] { read_text_file(file, "scene file"); }),
            file.string() + ": cannot open the scene file");
}

TEST_F(TextFileTest, ADirectoryNamesItAndWhatWasExpected) {
  EXPECT_EQ(input_error_of([&] { read_text_file(dir_, "viewer script"); }),
            dir_.string() + ": is a directory, expected a viewer script");
}

}  // namespace
}  // namespace tumble::app
