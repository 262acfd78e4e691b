// Trajectory CSV files, written under a temporary name and renamed into place.
#include "app/support/csv_writer.hpp"

#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <system_error>

#include "base/errors.hpp"
#include "base/file_checks.hpp"
#include "base/temporary_path.hpp"

namespace tumble::app {
namespace {

constexpr std::size_t kFlushBytes = 1 << 20;

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path path, const std::vector<std::filesystem::path>& inputs)
    : path_(std::move(path)) {
  // Only a new name or a regular file (through a link: its target) is ever replaced.
  destination_ = checked_output(path_, inputs);
  temporary_ = temporary_sibling(destination_);
  remove_stale_temporaries(destination_);
  file_ = std::fopen(temporary_.c_str(), "wb");
  if (file_ == nullptr) {
    throw tumble::InputError("cannot write '" + path_.string() + "': " + std::strerror(errno));
  }
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  if (file_ != nullptr) std::fclose(file_);
  std::error_code ignored;
  std::filesystem::remove(temporary_, ignored);
}

void AtomicFile::fail(const std::string& what) {
  const std::string reason = std::strerror(errno);
  if (file_ != nullptr) std::fclose(file_);
  file_ = nullptr;
  std::error_code ignored;
  std::filesystem::remove(temporary_, ignored);
  throw tumble::InputError("cannot write '" + path_.string() + "': " + what + ": " + reason);
}

void AtomicFile::write(std::string_view bytes) {
  if (file_ == nullptr) fail("file is closed");
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) fail("write failed");
}

void AtomicFile::commit() {
  if (file_ == nullptr) fail("file is closed");
  if (std::fflush(file_) != 0) fail("write failed");
  const int closed = std::fclose(file_);
  file_ = nullptr;
  if (closed != 0) fail("close failed");
  std::error_code error;
  std::filesystem::rename(temporary_, destination_, error);
  if (error) {
    std::filesystem::remove(temporary_, error);
    throw tumble::InputError("cannot write '" + path_.string() + "': rename failed");
  }
  committed_ = true;
}

void append_number(std::string& out, double value) {
  char buffer[32];
  const auto result =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, 17);
  out.append(buffer, result.ptr);
}

void append_csv_field(std::string& out, std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) {
    out.append(text);
    return;
  }
  out += '"';
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
}

TrajectoryCsv::TrajectoryCsv(std::filesystem::path path,
                             const std::vector<std::filesystem::path>& inputs)
    : file_(std::move(path), inputs) {
  buffer_.reserve(kFlushBytes + 4096);
  buffer_.append(kTrajectoryHeader).append("\n");
}

void TrajectoryCsv::write_rows(double t, const std::vector<engine::BodyModel>& bodies,
                               const std::vector<engine::BodyState>& states) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const engine::BodyModel& body = bodies[i];
    const engine::BodyState& state = states[i];
    const Eigen::Quaterniond q = engine::body_orientation(body, state);
    const Eigen::Vector3d omega = engine::angular_velocity(body, state);
    const double values[] = {state.position.x(),
                             state.position.y(),
                             state.position.z(),
                             q.w(),
                             q.x(),
                             q.y(),
                             q.z(),
                             state.velocity.x(),
                             state.velocity.y(),
                             state.velocity.z(),
                             omega.x(),
                             omega.y(),
                             omega.z(),
                             state.angular_momentum.x(),
                             state.angular_momentum.y(),
                             state.angular_momentum.z(),
                             engine::energy(body, state)};
    append_number(buffer_, t);
    buffer_ += ',';
    append_csv_field(buffer_, body.name);
    for (double value : values) {
      buffer_ += ',';
      append_number(buffer_, value);
    }
    buffer_ += '\n';
    ++rows_;
  }
  if (buffer_.size() >= kFlushBytes) flush();
}

void TrajectoryCsv::flush() {
  file_.write(buffer_);
  buffer_.clear();
}

void TrajectoryCsv::commit() {
  flush();
  file_.commit();
}

}  // namespace tumble::app
