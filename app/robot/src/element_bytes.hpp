#pragma once
/// @file Where an element is in an XML file's bytes, so that it can be replaced with every
/// other byte kept. pugixml reads the document and says where each element's name starts
/// (xml_node::offset_debug); this scanner finds the rest: the '<', the end of the start tag,
/// and the end of the element, skipping quoted attribute values, comments, CDATA sections and
/// processing instructions.

#include <cstddef>
#include <optional>
#include <string>

#include "app/robot/robot_model.hpp"

namespace tumble::app::robot {

/// An element's bytes: [begin, end) from its '<' to the end of its end tag (or of "/>"), and
/// the offset just after its start tag ('>'), unset for a self-closing element.
struct ElementBytes {
  ByteRange whole;
  std::optional<std::size_t> content_begin;
};

/// The element whose name starts at `name_offset` (pugixml's offset_debug of an element node
/// read from `text` as a UTF-8 buffer). Throws std::logic_error if `text` does not hold a
/// well-formed element there (pugixml has already accepted the document, so that is a bug).
ElementBytes element_bytes(const std::string& text, std::size_t name_offset);

/// The indentation of the line the element starts on ("  "), when only blanks precede it.
std::string line_indent(const std::string& text, std::size_t element_begin);

/// The indentation a new child of the element gets: that of its first child element when it
/// has one on a line of its own, else the element's own indentation plus `step`.
std::string child_indent(const std::string& text, const ElementBytes& element,
                         const std::string& step = "  ");

}  // namespace tumble::app::robot
