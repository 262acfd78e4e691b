#pragma once
/// @file What `tumble inspect` prints for each file, in each format, and the batch's summary.

#include <cstddef>
#include <exception>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/inspect/inspect_options.hpp"
#include "engine/mass/mesh_analysis.hpp"

namespace tumble::app {

/// How one file's inspection ended: a report, a one-line error (bad input), or a failure that
/// is a bug in tumble (rethrown where it is printed).
struct InspectOutcome {
  std::optional<engine::MeshReport> report;
  std::string error;
  std::exception_ptr failure;
};

/// Prints outcomes in the order they are given, in the options' format, and counts them.
class InspectPrinter {
 public:
  /// `batch`: the reports form a batch (several files, a directory or a list): the JSON
  /// report is then an array and each XML element is headed by a comment naming its file.
  InspectPrinter(const InspectOptions& options, std::ostream& out, std::ostream& err, bool batch);

  /// Prints `outcome` of `file` (the report on stdout, an error line on stderr; jsonl: an
  /// error object too). Rethrows a failure. `extra` (an object) is merged into the jsonl
  /// object (a part's "item").
  void print(const std::filesystem::path& file, InspectOutcome outcome,
             const nlohmann::json& extra = nullptr);

  /// Prints what waits for the end (the json document, when every file succeeded) and, for
  /// more than one file, the summary line on stderr. Returns the exit status.
  int finish();

 private:
  void print_report(const engine::MeshReport& report, const nlohmann::json& extra);

  const InspectOptions& options_;
  std::ostream& out_;
  std::ostream& err_;
  bool batch_;
  std::size_t ok_ = 0;
  std::size_t warned_ = 0;
  std::size_t refused_ = 0;
  std::vector<nlohmann::json> json_;  ///< the json format's reports, printed by finish()
};

/// `text` made safe inside an XML comment: no "--" in it and no '-' at its end.
std::string xml_comment_text(const std::string& text);

}  // namespace tumble::app
