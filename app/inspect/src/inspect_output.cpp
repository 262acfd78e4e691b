// `tumble inspect`'s output: the table, JSON, JSON lines and inertial elements, per file.
#include "app/inspect/inspect_output.hpp"

#include <ostream>

#include "app/robot/inertial_xml.hpp"
#include "app/scene/mesh_inspection.hpp"
#include "app/support/exit_status.hpp"

namespace tumble::app {
namespace {

/// The robot format of an XML output format.
robot::RobotFormat robot_format(InspectFormat format) {
  switch (format) {
    case InspectFormat::sdf:
      return robot::RobotFormat::sdf;
    case InspectFormat::mjcf:
      return robot::RobotFormat::mjcf;
    default:
      return robot::RobotFormat::urdf;
  }
}

/// The error without the "FILE: " its message starts with.
std::string without_file(const std::string& error, const std::string& file) {
  const std::string prefix = file + ": ";
  return error.compare(0, prefix.size(), prefix) == 0 ? error.substr(prefix.size()) : error;
}

}  // namespace

std::string xml_comment_text(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '-' && !out.empty() && out.back() == '-') out += ' ';
    out += c;
  }
  if (!out.empty() && out.back() == '-') out += ' ';
  return out;
}

InspectPrinter::InspectPrinter(const InspectOptions& options, std::ostream& out, std::ostream& err,
                               bool batch)
    : options_(options), out_(out), err_(err), batch_(batch) {}

void InspectPrinter::print(const std::filesystem::path& file, InspectOutcome outcome,
                           const nlohmann::json& extra) {
  if (outcome.failure) std::rethrow_exception(outcome.failure);
  if (!outcome.report) {
    ++refused_;
    err_ << "tumble inspect: error: " << outcome.error << "\n";
    if (options_.format == InspectFormat::jsonl) {
      nlohmann::json line = {{"file", file.string()},
                             {"error", without_file(outcome.error, file.string())}};
      if (extra.is_object()) line.update(extra);
      out_ << line.dump() << "\n" << std::flush;
    }
    return;
  }
  ++(outcome.report->warnings.empty() ? ok_ : warned_);
  print_report(*outcome.report, extra);
}

void InspectPrinter::print_report(const engine::MeshReport& report, const nlohmann::json& extra) {
  switch (options_.format) {
    case InspectFormat::text:
      out_ << (ok_ + warned_ > 1 ? "\n" : "") << format_report(report);
      return;
    case InspectFormat::json:
      json_.push_back(report_to_json(report));
      return;
    case InspectFormat::jsonl: {
      nlohmann::json line = report_to_json(report);
      if (extra.is_object()) line.update(extra);
      out_ << line.dump() << "\n" << std::flush;
      return;
    }
    default:
      break;
  }
  // The XML formats: the element, headed by the file's name in a batch; the warnings, which
  // the element has no place for, on stderr.
  if (batch_) out_ << "<!-- " << xml_comment_text(report.source) << " -->\n";
  out_ << robot::inertial_element(robot_format(options_.format), report.mass_properties,
                                  options_.frame)
       << "\n";
  for (const std::string& warning : report.warnings) {
    err_ << "tumble inspect: warning: " << report.source << ": " << warning << "\n";
  }
}

int InspectPrinter::finish() {
  const std::size_t total = ok_ + warned_ + refused_;
  if (options_.format == InspectFormat::json && refused_ == 0) {
    if (json_.size() == 1 && !batch_) {
      out_ << json_.front().dump(2) << "\n";
    } else {
      out_ << nlohmann::json(json_).dump(2) << "\n";
    }
  }
  if (total > 1) {
    err_ << "tumble inspect: inspected " << total << " files: " << ok_ << " ok, " << warned_
         << " with warnings, " << refused_ << " refused\n";
  }
  out_.flush();
  return refused_ == 0 ? kExitDone : kExitInputError;
}

}  // namespace tumble::app
