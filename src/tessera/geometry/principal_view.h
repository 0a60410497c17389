// SPDX-License-Identifier: MIT
// A three-dimensional orthonormal view of R^n for spatial hashing: the coordinates for n ≤ 3,
// else the three principal directions of a cloud of points.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <memory>

#include "tessera/core/ambient_space.h"

namespace tessera {

/// P: R^n → R³ with orthonormal rows, so ‖P(x − y)‖ ≤ ‖x − y‖ and a hash grid over P·x never
/// misses a neighbour. Any such view is correct; a good one keeps the points' spread. A random
/// view of R^n shrinks a surface's extent by about √(3/n) (at n = 1000 every cell would hold
/// hundreds of points), while M of a discretised PDE lies close to a few directions, which the
/// principal directions find. They come from subspace iteration started at three directions
/// drawn from a fixed seed, so that every run and every platform hashes alike.
class PrincipalView {
 public:
  /// The coordinates (n ≤ 3, padded with zeros) or, for n > 3, the fixed pseudo-random start.
  explicit PrincipalView(int ambient_dimension);
  /// Fitted to the columns of `points` (n × N).
  PrincipalView(int ambient_dimension, const Eigen::Ref<const Eigen::MatrixXd>& points);
  /// For points given by this rank's rows of a distributed space (SPMD): the same view on every
  /// rank and in one process (the directions are the rows of the same n×3 start).
  explicit PrincipalView(std::shared_ptr<const AmbientSpace> space);

  /// Refits to the points' principal directions; a degenerate cloud keeps the current view.
  void fit(const Eigen::Ref<const Eigen::MatrixXd>& points);
  /// Refits to an evenly spaced sample of at most 256 of `count` points, point(i) the i-th: a
  /// few hundred show the spread as well as all of them, and keep a refit at n = 10⁵ cheap.
  template <typename PointFunction>
  void fit_sample(int count, PointFunction point);

  Eigen::Vector3d operator()(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  /// The view's directions (n×3, orthonormal columns; empty for n ≤ 3), and the same set
  /// again: a checkpoint keeps a fitted view, which the points alone do not decide.
  const Eigen::MatrixXd& directions() const { return directions_; }
  void set_directions(const Eigen::MatrixXd& directions) { directions_ = directions; }
  /// The view of every column of `points` (n × N), in one product.
  Eigen::Matrix3Xd project(const Eigen::Ref<const Eigen::MatrixXd>& points) const;

 private:
  void orthonormalise();

  int n_;
  Eigen::MatrixXd directions_;  // n×3, orthonormal columns (n > 3 only); the local rows if split
  std::shared_ptr<const AmbientSpace> space_;  // null: in one process
};

template <typename PointFunction>
void PrincipalView::fit_sample(int count, PointFunction point) {
  // At most 256 points and 64 MB of them: at n = 10⁵ 256 points are 205 MB, held during the
  // fit at the atlas's peak; three directions need far fewer.
  constexpr int kMaxSample = 256;
  constexpr double kMaxSampleBytes = 64.0 * (1 << 20);
  if (n_ <= 3 || count < 2) {
    return;
  }
  const int max_sample = std::max(
      32, std::min(kMaxSample, static_cast<int>(kMaxSampleBytes / (8.0 * directions_.rows()))));
  const int stride = (count + max_sample - 1) / max_sample;
  Eigen::MatrixXd sample(directions_.rows(), (count + stride - 1) / stride);
  for (int i = 0, column = 0; i < count; i += stride, ++column) {
    sample.col(column) = point(i);
  }
  fit(sample);
}

/// When a growing set of points should refit its view: at 32 points, then each time the count
/// doubles, so that refits cost O(n) per point in all.
class RefitSchedule {
 public:
  bool due(int count) {
    if (count < next_) {
      return false;
    }
    next_ = 2 * count;
    return true;
  }
  /// The count at which the next refit is due (a checkpoint keeps it).
  int next() const { return next_; }
  void set_next(int next) { next_ = next; }

 private:
  int next_ = 32;
};

}  // namespace tessera
