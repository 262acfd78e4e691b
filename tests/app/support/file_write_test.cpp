// Whole files written with every write checked: a full disk or a file size limit is an error
// naming the file, never a file taken for written.
#include "app/support/file_write.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <csignal>
#include <filesystem>
#include <string>

#include "app/support/output_folder.hpp"
#include "support/run_command.hpp"

namespace tumble::app {
namespace {

namespace fs = std::filesystem;
using testing::read_text;

/// The WriteError `action()` throws; fails the test when it throws none.
template <typename Action>
WriteError write_error_of(Action&& action) {
  try {
    action();
  } catch (const WriteError& error) {
    return error;
  }
  ADD_FAILURE() << "no WriteError";
  return WriteError("", "");
}

class FileWriteTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::fresh_directory("FileWriteTest"); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(FileWriteTest, WritesTheWholeTextAndReplacesAnEarlierFile) {
  write_text_file(dir_ / "a.md", "an earlier, longer file\n");
  const std::string text(200000, 'x');
  write_text_file(dir_ / "a.md", text);
  EXPECT_EQ(read_text(dir_ / "a.md"), text);
}

TEST_F(FileWriteTest, AFullDeviceIsAnErrorNamingTheFile) {
  struct stat status {};
  if (::stat("/dev/full", &status) != 0 || !S_ISCHR(status.st_mode)) {
    GTEST_SKIP() << "/dev/full is not the full device here";
  }
  const WriteError error = write_error_of([] { write_text_file("/dev/full", "some text\n"); });
  EXPECT_EQ(error.file(), fs::path("/dev/full"));
  EXPECT_EQ(error.reason(), "No space left on device");
  EXPECT_STREQ(error.what(), "cannot write '/dev/full': No space left on device");
}

TEST_F(FileWriteTest, AWritePastTheFileSizeLimitIsAnError) {
  // RLIMIT_FSIZE is a per-file disk quota: the write past it fails with EFBIG (SIGXFSZ, which
  // would kill the process, ignored as tumble's main() does).
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit small = old;
  small.rlim_cur = 4096;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  const WriteError error =
      write_error_of([&] { write_text_file(dir_ / "big.csv", std::string(10000, 'x')); });
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_STREQ(error.what(),
               ("cannot write '" + (dir_ / "big.csv").string() + "': File too large").c_str());
}

TEST_F(FileWriteTest, AMissingFolderIsAnError) {
  const WriteError error = write_error_of([&] { write_text_file(dir_ / "no" / "a.md", "x"); });
  EXPECT_EQ(error.file(), dir_ / "no" / "a.md");
  EXPECT_EQ(error.reason(), "No such file or directory");
}

TEST(OutputWriteError, NamesAFileOfTheTemporaryFolderByItsFinalName) {
  const WriteError inside("/data/.out.tmp-42/plots/a.png", "File too large");
  EXPECT_STREQ(output_write_error(inside, "/data/.out.tmp-42", "/data/out").what(),
               "cannot write '/data/out/plots/a.png': File too large; nothing written to "
               "'/data/out'");
  const WriteError outside("/elsewhere/a.png", "No space left on device");
  const WriteError kept = output_write_error(outside, "/data/.out.tmp-42", "/data/out");
  EXPECT_EQ(kept.file(), fs::path("/elsewhere/a.png"));
  EXPECT_EQ(kept.reason(), "No space left on device; nothing written to '/data/out'");
}

}  // namespace
}  // namespace tumble::app
