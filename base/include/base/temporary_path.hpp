#pragma once
/// @file The one naming rule for outputs written whole or not at all.

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <filesystem>
#include <string>
#include <string_view>

namespace tumble {

/// The name a file or folder `target` is written under before it is renamed into place:
/// `.NAME.TAG-PID` beside it, so the rename stays on one filesystem (atomic), the half-written
/// output is hidden, and no two tumble processes share one. `TAG` is "tmp" for what is being
/// written, and another word for other stages (the output folder keeps the old one as "old").
/// A trailing '/' on `target` (a folder) is ignored.
inline std::filesystem::path temporary_sibling(const std::filesystem::path& target,
                                               std::string_view tag = "tmp") {
  std::filesystem::path clean = target;
  if (!clean.has_filename()) clean = clean.parent_path();
  const std::filesystem::path parent = clean.parent_path();
  const std::string name =
      "." + clean.filename().string() + "." + std::string(tag) + "-" + std::to_string(::getpid());
  return parent.empty() ? std::filesystem::path(name) : parent / name;
}

/// Removes what earlier runs for `target` left under temporary names (`.NAME.TAG-PID`, also
/// `.NAME.TAG-PID-old`) when process PID is gone: the leftovers of a run killed by SIGKILL or
/// a power cut. Those of a live process (another run, now) are left alone; errors are ignored.
inline void remove_stale_temporaries(const std::filesystem::path& target) {
  std::filesystem::path clean = target;
  if (!clean.has_filename()) clean = clean.parent_path();
  const std::filesystem::path parent = clean.parent_path().empty() ? "." : clean.parent_path();
  const std::string prefix = "." + clean.filename().string() + ".";
  std::error_code error;
  std::filesystem::directory_iterator entry(parent, error);
  for (; !error && entry != std::filesystem::directory_iterator(); entry.increment(error)) {
    const std::string name = entry->path().filename().string();
    if (!name.starts_with(prefix)) continue;
    const std::size_t dash = name.find('-', prefix.size());
    if (dash == std::string::npos) continue;
    const std::string tag = name.substr(prefix.size(), dash - prefix.size());
    if (tag != "tmp" && tag != "old") continue;
    std::string_view digits = std::string_view(name).substr(dash + 1);
    if (digits.ends_with("-old")) digits.remove_suffix(4);
    long pid = 0;
    const auto parsed = std::from_chars(digits.data(), digits.data() + digits.size(), pid);
    if (parsed.ec != std::errc() || parsed.ptr != digits.data() + digits.size() || pid <= 0) {
      continue;
    }
    if (pid == ::getpid() || ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
    std::error_code ignored;
    std::filesystem::remove_all(entry->path(), ignored);
  }
}

}  // namespace tumble
