// SPDX-License-Identifier: MIT
// Every covering method on the same problem, each mesh measured independently of the method
// that made it: `tessera compare`'s table and the bindings' tessera.compare.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tessera/methods/covering_methods.h"
#include "tessera/problems/problem_setup.h"

namespace tessera {

/// One method's row of the table, measured independently of the method.
struct CompareRow {
  std::string method;
  CoveringSummary run;   ///< termination, message, wall time, tolerance asked for
  int vertex_count = 0;  ///< vertices referenced by a triangle
  int triangle_count = 0;
  /// The larger of the centroid and edge-midpoint distances to M, measured by projecting those
  /// points (not produced by any method) onto M.
  double max_distance = 0.0;
  double min_angle_degrees = 0.0;
  int euler_characteristic = 0;
  bool valid = false;  ///< validate(mesh, problem, domain): no defect
  bool passes() const { return valid && run.is_complete(); }
};

struct CompareReport {
  std::vector<CompareRow> rows;  ///< covering_methods()'s order, the default first
  /// The distance bound every method ran to: the settings' tolerance, or default_tolerance of
  /// the problem where they give none (front and bezier have no bound of their own, so that
  /// their rows would not be comparable with the atlas's).
  double tolerance = 0.0;
  std::optional<int> expected_euler_characteristic;
  bool passes() const;  ///< every row passes (the CLI's exit status 0)
};

/// Runs every covering method on a fresh make_setup() each (`tessera compare` and the
/// bindings' tessera.compare), all to the same tolerance (CompareReport::tolerance); `on_row`
/// (optional) sees each row as soon as it is measured.
CompareReport compare_methods(const std::function<ProblemSetup()>& make_setup,
                              const MethodSettings& settings,
                              const std::function<void(const CompareRow&)>& on_row = {});

}  // namespace tessera
