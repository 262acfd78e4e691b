// Header counts against file sizes (see declared_counts.hpp for why and what is checked).
#include "declared_counts.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <string_view>
#include <vector>

#include "base/errors.hpp"
#include "input_file.hpp"

namespace tumble::engine::detail {
namespace {

constexpr std::size_t kHeaderLimit = 64 * 1024;  // headers longer than this are left to assimp
constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();

std::uint64_t saturating_mul(std::uint64_t a, std::uint64_t b) {
  return (b != 0 && a > kMax / b) ? kMax : a * b;
}
std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) {
  return a > kMax - b ? kMax : a + b;
}

/// The file's first bytes (up to kHeaderLimit).
std::string read_head(const std::filesystem::path& file) {
  const CFile stream(std::fopen(file.string().c_str(), "rb"));
  if (!stream) fail(file, "cannot be opened for reading");
  std::string head(kHeaderLimit, '\0');
  head.resize(std::fread(head.data(), 1, head.size(), stream.get()));
  return head;
}

/// Calls line(first, size) for every line of the file from byte `offset` on (without its
/// newline; a line longer than the buffer arrives in pieces, each taken for a line: the
/// counts below only ever need lower bounds) until it returns false.
template <typename Line>
void for_each_line(const std::filesystem::path& file, std::uint64_t offset, const Line& line) {
  const CFile stream(std::fopen(file.string().c_str(), "rb"));
  if (!stream || std::fseek(stream.get(), static_cast<long>(offset), SEEK_SET) != 0) {
    fail(file, "cannot be opened for reading");
  }
  constexpr std::size_t kChunk = 1 << 20;
  const auto buffer = std::make_unique<char[]>(kChunk);
  std::size_t kept = 0;  // bytes of an unfinished line at the buffer's start
  while (true) {
    const std::size_t got = std::fread(buffer.get() + kept, 1, kChunk - kept, stream.get());
    const std::size_t end = kept + got;
    const char* first = buffer.get();
    const char* const last = buffer.get() + end;
    while (const char* newline = static_cast<const char*>(std::memchr(first, '\n', last - first))) {
      if (!line(first, static_cast<std::size_t>(newline - first))) return;
      first = newline + 1;
    }
    kept = static_cast<std::size_t>(last - first);
    if (got == 0 || kept == kChunk) {  // the end, or a line longer than the buffer
      if (kept > 0 && !line(first, kept)) return;
      if (got == 0) return;
      kept = 0;
      continue;
    }
    std::memmove(buffer.get(), first, kept);
  }
}

/// The first character of a line that is not a space, or 0 for a blank line.
char first_visible(const char* text, std::size_t size) {
  for (std::size_t i = 0; i < size; ++i) {
    if (!std::isspace(static_cast<unsigned char>(text[i]))) return text[i];
  }
  return 0;
}

/// How many lines from `offset` hold something other than blanks and `#` comments, counted
/// up to `needed` (the scan stops there).
std::uint64_t data_lines(const std::filesystem::path& file, std::uint64_t offset,
                         std::uint64_t needed) {
  std::uint64_t lines = 0;
  for_each_line(file, offset, [&](const char* text, std::size_t size) {
    const char c = first_visible(text, size);
    if (c != 0 && c != '#') ++lines;
    return lines < needed;
  });
  return lines;
}

/// Refuses a header whose elements need more than the file has after it.
void require(const std::filesystem::path& file, const std::string& format,
             const std::string& declared, std::uint64_t needed, std::uint64_t available,
             const char* unit) {
  if (needed <= available) return;
  fail(file, "the " + format + " header declares " + declared + ": at least " +
                 (needed == kMax ? std::string("2^64") : std::to_string(needed)) + " " + unit +
                 " after the header, but the file has " + std::to_string(available) +
                 " (truncated, or the counts are wrong)");
}

/// Reads whitespace-separated tokens, skipping `#` comments to the end of their line.
class Tokens {
 public:
  explicit Tokens(std::string_view text) : text_(text) {}
  std::string_view next() {
    while (pos_ < text_.size()) {
      if (text_[pos_] == '#') {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
      } else if (std::isspace(static_cast<unsigned char>(text_[pos_]))) {
        ++pos_;
      } else {
        break;
      }
    }
    const std::size_t begin = pos_;
    while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    return text_.substr(begin, pos_ - begin);
  }
  /// The offset just past the line of the last token.
  std::size_t end_of_line() const {
    const std::size_t newline = text_.find('\n', pos_);
    return newline == std::string_view::npos ? text_.size() : newline + 1;
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
};

/// A decimal count (saturating), or nothing when `token` is not one.
std::optional<std::uint64_t> count_of(std::string_view token) {
  if (token.empty() || token.size() > 40) return std::nullopt;
  std::uint64_t value = 0;
  for (const char c : token) {
    if (c < '0' || c > '9') return std::nullopt;
    value = saturating_add(saturating_mul(value, 10), static_cast<std::uint64_t>(c - '0'));
  }
  return value;
}

std::optional<DeclaredFaces> check_off(const std::filesystem::path& file, std::uint64_t size) {
  const std::string head = read_head(file);
  Tokens tokens(head);
  const std::string_view keyword = tokens.next();
  if (!keyword.ends_with("OFF") && !keyword.ends_with("off")) return {};
  // 4OFF has four coordinates a vertex; nOFF (a lower-case n) states the dimension first.
  std::uint64_t dimension = keyword.starts_with("4") ? 4 : 3;
  if (keyword.find('n') != std::string_view::npos) {
    const auto stated = count_of(tokens.next());
    if (!stated) return {};
    dimension = std::max<std::uint64_t>(*stated, 1);
  }
  const std::string_view token = tokens.next();
  if (token == "BINARY") return {};  // binary OFF: left to assimp
  const auto vertices = count_of(token);
  const auto faces = count_of(tokens.next());
  if (!vertices || !faces) return {};
  const std::uint64_t offset = tokens.end_of_line();
  const std::string declared =
      std::to_string(*vertices) + " vertices and " + std::to_string(*faces) + " faces";
  // A vertex is `dimension` numbers of at least a digit and a separator, a face at least its
  // corner count and a newline.
  const std::uint64_t bytes =
      saturating_add(saturating_mul(*vertices, 2 * dimension), saturating_mul(*faces, 2));
  require(file, "OFF", declared, bytes, size - offset + 1, "bytes");
  const std::uint64_t lines = saturating_add(*vertices, *faces);
  require(file, "OFF", declared, lines, data_lines(file, offset, lines), "lines");
  return DeclaredFaces{*faces, "OFF header"};
}

/// One element of a PLY header: its count and the bytes (binary) or numbers (ASCII) each
/// instance takes at least.
struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::uint64_t min_bytes = 0;
  std::uint64_t properties = 0;
};

/// The size in bytes of a PLY scalar type, or 0 when it is not one.
std::uint64_t ply_type_bytes(std::string_view type) {
  for (const auto& [name, bytes] :
       std::array<std::pair<std::string_view, std::uint64_t>, 16>{{{"char", 1},
                                                                   {"uchar", 1},
                                                                   {"int8", 1},
                                                                   {"uint8", 1},
                                                                   {"short", 2},
                                                                   {"ushort", 2},
                                                                   {"int16", 2},
                                                                   {"uint16", 2},
                                                                   {"int", 4},
                                                                   {"uint", 4},
                                                                   {"int32", 4},
                                                                   {"uint32", 4},
                                                                   {"float", 4},
                                                                   {"float32", 4},
                                                                   {"double", 8},
                                                                   {"float64", 8}}}) {
    if (type == name) return bytes;
  }
  return 0;
}

/// The elements of a PLY header and the offset of its data, or nothing when the header is not
/// one this check understands.
struct PlyHeader {
  bool ascii = false;
  std::vector<PlyElement> elements;
  std::uint64_t data_offset = 0;
};

std::optional<PlyHeader> parse_ply_header(const std::string& head) {
  const std::size_t end = head.find("end_header");
  if (!head.starts_with("ply") || end == std::string::npos) return std::nullopt;
  PlyHeader header;
  const std::size_t newline = head.find('\n', end);
  if (newline == std::string::npos) return std::nullopt;
  header.data_offset = newline + 1;
  // Line by line: a comment may hold any word.
  std::string_view rest = std::string_view(head).substr(0, end);
  while (!rest.empty()) {
    const std::size_t line_end = std::min(rest.find('\n'), rest.size());
    Tokens tokens(rest.substr(0, line_end));
    rest.remove_prefix(std::min(line_end + 1, rest.size()));
    const std::string_view word = tokens.next();
    if (word == "format") {
      header.ascii = tokens.next() == "ascii";
    } else if (word == "element") {
      PlyElement element;
      element.name = std::string(tokens.next());
      const auto count = count_of(tokens.next());
      if (!count) return std::nullopt;
      element.count = *count;
      header.elements.push_back(element);
    } else if (word == "property") {
      if (header.elements.empty()) return std::nullopt;
      std::string_view type = tokens.next();
      if (type == "list") type = tokens.next();  // a list takes at least its count
      const std::uint64_t bytes = ply_type_bytes(type);
      if (bytes == 0) return std::nullopt;
      header.elements.back().min_bytes += bytes;
      ++header.elements.back().properties;
    }
  }
  return header;
}

std::optional<DeclaredFaces> check_ply(const std::filesystem::path& file, std::uint64_t size) {
  const std::string head = read_head(file);
  // assimp 5.2's header parser never returns when `end_header` is missing (a misspelt line):
  // refuse at once a file read whole (shorter than the head) without one. Longer files are
  // left to assimp, under the time limit of isolated_import.hpp.
  if (head.starts_with("ply") && head.size() < kHeaderLimit &&
      head.find("end_header") == std::string::npos) {
    fail(file,
         "the PLY header has no 'end_header' line (misspelt or missing), so where the data "
         "starts is unknown");
  }
  const std::optional<PlyHeader> header = parse_ply_header(head);
  if (!header) return std::nullopt;
  std::uint64_t bytes = 0, lines = 0;
  std::string declared;
  std::optional<DeclaredFaces> faces;
  for (const PlyElement& element : header->elements) {
    // ASCII: each number is at least a digit and a separator; one line per element.
    const std::uint64_t each = header->ascii ? 2 * element.properties : element.min_bytes;
    bytes = saturating_add(bytes, saturating_mul(element.count, each));
    lines = saturating_add(lines, element.count);
    declared +=
        (declared.empty() ? "" : ", ") + std::to_string(element.count) + " '" + element.name + "'";
    if (element.name == "face") faces = DeclaredFaces{element.count, "PLY header"};
  }
  const bool one = header->elements.size() == 1 && header->elements[0].count == 1;
  declared += one ? " element" : " elements";
  const std::uint64_t available = size - header->data_offset;
  require(file, "PLY", declared, bytes, available + (header->ascii ? 1 : 0), "bytes");
  if (header->ascii) {
    require(file, "PLY", declared, lines, data_lines(file, header->data_offset, lines), "lines");
  }
  return faces;
}

/// OBJ declares nothing: count its `f` lines.
DeclaredFaces count_obj_faces(const std::filesystem::path& file) {
  std::uint64_t faces = 0;
  for_each_line(file, 0, [&](const char* text, std::size_t size) {
    std::size_t i = 0;
    while (i < size && (text[i] == ' ' || text[i] == '\t')) ++i;
    if (i + 1 >= size || text[i] != 'f' || (text[i + 1] != ' ' && text[i + 1] != '\t')) {
      return true;
    }
    // A face line with at least one corner (assimp skips an empty `f` silently, as nothing).
    if (first_visible(text + i + 1, size - i - 1) != 0) ++faces;
    return true;
  });
  return DeclaredFaces{faces, "OBJ f lines"};
}

}  // namespace

std::optional<DeclaredFaces> check_declared_counts(const std::filesystem::path& file,
                                                   std::uintmax_t size) {
  const std::string extension = lower_extension(file);
  if (extension == ".off") return check_off(file, size);
  if (extension == ".ply") return check_ply(file, size);
  if (extension == ".obj") return count_obj_faces(file);
  return std::nullopt;
}

}  // namespace tumble::engine::detail
