// Error paths of the image sinks: the type of each error (tumble::InputError for what the user
// can fix, std::logic_error / std::invalid_argument for the caller's mistakes, plain
// std::runtime_error for the system's), its one-line message, and that no file descriptor,
// child process or temporary file outlives a failure.
#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "media/image_sink.hpp"
#include "support/run_command.hpp"

namespace tumble::media {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::ThrowsMessage;
using tumble::testing::directory_entries;

constexpr int kSide = 16;

SinkOptions small_options() {
  SinkOptions options;
  options.width = kSide;
  options.height = kSide;
  options.fps = 10.0;
  return options;
}

Image small_frame() {
  return {kSide, kSide, std::vector<std::uint8_t>(4 * kSide * kSide, 128)};
}

/// The descriptors this process holds, ascending (without the one used to list them).
std::vector<int> open_descriptors() {
  std::vector<int> fds;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/fd")) {
    fds.push_back(std::stoi(entry.path().filename().string()));
  }
  std::erase_if(fds, [](int fd) { return ::fcntl(fd, F_GETFD) == -1; });
  std::sort(fds.begin(), fds.end());
  return fds;
}

/// Whether this process has no child, running or a zombie.
bool no_child_process() {
  return ::waitpid(-1, nullptr, WNOHANG) == -1 && errno == ECHILD;
}

/// Sets PATH for its lifetime.
class PathGuard {
 public:
  explicit PathGuard(const std::string& path) {
    const char* old = std::getenv("PATH");
    had_ = old != nullptr;
    if (had_) old_ = old;
    ::setenv("PATH", path.c_str(), 1);
  }
  ~PathGuard() {
    if (had_) {
      ::setenv("PATH", old_.c_str(), 1);
    } else {
      ::unsetenv("PATH");
    }
  }
  PathGuard(const PathGuard&) = delete;
  PathGuard& operator=(const PathGuard&) = delete;

 private:
  bool had_ = false;
  std::string old_;
};

/// What an action threw: the dynamic type and message (empty type when nothing).
struct Thrown {
  std::string message;
  bool input_error = false;
  bool runtime_error = false;
};

template <typename Action>
Thrown thrown_by(Action&& action) {
  Thrown thrown;
  try {
    action();
  } catch (const InputError& error) {
    thrown = {error.what(), true, true};
  } catch (const std::runtime_error& error) {
    thrown = {error.what(), false, true};
  }
  return thrown;
}

/// A directory holding an executable `ffmpeg` shell script with `body`.
std::filesystem::path fake_ffmpeg(const std::string& name, const std::string& body,
                                  std::filesystem::perms perms) {
  const auto dir = tumble::testing::fresh_directory(name);
  {
    std::ofstream script(dir / "ffmpeg");
    script << "#!/bin/sh\n" << body;
  }
  std::filesystem::permissions(dir / "ffmpeg", perms);
  return dir;
}

TEST(SinkErrors, SecondPipeFailingLeaksNoDescriptor) {
  const auto dir = tumble::testing::fresh_directory("pipe_fail");
  const std::vector<int> before = open_descriptors();
  // A limit with exactly two free descriptor numbers below it: the probe of the output opens
  // and closes one, ffmpeg's stdin pipe takes both, its stderr pipe gets none.
  rlim_t limit = 0;
  for (int fd = 0, spare = 0; spare < 2; ++fd) {
    if (!std::binary_search(before.begin(), before.end(), fd) && ++spare == 2) {
      limit = static_cast<rlim_t>(fd + 1);
    }
  }
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_NOFILE, &old), 0);
  rlimit lowered = old;
  lowered.rlim_cur = limit;
  ASSERT_EQ(::setrlimit(RLIMIT_NOFILE, &lowered), 0);
  const Thrown thrown = thrown_by([&] { open_image_sink(dir / "out.mp4", small_options()); });
  ASSERT_EQ(::setrlimit(RLIMIT_NOFILE, &old), 0);

  // The system's failure, not the user's: a runtime_error that is no InputError.
  EXPECT_TRUE(thrown.runtime_error);
  EXPECT_FALSE(thrown.input_error);
  EXPECT_THAT(thrown.message, AllOf(HasSubstr("'" + (dir / "out.mp4").string() + "'"),
                                    HasSubstr("cannot start ffmpeg: pipe: Too many open files")));
  EXPECT_EQ(open_descriptors(), before);
  EXPECT_TRUE(no_child_process());
  EXPECT_TRUE(directory_entries(dir).empty());
  std::filesystem::remove_all(dir);
}

