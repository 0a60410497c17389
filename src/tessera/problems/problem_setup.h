// SPDX-License-Identifier: MIT
// A problem ready to be covered: F, a start point, the domain and what is known about M.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>

#include "tessera/core/domain.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/problems/view.h"

namespace tessera {

/// Everything a covering method needs besides its options. Built by the catalogue
/// (make_catalogue_problem) or from a problem file (load_problem_file).
struct ProblemSetup {
  std::unique_ptr<ImplicitProblem> problem;
  Eigen::VectorXd start;  ///< n-vector near M; the method first projects it onto M
  Domain domain;          ///< polyhedral domain S; unbounded when it has no half-spaces
  double suggested_step = 0.1;  ///< a typical edge length that resolves M, in ambient units
  std::string description;      ///< one line for reports
  /// Euler characteristic of the component of M ∩ S that contains the start, when known
  /// (2 for a sphere, 0 for a torus, 1 for a disk). Used by `tessera check` and the tests.
  std::optional<int> expected_euler_characteristic;
  /// Exact area of that component, when known (used by the convergence tests and reports).
  std::optional<double> exact_area;
  /// The view the surface is written in unless another is asked for (a problem file's `view`
  /// line); none: default_view(*problem), which is every coordinate unless n is large.
  std::optional<View> view;
};

}  // namespace tessera
