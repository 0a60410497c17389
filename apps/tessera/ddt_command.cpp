// SPDX-License-Identifier: MIT
#include "ddt_command.h"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <iterator>
#include <memory>
#include <optional>

#include "tessera/core/error.h"
#include "tessera/io/mesh_io.h"
#include "tessera/io/output_checks.h"
#include "tessera/io/scattered_data_csv.h"
#include "tessera/methods/planar/delaunay.h"
#include "tessera/methods/planar/equidistribution_criterion.h"
#include "tessera/methods/planar/franke_functions.h"
#include "tessera/methods/planar/interpolation_error.h"
#include "tessera/methods/planar/local_optimisation.h"
#include "tessera/methods/planar/malcolm_tables.h"

namespace tessera::app {
namespace {

CostOrdering parse_norm(const std::string& norm) {
  if (norm == "l1") {
    return CostOrdering::L1;
  }
  if (norm == "l2") {
    return CostOrdering::L2;
  }
  return CostOrdering::Lexicographic;
}

// One row of the error table: the triangulation after LOP with `criterion_name`.
struct Row {
  std::string label;
  InterpolationError error;
  std::string swaps;
};

Row optimise_and_measure(const PlanarTriangulation& start, const std::string& criterion_name,
                         CostOrdering ordering, SwapTest test,
                         const std::optional<FrankeFunction>& function, int grid,
                         PlanarTriangulation* result, unsigned sweep_order_seed = 0) {
  PlanarTriangulation triangulation = start;
  LocalOptimisationOptions options;
  options.ordering = ordering;
  options.test = test;
  options.sweep_order_seed = sweep_order_seed;
  LocalOptimisationSummary summary;
  if (criterion_name == "equid") {
    TESSERA_CHECK(function.has_value(),
                  "--criterion equid needs --function: it uses the function's second derivatives");
    const FrankeFunction f = *function;
    const EquidistributionCriterion equid([f](double x, double y) { return hessian(f, x, y); });
    summary = optimise_locally(triangulation, equid, options);
  } else {
    const auto kind = parse_criterion(criterion_name);
    TESSERA_CHECK(kind.has_value(), "--criterion '" << criterion_name
                                                    << "' is unknown; criteria: delaunay, mwt, "
                                                       "maxmin3d, mwt3d, abn, jnd, pf, pd, equid");
    options.criterion = *kind;
    summary = optimise_locally(triangulation, options);
  }
  Row row;
  row.label = summary.criterion.empty() ? criterion_name : summary.criterion;
  row.swaps = summary.brief_report();
  if (function) {
    const FrankeFunction f = *function;
    InterpolationErrorOptions error_options;
    error_options.grid_size = grid;
    row.error = interpolation_error(
        triangulation, [f](double x, double y) { return evaluate(f, x, y); }, error_options);
  }
  if (result != nullptr) {
    *result = std::move(triangulation);
  }
  return row;
}

void print_row(const Row& row, bool has_function) {
  if (has_function) {
    std::printf("%-16s mean %.5f  rms %.5f  max %.5f   (%s)\n", row.label.c_str(), row.error.mean,
                row.error.rms, row.error.max, row.swaps.c_str());
  } else {
    std::printf("%-16s (%s)\n", row.label.c_str(), row.swaps.c_str());
  }
}

}  // namespace

int run_ddt(const DdtCommand& command) {
  if (!command.output.empty()) {
    check_mesh_output(command.output);
    check_replaces_same_kind("-o", command.output, TesseraFileKind::Mesh);
  }
  TESSERA_CHECK(command.function.empty() || command.value_column.empty(),
                "give either --function or --value-column, not both");
  std::optional<FrankeFunction> function;
  if (!command.function.empty()) {
    function = parse_franke_function(command.function);
    TESSERA_CHECK(function.has_value(), "--function '" << command.function
                                                       << "' is unknown; functions: F1, F2, "
                                                          "F7, F8, F9");
  }
  ScatteredDataCsvOptions csv;
  csv.value_column = command.value_column;
  const ScatteredData data = read_scattered_data_csv(command.points, csv);
  Eigen::VectorXd values;
  if (function) {
    values = sample(*function, data.points);
  } else {
    TESSERA_CHECK(data.has_values(), command.points
                                         << ": no value column; give --function F1|F2|F7|F8|F9 "
                                            "or --value-column NAME");
    values = data.values;
  }
  DelaunaySummary delaunay;
  const PlanarTriangulation start = delaunay_triangulation(data.points, values, &delaunay);
  if (delaunay.cocircular_edges > 0) {
    // Either diagonal is Delaunay there; say which rule chose (see delaunay.h).
    std::printf(
        "%d cocircular quadrilateral(s): diagonal avoids the later node in input order "
        "(%d swap(s) from CGAL's choice)\n",
        delaunay.cocircular_edges, delaunay.rule_swaps);
  }
  const SwapTest test = command.test == "local" ? SwapTest::Local : SwapTest::Global;
  if (command.all_criteria) {
    std::printf("%d points, %s test; mean, RMS and max of |f_T − f| on a %d×%d grid of [0,1]²\n",
                static_cast<int>(data.points.cols()), command.test.c_str(), command.grid,
                command.grid);
    const bool with_report = command.compare_report == 33 || command.compare_report == 100;
    if (command.orders > 1) {
      std::printf("spread over %d sweep orders (index order, then random permutations)\n",
                  command.orders);
    }
    for (std::size_t r = 0; r < kAllCriteriaRowCount; ++r) {
      const AllCriteriaRow& row = kAllCriteriaRows[r];
      if (std::string(row.criterion) == "equid" && !function) {
        continue;
      }
      Row measured = optimise_and_measure(start, row.criterion, row.ordering, test, function,
                                          command.grid, nullptr);
      if (!function) {
        print_row(measured, false);
        continue;
      }
      double lowest = measured.error.mean;
      double highest = measured.error.mean;
      for (int seed = 1; seed < command.orders; ++seed) {
        const Row other = optimise_and_measure(start, row.criterion, row.ordering, test, function,
                                               command.grid, nullptr, static_cast<unsigned>(seed));
        lowest = std::min(lowest, other.error.mean);
        highest = std::max(highest, other.error.mean);
      }
      std::printf("%-16s mean %.5f", measured.label.c_str(), measured.error.mean);
      if (command.orders > 1) {
        std::printf("  orders %.5f … %.5f", lowest, highest);
      }
      if (with_report) {
        const double value = malcolm_table_value(command.compare_report, r, *function);
        std::printf("  report %.5f", value);
        if (command.orders > 1) {
          std::printf(" (%s)",
                      is_in_spread(value, lowest, highest) ? "in spread" : "outside spread");
        }
      }
      std::printf("  rms %.5f  max %.5f\n", measured.error.rms, measured.error.max);
    }
    return 0;
  }
  PlanarTriangulation result;
  const Row row = optimise_and_measure(start, command.criterion, parse_norm(command.norm), test,
                                       function, command.grid, &result);
  print_row(row, function.has_value());
  if (function) {
    std::printf("grid points inside the hull %d, outside (left out) %d\n", row.error.points_inside,
                row.error.points_outside);
  }
  if (!command.output.empty()) {
    MeshFileOptions options;
    options.vertex_scalars.push_back(
        {"value", std::vector<double>(result.values().data(),
                                      result.values().data() + result.values().size())});
    write_mesh(command.output, result.to_mesh(), options);
    std::cout << "wrote " << command.output << "\n";
  }
  return 0;
}

}  // namespace tessera::app
