// The one spawner (base/process.hpp): streams as asked, output collected, errors by whose they are
// to fix, cancel and kill that leave no child behind, the one-line error texts.
#include "base/process.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/errors.hpp"
#include "support/run_command.hpp"

namespace tumble {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

/// Whether a process of that id is still there (running or a zombie not reaped).
bool exists(pid_t pid) {
  return ::kill(pid, 0) == 0 || errno != ESRCH;
}

TEST(Process, CollectsOutputErrorAndExitStatus) {
  const ProcessResult result =
      run_process({"sh", "-c", "printf 'one\\ntwo\\n'; echo oops >&2; exit 3"});
  EXPECT_EQ(result.status, 3);
  EXPECT_EQ(result.signal, 0);
  EXPECT_FALSE(result.cancelled);
  EXPECT_EQ(result.out, "one\ntwo\n");
  EXPECT_EQ(result.err, "oops\n");
  EXPECT_EQ(result.shell_status(), 3);
}

TEST(Process, StandardInputIsTheNullDevice) {
  // `cat` reads the end of its input at once: it would wait for ever on a terminal.
  const ProcessResult result = run_process({"cat"});
  EXPECT_EQ(result.status, 0);
  EXPECT_EQ(result.out, "");
}

TEST(Process, KeepsOnlyTheTailOfALongError) {
  // 100,000 lines of 10 bytes on stderr: the last 16 KiB or so are kept, ending with the last.
  const ProcessResult result =
      run_process({"sh", "-c",
                   "i=0; while [ $i -lt 100000 ]; do echo line-$((i + 100000)); "
                   "i=$((i + 1)); done >&2"});
  EXPECT_EQ(result.status, 0);
  EXPECT_LE(result.err.size(), 2 * kErrorTail);
  EXPECT_GE(result.err.size(), kErrorTail);
  EXPECT_THAT(result.err, ::testing::EndsWith("line-199999\n"));
  EXPECT_EQ(last_line(result.err), "line-199999");
}

TEST(Process, AProgramNotOnPathIsBadInput) {
  EXPECT_THAT(
      [] {
        run_process({"tumble-no-such-program", "--help"});
      },
      ThrowsMessage<InputError>("tumble-no-such-program not found on PATH"));
}

TEST(Process, AFileThatCannotBeExecutedIsBadInput) {
  const auto dir = testing::fresh_directory("process_not_executable");
  const auto script = dir / "tool";
  std::ofstream(script) << "#!/bin/sh\necho hello\n";
  std::filesystem::permissions(script, std::filesystem::perms::owner_read);
  if (::geteuid() == 0) {
    // root may read it but still not execute a file without an execute bit.
    EXPECT_THAT(
        [&] { run_process({script.string()}); },
        ThrowsMessage<InputError>("cannot start " + script.string() + ": Permission denied"));
  } else {
    EXPECT_THROW(run_process({script.string()}), InputError);
  }
  std::filesystem::remove_all(dir);
}

TEST(Process, NoProgramIsTheCallersMistake) {
  EXPECT_THROW(run_process({}), std::invalid_argument);
}

TEST(Process, ASignalIsReportedAsTheShellDoes) {
  const ProcessResult result = run_process({"sh", "-c", "kill -TERM $$"});
  EXPECT_EQ(result.status, -1);
  EXPECT_EQ(result.signal, SIGTERM);
  EXPECT_EQ(result.shell_status(), 128 + SIGTERM);
}

TEST(Process, CancelKillsTheChildAndReturnsWithWhatItSaid) {
  int asked = 0;
  const auto start = std::chrono::steady_clock::now();
  const ProcessResult result = run_process({"sh", "-c", "echo started; exec sleep 60"}, [&] {
    return ++asked > 2;  // the third look (after about 200 ms)
  });
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_TRUE(result.cancelled);
  EXPECT_EQ(result.signal, SIGKILL);
  EXPECT_EQ(result.out, "started\n");
  EXPECT_LT(seconds, 30.0);  // not the minute of the sleep (a bound, not a timing)
}

TEST(Process, PipesBothWaysAndFilesAsStreams) {
  const auto dir = testing::fresh_directory("process_streams");
  {
    ChildProcess child({"tr", "a-z", "A-Z"}, ChildStream::pipe(), ChildStream::pipe());
    ASSERT_GE(child.input(), 0);
    ASSERT_GE(child.output(), 0);
    EXPECT_EQ(child.error(), -1);
    const std::string text = "shout this\n";
    ASSERT_EQ(::write(child.input(), text.data(), text.size()), static_cast<ssize_t>(text.size()));
    child.close_input();
    EXPECT_EQ(child.input(), -1);
    std::string out;
    std::string err;
    EXPECT_FALSE(child.collect(out, err));
    EXPECT_EQ(out, "SHOUT THIS\n");
    EXPECT_EQ(child.wait().status, 0);
    EXPECT_EQ(child.wait().status, 0);  // waited once; the same answer again
  }
  std::ofstream(dir / "in.txt") << "from a file\n";
  ChildProcess child({"sh", "-c", "cat; echo to-err >&2"}, ChildStream::file(dir / "in.txt"),
                     ChildStream::file(dir / "out.txt"), ChildStream::file(dir / "err.txt"));
  EXPECT_EQ(child.wait().status, 0);
  EXPECT_EQ(testing::read_text(dir / "out.txt"), "from a file\n");
  EXPECT_EQ(testing::read_text(dir / "err.txt"), "to-err\n");
  EXPECT_THAT(
      [&] { ChildProcess({"cat"}, ChildStream::file(dir / "missing.txt")); },
      ThrowsMessage<InputError>(HasSubstr("cannot start cat: cannot open '" +
                                          (dir / "missing.txt").string() + "': No such file")));
  std::filesystem::remove_all(dir);
}

TEST(Process, AChildProcessGoneOutOfScopeIsKilledAndReaped) {
  pid_t pid = -1;
  {
    ChildProcess child({"sleep", "60"});
    pid = child.pid();
    ASSERT_GT(pid, 0);
    EXPECT_TRUE(exists(pid));
  }
  EXPECT_FALSE(exists(pid));  // neither running nor left a zombie
  ChildProcess moved_from({"sleep", "60"});
  ChildProcess owner = std::move(moved_from);
  EXPECT_EQ(moved_from.pid(), -1);
  EXPECT_EQ(owner.kill().signal, SIGKILL);
}

TEST(Process, RunAttachedGivesTheExit) {
  EXPECT_EQ(run_attached({"sh", "-c", "exit 7"}).status, 7);
  EXPECT_EQ(run_attached({"true"}).shell_status(), 0);
}

TEST(Process, LastLinesForOneLineErrors) {
  EXPECT_EQ(last_lines(""), "no message on stderr");
  EXPECT_EQ(last_lines("\n\n"), "no message on stderr");
  EXPECT_EQ(last_lines("only\n"), "only");
  EXPECT_EQ(last_lines("a\nlibx264: width not divisible by 2\r\nError initializing\n"),
            "libx264: width not divisible by 2 / Error initializing");
  EXPECT_EQ(last_line("first\nsecond  \n\n"), "second");
  EXPECT_EQ(last_line("one"), "one");
  EXPECT_EQ(last_line("\n"), "");
  EXPECT_EQ(last_line(""), "");
}

/// The entries of an environment, which must end with a null (a failure if it does not).
std::vector<std::string> entries_of(const std::vector<char*>& environment) {
  if (environment.empty() || environment.back() != nullptr) {
    ADD_FAILURE() << "the environment does not end with a null";
    return {};
  }
  std::vector<std::string> out;
  for (const char* entry : environment) {
    if (entry != nullptr) out.emplace_back(entry);
  }
  return out;
}

TEST(Process, EnvironmentWithHugePagesAddsTheTunableUnlessOneIsSet) {
  const char* before = std::getenv("GLIBC_TUNABLES");
  const std::string saved = before != nullptr ? before : "";
  ::setenv("TUMBLE_TEST_MARK", "kept", 1);

  ::unsetenv("GLIBC_TUNABLES");
  std::vector<std::string> entries = entries_of(environment_with_huge_pages());
  EXPECT_THAT(entries, ::testing::Contains("TUMBLE_TEST_MARK=kept"));
  EXPECT_EQ(std::count(entries.begin(), entries.end(), "GLIBC_TUNABLES=glibc.malloc.hugetlb=1"), 1);

  // A tunable the user set is theirs: left as it is, none added.
  ::setenv("GLIBC_TUNABLES", "glibc.malloc.check=0", 1);
  entries = entries_of(environment_with_huge_pages());
  EXPECT_THAT(entries, ::testing::Contains("GLIBC_TUNABLES=glibc.malloc.check=0"));
  EXPECT_EQ(std::count_if(entries.begin(), entries.end(),
                          [](const std::string& e) { return e.starts_with("GLIBC_TUNABLES="); }),
            1);

  if (before != nullptr) {
    ::setenv("GLIBC_TUNABLES", saved.c_str(), 1);
  } else {
    ::unsetenv("GLIBC_TUNABLES");
  }
  ::unsetenv("TUMBLE_TEST_MARK");
}

}  // namespace
}  // namespace tumble
