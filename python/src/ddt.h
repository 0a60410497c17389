// SPDX-License-Identifier: MIT
// `tessera ddt` for the bindings, in its own file: the planar methods' SwapCriterion (a class)
// and mesh improvement's SwapCriterion (an enum) cannot meet in one translation unit.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "tessera/geometry/triangle_mesh.h"

namespace tessera::python {

struct DataDependentOptions {
  std::string function;   ///< "F1" … "F9" (Franke's), sampled at the points; empty: values given
  std::string criterion;  ///< delaunay, mwt, maxmin3d, mwt3d, abn, jnd, pf, pd or equid
  std::string norm;       ///< l1, l2 or lex
  std::string test;       ///< local or global
  int grid = 33;          ///< interpolation error on grid × grid points of [0,1]²
  unsigned sweep_order_seed = 0;
};

struct DataDependentTriangulation {
  TriangleMesh mesh;         ///< in R^3: x, y, value
  std::vector<double> values;  ///< the data value of every vertex
  std::string summary_json;  ///< criterion, swaps, and the interpolation error for a function
};

/// Delaunay triangulation of the points, then local optimisation by the criterion (Malcolm).
/// \param points 2×N. \param values N data values, or none when options.function is given.
/// \throw InvalidArgument with the CLI's messages for an unknown function or criterion.
DataDependentTriangulation triangulate_data(const Eigen::Matrix2Xd& points,
                                            const std::optional<Eigen::VectorXd>& values,
                                            const DataDependentOptions& options);

}  // namespace tessera::python
