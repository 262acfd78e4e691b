// parse_strict_json: comments allowed; duplicate keys, numbers beyond a double and syntax
// errors reported with the source, line, column and JSON path.
#include "app/scene/strict_json.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <chrono>
#include <string>

#include "support/input_error.hpp"

namespace tumble::app {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;
using ::testing::StartsWith;

std::string strict_json_error_of(const std::string& text,
                                 const std::string& source = "scene.json") {
  return testing::input_error_of([&] { parse_strict_json(text, source); }, "'" + text + "'");
}

TEST(StrictJson, ReadsPlainJsonIntoTheSameDocumentAsNlohmann) {
  const std::string text =
      R"({"name": "brick", "mass": 2.5, "count": 3, "big": 18446744073709551615,
          "negative": -7, "flags": [true, false, null], "nested": {"a": {"b": [1, [2, 3]]}},
          "text": "a \"quoted\" \u00e9 string"})";
  const json parsed = parse_strict_json(text, "f.json");
  EXPECT_EQ(parsed, json::parse(text));
  EXPECT_EQ(parsed["nested"]["a"]["b"][1][1].get<int>(), 3);
  EXPECT_EQ(parsed["big"].get<unsigned long long>(), 18446744073709551615ull);
  EXPECT_EQ(parsed["negative"].get<int>(), -7);
  EXPECT_TRUE(parsed["flags"][2].is_null());
  EXPECT_EQ(parsed["text"].get<std::string>(), "a \"quoted\" \xc3\xa9 string");
}

TEST(StrictJson, TopLevelScalarsAndEmptyContainers) {
  EXPECT_EQ(parse_strict_json("42", "f"), json(42));
  EXPECT_EQ(parse_strict_json("\"x\"", "f"), json("x"));
  EXPECT_EQ(parse_strict_json("[]", "f"), json::array());
  EXPECT_EQ(parse_strict_json("{}", "f"), json::object());
  EXPECT_EQ(parse_strict_json("[[], {}, [[]]]", "f"), json::parse("[[], {}, [[]]]"));
}

TEST(StrictJson, IgnoresLineAndBlockComments) {
  const json parsed = parse_strict_json(
      "// a scene\n"
      "{\n"
      "  \"dt\": 0.01, // seconds\n"
      "  /* the bodies,\n"
      "     one per line */\n"
      "  \"bodies\": [ /* none */ ]\n"
      "}\n",
      "scene.json");
  EXPECT_EQ(parsed, json::parse(R"({"dt": 0.01, "bodies": []})"));
}

TEST(StrictJson, CommentMarkersInsideStringsAreText) {
  const json parsed = parse_strict_json(R"({"url": "http://x/*y*/", "c": "//"})", "f");
  EXPECT_EQ(parsed["url"].get<std::string>(), "http://x/*y*/");
  EXPECT_EQ(parsed["c"].get<std::string>(), "//");
}

TEST(StrictJson, DuplicateKeyAtTheTopLevelNamesTheKey) {
  EXPECT_EQ(strict_json_error_of(R"({"dt": 0.01, "dt": 0.02})"),
            "scene.json: dt: duplicate key (each key may appear once)");
}

TEST(StrictJson, DuplicateKeyDeepInsideNamesItsFullPath) {
  const std::string text = R"({
  "bodies": [
    {"name": "a"},
    {"inertia": {"principal": [1, 2, {"k": 1, "k": 2}]}}
  ]
})";
  EXPECT_EQ(
      strict_json_error_of(text, "deep.json"),
      "deep.json: bodies[1].inertia.principal[2].k: duplicate key (each key may appear once)");
}

TEST(StrictJson, TheSameKeyInDifferentObjectsIsNoDuplicate) {
  const json parsed =
      parse_strict_json(R"({"bodies": [{"mass": 1}, {"mass": 2}], "mass": {"mass": 3}})", "f");
  EXPECT_EQ(parsed["bodies"][1]["mass"].get<int>(), 2);
  EXPECT_EQ(parsed["mass"]["mass"].get<int>(), 3);
}

TEST(StrictJson, KeysDifferingOnlyInCaseAreDistinct) {
  const json parsed = parse_strict_json(R"({"Mass": 1, "mass": 2})", "f");
  EXPECT_EQ(parsed.size(), 2u);
}

TEST(StrictJson, NumberBeyondADoublePointsAtItsStartWithLineColumnAndPath) {
  // Line 3 is `    "b": [1, 1e999]`: the number starts at column 14.
  const std::string text = "{\n  \"a\": {\n    \"b\": [1, 1e999]\n  }\n}\n";
  EXPECT_EQ(strict_json_error_of(text),
            "scene.json:3:14: a.b[1]: expected a finite number, got 1e999 (beyond the range of a "
            "double)");
}

