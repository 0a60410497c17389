// SPDX-License-Identifier: MIT
// Franke's test functions for scattered-data interpolation, numbered as in Dyn, Levin and
// Rippa and in Malcolm's report.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>

namespace tessera {

/// Test functions on the unit square (Malcolm section 6(2); corrections from issue 5):
///   F1  Franke's function: 0.75 exp(−((9x−2)² + (9y−2)²)/4) + 0.75 exp(−(9x+1)²/49 − (9y+1)/10)
///       + 0.5 exp(−((9x−7)² + (9y−3)²)/4) − 0.2 exp(−(9x−4)² − (9y−7)²)   (y part of the
///       second term not squared, as Franke wrote it)
///   F2  (tanh(9y − 9x) + 1)/9, a cliff along the diagonal
///   F7  a ramp and a cosine mountain centred at ξ = 1.5, y = 0.5, where ξ = 2.1x − 0.1:
///       1 if y − ξ ≥ ½; 2(y − ξ) if 0 ≤ y − ξ ≤ ½; (cos(4πr) + 1)/2 if r ≤ ¼; 0 otherwise,
///       r = √((ξ − 1.5)² + (y − 0.5)²)   (first derivatives jump)
///   F8  tanh(−3g) + 1 with g = 0.595576 (y + 3.79762)² − x − 10   (the report's
///       "tanh(−3g + 1)" is an OCR error)
///   F9  (1 − x/2)⁶(1 − y/2)⁶ + 1000 (1 − x)³x³(1 − y)³y³ + y⁶(1 − x/2)⁶ + x⁶(1 − y/2)⁶
///       (the report's "(1 − x⁴)³" is read as (1 − x)³, symmetric with the y factor)
enum class FrankeFunction { F1, F2, F7, F8, F9 };

/// "F1", "F2", "F7", "F8", "F9".
std::string to_string(FrankeFunction function);
/// Accepts "F1" … "F9" in either case; nullopt for other names.
std::optional<FrankeFunction> parse_franke_function(std::string_view name);

double evaluate(FrankeFunction function, double x, double y);
/// Exact second derivatives [[f_xx, f_xy], [f_xy, f_yy]] (forward-mode hyper-dual numbers, no
/// finite differences), e.g. for EquidistributionCriterion. F7 is piecewise: the Hessian of
/// the piece at (x, y); at the mountain's top (r = 0) it is not finite.
Eigen::Matrix2d hessian(FrankeFunction function, double x, double y);
/// Values at the columns of `points` (2×N).
Eigen::VectorXd sample(FrankeFunction function, const Eigen::Ref<const Eigen::Matrix2Xd>& points);

}  // namespace tessera
