#pragma once
/// @file The one naming rule for outputs written whole or not at all.

#include <unistd.h>

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

}  // namespace tumble
