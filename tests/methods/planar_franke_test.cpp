// SPDX-License-Identifier: MIT
// Franke's test functions: values at known points, the pieces of F7, the names.
#include "tessera/methods/planar/franke_functions.h"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>

namespace tessera {
namespace {

TEST(FrankeFunctions, F1HasTheUnsquaredYInItsSecondTerm) {
  // At (0, 0), by hand: 0.75 e^{−2} + 0.75 e^{−1/49 − 1/10} + 0.5 e^{−(49 + 9)/4} − 0.2 e^{−16 −
  // 49}.
  const double expected = 0.75 * std::exp(-2.0) + 0.75 * std::exp(-1.0 / 49 - 0.1) +
                          0.5 * std::exp(-58.0 / 4) - 0.2 * std::exp(-65.0);
  EXPECT_NEAR(evaluate(FrankeFunction::F1, 0, 0), expected, 1e-15);
  // Franke's function peaks near (0.2, 0.2) at about 1.22.
  EXPECT_NEAR(evaluate(FrankeFunction::F1, 2.0 / 9, 2.0 / 9), 1.2, 0.05);
}

TEST(FrankeFunctions, F2IsACliffAlongTheDiagonal) {
  EXPECT_DOUBLE_EQ(evaluate(FrankeFunction::F2, 0.3, 0.3), 1.0 / 9);
  EXPECT_NEAR(evaluate(FrankeFunction::F2, 1, 0), 0.0, 1e-7);
  EXPECT_NEAR(evaluate(FrankeFunction::F2, 0, 1), 2.0 / 9, 1e-7);
}

TEST(FrankeFunctions, F7HasAPlateauARampAndAMountainCentredAtXiOneAndAHalf) {
  // ξ = 2.1x − 0.1; the mountain's top is at ξ = 1.5, y = 0.5, i.e. x = 1.6/2.1.
  EXPECT_DOUBLE_EQ(evaluate(FrankeFunction::F7, 1.6 / 2.1, 0.5), 1.0);
  EXPECT_DOUBLE_EQ(evaluate(FrankeFunction::F7, 0.0, 1.0), 1.0);           // y − ξ = 1.1 ≥ ½
  EXPECT_DOUBLE_EQ(evaluate(FrankeFunction::F7, 0.0, 0.2), 0.6);           // ramp: 2(0.2 + 0.1)
  EXPECT_DOUBLE_EQ(evaluate(FrankeFunction::F7, 0.5, 0.0), 0.0);           // flat ground
  EXPECT_NEAR(evaluate(FrankeFunction::F7, 1.6 / 2.1, 0.75), 0.0, 1e-15);  // foot, r = ¼
}

TEST(FrankeFunctions, F8AndF9MatchTheirFormulas) {
  const double g = 0.595576 * std::pow(0.5 + 3.79762, 2) - 0.5 - 10;
  EXPECT_DOUBLE_EQ(evaluate(FrankeFunction::F8, 0.5, 0.5), std::tanh(-3 * g) + 1);
  // F9 at (0, 0) is 1 (only the first term); at (1, 1) the terms are 2⁻¹², 0, 2⁻⁶ and 2⁻⁶.
  EXPECT_DOUBLE_EQ(evaluate(FrankeFunction::F9, 0, 0), 1.0);
  EXPECT_DOUBLE_EQ(evaluate(FrankeFunction::F9, 1, 1), 1.0 / 4096 + 2.0 / 64);
  // The bump term 1000 ((1 − x) x (1 − y) y)³ is 1000 · 4⁻⁶ at the centre.
  const double h = std::pow(0.75, 6);
  EXPECT_DOUBLE_EQ(evaluate(FrankeFunction::F9, 0.5, 0.5),
                   h * h + 1000 * std::pow(1.0 / 16, 3) + 2 * std::pow(0.5, 6) * h);
}

TEST(FrankeFunctions, HessiansMatchCentralDifferences) {
  // Central differences with step h = 1e-4 are accurate to O(h²) times the fourth
  // derivatives, plus rounding of about 1e-16/h² = 1e-8; F2 and F8 are steep, so the
  // tolerance is relative to |H|.
  const double h = 1e-4;
  for (FrankeFunction f : {FrankeFunction::F1, FrankeFunction::F2, FrankeFunction::F7,
                           FrankeFunction::F8, FrankeFunction::F9}) {
    // (0.8, 0.45) lies on F7's mountain, away from its kinks.
    for (const auto& [x, y] : {std::pair{0.3, 0.6}, std::pair{0.8, 0.45}, std::pair{0.55, 0.5}}) {
      const auto value = [f](double u, double v) { return evaluate(f, u, v); };
      Eigen::Matrix2d expected;
      expected(0, 0) = (value(x + h, y) - 2 * value(x, y) + value(x - h, y)) / (h * h);
      expected(1, 1) = (value(x, y + h) - 2 * value(x, y) + value(x, y - h)) / (h * h);
      expected(0, 1) = expected(1, 0) =
          (value(x + h, y + h) - value(x + h, y - h) - value(x - h, y + h) + value(x - h, y - h)) /
          (4 * h * h);
      const Eigen::Matrix2d H = hessian(f, x, y);
      EXPECT_LT((H - expected).norm(), 1e-4 * (1 + expected.norm()))
          << to_string(f) << " at (" << x << ", " << y << "):\n"
          << H << "\nexpected\n"
          << expected;
    }
  }
}

TEST(FrankeFunctions, NamesRoundTrip) {
  for (FrankeFunction f : {FrankeFunction::F1, FrankeFunction::F2, FrankeFunction::F7,
                           FrankeFunction::F8, FrankeFunction::F9}) {
    EXPECT_EQ(parse_franke_function(to_string(f)), f);
  }
  EXPECT_EQ(parse_franke_function("f7"), FrankeFunction::F7);
  EXPECT_FALSE(parse_franke_function("F3").has_value());
  EXPECT_FALSE(parse_franke_function("G1").has_value());
}

}  // namespace
}  // namespace tessera
