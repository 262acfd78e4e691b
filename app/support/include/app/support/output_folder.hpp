#pragma once
/// @file Output folders written whole or not at all (`tumble bench -o DIR`, `tumble stability
/// -o DIR`): everything goes to .DIR.tmp-PID, which takes DIR's place only when finished.

#include <filesystem>
#include <string>

#include "app/support/file_write.hpp"

namespace tumble::app {

/// What marks a folder as an earlier output of a command, which may be replaced: a report file
/// whose first line starts with `title`, beside a data file.
struct OutputFolderKind {
  std::string command;  ///< the command, for messages ("bench")
  std::string report;   ///< "report.md"
  std::string title;    ///< "# tumble bench"
  std::string data;     ///< "results.csv"
};

/// Checks that `dir` may be written, and creates and returns .DIR.tmp-PID. `dir` may be absent
/// (its parent must exist), empty, or an earlier output of this kind holding nothing but its
/// reports, CSVs and plots (.md, .csv, .png, .svg files); anything else is refused, since
/// replacing it would delete the user's files. A symbolic link to a folder is written through
/// (the link stays). Temporaries of dead processes (`.DIR.tmp-PID` of a killed run) are removed
/// first. Throws tumble::InputError naming -o and the folder.
std::filesystem::path start_output_folder(const std::filesystem::path& dir,
                                          const OutputFolderKind& kind);

/// Moves the finished .DIR.tmp-PID into place, replacing an earlier DIR (moved aside first and
/// removed last). Throws tumble::InputError naming -o and the folder.
void finish_output_folder(const std::filesystem::path& tmp, const std::filesystem::path& dir);

/// The error of a failed write into the temporary folder `tmp` of `dir`, naming the file by the
/// name it was to have: "cannot write 'DIR/NAME': REASON; nothing written to 'DIR'" (the
/// temporary folder is removed by the caller). A file outside `tmp` keeps its own name.
WriteError output_write_error(const WriteError& error, const std::filesystem::path& tmp,
                              const std::filesystem::path& dir);

}  // namespace tumble::app