TEST(SinkErrors, MissingFfmpegLeavesNoDescriptorOrProcess) {
  const auto dir = tumble::testing::fresh_directory("no_ffmpeg_fds");
  const std::vector<int> before = open_descriptors();
  {
    const PathGuard path("/nonexistent");
    EXPECT_THAT([&] { open_image_sink(dir / "out.webm", small_options()); },
                ThrowsMessage<InputError>(
                    AllOf(HasSubstr("cannot write '" + (dir / "out.webm").string() + "'"),
                          HasSubstr("ffmpeg not found on PATH"), Not(HasSubstr("\n")))));
  }
  EXPECT_EQ(open_descriptors(), before);
  EXPECT_TRUE(no_child_process());
  EXPECT_TRUE(directory_entries(dir).empty());
  std::filesystem::remove_all(dir);
}

TEST(SinkErrors, FfmpegThatCannotBeExecutedIsBadInputAndLeavesNothing) {
  // Not executable: posix_spawnp fails with EACCES (for root too: no execute bit at all).
  const auto bin =
      fake_ffmpeg("ffmpeg_noexec", "exit 0\n",
                  std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
  const auto dir = tumble::testing::fresh_directory("noexec_out");
  const std::vector<int> before = open_descriptors();
  {
    const PathGuard path(bin.string());
    EXPECT_THAT([&] { open_image_sink(dir / "out.gif", small_options()); },
                ThrowsMessage<InputError>(
                    AllOf(HasSubstr("cannot write '" + (dir / "out.gif").string() + "'"),
                          HasSubstr("cannot start ffmpeg: Permission denied"))));
  }
  EXPECT_EQ(open_descriptors(), before);
  EXPECT_TRUE(no_child_process());
  EXPECT_TRUE(directory_entries(dir).empty());
  std::filesystem::remove_all(dir);
  std::filesystem::remove_all(bin);
}

TEST(SinkErrors, FfmpegFailingOnTheOutputIsBadInputWithItsLastLines) {
  const auto bin = fake_ffmpeg("ffmpeg_fails",
                               "echo 'first complaint' >&2\n"
                               "echo 'second complaint' >&2\n"
                               "echo 'Error opening output: Read-only file system' >&2\n"
                               "exit 1\n",
                               std::filesystem::perms::owner_all);
  const auto dir = tumble::testing::fresh_directory("fails_out");
  const std::vector<int> before = open_descriptors();
  {
    const PathGuard path(bin.string());
    auto sink = open_image_sink(dir / "out.mp4", small_options());
    const Image frame = small_frame();
    const auto expected = ThrowsMessage<InputError>(AllOf(
        HasSubstr("ffmpeg failed writing '" + (dir / "out.mp4").string() + "' (exit status 1)"),
        HasSubstr("second complaint / Error opening output: Read-only file system"),
        Not(HasSubstr("first complaint")), Not(HasSubstr("\n"))));
    EXPECT_THAT(
        [&] {
          for (int i = 0; i < 200; ++i) sink->write(frame);
          sink->finish();
        },
        expected);
    // The failure is repeated, not turned into "closed"; finish() has nothing more to do.
    EXPECT_THAT([&] { sink->write(frame); }, expected);
    sink->finish();
  }
  EXPECT_EQ(open_descriptors(), before);
  EXPECT_TRUE(no_child_process());
  EXPECT_TRUE(directory_entries(dir).empty());
  std::filesystem::remove_all(dir);
  std::filesystem::remove_all(bin);
}

TEST(SinkErrors, FinishedVideoLeavesNoDescriptorAndRefusesFrames) {
  const auto dir = tumble::testing::fresh_directory("finished_video");
  const std::vector<int> before = open_descriptors();
  {
    auto sink = open_image_sink(dir / "out.mp4", small_options());
    sink->write(small_frame());
    sink->write(small_frame());
    sink->finish();
    EXPECT_THAT([&] { sink->write(small_frame()); },
                ThrowsMessage<std::logic_error>(
                    HasSubstr("video sink '" + (dir / "out.mp4").string() + "' is closed")));
    EXPECT_EQ(open_descriptors(), before);
    EXPECT_TRUE(no_child_process());
  }
  EXPECT_EQ(directory_entries(dir), std::vector<std::string>{"out.mp4"});
  std::filesystem::remove_all(dir);
}

TEST(SinkErrors, VideoThatCannotTakeItsNameIsBadInputAndLeavesNoTemporary) {
  const auto dir = tumble::testing::fresh_directory("rename_fails");
  auto sink = open_image_sink(dir / "out.mp4", small_options());
  sink->write(small_frame());
  // Something else takes the name meanwhile: a non-empty directory cannot be replaced by a file.
  std::filesystem::create_directories(dir / "out.mp4" / "inside");
  const auto expected = ThrowsMessage<InputError>(
      HasSubstr("cannot move video into '" + (dir / "out.mp4").string() + "': "));
  EXPECT_THAT([&] { sink->finish(); }, expected);
  EXPECT_THAT([&] { sink->write(small_frame()); }, expected);
  EXPECT_EQ(directory_entries(dir), std::vector<std::string>{"out.mp4"});
  EXPECT_TRUE(std::filesystem::is_directory(dir / "out.mp4" / "inside"));
  std::filesystem::remove_all(dir);
}

TEST(SinkErrors, FinishedPngSequenceRefusesFrames) {
  const auto dir = tumble::testing::fresh_directory("finished_png");
  auto sink = open_image_sink(dir / "frames/", small_options());
  sink->write(small_frame());
  sink->finish();
  EXPECT_THAT([&] { sink->write(small_frame()); },
              ThrowsMessage<std::logic_error>(
                  HasSubstr("PNG sink '" + (dir / "frames").string() + "' is closed")));
  EXPECT_EQ(directory_entries(dir / "frames"), std::vector<std::string>{"frame_000000.png"});
  std::filesystem::remove_all(dir);
}

TEST(SinkErrors, FolderOfOtherFilesIsNotReplaced) {
  const auto dir = tumble::testing::fresh_directory("png_refuse");
  std::filesystem::create_directory(dir / "frames");
  std::ofstream(dir / "frames" / "notes.txt") << "keep me\n";
  EXPECT_THAT([&] { open_image_sink(dir / "frames/", small_options()); },
              ThrowsMessage<InputError>(
                  AllOf(HasSubstr("refusing to replace '" + (dir / "frames").string() + "'"),
                        HasSubstr("files other than frame_*.png"))));
  EXPECT_EQ(directory_entries(dir), std::vector<std::string>{"frames"});
  EXPECT_EQ(directory_entries(dir / "frames"), std::vector<std::string>{"notes.txt"});
  std::filesystem::remove_all(dir);
}

TEST(SinkErrors, FileWhereTheFramesFolderShouldBeIsBadInput) {
  const auto dir = tumble::testing::fresh_directory("png_file");
  std::ofstream(dir / "frames") << "a file\n";
  EXPECT_THAT([&] { open_image_sink(dir / "frames/", small_options()); },
              ThrowsMessage<InputError>(AllOf(HasSubstr("'" + (dir / "frames").string() + "'"),
                                              HasSubstr("it exists and is not a directory"))));
  EXPECT_EQ(directory_entries(dir), std::vector<std::string>{"frames"});
  std::filesystem::remove_all(dir);
}

TEST(SinkErrors, ALinkToADeviceIsNeverReplaced) {
  // Before, the temporary was renamed over the link (and, for /dev/full given itself as root,
  // over the device node).
  const auto dir = tumble::testing::fresh_directory("sink_device");
  std::filesystem::create_symlink("/dev/null", dir / "out.mp4");
  EXPECT_THAT([&] { open_image_sink(dir / "out.mp4", small_options()); },
              ThrowsMessage<InputError>(
                  HasSubstr("cannot write '" + (dir / "out.mp4").string() +
                            "': it is a symbolic link to a character device, not a regular file")));
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "out.mp4"));
  EXPECT_EQ(directory_entries(dir), std::vector<std::string>{"out.mp4"});
  std::filesystem::remove_all(dir);
}

