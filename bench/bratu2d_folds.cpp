// SPDX-License-Identifier: MIT
// Where the fold surface of the catalogue's `bratu2d` lies: for several ε, λ along the centre
// value u_c (ArrheniusBratu2D::point_with_amplitude), its local extrema (the ignition and
// extinction folds, refined by golden-section search) and the cusp ε_c where they meet (the root
// of g(ε) = min over u_c of dλ/du_c, by the secant method). The numbers are quoted in the class
// comment of ArrheniusBratu2D (src/tessera/problems/examples.h).
//
// With `disk` it checks instead the claim behind the catalogue's expected Euler characteristic:
// M is a graph over (u_c, ε), so M ∩ S is a disk if on every line ε = const the centre values
// with 0.5 ≤ λ ≤ 20 and u_c ≤ 20 form one interval (sampled every 0.25 in u_c; ε every `step`).
//
//     tessera_bratu2d_folds [N] [largest u_c] [spacing]   defaults: N = 100, u_c up to 20,
//                                                         folds bracketed every 0.25 in u_c
//     tessera_bratu2d_folds N largest disk [ε step]       default ε step 0.01
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "tessera/problems/examples.h"

namespace {

struct Extremum {
  double amplitude;
  double lambda;
  bool is_maximum;
};

// Golden-section search for the extremum of f on [a, b] (a maximum if `maximise`).
Extremum golden_section(const std::function<double(double)>& f, double a, double b, bool maximise) {
  const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
  const double sign = maximise ? -1.0 : 1.0;
  double c = b - ratio * (b - a);
  double d = a + ratio * (b - a);
  double fc = sign * f(c);
  double fd = sign * f(d);
  while (b - a > 1e-3) {
    if (fc < fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - ratio * (b - a);
      fc = sign * f(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + ratio * (b - a);
      fd = sign * f(d);
    }
  }
  const double amplitude = (a + b) / 2.0;
  return {amplitude, f(amplitude), maximise};
}

}  // namespace

int main(int argc, char** argv) {
  const int N = argc > 1 ? std::atoi(argv[1]) : 100;
  const double largest = argc > 2 ? std::atof(argv[2]) : 20.0;
  const tessera::ArrheniusBratu2D problem(N);
  const int lambda_index = N * N;
  const auto lambda = [&](double amplitude, double epsilon) {
    return problem.point_with_amplitude(amplitude, epsilon)(lambda_index);
  };
  std::printf("bratu2d N = %d (n = %d), u_c in [0, %g]\n", N, problem.ambient_dimension(), largest);

  if (argc > 3 && std::string(argv[3]) == "disk") {
    const double epsilon_step = argc > 4 ? std::atof(argv[4]) : 0.01;
    int lines_with_one_interval = 0;
    int lines = 0;
    for (double epsilon = 0.0; epsilon <= 0.3 + 1e-9; epsilon += epsilon_step) {
      int runs = 0;
      bool inside_before = false;
      double lowest = 1e300, highest = -1e300;
      for (double amplitude = 0.0; amplitude <= largest + 1e-9; amplitude += 0.25) {
        const double value = lambda(amplitude, epsilon);
        lowest = std::min(lowest, value);
        highest = std::max(highest, value);
        const bool inside = value >= 0.5 && value <= 20.0;
        runs += inside && !inside_before;
        inside_before = inside;
      }
      ++lines;
      lines_with_one_interval += runs == 1;
      std::printf("epsilon %.3f: %d interval(s); lambda in [%.4f, %.4f]\n", epsilon, runs, lowest,
                  highest);
      std::fflush(stdout);
    }
    std::printf("%d of %d lines meet {0.5 <= lambda <= 20, u_c <= %g} in one interval\n",
                lines_with_one_interval, lines, largest);
    return lines_with_one_interval == lines ? 0 : 1;
  }

  // The folds: extrema of λ along u_c, bracketed on a grid and refined.
  const double spacing = argc > 3 ? std::atof(argv[3]) : 0.25;
  for (const double epsilon : {0.0, 0.05, 0.1, 0.15, 0.2, 0.22, 0.23, 0.24, 0.25, 0.3}) {
    std::vector<double> grid, values;
    for (double amplitude = spacing; amplitude <= largest + 1e-9; amplitude += spacing) {
      grid.push_back(amplitude);
      values.push_back(lambda(amplitude, epsilon));
    }
    std::printf("epsilon %.3f: lambda(u_c = %g) = %.4f", epsilon, largest, values.back());
    for (std::size_t k = 1; k + 1 < grid.size(); ++k) {
      const bool is_maximum = values[k] > values[k - 1] && values[k] >= values[k + 1];
      const bool is_minimum = values[k] < values[k - 1] && values[k] <= values[k + 1];
      if (is_maximum || is_minimum) {
        const Extremum fold = golden_section([&](double a) { return lambda(a, epsilon); },
                                             grid[k - 1], grid[k + 1], is_maximum);
        std::printf("; %s fold at u_c = %.3f, lambda = %.5f",
                    is_maximum ? "ignition" : "extinction", fold.amplitude, fold.lambda);
      }
    }
    std::printf("\n");
    std::fflush(stdout);
  }

  // The cusp: g(ε) = min over u_c of dλ/du_c (central differences) is negative while the branch
  // is S-shaped and positive above the cusp; its root is ε_c, and the minimiser is u_c there.
  constexpr double kDelta = 1e-3;
  double cusp_amplitude = 0.0;
  const auto g = [&](double epsilon) {
    const auto slope = [&](double amplitude) {
      return (lambda(amplitude + kDelta, epsilon) - lambda(amplitude - kDelta, epsilon)) /
             (2.0 * kDelta);
    };
    const Extremum steepest_descent = golden_section(slope, 1.0, 10.0, /*maximise=*/false);
    cusp_amplitude = steepest_descent.amplitude;
    return steepest_descent.lambda;
  };
  double a = 0.22, b = 0.26;
  double ga = g(a), gb = g(b);
  for (int iteration = 0; iteration < 8 && std::abs(b - a) > 1e-6; ++iteration) {
    const double c = b - gb * (b - a) / (gb - ga);
    a = b;
    ga = gb;
    b = c;
    gb = g(b);
    std::printf("secant: epsilon %.6f, min dlambda/du_c = %.3e at u_c = %.3f\n", b, gb,
                cusp_amplitude);
    std::fflush(stdout);
  }
  std::printf("cusp: epsilon_c = %.4f, u_c = %.3f, lambda = %.5f\n", b, cusp_amplitude,
              lambda(cusp_amplitude, b));
  return 0;
}
