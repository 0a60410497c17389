// SPDX-License-Identifier: MIT
// A uniform hash grid over a fixed 3-D projection of R^n for "which vertices are near x" queries.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "tessera/core/ambient_space.h"
#include "tessera/geometry/principal_view.h"

namespace tessera {

/// Points are bucketed by a 3-D view P·x (PrincipalView: orthonormal rows, the identity when
/// n = 3, refitted to the points' principal directions as their number doubles).
/// Since ‖P(x − y)‖ ≤ ‖x − y‖, every point within `radius` of a query lies in the 27 cells
/// around it; candidates are then checked with the true distance in R^n. Cost per query is
/// O(1) for meshes of bounded density, independent of the number of points.
class PointGrid {
 public:
  PointGrid(int ambient_dimension, double cell_size);
  /// For points given by this rank's rows of `space` (SPMD; all of R^n in one process, where
  /// this is PointGrid(n, cell_size)): the view and the distances are reductions over the
  /// ranks, so every rank finds the same ids. Every call is then collective.
  PointGrid(std::shared_ptr<const AmbientSpace> space, double cell_size);

  void insert(int id, const Eigen::Ref<const Eigen::VectorXd>& x);
  void remove(int id, const Eigen::Ref<const Eigen::VectorXd>& x);
  /// Refits the view to the stored points and rehashes them when their number has doubled
  /// since the last fit (O(n) per point in all). `position(id)` returns the stored point.
  template <typename PositionFunction>
  void refit_if_due(PositionFunction position);
  /// Ids of inserted points whose stored position is within `radius` ≤ cell_size of x,
  /// in increasing id order (deterministic). `position(id)` returns the stored point.
  /// The view and the refit schedule: with the ids and their points, what decides the grid's
  /// answers (a checkpoint keeps them; the cells follow by inserting the ids again).
  const Eigen::MatrixXd& view_directions() const { return view_.directions(); }
  int next_refit() const { return schedule_.next(); }
  /// Empties the grid and sets its view and schedule (as view_directions and next_refit gave).
  void reset(const Eigen::MatrixXd& view_directions, int next_refit) {
    cells_.clear();
    size_ = 0;
    view_.set_directions(view_directions);
    schedule_.set_next(next_refit);
  }
  int size() const { return size_; }
  template <typename PositionFunction>
  std::vector<int> near(const Eigen::Ref<const Eigen::VectorXd>& x, double radius,
                        PositionFunction position) const;

 private:
  std::int64_t key(const Eigen::Vector3d& cell) const;
  Eigen::Vector3d cell_of(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  std::vector<int> candidates(const Eigen::Ref<const Eigen::VectorXd>& x) const;

  int ambient_dimension_;  // n, also when the points are split
  PrincipalView view_;
  std::shared_ptr<const AmbientSpace> space_;  // null: in one process
  RefitSchedule schedule_;
  int size_ = 0;
  double cell_size_;
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
};

template <typename PositionFunction>
void PointGrid::refit_if_due(PositionFunction position) {
  if (ambient_dimension_ <= 3 || !schedule_.due(size_)) {
    return;
  }
  std::vector<int> ids;
  ids.reserve(size_);
  for (const auto& [cell, members] : cells_) {
    ids.insert(ids.end(), members.begin(), members.end());
  }
  std::sort(ids.begin(), ids.end());  // deterministic sample, whatever the hash order
  view_.fit_sample(static_cast<int>(ids.size()), [&](int i) { return position(ids[i]); });
  cells_.clear();
  size_ = 0;
  for (int id : ids) {
    insert(id, position(id));
  }
}

template <typename PositionFunction>
std::vector<int> PointGrid::near(const Eigen::Ref<const Eigen::VectorXd>& x, double radius,
                                 PositionFunction position) const {
  std::vector<int> result;
  const std::vector<int> found = candidates(x);
  if (!space_) {
    for (int id : found) {
      if ((position(id) - x).norm() <= radius) {
        result.push_back(id);
      }
    }
    return result;
  }
  // Split points: every candidate's squared distance in one reduction.
  std::vector<double> squares(found.size());
  for (std::size_t k = 0; k < found.size(); ++k) {
    squares[k] = (position(found[k]) - x).squaredNorm();
  }
  if (!squares.empty()) {
    space_->sum(squares.data(), static_cast<int>(squares.size()));
  }
  for (std::size_t k = 0; k < found.size(); ++k) {
    if (std::sqrt(squares[k]) <= radius) {
      result.push_back(found[k]);
    }
  }
  return result;
}

}  // namespace tessera
