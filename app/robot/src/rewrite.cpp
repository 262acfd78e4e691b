// A robot file with only its inertial elements changed.
#include "app/robot/rewrite.hpp"

#include <algorithm>
#include <stdexcept>

#include "base/errors.hpp"
#include "element_bytes.hpp"

namespace tumble::app::robot {
namespace {

struct Edit {
  ByteRange range;  // replaced bytes (empty for an insertion)
  std::string text;
};

/// `element` with the file's line break: "\r\n" in a file whose first line ends so, so that
/// a rewritten CRLF file does not mix line endings.
std::string with_line_breaks(const std::string& text, std::string element) {
  const std::size_t first = text.find('\n');
  if (first == std::string::npos || first == 0 || text[first - 1] != '\r') return element;
  std::string out;
  out.reserve(element.size() + element.size() / 16);
  for (const char c : element) {
    if (c == '\n') out += '\r';
    out += c;
  }
  return out;
}

/// The unit of indentation the file uses: a tab if the link's children are indented by tabs.
std::string indent_step(const Link& link) {
  return link.child_indent.find('\t') != std::string::npos ? "\t" : "  ";
}

/// `text` as an XML comment and a line break to `indent`; "--" may not appear inside one.
std::string comment_line(std::string text, const std::string& indent) {
  for (std::size_t at = text.find("--"); at != std::string::npos; at = text.find("--", at)) {
    text.replace(at, 2, "- -");
  }
  return "<!-- " + text + " -->\n" + indent;
}

}  // namespace

std::string rewritten_text(const Robot& robot,
                           const std::vector<std::optional<engine::MassProperties>>& inertials,
                           InertialFrame frame, const std::vector<std::string>& comments) {
  if (inertials.size() != robot.links.size() ||
      (!comments.empty() && comments.size() != robot.links.size())) {
    throw std::invalid_argument("rewritten_text: one inertial per link expected");
  }
  std::vector<Edit> edits;
  for (std::size_t i = 0; i < robot.links.size(); ++i) {
    if (!inertials[i]) continue;
    const Link& link = robot.links[i];
    const std::string step = indent_step(link);
    if (link.inertial_bytes) {
      const std::string indent = line_indent(robot.text, link.inertial_bytes->begin);
      edits.push_back({*link.inertial_bytes,
                       (comments.empty() ? "" : comment_line(comments[i], indent)) +
                           inertial_element(robot.format, *inertials[i], frame, indent, step)});
    } else if (link.insert_at) {
      const std::string& indent = link.child_indent;
      edits.push_back({{*link.insert_at, *link.insert_at},
                       "\n" + indent + (comments.empty() ? "" : comment_line(comments[i], indent)) +
                           inertial_element(robot.format, *inertials[i], frame, indent, step)});
    } else {
      throw InputError(robot.file.string() + ": link '" + link.name +
                       "': has no place for an inertial element (it is a self-closing tag)");
    }
  }
  for (Edit& edit : edits) edit.text = with_line_breaks(robot.text, std::move(edit.text));
  std::sort(edits.begin(), edits.end(),
            [](const Edit& a, const Edit& b) { return a.range.begin < b.range.begin; });
  std::string out;
  out.reserve(robot.text.size() + 512 * edits.size());
  std::size_t at = 0;
  for (const Edit& edit : edits) {
    if (edit.range.begin < at) throw std::logic_error("rewritten_text: overlapping inertials");
    out.append(robot.text, at, edit.range.begin - at);
    out += edit.text;
    at = edit.range.end;
  }
  out.append(robot.text, at, std::string::npos);
  return out;
}

}  // namespace tumble::app::robot
