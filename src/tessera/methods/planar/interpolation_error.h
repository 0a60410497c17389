// SPDX-License-Identifier: MIT
// Error of the piecewise linear interpolant on a planar triangulation against a known
// function, measured on a uniform grid.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>

#include "tessera/methods/planar/planar_triangulation.h"

namespace tessera {

struct InterpolationErrorOptions {
  int grid_size = 33;                  ///< grid_size × grid_size points (Malcolm: 33×33)
  Eigen::Vector2d lower = {0.0, 0.0};  ///< the unit square, as in the report
  Eigen::Vector2d upper = {1.0, 1.0};
  bool is_valid(std::string* why) const;
};

/// Pointwise error |f_T − f| over the grid points inside the triangulation.
struct InterpolationError {
  double mean = 0.0;  ///< the figure of Malcolm's tables
  double rms = 0.0;
  double max = 0.0;
  int points_inside = 0;
  int points_outside = 0;  ///< grid points outside the convex hull of the data: left out
};

/// Value at (x, y) of the piecewise linear interpolant of the triangulation's values, or
/// nullopt outside the triangulation. Points on an edge (within a relative 1e-12 in
/// barycentric coordinates) count as inside. O(triangles).
std::optional<double> interpolate(const PlanarTriangulation& triangulation, double x, double y);

/// \param function f(x, y), the function the values were sampled from.
/// \throw InvalidArgument if the options are invalid.
InterpolationError interpolation_error(const PlanarTriangulation& triangulation,
                                       const std::function<double(double, double)>& function,
                                       const InterpolationErrorOptions& options = {});

}  // namespace tessera
