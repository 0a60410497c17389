// SPDX-License-Identifier: MIT
#include "tessera/core/ambient_space.h"

#include <algorithm>
#include <cmath>

#include "tessera/core/error.h"

namespace tessera {

AmbientSpace::AmbientSpace(int dimension) : AmbientSpace(dimension, 0, dimension, dimension - 2) {}

AmbientSpace::AmbientSpace(int dimension, int first_row, int local_rows, int local_equations)
    : dimension_(dimension),
      first_row_(first_row),
      local_rows_(local_rows),
      local_equations_(local_equations) {}

void AmbientSpace::sum(double* /*values*/, int /*count*/) const {}

void AmbientSpace::maximum(double* /*values*/, int /*count*/) const {}

void AmbientSpace::gather_to_root(const double* local, int count, double* whole) const {
  std::copy_n(local, static_cast<std::size_t>(local_rows_) * static_cast<std::size_t>(count),
              whole);
}

double AmbientSpace::dot(const Eigen::Ref<const Eigen::VectorXd>& a,
                         const Eigen::Ref<const Eigen::VectorXd>& b) const {
  double value = a.dot(b);
  sum(&value, 1);
  return value;
}

double AmbientSpace::squared_norm(const Eigen::Ref<const Eigen::VectorXd>& a) const {
  double value = a.squaredNorm();
  sum(&value, 1);
  return value;
}

double AmbientSpace::norm(const Eigen::Ref<const Eigen::VectorXd>& a) const {
  if (!is_distributed()) {
    return a.norm();  // Eigen's own (the serial results stay what they were)
  }
  return std::sqrt(squared_norm(a));
}

double AmbientSpace::distance(const Eigen::Ref<const Eigen::VectorXd>& a,
                              const Eigen::Ref<const Eigen::VectorXd>& b) const {
  if (!is_distributed()) {
    return (a - b).norm();
  }
  double value = (a - b).squaredNorm();
  sum(&value, 1);
  return std::sqrt(value);
}

Eigen::MatrixXd AmbientSpace::products(const Eigen::Ref<const Eigen::MatrixXd>& A,
                                       const Eigen::Ref<const Eigen::MatrixXd>& B) const {
  TESSERA_ASSERT(A.rows() == B.rows());
  Eigen::MatrixXd result = A.transpose() * B;
  sum(result.data(), static_cast<int>(result.size()));
  return result;
}

Eigen::Vector2d AmbientSpace::tangent_coordinates(const Eigen::Ref<const Eigen::MatrixXd>& T,
                                                  const Eigen::Ref<const Eigen::VectorXd>& v) const {
  Eigen::Vector2d result = T.transpose() * v;
  sum(result.data(), 2);
  return result;
}

double AmbientSpace::frobenius_norm(const Eigen::Ref<const Eigen::MatrixXd>& A) const {
  if (!is_distributed()) {
    return A.norm();
  }
  double value = A.squaredNorm();
  sum(&value, 1);
  return std::sqrt(value);
}

bool AmbientSpace::all_finite(const Eigen::Ref<const Eigen::MatrixXd>& A) const {
  return maximum(A.allFinite() ? 0.0 : 1.0) == 0.0;
}

double AmbientSpace::coordinate(const Eigen::Ref<const Eigen::VectorXd>& x, int i) const {
  TESSERA_ASSERT(i >= 0 && i < dimension_);
  if (!is_distributed()) {
    return x(i);
  }
  double value = holds_row(i) ? x(i - first_row_) : 0.0;
  sum(&value, 1);
  return value;
}

}  // namespace tessera
