// SPDX-License-Identifier: MIT
// Tick values at round steps and their labels: what the axes of the surface pictures, their
// colour bars and the bifurcation diagram print.
#pragma once

#include <string>
#include <vector>

namespace tessera {

/// About `target` tick values covering [low, high] at a round step (1, 2 or 5 × 10^k), from the
/// first multiple of the step at or above `low` to the last at or below `high` (Heckbert's "nice
/// numbers"); a single value where low == high. Each tick is i·step, not a running sum, so 0.3
/// is 3 × 0.1 and prints as 0.3.
/// \pre low <= high, both finite; target >= 2.
/// \throw InvalidArgument if a precondition fails (the message names the values).
std::vector<double> nice_ticks(double low, double high, int target);

/// nice_ticks with `target` raised until at least `minimum` ticks fall inside [low, high]
/// (nice_ticks(0.02, 0.999, 4) is {0.5} alone, its step 0.5; this gives 0.2, 0.4, 0.6, 0.8), or
/// up to three times `target`.
/// \pre as nice_ticks; minimum >= 1.
std::vector<double> nice_ticks_at_least(double low, double high, int target, int minimum);

/// Labels of increasing tick values with the fewest decimals (one count for all, as plots
/// print them: 0, 0.5, 1.0, 1.5) that tell them apart and give each value back to a millionth
/// of the smallest step between them: not 0.9999 or 2.127e-06. Fixed-point notation where the
/// largest value lies between 10⁻⁴ and 10⁶, else the fewest significant digits in the short
/// exponent form ("2e-6", "1.5e-6", "3e7"). Zero prints as "0" or "0.0" (never "-0").
/// \pre every value finite.
std::vector<std::string> tick_labels(const std::vector<double>& ticks);

}  // namespace tessera
