// What the URDF and SDF readers share.
#include "xml_values.hpp"

#include <charconv>
#include <cmath>

#include "base/errors.hpp"
#include "element_bytes.hpp"

namespace tumble::app::robot {
namespace {

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

/// The numbers of `text`, or nothing when a token is not a finite number.
std::optional<std::vector<double>> tokens(const std::string& text) {
  std::vector<double> out;
  std::size_t at = 0;
  while (true) {
    while (at < text.size() && is_blank(text[at])) ++at;
    if (at == text.size()) return out;
    std::size_t end = at;
    while (end < text.size() && !is_blank(text[end])) ++end;
    const char* first = text.data() + at;
    if (*first == '+' && end - at > 1) ++first;
    double value = 0.0;
    const auto result = std::from_chars(first, text.data() + end, value);
    if (result.ec != std::errc() || result.ptr != text.data() + end || !std::isfinite(value)) {
      return std::nullopt;
    }
    out.push_back(value);
    at = end;
  }
}

std::string expected_counts(const std::vector<std::size_t>& counts) {
  if (counts.size() == 1 && counts[0] == 1) return "a number";
  std::string out;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    out += (i == 0 ? "" : i + 1 == counts.size() ? " or " : ", ") + std::to_string(counts[i]);
  }
  return out + " numbers";
}

}  // namespace

void load_robot_document(pugi::xml_document& document, const std::string& text,
                         const std::filesystem::path& file) {
  const pugi::xml_parse_result result =
      document.load_buffer(text.data(), text.size(), pugi::parse_default, pugi::encoding_utf8);
  if (!result) {
    const auto offset = static_cast<std::size_t>(std::max<std::ptrdiff_t>(result.offset, 0));
    throw InputError(file.string() + ": line " + std::to_string(line_of(text, offset)) +
                     ": XML error: " + result.description());
  }
}

std::vector<double> parse_numbers(const std::string& text, const std::vector<std::size_t>& counts,
                                  const std::string& where) {
  const std::optional<std::vector<double>> values = tokens(text);
  if (values) {
    for (const std::size_t count : counts) {
      if (values->size() == count) return *values;
    }
  }
  throw InputError(where + ": expected " + expected_counts(counts) + ", got '" + text + "'");
}

double parse_number(const std::string& text, const std::string& where) {
  return parse_numbers(text, {1}, where)[0];
}

double parse_positive(const std::string& text, const std::string& where) {
  const std::optional<std::vector<double>> values = tokens(text);
  if (!values || values->size() != 1 || (*values)[0] <= 0.0) {
    throw InputError(where + ": expected a positive number, got '" + text + "'");
  }
  return (*values)[0];
}

Eigen::Vector3d parse_positive_vector(const std::string& text, const std::string& where) {
  const std::optional<std::vector<double>> values = tokens(text);
  if (!values || values->size() != 3 || (*values)[0] <= 0.0 || (*values)[1] <= 0.0 ||
      (*values)[2] <= 0.0) {
    throw InputError(where + ": expected 3 positive numbers, got '" + text + "'");
  }
  return {(*values)[0], (*values)[1], (*values)[2]};
}

Eigen::Isometry3d pose_from(const Eigen::Vector3d& xyz, const Eigen::Matrix3d& rotation) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotation;
  pose.translation() = xyz;
  return pose;
}

Eigen::Matrix3d inertia_matrix(double ixx, double ixy, double ixz, double iyy, double iyz,
                               double izz) {
  Eigen::Matrix3d inertia;
  inertia << ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz;
  return inertia;
}

void locate_inertial(Link& link, const std::string& text, const pugi::xml_node& link_node,
                     const pugi::xml_node& inertial_node) {
  const ElementBytes bytes = element_bytes(text, link_node.offset_debug());
  link.insert_at = bytes.content_begin;
  link.child_indent = child_indent(text, bytes);
  if (inertial_node) {
    link.inertial_bytes = element_bytes(text, inertial_node.offset_debug()).whole;
  }
}

void note_other_geometry(Link& link, const pugi::xml_node& link_node, GeometrySource from) {
  if (!link.geometries.empty()) return;
  const bool collision = from == GeometrySource::collision;
  if (!link_node.child(collision ? "visual" : "collision")) return;
  link.notes.push_back(collision ? "has no <collision> geometry, only <visual> (--from visual)"
                                 : "has no <visual> geometry, only <collision> (--from collision)");
}

std::size_t line_of(const std::string& text, std::size_t offset) {
  std::size_t line = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) line += text[i] == '\n' ? 1 : 0;
  return line;
}

}  // namespace tumble::app::robot
