// read_text_file: whole files named by the user, with errors that name them.
#include "app/support/text_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
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
            file.string() + ": cannot open the scene file: no such file or directory");
}

TEST_F(TextFileTest, ADirectoryNamesItAndWhatWasExpected) {
  EXPECT_EQ(input_error_of([&] { read_text_file(dir_, "viewer script"); }),
            dir_.string() + ": is a directory, expected a viewer script");
}

TEST_F(TextFileTest, ADeviceIsRefusedWithoutBeingRead) {
  // /dev/zero would be read until memory runs out; it is refused before it is opened.
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(input_error_of([&] { read_text_file("/dev/zero", "scene file"); }),
            "/dev/zero: is a character device, not a regular file; expected a scene file");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
}

TEST_F(TextFileTest, AFifoIsRefusedWithoutBlocking) {
  // Opening a FIFO for reading blocks until a writer comes: none will.
  const fs::path fifo = dir_ / "scene.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  EXPECT_EQ(input_error_of([&] { read_text_file(fifo, "scene file"); }),
            fifo.string() + ": is a FIFO, not a regular file; expected a scene file");
}

TEST_F(TextFileTest, ALoopOfSymbolicLinksIsReportedAsALoop) {
  fs::create_symlink(dir_ / "b.json", dir_ / "a.json");
  fs::create_symlink(dir_ / "a.json", dir_ / "b.json");
  EXPECT_EQ(input_error_of([&] { read_text_file(dir_ / "a.json", "scene file"); }),
            (dir_ / "a.json").string() + ": cannot open the scene file: a loop of symbolic links");
}

TEST_F(TextFileTest, ALinkToARegularFileIsRead) {
  { std::ofstream(dir_ / "real.json") << "{}"; }
  fs::create_symlink(dir_ / "real.json", dir_ / "link.json");
  EXPECT_EQ(read_text_file(dir_ / "link.json", "scene file"), "{}");
}

TEST_F(TextFileTest, AFileLargerThanTheLimitIsRefusedUnread) {
  const fs::path big = dir_ / "big.json";
  { std::ofstream(big) << "x"; }
  fs::resize_file(big, kMaxTextFileBytes + 1);  // sparse: nothing is written
  EXPECT_EQ(input_error_of([&] { read_text_file(big, "scene file"); }),
            big.string() + ": is 67108865 bytes, more than a scene file may hold (64 MiB)");
  fs::resize_file(big, 1000);
  EXPECT_EQ(read_text_file(big, "scene file").size(), 1000u);
}

}  // namespace
}  // namespace tumble::app
