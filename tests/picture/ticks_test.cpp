// SPDX-License-Identifier: MIT
// Ticks (ticks.h): round steps of 1, 2 or 5 × 10^k inside the range, at least a few of them when
// asked, and labels with the fewest decimals that give the values back and tell them apart.
#include "tessera/picture/ticks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <set>

#include "tessera/core/error.h"

namespace tessera {
namespace {

// The step of `ticks` is 1, 2 or 5 times a power of ten, and every tick a multiple of it.
void expect_nice(const std::vector<double>& ticks) {
  ASSERT_GE(ticks.size(), 2u);
  const double step = ticks[1] - ticks[0];
  const double power = std::pow(10.0, std::floor(std::log10(step) + 1e-9));
  const double mantissa = step / power;
  EXPECT_TRUE(std::abs(mantissa - 1) < 1e-9 || std::abs(mantissa - 2) < 1e-9 ||
              std::abs(mantissa - 5) < 1e-9)
      << "step " << step;
  for (const double tick : ticks) {
    EXPECT_NEAR(tick / step, std::round(tick / step), 1e-6) << tick;  // ticks are i·step
  }
}

TEST(Ticks, AtLeastAsManyAsAskedFallInsideTheRange) {
  // The range of x1 of the CSTR: nice_ticks alone gives 0.5 (step 0.5, 0 and 1 just outside).
  EXPECT_EQ(nice_ticks(0.0225, 0.9988, 4), std::vector<double>{0.5});
  const auto ticks = nice_ticks_at_least(0.0225, 0.9988, 4, 3);
  EXPECT_EQ(ticks.size(), 4u);  // 0.2, 0.4, 0.6, 0.8
  expect_nice(ticks);
  for (const auto& [low, high] : {std::pair{0.0704, 19.93}, std::pair{-1.474, 1.468},
                                  std::pair{2.1e-9, 2.127e-6}, std::pair{0.99990, 0.99996}}) {
    const auto values = nice_ticks_at_least(low, high, 5, 4);
    EXPECT_GE(values.size(), 4u) << low << " " << high;
    expect_nice(values);
    // Inside the range, to the rounding of i·step.
    EXPECT_GE(values.front(), low - 1e-12 * std::abs(low));
    EXPECT_LE(values.back(), high + 1e-12 * std::abs(high));
  }
}

TEST(Ticks, LabelsHaveTheFewestDecimalsThatGiveTheValuesBack) {
  using Labels = std::vector<std::string>;
  EXPECT_EQ(tick_labels({0.0, 0.5, 1.0, 1.5}), (Labels{"0.0", "0.5", "1.0", "1.5"}));
  EXPECT_EQ(tick_labels({-1.0, 0.0, 1.0}), (Labels{"-1", "0", "1"}));
  EXPECT_EQ(tick_labels({5.0, 10.0, 15.0, 20.0}), (Labels{"5", "10", "15", "20"}));
  EXPECT_EQ(tick_labels({10000.0, 12000.0, 14000.0}), (Labels{"10000", "12000", "14000"}));
  EXPECT_EQ(tick_labels({0.1, 0.2, 0.30000000000000004}), (Labels{"0.1", "0.2", "0.3"}));
  // Below 10⁻⁴: the short exponent form with as few significant digits as needed.
  EXPECT_EQ(tick_labels({0.0, 5e-7, 1e-6, 1.5e-6, 2e-6}),
            (Labels{"0", "5e-7", "1e-6", "1.5e-6", "2e-6"}));
  EXPECT_EQ(tick_labels({2e7, 4e7}), (Labels{"2e7", "4e7"}));
  // Close values keep the digits that tell them apart.
  EXPECT_EQ(tick_labels({0.99990, 0.99992, 0.99994}), (Labels{"0.99990", "0.99992", "0.99994"}));
  // Never "-0", whatever rounding left.
  EXPECT_EQ(tick_labels({-1e-17, 0.5}), (Labels{"0.0", "0.5"}));
  EXPECT_EQ(tick_labels({3.0}), Labels{"3"});
  EXPECT_TRUE(tick_labels({}).empty());
  EXPECT_THROW(tick_labels({1.0, NAN}), InvalidArgument);
}

// Whatever the range, the labels of nice ticks are distinct, read back to their values, and
// none is longer than 12 characters (999.5000002: a step of 10⁻⁷ at 10³).
TEST(Ticks, LabelsOfNiceTicksReadBackAndDiffer) {
  for (const double low : {-3.7e-5, 0.0, 0.0704, 2.435, 999.5}) {
    for (const double width : {1e-6, 3e-3, 0.29, 9.5, 19.9, 4e4}) {
      const auto ticks = nice_ticks_at_least(low, low + width, 6, 4);
      const auto labels = tick_labels(ticks);
      ASSERT_EQ(labels.size(), ticks.size());
      std::set<std::string> distinct(labels.begin(), labels.end());
      EXPECT_EQ(distinct.size(), labels.size()) << low << " + " << width;
      const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1.0;
      for (std::size_t i = 0; i < ticks.size(); ++i) {
        EXPECT_NEAR(std::strtod(labels[i].c_str(), nullptr), ticks[i], 1e-6 * step) << labels[i];
        EXPECT_LE(labels[i].size(), 12u) << labels[i];
      }
    }
  }
}

}  // namespace
}  // namespace tessera
