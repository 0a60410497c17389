// SPDX-License-Identifier: MIT
#include "tessera/geometry/principal_view.h"

#include <cmath>
#include <random>

namespace tessera {

PrincipalView::PrincipalView(int ambient_dimension) : n_(ambient_dimension) {
  if (n_ <= 3) {
    return;
  }
  std::mt19937_64 generator(0x7e55e7a);  // fixed: deterministic hashing
  std::normal_distribution<double> normal;
  directions_.resize(n_, 3);
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < n_; ++i) {
      directions_(i, j) = normal(generator);
    }
  }
  orthonormalise();
}

PrincipalView::PrincipalView(std::shared_ptr<const AmbientSpace> space)
    : PrincipalView(space->dimension()) {
  if (space->is_distributed()) {
    if (n_ > 3) {
      directions_ =
          Eigen::MatrixXd(directions_.middleRows(space->first_row(), space->local_rows()));
    }
    space_ = std::move(space);  // the rows of an orthonormal start: orthonormal over the ranks
  }
}

PrincipalView::PrincipalView(int ambient_dimension,
                             const Eigen::Ref<const Eigen::MatrixXd>& points)
    : PrincipalView(ambient_dimension) {
  fit(points);
}

void PrincipalView::fit(const Eigen::Ref<const Eigen::MatrixXd>& points) {
  if (n_ <= 3 || points.cols() < 2) {
    return;
  }
  const Eigen::VectorXd mean = points.rowwise().mean();
  // (X − m)(X − m)ᵀ D without forming the n×n covariance: O(n·N) per iteration. The largest
  // spreads separate quickly; the view only needs to keep most of the spread, not to be exact.
  constexpr int kIterations = 8;
  Eigen::MatrixXd next;
  for (int iteration = 0; iteration < kIterations; ++iteration) {
    Eigen::MatrixXd coordinates;
    if (space_) {
      // Xᵀ D and mᵀ D are sums over the rows: reduced over the ranks in one call.
      Eigen::MatrixXd products(points.cols() + 1, 3);
      products.topRows(points.cols()) = points.transpose() * directions_;
      products.bottomRows(1) = mean.transpose() * directions_;
      space_->sum(products.data(), static_cast<int>(products.size()));
      coordinates = products.topRows(points.cols()) -
                    Eigen::VectorXd::Ones(points.cols()) * products.bottomRows(1);
    } else {
      coordinates = points.transpose() * directions_ -
                    Eigen::VectorXd::Ones(points.cols()) * (mean.transpose() * directions_);
    }
    next = points * coordinates - mean * coordinates.colwise().sum();
    const bool degenerate =
        space_ ? !space_->all_finite(next) || space_->frobenius_norm(next) == 0.0
               : !next.allFinite() || next.norm() == 0.0;
    if (degenerate) {
      return;  // degenerate cloud: keep the last orthonormal directions
    }
    directions_ = next;
    orthonormalise();
  }
}

Eigen::Vector3d PrincipalView::operator()(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  if (n_ > 3) {
    Eigen::Vector3d y = directions_.transpose() * x;
    if (space_) {
      space_->sum(y.data(), 3);
    }
    return y;
  }
  if (space_) {
    Eigen::Vector3d y = Eigen::Vector3d::Zero();
    for (int i = 0; i < n_; ++i) {
      y(i) = space_->coordinate(x, i);
    }
    return y;
  }
  Eigen::Vector3d y = Eigen::Vector3d::Zero();
  for (int i = 0; i < n_; ++i) {
    y(i) = x(i);
  }
  return y;
}

Eigen::Matrix3Xd PrincipalView::project(const Eigen::Ref<const Eigen::MatrixXd>& points) const {
  if (n_ > 3) {
    Eigen::Matrix3Xd y = directions_.transpose() * points;
    if (space_) {
      space_->sum(y.data(), static_cast<int>(y.size()));
    }
    return y;
  }
  if (space_) {
    Eigen::Matrix3Xd y = Eigen::Matrix3Xd::Zero(3, points.cols());
    for (Eigen::Index j = 0; j < points.cols(); ++j) {
      y.col(j) = (*this)(points.col(j));
    }
    return y;
  }
  Eigen::Matrix3Xd y = Eigen::Matrix3Xd::Zero(3, points.cols());
  y.topRows(n_) = points.topRows(n_);
  return y;
}

// Gram–Schmidt, twice for stability; a column that vanishes is replaced by a unit vector.
void PrincipalView::orthonormalise() {
  for (int pass = 0; pass < 2; ++pass) {
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < j; ++k) {
        const double overlap = space_ ? space_->dot(directions_.col(k), directions_.col(j))
                                      : directions_.col(k).dot(directions_.col(j));
        directions_.col(j) -= overlap * directions_.col(k);
      }
      const double norm = space_ ? space_->norm(directions_.col(j)) : directions_.col(j).norm();
      if (norm > 0 && std::isfinite(norm)) {
        directions_.col(j) /= norm;
      } else {
        directions_.col(j).setZero();
        if (!space_ || space_->holds_row(j)) {
          directions_(space_ ? j - space_->first_row() : j, j) = 1.0;
        }
      }
    }
  }
}

}  // namespace tessera
