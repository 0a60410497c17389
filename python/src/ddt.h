// SPDX-License-Identifier: MIT
// `tessera ddt` for the bindings, in its own file so that module.cpp includes no header of the
// planar methods (whose Delaunay triangulation is CGAL's).
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
  TriangleMesh mesh;           ///< in R^3: x, y, value
  std::vector<double> values;  ///< the data value of every vertex
  std::string summary_json;    ///< criterion, swaps, and the interpolation error for a function
};

/// `tessera ddt --all-criteria [--orders K] [--compare-report 33|100]`.
struct AllCriteriaOptions {
  int orders = 1;          ///< sweep orders tried per row (index order, then random ones)
  int compare_report = 0;  ///< 33 or 100: Malcolm's Table 1 or 2 value beside each row
};

/// Delaunay triangulation of the points, then local optimisation by the criterion (Malcolm).
/// \param points 2×N. \param values N data values, or none when options.function is given.
/// \throw InvalidArgument with the CLI's messages for an unknown function or criterion.
DataDependentTriangulation triangulate_data(const Eigen::Matrix2Xd& points,
                                            const std::optional<Eigen::VectorXd>& values,
                                            const DataDependentOptions& options);

/// One triangulation per row of the CLI's --all-criteria table (delaunay, mwt3d, abn, jnd, pf,
/// pd with l1 and l2, equid when options.function is given), in the table's order. Each summary
/// is triangulate_data's (its "criterion" is the table's label) with "norm", and with a function
/// "orders" (the spread of the mean error over the sweep orders) and "report" (Malcolm's value) as
/// asked. options.criterion and options.norm are not used.
std::vector<DataDependentTriangulation> triangulate_all_criteria(
    const Eigen::Matrix2Xd& points, const std::optional<Eigen::VectorXd>& values,
    const DataDependentOptions& options, const AllCriteriaOptions& all);

}  // namespace tessera::python