TEST(SinkErrors, ALinkToAFileOrFolderIsWrittenThroughAndStays) {
  const auto dir = tumble::testing::fresh_directory("sink_link");
  std::filesystem::create_directories(dir / "real" / "frames");
  std::ofstream(dir / "real" / "video.mp4") << "old";
  std::ofstream(dir / "real" / "frames" / "frame_000007.png") << "old";
  std::filesystem::create_symlink("real/video.mp4", dir / "out.mp4");
  std::filesystem::create_symlink("real/frames", dir / "frames");
  for (const char* name : {"out.mp4", "frames/"}) {
    auto sink = open_image_sink(dir / name, small_options());
    sink->write(small_frame());
    sink->finish();
  }
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "out.mp4"));
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "frames"));
  EXPECT_EQ(tumble::testing::read_text(dir / "real" / "video.mp4").substr(4, 4), "ftyp");
  EXPECT_EQ(directory_entries(dir / "real"), (std::vector<std::string>{"frames", "video.mp4"}));
  EXPECT_EQ(directory_entries(dir / "real" / "frames"),
            std::vector<std::string>{"frame_000000.png"});
  EXPECT_EQ(directory_entries(dir), (std::vector<std::string>{"frames", "out.mp4", "real"}));
  std::filesystem::remove_all(dir);
}

