// SPDX-License-Identifier: MIT
// A uniform hash grid over a fixed 3-D projection of R^n for "which vertices are near x" queries.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace tessera {

/// The 3×n matrix with orthonormal rows that spatial grids bucket points of R^n by: the identity
/// for n ≤ 3, a fixed pseudo-random projection otherwise. ‖P(x − y)‖ ≤ ‖x − y‖.
Eigen::MatrixXd grid_projection(int ambient_dimension);

/// Points are bucketed by a 3-D projection P·x (P has orthonormal rows; the identity when n = 3).
/// Since ‖P(x − y)‖ ≤ ‖x − y‖, every point within `radius` of a query lies in the 27 cells
/// around it; candidates are then checked with the true distance in R^n. Cost per query is
/// O(1) for meshes of bounded density, independent of the number of points.
class PointGrid {
 public:
  PointGrid(int ambient_dimension, double cell_size);

  void insert(int id, const Eigen::Ref<const Eigen::VectorXd>& x);
  void remove(int id, const Eigen::Ref<const Eigen::VectorXd>& x);
  /// Ids of inserted points whose stored position is within `radius` ≤ cell_size of x,
  /// in increasing id order (deterministic). `position(id)` returns the stored point.
  template <typename PositionFunction>
  std::vector<int> near(const Eigen::Ref<const Eigen::VectorXd>& x, double radius,
                        PositionFunction position) const;

 private:
  std::int64_t key(const Eigen::Vector3d& cell) const;
  Eigen::Vector3d cell_of(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  std::vector<int> candidates(const Eigen::Ref<const Eigen::VectorXd>& x) const;

  Eigen::MatrixXd projection_;  // 3×n
  double cell_size_;
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
};

template <typename PositionFunction>
std::vector<int> PointGrid::near(const Eigen::Ref<const Eigen::VectorXd>& x, double radius,
                                 PositionFunction position) const {
  std::vector<int> result;
  for (int id : candidates(x)) {
    if ((position(id) - x).norm() <= radius) {
      result.push_back(id);
    }
  }
  return result;
}

}  // namespace tessera
