// SPDX-License-Identifier: MIT
#include "tessera/geometry/bezier_patch.h"

#include "tessera/core/error.h"

namespace tessera {
namespace {


// One de Casteljau level: degree-k points (indexed by multi-index) to degree k−1.
// Points of degree k are stored in a map from (α0, α1) to a column (α2 = k − α0 − α1).
Eigen::MatrixXd casteljau_step(const Eigen::MatrixXd& points, int degree,
                               const Eigen::Vector3d& lambda) {
  // Layout of a degree-k set: index(α0, α1) = α0·(k+1) + α1 in a (k+1)² table (sparse use).
  const int k = degree;
  Eigen::MatrixXd next = Eigen::MatrixXd::Zero(points.rows(), k * k);
  for (int a0 = 0; a0 < k; ++a0) {
    for (int a1 = 0; a0 + a1 < k; ++a1) {
      next.col(a0 * k + a1) = lambda(0) * points.col((a0 + 1) * (k + 1) + a1) +
                              lambda(1) * points.col(a0 * (k + 1) + a1 + 1) +
                              lambda(2) * points.col(a0 * (k + 1) + a1);
    }
  }
  return next;
}

}  // namespace

const std::array<CubicBezierPatch::MultiIndex, 10>& CubicBezierPatch::multi_indices() {
  static const std::array<MultiIndex, 10> indices = {{{3, 0, 0},
                                                      {0, 3, 0},
                                                      {0, 0, 3},
                                                      {2, 1, 0},
                                                      {2, 0, 1},
                                                      {1, 2, 0},
                                                      {0, 2, 1},
                                                      {1, 0, 2},
                                                      {0, 1, 2},
                                                      {1, 1, 1}}};
  return indices;
}

int CubicBezierPatch::column_of(const MultiIndex& alpha) {
  const auto& indices = multi_indices();
  for (int c = 0; c < 10; ++c) {
    if (indices[c] == alpha) {
      return c;
    }
  }
  TESSERA_CHECK(false, "(" << alpha[0] << ", " << alpha[1] << ", " << alpha[2]
                           << ") is not a cubic multi-index");
  return -1;
}

CubicBezierPatch::CubicBezierPatch(Eigen::MatrixXd control_points)
    : control_points_(std::move(control_points)) {
  TESSERA_CHECK(control_points_.cols() == 10,
                "a cubic Bézier patch has 10 control points, got " << control_points_.cols());
}

CubicBezierPatch CubicBezierPatch::nine_parameter_interpolant(
    const Eigen::Ref<const Eigen::MatrixXd>& values,
    const std::array<std::array<Eigen::VectorXd, 3>, 3>& derivatives) {
  TESSERA_CHECK(values.cols() == 3, "nine-parameter interpolant: need 3 vertex values, got "
                                        << values.cols());
  const int n = static_cast<int>(values.rows());
  Eigen::MatrixXd b(n, 10);
  Eigen::VectorXd edge_sum = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < 3; ++i) {
    MultiIndex corner{0, 0, 0};
    corner[i] = 3;
    b.col(column_of(corner)) = values.col(i);
    for (int j = 0; j < 3; ++j) {
      if (j == i) {
        continue;
      }
      TESSERA_CHECK(derivatives[i][j].size() == n, "derivative (" << i << ", " << j
                                                                  << ") has size "
                                                                  << derivatives[i][j].size());
      MultiIndex alpha{0, 0, 0};
      alpha[i] = 2;
      alpha[j] = 1;
      // Eq. 3.3 ii: b_{2e_i+e_j} = g(e_i) + D_{e_j−e_i} g(e_i) / 3.
      b.col(column_of(alpha)) = values.col(i) + derivatives[i][j] / 3.0;
      edge_sum += b.col(column_of(alpha));
    }
  }
  // Eq. 3.3 iii: the centre point that gives quadratic precision.
  b.col(column_of({1, 1, 1})) = edge_sum / 4.0 - values.rowwise().sum() / 6.0;
  return CubicBezierPatch(std::move(b));
}

CubicBezierPatch CubicBezierPatch::interpolate_triangle_on_manifold(
    const Eigen::Ref<const Eigen::MatrixXd>& vertices,
    const std::array<Eigen::MatrixXd, 3>& tangent_bases, double edge_length_factor) {
  TESSERA_CHECK(vertices.cols() == 3, "a triangle has 3 vertices, got " << vertices.cols());
  TESSERA_CHECK(edge_length_factor > 0, "edge_length_factor = " << edge_length_factor
                                                                << " must be > 0");
  const int n = static_cast<int>(vertices.rows());
  std::array<std::array<Eigen::VectorXd, 3>, 3> derivatives;
  for (int i = 0; i < 3; ++i) {
    const Eigen::MatrixXd& T = tangent_bases[i];
    TESSERA_CHECK(T.rows() == n && T.cols() == 2,
                  "tangent basis " << i << " must be " << n << "×2, got " << T.rows() << "×"
                                   << T.cols());
    for (int j = 0; j < 3; ++j) {
      if (j == i) {
        continue;
      }
      const Eigen::VectorXd edge = vertices.col(j) - vertices.col(i);
      Eigen::VectorXd t = T * (T.transpose() * edge);  // eq. 3.4 ii
      const double norm = t.norm();
      TESSERA_CHECK(norm > 0, "edge (" << i << ", " << j
                                       << ") is normal to the tangent plane at vertex " << i);
      derivatives[i][j] = edge_length_factor * edge.norm() * (t / norm);  // eq. 3.4 i
    }
  }
  return nine_parameter_interpolant(vertices, derivatives);
}

Eigen::VectorXd CubicBezierPatch::evaluate(const Eigen::Vector3d& barycentric) const {
  // Degree-3 table indexed (α0, α1) → α0·4 + α1.
  Eigen::MatrixXd level = Eigen::MatrixXd::Zero(control_points_.rows(), 16);
  const auto& indices = multi_indices();
  for (int c = 0; c < 10; ++c) {
    level.col(indices[c][0] * 4 + indices[c][1]) = control_points_.col(c);
  }
  for (int degree = 3; degree > 0; --degree) {
    level = casteljau_step(level, degree, barycentric);
  }
  return level.col(0);
}

Eigen::VectorXd CubicBezierPatch::derivative(const Eigen::Vector3d& barycentric,
                                             const Eigen::Vector3d& direction) const {
  // D_d p(λ) = 3 Σ_{|β|=2} (Σ_i d_i b_{β+e_i}) B²_β(λ): one de Casteljau step with d, then
  // two with λ.
  Eigen::MatrixXd level = Eigen::MatrixXd::Zero(control_points_.rows(), 16);
  const auto& indices = multi_indices();
  for (int c = 0; c < 10; ++c) {
    level.col(indices[c][0] * 4 + indices[c][1]) = control_points_.col(c);
  }
  level = 3.0 * casteljau_step(level, 3, direction);
  for (int degree = 2; degree > 0; --degree) {
    level = casteljau_step(level, degree, barycentric);
  }
  return level.col(0);
}

}  // namespace tessera