TEST(SinkErrors, AnInputGivenAsTheOutputIsRefusedThroughALinkToo) {
  const auto dir = tumble::testing::fresh_directory("sink_input");
  std::ofstream(dir / "scene.gif") << "an input";
  std::filesystem::create_symlink("scene.gif", dir / "out.gif");
  SinkOptions options = small_options();
  options.inputs = {dir / "scene.gif"};
  for (const char* name : {"scene.gif", "out.gif"}) {
    EXPECT_THAT([&] { open_image_sink(dir / name, options); },
                ThrowsMessage<InputError>(
                    HasSubstr("cannot write '" + (dir / name).string() + "': it is the input '" +
                              (dir / "scene.gif").string() + "' (an input is never overwritten)")));
  }
  EXPECT_EQ(tumble::testing::read_text(dir / "scene.gif"), "an input");
  EXPECT_EQ(directory_entries(dir), (std::vector<std::string>{"out.gif", "scene.gif"}));
  std::filesystem::remove_all(dir);
}

TEST(SinkErrors, AStaleTemporaryOfADeadProcessIsRemoved) {
  const auto dir = tumble::testing::fresh_directory("sink_stale");
  const auto dead = tumble::testing::run_command("sh -c 'echo $$'");
  const std::string pid = dead.out.substr(0, dead.out.find('\n'));
  std::ofstream(dir / (".out.mp4.tmp-" + pid)) << "half a video";
  auto sink = open_image_sink(dir / "out.mp4", small_options());
  sink->write(small_frame());
  sink->finish();
  EXPECT_EQ(directory_entries(dir), std::vector<std::string>{"out.mp4"});
  std::filesystem::remove_all(dir);
}

TEST(SinkErrors, InvalidOptionsAreTheCallers) {
  SinkOptions options = small_options();
  options.fps = 0.0;
  EXPECT_THAT([&] { open_image_sink("/tmp/out.mp4", options); },
              ThrowsMessage<std::invalid_argument>(
                  HasSubstr("output '/tmp/out.mp4': invalid size 16x16 or frame rate")));
}

}  // namespace
}  // namespace tumble::media
