// SPDX-License-Identifier: MIT
// Error of the piecewise linear interpolant on a planar triangulation against a known
// function, measured on a uniform grid.
#include "tessera/methods/planar/interpolation_error.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "tessera/core/error.h"

namespace tessera {
namespace {

// Grid points on the hull (the corners and sides of the unit square are typical) must count
// as inside despite rounding in the barycentric coordinates.
constexpr double kBarycentricSlack = 1e-12;

}  // namespace

bool InterpolationErrorOptions::is_valid(std::string* why) const {
  std::ostringstream message;
  if (grid_size < 2) {
    message << "InterpolationErrorOptions::grid_size = " << grid_size << " must be >= 2";
  } else if (!(lower.x() < upper.x() && lower.y() < upper.y())) {
    message << "InterpolationErrorOptions: lower = (" << lower.x() << ", " << lower.y()
            << ") must be below upper = (" << upper.x() << ", " << upper.y()
            << ") in both coordinates";
  } else {
    return true;
  }
  if (why != nullptr) {
    *why = message.str();
  }
  return false;
}

std::optional<double> interpolate(const PlanarTriangulation& triangulation, double x, double y) {
  const Eigen::Vector2d p(x, y);
  for (const Triangle& t : triangulation.triangles()) {
    const Eigen::Vector2d a = triangulation.point(t[0]);
    const Eigen::Vector2d b = triangulation.point(t[1]);
    const Eigen::Vector2d c = triangulation.point(t[2]);
    const double area = orientation(a, b, c);
    const double la = orientation(p, b, c) / area;
    const double lb = orientation(a, p, c) / area;
    const double lc = 1.0 - la - lb;
    if (la >= -kBarycentricSlack && lb >= -kBarycentricSlack && lc >= -kBarycentricSlack) {
      return la * triangulation.value(t[0]) + lb * triangulation.value(t[1]) +
             lc * triangulation.value(t[2]);
    }
  }
  return std::nullopt;
}

InterpolationError interpolation_error(const PlanarTriangulation& triangulation,
                                       const std::function<double(double, double)>& function,
                                       const InterpolationErrorOptions& options) {
  std::string why;
  TESSERA_CHECK(options.is_valid(&why), why);
  InterpolationError error;
  double sum = 0.0;
  double sum_of_squares = 0.0;
  const int m = options.grid_size;
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) {
      const double x = options.lower.x() + (options.upper.x() - options.lower.x()) * i / (m - 1);
      const double y = options.lower.y() + (options.upper.y() - options.lower.y()) * j / (m - 1);
      const std::optional<double> value = interpolate(triangulation, x, y);
      if (!value) {
        ++error.points_outside;
        continue;
      }
      const double e = std::abs(*value - function(x, y));
      ++error.points_inside;
      sum += e;
      sum_of_squares += e * e;
      error.max = std::max(error.max, e);
    }
  }
  if (error.points_inside > 0) {
    error.mean = sum / error.points_inside;
    error.rms = std::sqrt(sum_of_squares / error.points_inside);
  }
  return error;
}

}  // namespace tessera
