// Comma-separated option lists: splitting, positive numbers and integrator names.
#include "app/scene/option_lists.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/input_error.hpp"

namespace tumble::app {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using testing::input_error_of;

std::vector<std::string> names_of(const std::vector<const engine::IntegratorInfo*>& list) {
  std::vector<std::string> names;
  for (const auto* info : list) names.push_back(info->name);
  return names;
}

TEST(SplitOptionList, SplitsOnCommasAndTrimsBlanks) {
  EXPECT_THAT(split_option_list("a, b,c", "--x"), ElementsAre("a", "b", "c"));
  EXPECT_THAT(split_option_list(" \tone \t", "--x"), ElementsAre("one"));
  EXPECT_THAT(split_option_list("a b, c", "--x"), ElementsAre("a b", "c"));
}

TEST(SplitOptionList, EmptyListsAndEmptyItemsAreErrorsNamingTheOption) {
  const std::string expected =
      "--cases: expected a comma-separated list without empty items, got '";
  EXPECT_EQ(input_error_of([] { split_option_list("", "--cases"); }), expected + "'");
  EXPECT_EQ(input_error_of([] { split_option_list("a,,b", "--cases"); }), expected + "a,,b'");
  EXPECT_EQ(input_error_of([] { split_option_list(",a", "--cases"); }), expected + ",a'");
  EXPECT_EQ(input_error_of([] { split_option_list("a,", "--cases"); }), expected + "a,'");
  EXPECT_EQ(input_error_of([] { split_option_list("a, ,b", "--cases"); }), expected + "a, ,b'");
  EXPECT_EQ(input_error_of([] { split_option_list(" ", "--cases"); }), expected + " '");
}

TEST(ParsePositiveList, KeepsOrderAndDuplicates) {
  EXPECT_THAT(parse_positive_list("0.01, 1e-3,0.01,2", "--dts"),
              ElementsAre(0.01, 1e-3, 0.01, 2.0));
}

TEST(ParsePositiveList, RefusesZeroNegativeNonFiniteAndText) {
  for (const std::string bad : {"0", "-0.1", "inf", "nan", "abc", "0.1s", "1e999"}) {
    EXPECT_EQ(input_error_of([&] { parse_positive_list("0.5, " + bad, "--dts"); }, bad),
              "--dts: expected a positive number, got '" + bad + "'");
  }
  EXPECT_THAT(input_error_of([] { parse_positive_list("", "--tolerances"); }),
              HasSubstr("--tolerances: expected a comma-separated list"));
}

TEST(ParseIntegratorList, NamesInOrderEachOnce) {
  EXPECT_THAT(names_of(parse_integrator_list("rk4, explicit-euler,rk4,dopri", "--integrators")),
              ElementsAre("rk4", "explicit-euler", "dopri"));
  const auto list = parse_integrator_list("midpoint", "--integrators");
  ASSERT_EQ(list.size(), 1u);
  EXPECT_EQ(list[0], &engine::integrator_info(engine::IntegratorKind::kMidpoint));
}

TEST(ParseIntegratorList, UnknownNameListsEveryIntegrator) {
  const std::string message =
      input_error_of([] { parse_integrator_list("rk4,leapfrog", "--integrators"); });
  EXPECT_THAT(message,
              HasSubstr("--integrators: unknown integrator 'leapfrog'; expected one of: "));
  for (const auto& info : engine::integrator_catalog()) EXPECT_THAT(message, HasSubstr(info.name));
  EXPECT_THAT(input_error_of([] { parse_integrator_list("RK4", "-i"); }),
              HasSubstr("-i: unknown integrator 'RK4'"));
}

}  // namespace
}  // namespace tumble::app
