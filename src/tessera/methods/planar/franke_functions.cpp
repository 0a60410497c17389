// SPDX-License-Identifier: MIT
// Franke's test functions for scattered-data interpolation, numbered as in Dyn, Levin and
// Rippa and in Malcolm's report.
#include "tessera/methods/planar/franke_functions.h"

#include <array>
#include <cctype>
#include <cmath>
#include <numbers>
#include <utility>

namespace tessera {
namespace {

constexpr std::array<std::pair<FrankeFunction, std::string_view>, 5> kFrankeNames = {{
    {FrankeFunction::F1, "F1"},
    {FrankeFunction::F2, "F2"},
    {FrankeFunction::F7, "F7"},
    {FrankeFunction::F8, "F8"},
    {FrankeFunction::F9, "F9"},
}};

// Hyper-dual numbers v + d1 ε1 + d2 ε2 + d12 ε1ε2 with ε1² = ε2² = 0: evaluating f at
// x + ε1 e_i + ε2 e_j gives ∂²f/∂x_i∂x_j exactly (to rounding) in d12, with no step size.
struct HyperDual {
  double v = 0.0;
  double d1 = 0.0;
  double d2 = 0.0;
  double d12 = 0.0;
};

HyperDual operator+(HyperDual a, HyperDual b) {
  return {a.v + b.v, a.d1 + b.d1, a.d2 + b.d2, a.d12 + b.d12};
}
HyperDual operator-(HyperDual a, HyperDual b) {
  return {a.v - b.v, a.d1 - b.d1, a.d2 - b.d2, a.d12 - b.d12};
}
HyperDual operator-(HyperDual a) { return {-a.v, -a.d1, -a.d2, -a.d12}; }
HyperDual operator*(HyperDual a, HyperDual b) {
  return {a.v * b.v, a.v * b.d1 + a.d1 * b.v, a.v * b.d2 + a.d2 * b.v,
          a.v * b.d12 + a.d1 * b.d2 + a.d2 * b.d1 + a.d12 * b.v};
}
HyperDual operator+(HyperDual a, double c) { return a + HyperDual{c}; }
HyperDual operator-(HyperDual a, double c) { return a - HyperDual{c}; }
HyperDual operator-(double c, HyperDual a) { return HyperDual{c} - a; }
HyperDual operator*(double c, HyperDual a) { return {c * a.v, c * a.d1, c * a.d2, c * a.d12}; }
HyperDual operator/(HyperDual a, double c) { return (1.0 / c) * a; }
bool operator>=(HyperDual a, double c) { return a.v >= c; }
bool operator<=(HyperDual a, double c) { return a.v <= c; }

// f(a) by the chain rule, from f, f' and f'' at a.v.
HyperDual chain(HyperDual a, double f, double df, double ddf) {
  return {f, df * a.d1, df * a.d2, df * a.d12 + ddf * a.d1 * a.d2};
}
HyperDual exp(HyperDual a) {
  const double e = std::exp(a.v);
  return chain(a, e, e, e);
}
HyperDual tanh(HyperDual a) {
  const double t = std::tanh(a.v);
  return chain(a, t, 1 - t * t, -2 * t * (1 - t * t));
}
HyperDual cos(HyperDual a) { return chain(a, std::cos(a.v), -std::sin(a.v), -std::cos(a.v)); }
HyperDual sqrt(HyperDual a) {
  const double r = std::sqrt(a.v);
  return chain(a, r, 0.5 / r, -0.25 / (r * a.v));
}
HyperDual pow(HyperDual a, int n) {
  return chain(a, std::pow(a.v, n), n * std::pow(a.v, n - 1), n * (n - 1) * std::pow(a.v, n - 2));
}

template <typename T>
T franke(T x, T y) {
  using std::exp;
  using std::pow;
  return 0.75 * exp(-(pow(9 * x - 2, 2) + pow(9 * y - 2, 2)) / 4) +
         0.75 * exp(-pow(9 * x + 1, 2) / 49 - (9 * y + 1) / 10) +
         0.5 * exp(-(pow(9 * x - 7, 2) + pow(9 * y - 3, 2)) / 4) -
         0.2 * exp(-pow(9 * x - 4, 2) - pow(9 * y - 7, 2));
}

template <typename T>
T ramp_and_mountain(T x, T y) {
  using std::cos;
  using std::pow;
  using std::sqrt;
  const T xi = 2.1 * x - 0.1;
  const T r = sqrt(pow(xi - 1.5, 2) + pow(y - 0.5, 2));
  if (y - xi >= 0.5) {
    return T{1.0};
  }
  if (y - xi >= 0.0) {
    return 2.0 * (y - xi);
  }
  if (r <= 0.25) {
    return (cos(4 * std::numbers::pi * r) + 1) / 2;
  }
  return T{0.0};
}

template <typename T>
T polynomial(T x, T y) {
  using std::pow;
  const T hx = pow(1 - x / 2, 6);
  const T hy = pow(1 - y / 2, 6);
  return hx * hy + 1000 * pow((1 - x) * x * (1 - y) * y, 3) + pow(y, 6) * hx + pow(x, 6) * hy;
}

template <typename T>
T evaluate_any(FrankeFunction function, T x, T y) {
  using std::pow;
  using std::tanh;
  switch (function) {
    case FrankeFunction::F1:
      return franke(x, y);
    case FrankeFunction::F2:
      return (tanh(9 * y - 9 * x) + 1) / 9;
    case FrankeFunction::F7:
      return ramp_and_mountain(x, y);
    case FrankeFunction::F8: {
      const T g = 0.595576 * pow(y + 3.79762, 2) - x - 10;
      return tanh(-3 * g) + 1;
    }
    case FrankeFunction::F9:
      return polynomial(x, y);
  }
  return T{0.0};
}

}  // namespace

std::string to_string(FrankeFunction function) {
  for (const auto& [f, name] : kFrankeNames) {
    if (f == function) {
      return std::string(name);
    }
  }
  return "unknown";
}

std::optional<FrankeFunction> parse_franke_function(std::string_view name) {
  if (name.size() != 2 || std::toupper(static_cast<unsigned char>(name[0])) != 'F') {
    return std::nullopt;
  }
  for (const auto& [f, n] : kFrankeNames) {
    if (n[1] == name[1]) {
      return f;
    }
  }
  return std::nullopt;
}

double evaluate(FrankeFunction function, double x, double y) {
  return evaluate_any(function, x, y);
}

Eigen::Matrix2d hessian(FrankeFunction function, double x, double y) {
  const auto second = [&](bool first_x, bool second_x) {
    const HyperDual hx{x, first_x ? 1.0 : 0.0, second_x ? 1.0 : 0.0, 0.0};
    const HyperDual hy{y, first_x ? 0.0 : 1.0, second_x ? 0.0 : 1.0, 0.0};
    return evaluate_any(function, hx, hy).d12;
  };
  Eigen::Matrix2d H;
  H(0, 0) = second(true, true);
  H(0, 1) = H(1, 0) = second(true, false);
  H(1, 1) = second(false, false);
  return H;
}

Eigen::VectorXd sample(FrankeFunction function, const Eigen::Ref<const Eigen::Matrix2Xd>& points) {
  Eigen::VectorXd values(points.cols());
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    values[i] = evaluate(function, points(0, i), points(1, i));
  }
  return values;
}

}  // namespace tessera
