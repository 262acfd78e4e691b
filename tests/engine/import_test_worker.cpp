// A worker program for the import worker's tests (import/import_worker_test.cpp): the same loop
// as tumble-import (engine/import/worker/worker_serve.hpp), with tasks that answer, crash, loop,
// allocate or fail on request, so that every way a worker can end is checked against the one-line
// refusal the parent gives.
#include <sys/resource.h>
#include <unistd.h>

#include <array>
#include <csignal>
#include <ctime>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/errors.hpp"
#include "worker_serve.hpp"

namespace {

using tumble::engine::detail::AnswerWriter;

double process_cpu_seconds() {
  timespec now{};
  ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

/// The test pattern of `count` bytes: byte i is (i * 7 + 3) mod 251.
void write_pattern(AnswerWriter& out, std::uint64_t count) {
  std::vector<unsigned char> bytes(count);
  for (std::uint64_t i = 0; i < count; ++i)
    bytes[i] = static_cast<unsigned char>((i * 7 + 3) % 251);
  out.bytes(bytes.data(), bytes.size());
}

/// request[0] says what to do; the answer of "echo" is every text of the request, then
/// request[1] bytes of the pattern.
void test_task(const std::vector<std::string>& request, AnswerWriter& out) {
  const std::string& what = request.at(0);
  if (what == "spin") {  // use request[1] seconds of CPU time, then answer
    const double until = process_cpu_seconds() + std::stod(request.at(1));
    volatile std::uint64_t spin = 0;
    while (process_cpu_seconds() < until) spin = spin + 1;
  } else if (what == "loop") {
    volatile std::uint64_t spin = 0;
    while (true) spin = spin + 1;
  } else if (what == "crash") {
    std::raise(SIGSEGV);
  } else if (what == "kill") {
    std::raise(SIGKILL);
  } else if (what == "exit") {
    ::_exit(9);
  } else if (what == "error") {
    throw tumble::InputError(request.at(1));
  } else if (what == "throw") {
    throw std::runtime_error(request.at(1));
  } else if (what == "allocate") {
    std::vector<char> huge(std::size_t{1} << 30, 'x');  // 1 GiB against a 256 MiB limit
    out.bytes(&huge[12345], 1);
    return;
  } else if (what == "no-space") {  // a file size limit, as `prlimit --fsize` sets
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit small{4096, 4096};
    ::setrlimit(RLIMIT_FSIZE, &small);
    write_pattern(out, 100000);
    return;
  } else if (what == "descriptors") {  // the descriptors it holds, as /proc lists them
    for (const auto& entry : std::filesystem::directory_iterator("/proc/self/fd")) {
      out.text(entry.path().filename().string());
    }
    return;
  }
  for (const std::string& text : request) out.text(text);
  if (request.size() > 1) write_pattern(out, std::stoull(request[1]));
}

}  // namespace

int main(int argc, char** argv) {
  using namespace tumble::engine::detail;
  const std::array tasks{WorkerTaskEntry{"test", test_task}};
  return serve_import_requests(argc, argv, tasks);
}
