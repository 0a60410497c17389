// SPDX-License-Identifier: MIT
// A problem seen in its metric's coordinates y = W x (core/scaled_problem.h, when it has
// coordinate blocks with weights), its evaluations counted: what the Newton solvers on a
// finished mesh (fold, level and Hopf curves) work on, so that their lengths, tolerances and
// minimum-norm corrections are the metric's, as the covering's are.
#pragma once

#include <Eigen/Core>
#include <memory>

#include "tessera/core/counted_problem.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/core/scaled_problem.h"

namespace tessera {

class MetricProblem {
 public:
  /// \param problem  must outlive this object.
  explicit MetricProblem(const ImplicitProblem& problem);

  /// The problem in y = W x, counted.
  const CountedProblem& counted() const { return *counted_; }
  /// W's diagonal; empty when the metric is Euclidean.
  const Eigen::VectorXd& weights() const { return weights_; }
  Eigen::VectorXd to_metric(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  Eigen::VectorXd from_metric(const Eigen::Ref<const Eigen::VectorXd>& y) const;
  /// ‖W d‖: the metric length of a difference d of points in the problem's coordinates.
  double length(const Eigen::Ref<const Eigen::VectorXd>& d) const;
  WorkCounts work() const;

 private:
  Eigen::VectorXd weights_;
  std::unique_ptr<ScaledProblem> scaled_;
  std::unique_ptr<CountedProblem> counted_;
};

}  // namespace tessera
