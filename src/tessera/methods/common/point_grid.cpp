// SPDX-License-Identifier: MIT
#include "tessera/methods/common/point_grid.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "tessera/core/error.h"

namespace tessera {

PointGrid::PointGrid(int ambient_dimension, double cell_size)
    : ambient_dimension_(ambient_dimension), view_(ambient_dimension), cell_size_(cell_size) {
  TESSERA_CHECK(cell_size > 0, "PointGrid cell size " << cell_size << " must be > 0");
}

PointGrid::PointGrid(std::shared_ptr<const AmbientSpace> space, double cell_size)
    : ambient_dimension_(space->dimension()), view_(space), cell_size_(cell_size) {
  TESSERA_CHECK(cell_size > 0, "PointGrid cell size " << cell_size << " must be > 0");
  if (space->is_distributed()) {
    space_ = std::move(space);
  }
}

Eigen::Vector3d PointGrid::cell_of(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  Eigen::Vector3d projected = view_(x);
  return (projected / cell_size_).array().floor();
}

std::int64_t PointGrid::key(const Eigen::Vector3d& cell) const {
  // 21 bits per axis: cells are hashed, so collisions of far cells only cost a distance check.
  const auto wrap = [](double c) {
    return static_cast<std::int64_t>(static_cast<std::int64_t>(c) & ((1 << 21) - 1));
  };
  return (wrap(cell(0)) << 42) | (wrap(cell(1)) << 21) | wrap(cell(2));
}

void PointGrid::insert(int id, const Eigen::Ref<const Eigen::VectorXd>& x) {
  cells_[key(cell_of(x))].push_back(id);
  ++size_;
}

void PointGrid::remove(int id, const Eigen::Ref<const Eigen::VectorXd>& x) {
  auto it = cells_.find(key(cell_of(x)));
  if (it == cells_.end()) {
    return;
  }
  auto& ids = it->second;
  const auto removed = std::remove(ids.begin(), ids.end(), id);
  size_ -= static_cast<int>(ids.end() - removed);
  ids.erase(removed, ids.end());
}

std::vector<int> PointGrid::candidates(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  const Eigen::Vector3d center = cell_of(x);
  std::vector<int> result;
  for (int dx = -1; dx <= 1; ++dx) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dz = -1; dz <= 1; ++dz) {
        auto it = cells_.find(key(center + Eigen::Vector3d(dx, dy, dz)));
        if (it != cells_.end()) {
          result.insert(result.end(), it->second.begin(), it->second.end());
        }
      }
    }
  }
  std::sort(result.begin(), result.end());
  result.erase(std::unique(result.begin(), result.end()), result.end());
  return result;
}

}  // namespace tessera