TEST(StrictJson, NegativeOverflowAndOverflowAsAMemberValue) {
  EXPECT_EQ(strict_json_error_of(R"({"mass": -1e400})", "m.json"),
            "m.json:1:10: mass: expected a finite number, got -1e400 (beyond the range of a "
            "double)");
}

TEST(StrictJson, OverflowAtTheTopLevelHasNoPath) {
  EXPECT_EQ(strict_json_error_of("1e999", "top.json"),
            "top.json:1:1: expected a finite number, got 1e999 (beyond the range of a double)");
}

TEST(StrictJson, AnIntegerWithMoreDigitsThanADoubleHoldsIsAnError) {
  const std::string huge = "1" + std::string(400, '0');
  const std::string message = strict_json_error_of("[" + huge + "]");
  EXPECT_THAT(message, StartsWith("scene.json:1:2: [0]: expected a finite number, got " + huge));
}

TEST(StrictJson, LargestAndSmallestDoublesAreAccepted) {
  const json parsed = parse_strict_json("[1.7976931348623157e308, 4.9e-324, 1e-400]", "f");
  EXPECT_EQ(parsed[0].get<double>(), 1.7976931348623157e308);
  EXPECT_EQ(parsed[1].get<double>(), 4.9e-324);
  EXPECT_EQ(parsed[2].get<double>(), 0.0);  // underflow is rounding, not an error
}

TEST(StrictJson, SyntaxErrorNamesSourceLineAndColumn) {
  const std::string message = strict_json_error_of("{\n  \"a\": 1\n  \"b\": 2\n}", "s.json");
  EXPECT_THAT(message, StartsWith("s.json:3:"));
  EXPECT_THAT(message, HasSubstr(": malformed JSON: "));
  EXPECT_THAT(message, ::testing::Not(HasSubstr("[json.exception")));
}

TEST(StrictJson, TrailingCommaIsMalformed) {
  const std::string message = strict_json_error_of(R"({"a": 1,})", "t.json");
  EXPECT_THAT(message, StartsWith("t.json:1:"));
  EXPECT_THAT(message, HasSubstr("malformed JSON"));
}

TEST(StrictJson, EmptyTextTrailingGarbageAndUnclosedCommentsAreMalformed) {
  EXPECT_THAT(strict_json_error_of("", "e.json"), StartsWith("e.json:1:1: malformed JSON"));
  EXPECT_THAT(strict_json_error_of("{} x", "g.json"), StartsWith("g.json:1:"));
  EXPECT_THAT(strict_json_error_of("{} x", "g.json"), HasSubstr("malformed JSON"));
  EXPECT_THAT(strict_json_error_of("{\"a\": 1 /* never closed", "c.json"),
              HasSubstr("malformed JSON"));
  EXPECT_THAT(strict_json_error_of("[1, 2", "u.json"), HasSubstr("malformed JSON"));
}

TEST(StrictJson, SyntaxErrorOnALaterLineCountsEveryNewline) {
  const std::string message = strict_json_error_of("[\n1,\n2,\n\n  ?]", "n.json");
  EXPECT_THAT(message, StartsWith("n.json:5:"));
}

/// The peak resident memory of this process so far, in bytes.
long peak_memory_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss * 1024L;
}

TEST(StrictJson, NestingDeeperThanTheLimitIsRefusedFastWithBoundedMemory) {
  // 40,000 levels in 80 KB: a copy of the path per level took 3 GB and minutes.
  const std::string text = std::string(40000, '[') + std::string(40000, ']');
  const long before = peak_memory_bytes();
  const auto start = std::chrono::steady_clock::now();
  const std::string message = strict_json_error_of(text);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(peak_memory_bytes() - before, 64L << 20);
  EXPECT_LT(seconds, 1.0);
  std::string path;
  for (int i = 0; i < 256; ++i) path += "[0]";
  EXPECT_EQ(message,
            "scene.json: " + path + ": nested deeper than 256 levels of arrays and objects");
}

TEST(StrictJson, TheDepthLimitCountsObjectsAndNamesTheKeys) {
  std::string text;
  for (int i = 0; i < 300; ++i) text += R"({"a": )";
  const std::string message = strict_json_error_of(text);
  std::string path = "a";
  for (int i = 1; i < 256; ++i) path += ".a";
  EXPECT_EQ(message,
            "scene.json: " + path + ": nested deeper than 256 levels of arrays and objects");
}

TEST(StrictJson, NestingUpToTheLimitIsRead) {
  const std::string text = std::string(256, '[') + "7" + std::string(256, ']');
  json parsed = parse_strict_json(text, "deep.json");
  const json* inner = &parsed;
  for (int i = 0; i < 255; ++i) inner = &(*inner)[0];
  EXPECT_EQ((*inner)[0].get<int>(), 7);
}

}  // namespace
}  // namespace tumble::app
