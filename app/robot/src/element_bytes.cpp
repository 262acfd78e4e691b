// Where an element is in an XML file's bytes.
#include "element_bytes.hpp"

#include <stdexcept>

namespace tumble::app::robot {
namespace {

[[noreturn]] void malformed(std::size_t at) {
  throw std::logic_error("XML element scan: malformed markup at byte " + std::to_string(at));
}

/// The offset just past the '>' of the tag starting at `at` ('<'), skipping quoted values.
std::size_t tag_end(const std::string& text, std::size_t at) {
  char quote = 0;
  for (std::size_t i = at + 1; i < text.size(); ++i) {
    const char c = text[i];
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '>') {
      return i + 1;
    }
  }
  malformed(at);
}

/// The offset just past a construct that starts with `open` at `at` and ends with `close`.
std::size_t past(const std::string& text, std::size_t at, const char* close) {
  const std::size_t end = text.find(close, at);
  if (end == std::string::npos) malformed(at);
  return end + std::char_traits<char>::length(close);
}

}  // namespace

ElementBytes element_bytes(const std::string& text, std::size_t name_offset) {
  if (name_offset == 0 || name_offset > text.size() || text[name_offset - 1] != '<') {
    malformed(name_offset);
  }
  ElementBytes out;
  out.whole.begin = name_offset - 1;
  std::size_t at = tag_end(text, out.whole.begin);
  if (text[at - 2] == '/') {
    out.whole.end = at;
    return out;
  }
  out.content_begin = at;
  int depth = 1;
  while (depth > 0) {
    at = text.find('<', at);
    if (at == std::string::npos) malformed(out.whole.begin);
    if (text.compare(at, 4, "<!--") == 0) {
      at = past(text, at, "-->");
    } else if (text.compare(at, 9, "<![CDATA[") == 0) {
      at = past(text, at, "]]>");
    } else if (text.compare(at, 2, "<?") == 0) {
      at = past(text, at, "?>");
    } else if (text.compare(at, 2, "<!") == 0) {
      at = tag_end(text, at);
    } else if (text.compare(at, 2, "</") == 0) {
      at = tag_end(text, at);
      --depth;
    } else {
      at = tag_end(text, at);
      if (text[at - 2] != '/') ++depth;
    }
  }
  out.whole.end = at;
  return out;
}

std::string line_indent(const std::string& text, std::size_t element_begin) {
  std::size_t start = element_begin;
  while (start > 0 && (text[start - 1] == ' ' || text[start - 1] == '\t')) --start;
  if (start > 0 && text[start - 1] != '\n') return "";
  return text.substr(start, element_begin - start);
}

std::string child_indent(const std::string& text, const ElementBytes& element,
                         const std::string& step) {
  if (element.content_begin) {
    std::size_t at = *element.content_begin;
    while (at < text.size() &&
           (text[at] == ' ' || text[at] == '\t' || text[at] == '\n' || text[at] == '\r')) {
      ++at;
    }
    if (at < element.whole.end && text[at] == '<' && text.compare(at, 2, "</") != 0 &&
        at > *element.content_begin) {
      const std::string indent = line_indent(text, at);
      if (!indent.empty() || text[at - 1] == '\n') return indent;
    }
  }
  return line_indent(text, element.whole.begin) + step;
}

}  // namespace tumble::app::robot
