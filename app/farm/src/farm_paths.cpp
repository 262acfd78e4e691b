// Whether a farmed job's paths exist and which filesystems they are on.
#include "app/farm/farm_paths.hpp"

#include <sys/statfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <iomanip>
#include <sstream>

#include "base/errors.hpp"

namespace tumble::app {

namespace {

struct KnownFilesystem {
  std::uint32_t magic;
  const char* name;
  Sharing sharing;
};

// statfs(2) f_type values (linux/magic.h, and the vendors' own for Lustre, GPFS, BeeGFS,
// PanFS).
constexpr KnownFilesystem kFilesystems[] = {
    {0x6969, "nfs", Sharing::kNetwork},          {0x517B, "smb", Sharing::kNetwork},
    {0xFF534D42, "cifs", Sharing::kNetwork},     {0xFE534D42, "smb2", Sharing::kNetwork},
    {0x0BD00BD0, "lustre", Sharing::kNetwork},   {0x47504653, "gpfs", Sharing::kNetwork},
    {0x19830326, "beegfs", Sharing::kNetwork},   {0x00C36400, "ceph", Sharing::kNetwork},
    {0x5346414F, "afs", Sharing::kNetwork},      {0x6B414653, "afs", Sharing::kNetwork},
    {0x73757245, "coda", Sharing::kNetwork},     {0x7461636F, "ocfs2", Sharing::kNetwork},
    {0x01161970, "gfs2", Sharing::kNetwork},     {0xAAD7AAEA, "panfs", Sharing::kNetwork},
    {0x20030528, "orangefs", Sharing::kNetwork}, {0x564C, "ncp", Sharing::kNetwork},
    {0x65735546, "fuse", Sharing::kUnknown},     {0x01021997, "9p", Sharing::kUnknown},
    {0xEF53, "ext4", Sharing::kLocal},           {0x58465342, "xfs", Sharing::kLocal},
    {0x9123683E, "btrfs", Sharing::kLocal},      {0x01021994, "tmpfs", Sharing::kLocal},
    {0x794C7630, "overlay", Sharing::kLocal},    {0x858458F6, "ramfs", Sharing::kLocal},
    {0x2FC12FC1, "zfs", Sharing::kLocal},        {0xF2F52010, "f2fs", Sharing::kLocal},
    {0x73717368, "squashfs", Sharing::kLocal},   {0x9660, "iso9660", Sharing::kLocal},
    {0x4D44, "vfat", Sharing::kLocal},           {0x2011BAB0, "exfat", Sharing::kLocal},
    {0x5346544E, "ntfs", Sharing::kLocal},       {0x52654973, "reiserfs", Sharing::kLocal},
    {0x3153464A, "jfs", Sharing::kLocal},        {0xCA451A4E, "bcachefs", Sharing::kLocal},
};

/// `path` or its nearest ancestor that exists (an output not written yet).
std::filesystem::path existing_ancestor(std::filesystem::path path) {
  std::error_code error;
  while (!std::filesystem::exists(path, error) && path.has_relative_path()) {
    path = path.parent_path();
  }
  return path;
}

std::string quoted(const std::filesystem::path& path) {
  return "'" + path.string() + "'";
}

void check_executable(const std::filesystem::path& file) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error) || ::access(file.c_str(), X_OK) != 0) {
    throw InputError("tumble executable " + quoted(file) + ": not an executable file" +
                     (file.filename() == "tumble-draw" ? " (it is built beside tumble)" : ""));
  }
}

}  // namespace

FilesystemKind filesystem_kind(std::int64_t f_type) {
  const auto magic = static_cast<std::uint32_t>(f_type);
  for (const KnownFilesystem& known : kFilesystems) {
    if (known.magic == magic) return {known.name, known.sharing};
  }
  std::ostringstream hex;
  hex << "0x" << std::hex << magic;
  return {hex.str(), Sharing::kUnknown};
}

FilesystemKind filesystem_of(const std::filesystem::path& path) {
  const std::filesystem::path existing = existing_ancestor(path);
  struct statfs info {};
  if (::statfs(existing.c_str(), &info) != 0) {
    throw InputError(quoted(existing) + ": cannot tell its filesystem: " + std::strerror(errno));
  }
  return filesystem_kind(static_cast<std::int64_t>(info.f_type));
}

JobPaths job_paths(const FarmJob& job, const std::filesystem::path& tumble,
                   const std::vector<std::filesystem::path>& extra_inputs) {
  JobPaths paths;
  paths.inputs = job.inputs;
  for (const auto& extra : extra_inputs) {
    bool known = false;
    for (const auto& input : paths.inputs) known = known || input == extra;
    if (!known) paths.inputs.push_back(extra);
  }
  paths.output_folder = job.output.parent_path();
  paths.executables.push_back(tumble);
  if (job.command == "render" || job.command == "compare") {
    paths.executables.push_back(tumble.parent_path() / "tumble-draw");
  }
  return paths;
}

void check_job_paths(const JobPaths& paths) {
  std::error_code error;
  for (const auto& input : paths.inputs) {
    if (!std::filesystem::exists(input, error)) {
      throw InputError("input " + quoted(input) + ": no such file or folder");
    }
  }
  if (!std::filesystem::is_directory(paths.output_folder, error)) {
    throw InputError("output folder " + quoted(paths.output_folder) + ": no such folder");
  }
  if (::access(paths.output_folder.c_str(), W_OK | X_OK) != 0) {
    throw InputError("output folder " + quoted(paths.output_folder) +
                     ": not writable: " + std::strerror(errno));
  }
  for (const auto& executable : paths.executables) check_executable(executable);
}

std::vector<std::string> sharing_notes(const JobPaths& paths, bool& local) {
  local = false;
  std::vector<std::string> notes;
  const auto note = [&](const std::filesystem::path& path, bool executable) {
    const FilesystemKind kind = filesystem_of(path);
    if (kind.sharing == Sharing::kNetwork) return;
    if (kind.sharing == Sharing::kUnknown) {
      notes.push_back(quoted(path) + " is on a " + kind.name +
                      " filesystem: tumble cannot tell whether workers on other machines see it");
    } else if (executable) {
      notes.push_back(quoted(path) + " is on a local filesystem (" + kind.name +
                      "): it must be installed at the same path on every worker");
    } else {
      local = true;
      notes.push_back(quoted(path) + " is on a local filesystem (" + kind.name +
                      "); workers on other machines will not see it");
    }
  };
  for (const auto& input : paths.inputs) note(input, false);
  note(paths.output_folder, false);
  for (const auto& executable : paths.executables) note(executable, true);
  return notes;
}

}  // namespace tumble::app
