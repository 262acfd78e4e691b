// Where elements are in an XML file's bytes (element_bytes.hpp), and the rewrite that replaces
// only inertial elements (rewrite.hpp): every byte outside them stays as it was.
#include "element_bytes.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <pugixml.hpp>
#include <string>

#include "app/robot/rewrite.hpp"
#include "base/errors.hpp"

namespace tumble::app::robot {
namespace {

/// pugixml's offset of the first element called `name` (depth first).
std::size_t name_offset(const std::string& text, const char* name) {
  pugi::xml_document document;
  EXPECT_TRUE(
      document.load_buffer(text.data(), text.size(), pugi::parse_default, pugi::encoding_utf8));
  const pugi::xml_node node =
      document.find_node([&](const pugi::xml_node& n) { return std::string(n.name()) == name; });
  EXPECT_TRUE(node) << name;
  return static_cast<std::size_t>(node.offset_debug());
}

std::string bytes_of(const std::string& text, const char* name) {
  const ElementBytes element = element_bytes(text, name_offset(text, name));
  return text.substr(element.whole.begin, element.whole.end - element.whole.begin);
}

TEST(ElementBytes, FindsTheWholeElementPastTrickyContent) {
  const std::string text =
      "<?xml version=\"1.0\"?>\n<robot>\n  <link name=\"a>b\">\n"
      "    <inertial><!-- </inertial> --><mass value='1'/><![CDATA[</inertial>]]>"
      "<?pi </inertial>?><inertial/></inertial>\n  </link>\n</robot>\n";
  EXPECT_EQ(bytes_of(text, "inertial"),
            "<inertial><!-- </inertial> --><mass value='1'/><![CDATA[</inertial>]]>"
            "<?pi </inertial>?><inertial/></inertial>");
  const ElementBytes link = element_bytes(text, name_offset(text, "link"));
  ASSERT_TRUE(link.content_begin);
  EXPECT_EQ(text.substr(link.whole.begin, *link.content_begin - link.whole.begin),
            "<link name=\"a>b\">");
  EXPECT_EQ(line_indent(text, link.whole.begin), "  ");
  EXPECT_EQ(child_indent(text, link), "    ");
}

TEST(ElementBytes, SelfClosingElementsHaveNoContent) {
  const std::string text = "<robot>\n\t<link name='a' />\n</robot>";
  const ElementBytes link = element_bytes(text, name_offset(text, "link"));
  EXPECT_FALSE(link.content_begin);
  EXPECT_EQ(text.substr(link.whole.begin, link.whole.end - link.whole.begin), "<link name='a' />");
  EXPECT_EQ(child_indent(text, link, "\t"), "\t\t");
}

TEST(ElementBytes, AnOffsetThatIsNoElementIsABug) {
  const std::string text = "<robot><link/></robot>";
  EXPECT_THROW(element_bytes(text, 0), std::logic_error);
  EXPECT_THROW(element_bytes(text, 3), std::logic_error);
  EXPECT_THROW(element_bytes("<robot><link", 8), std::logic_error);
}

/// A URDF-like robot of two links, the first with an inertial, the second without.
Robot two_links() {
  Robot robot;
  robot.format = RobotFormat::urdf;
  robot.file = "two.urdf";
  robot.text =
      "<robot name='r'>  <!-- kept -->\n"
      "  <link name='a'>\n"
      "    <inertial>\n      <mass value='9'/>\n    </inertial>\n"
      "    <visual/>\n"
      "  </link>\n"
      "  <link name='b'>\n"
      "    <collision/>\n"
      "  </link>\n"
      "</robot>\n";
  Link a;
  a.name = "a";
  const std::size_t inertial = robot.text.find("<inertial>");
  a.inertial_bytes = ByteRange{inertial, robot.text.find("</inertial>") + 11};
  Link b;
  b.name = "b";
  b.insert_at = robot.text.find("<link name='b'>") + 15;
  b.child_indent = "    ";
  robot.links = {a, b};
  return robot;
}

TEST(Rewrite, ReplacesAndInsertsOnlyInertials) {
  const Robot robot = two_links();
  engine::MassProperties p;
  p.mass = 2.5;
  p.center_of_mass = {0.5, 0.0, -0.25};
  p.inertia = Eigen::Vector3d(1.0, 2.0, 3.0).asDiagonal();
  const std::string out = rewritten_text(robot, {p, p}, InertialFrame::mesh);
  const std::string element =
      "<inertial>\n"
      "      <origin xyz=\"0.5 0 -0.25\" rpy=\"0 0 0\"/>\n"
      "      <mass value=\"2.5\"/>\n"
      "      <inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"2\" iyz=\"0\" izz=\"3\"/>\n"
      "    </inertial>";
  EXPECT_EQ(out,
            "<robot name='r'>  <!-- kept -->\n"
            "  <link name='a'>\n"
            "    " +
                element +
                "\n"
                "    <visual/>\n"
                "  </link>\n"
                "  <link name='b'>\n"
                "    " +
                element +
                "\n"
                "    <collision/>\n"
                "  </link>\n"
                "</robot>\n");
  // Unset entries leave their links alone.
  EXPECT_EQ(rewritten_text(robot, {std::nullopt, std::nullopt}, InertialFrame::mesh), robot.text);
}

TEST(Rewrite, ALinkWithNoPlaceIsNamed) {
  Robot robot = two_links();
  robot.links[1].insert_at.reset();
  engine::MassProperties p;
  p.mass = 1.0;
  EXPECT_THAT(
      [&] {
        rewritten_text(robot, {std::nullopt, p}, InertialFrame::mesh);
      },
      ::testing::ThrowsMessage<InputError>(::testing::HasSubstr("two.urdf: link 'b'")));
}

}  // namespace
}  // namespace tumble::app::robot
