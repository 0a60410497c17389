// SPDX-License-Identifier: MIT
#include "ddt.h"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "tessera/core/error.h"
#include "tessera/methods/planar/delaunay.h"
#include "tessera/methods/planar/equidistribution_criterion.h"
#include "tessera/methods/planar/franke_functions.h"
#include "tessera/methods/planar/interpolation_error.h"
#include "tessera/methods/planar/local_optimisation.h"
#include "tessera/methods/planar/malcolm_tables.h"

namespace tessera::python {

namespace {

DataDependentTriangulation triangulate(const Eigen::Matrix2Xd& points,
                                       const std::optional<Eigen::VectorXd>& values,
                                       const DataDependentOptions& options, nlohmann::json& json) {
  std::optional<FrankeFunction> function;
  if (!options.function.empty()) {
    function = parse_franke_function(options.function);
    TESSERA_CHECK(function.has_value(), "function '" << options.function
                                                     << "' is unknown; functions: F1, F2, F7, "
                                                        "F8, F9");
  }
  TESSERA_CHECK(function || values,
                "ddt needs values, or function F1|F2|F7|F8|F9 to sample at the points");
  TESSERA_CHECK(!(function && values), "give either values or function, not both");
  std::optional<CriterionKind> kind;
  if (options.criterion != "equid") {
    kind = parse_criterion(options.criterion);
    TESSERA_CHECK(kind.has_value(), "criterion '" << options.criterion
                                                  << "' is unknown; criteria: delaunay, mwt, "
                                                     "maxmin3d, mwt3d, abn, jnd, pf, pd, equid");
  }
  TESSERA_CHECK(kind || function,
                "criterion equid needs function: it uses the function's second derivatives");
  const Eigen::VectorXd data = function ? sample(*function, points) : *values;
  TESSERA_CHECK(data.size() == points.cols(),
                "ddt: " << data.size() << " values for " << points.cols() << " points");
  DelaunaySummary delaunay;
  PlanarTriangulation triangulation = delaunay_triangulation(points, data, &delaunay);
  LocalOptimisationOptions optimisation;
  optimisation.ordering = options.norm == "l1"   ? CostOrdering::L1
                          : options.norm == "l2" ? CostOrdering::L2
                                                 : CostOrdering::Lexicographic;
  optimisation.test = options.test == "local" ? SwapTest::Local : SwapTest::Global;
  optimisation.sweep_order_seed = options.sweep_order_seed;
  LocalOptimisationSummary summary;
  if (kind) {
    optimisation.criterion = *kind;
    summary = optimise_locally(triangulation, optimisation);
  } else {
    const FrankeFunction f = *function;
    const EquidistributionCriterion equid([f](double x, double y) { return hessian(f, x, y); });
    summary = optimise_locally(triangulation, equid, optimisation);
  }
  json = {{"criterion", summary.criterion.empty() ? options.criterion : summary.criterion},
          {"swaps", summary.brief_report()},
          {"cocircular_edges", delaunay.cocircular_edges},
          {"vertex_count", triangulation.vertex_count()},
          {"triangle_count", triangulation.triangle_count()}};
  if (function) {
    const FrankeFunction f = *function;
    InterpolationErrorOptions error_options;
    error_options.grid_size = options.grid;
    const InterpolationError error = interpolation_error(
        triangulation, [f](double x, double y) { return evaluate(f, x, y); }, error_options);
    json["error"] = {{"mean", error.mean},
                     {"rms", error.rms},
                     {"max", error.max},
                     {"grid", options.grid},
                     {"points_inside", error.points_inside},
                     {"points_outside", error.points_outside}};
  }
  DataDependentTriangulation result;
  const Eigen::VectorXd& z = triangulation.values();
  result.values.assign(z.data(), z.data() + z.size());
  result.mesh = triangulation.to_mesh();
  return result;
}

}  // namespace

DataDependentTriangulation triangulate_data(const Eigen::Matrix2Xd& points,
                                            const std::optional<Eigen::VectorXd>& values,
                                            const DataDependentOptions& options) {
  nlohmann::json json;
  DataDependentTriangulation result = triangulate(points, values, options, json);
  result.summary_json = json.dump(2);
  return result;
}

std::vector<DataDependentTriangulation> triangulate_all_criteria(
    const Eigen::Matrix2Xd& points, const std::optional<Eigen::VectorXd>& values,
    const DataDependentOptions& options, const AllCriteriaOptions& all) {
  const bool has_function = !options.function.empty();
  std::optional<FrankeFunction> function;
  if (has_function) {
    function = parse_franke_function(options.function);
    TESSERA_CHECK(function.has_value(), "function '" << options.function
                                                     << "' is unknown; functions: F1, F2, F7, "
                                                        "F8, F9");
  }
  TESSERA_CHECK(all.orders >= 1, "orders: " << all.orders << " is not >= 1");
  TESSERA_CHECK(all.compare_report == 0 || all.compare_report == 33 || all.compare_report == 100,
                "compare_report: " << all.compare_report << " is not 33 or 100");
  std::vector<DataDependentTriangulation> results;
  for (std::size_t r = 0; r < kAllCriteriaRowCount; ++r) {
    const AllCriteriaRow& row = kAllCriteriaRows[r];
    if (std::string(row.criterion) == "equid" && !has_function) {
      continue;  // as the CLI: equid needs the function's second derivatives
    }
    DataDependentOptions row_options = options;
    row_options.criterion = row.criterion;
    row_options.norm = row.norm;
    row_options.sweep_order_seed = 0;
    nlohmann::json json;
    DataDependentTriangulation result = triangulate(points, values, row_options, json);
    json["norm"] = row.norm;
    if (function) {
      const double mean = json["error"]["mean"].get<double>();
      double lowest = mean;
      double highest = mean;
      for (int seed = 1; seed < all.orders; ++seed) {
        row_options.sweep_order_seed = static_cast<unsigned>(seed);
        nlohmann::json other;
        triangulate(points, values, row_options, other);
        lowest = std::min(lowest, other["error"]["mean"].get<double>());
        highest = std::max(highest, other["error"]["mean"].get<double>());
      }
      if (all.orders > 1) {
        json["orders"] = {
            {"count", all.orders}, {"lowest_mean", lowest}, {"highest_mean", highest}};
      }
      if (all.compare_report != 0) {
        const double value = malcolm_table_value(all.compare_report, r, *function);
        json["report"] = {{"table", all.compare_report == 33 ? 1 : 2}, {"mean", value}};
        if (all.orders > 1) {
          json["report"]["in_spread"] = is_in_spread(value, lowest, highest);
        }
      }
    }
    result.summary_json = json.dump(2);
    results.push_back(std::move(result));
  }
  return results;
}

}  // namespace tessera::python
