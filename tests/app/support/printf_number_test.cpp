// printf_number: numbers in messages and reports as printf prints them.
#include "app/support/printf_number.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace tumble::app {
namespace {

TEST(PrintfNumber, DefaultsToSixSignificantDigits) {
  EXPECT_EQ(printf_number(1.0 / 3.0), "0.333333");
  EXPECT_EQ(printf_number(123456789.0), "1.23457e+08");
  EXPECT_EQ(printf_number(2.0), "2");
  EXPECT_EQ(printf_number(-0.0001), "-0.0001");
  EXPECT_EQ(printf_number(0.00001), "1e-05");
}

TEST(PrintfNumber, UsesTheGivenFormat) {
  EXPECT_EQ(printf_number(M_PI, "%.9g"), "3.14159265");
  EXPECT_EQ(printf_number(2.5, "%.2f"), "2.50");
  EXPECT_EQ(printf_number(1234.5, "%.1e"), "1.2e+03");
  EXPECT_EQ(printf_number(0.125, "t = %.3f s"), "t = 0.125 s");
}

TEST(PrintfNumber, RoundsHalfToEvenAsPrintfDoes) {
  EXPECT_EQ(printf_number(0.125, "%.2f"), "0.12");  // 0.125 is exact: ties to even
  EXPECT_EQ(printf_number(0.375, "%.2f"), "0.38");
}

TEST(PrintfNumber, NonFiniteValues) {
  EXPECT_EQ(printf_number(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(printf_number(-std::numeric_limits<double>::infinity()), "-inf");
  EXPECT_EQ(printf_number(std::nan("")), "nan");
}

TEST(PrintfNumber, LongOutputIsCutToTheBufferNotOverrun) {
  const std::string text = printf_number(1e300, "%.2f");
  EXPECT_EQ(text.size(), 63u);  // 64-byte buffer, terminator included
  EXPECT_EQ(text.substr(0, 3), "100");
}

}  // namespace
}  // namespace tumble::app
