// SPDX-License-Identifier: MIT
// Cubic triangular Bézier patches in R^n and Hohmann's nine-parameter interpolant of a triangle
// on M (Hohmann 1991, section 3, eqs. 3.3 and 3.5).
#pragma once

#include <Eigen/Core>
#include <array>

namespace tessera {

/// p(λ) = Σ_{|α|=3} b_α B³_α(λ) over barycentric coordinates λ = (λ0, λ1, λ2), Σλ = 1, with
/// Bernstein polynomials B³_α = 3!/α! λ^α. The ten Bézier points are the columns of an n×10
/// matrix in the order of `multi_indices()`:
///   (3,0,0) (0,3,0) (0,0,3) (2,1,0) (2,0,1) (1,2,0) (0,2,1) (1,0,2) (0,1,2) (1,1,1).
class CubicBezierPatch {
 public:
  using MultiIndex = std::array<int, 3>;
  static const std::array<MultiIndex, 10>& multi_indices();
  /// Column of b_α in control_points(). \pre |α| = 3, α ≥ 0.
  static int column_of(const MultiIndex& alpha);

  /// \param control_points n×10 in the order of multi_indices().
  explicit CubicBezierPatch(Eigen::MatrixXd control_points);

  /// Eq. 3.3: the standard nine-parameter interpolant of values g(e_i) (columns of `values`,
  /// n×3) and directional derivatives D_{e_j−e_i} g(e_i), given as `derivatives[i][j]`
  /// (n-vectors, i ≠ j; the diagonal is ignored). Reproduces quadratic g exactly.
  static CubicBezierPatch nine_parameter_interpolant(
      const Eigen::Ref<const Eigen::MatrixXd>& values,
      const std::array<std::array<Eigen::VectorXd, 3>, 3>& derivatives);

  /// Eq. 3.5: the interpolant of the triangle y0, y1, y2 on M (columns of `vertices`, n×3) with
  /// tangent spaces spanned by `tangent_bases[i]` (n×2, orthonormal). The derivative along the
  /// edge from y_i to y_j is l_ij·t_ij, t_ij the normed projection of y_j − y_i onto T_{y_i}M,
  /// l_ij = edge_length_factor·‖y_j − y_i‖ (Hohmann, after Farin: 1.2; the Bézier point is
  /// then y_i + 0.4‖y_j − y_i‖ t_ij).
  static CubicBezierPatch interpolate_triangle_on_manifold(
      const Eigen::Ref<const Eigen::MatrixXd>& vertices,
      const std::array<Eigen::MatrixXd, 3>& tangent_bases, double edge_length_factor = 1.2);

  int ambient_dimension() const { return static_cast<int>(control_points_.rows()); }
  const Eigen::MatrixXd& control_points() const { return control_points_; }

  /// p(λ) by de Casteljau's algorithm (barycentric λ; points outside the triangle extrapolate).
  Eigen::VectorXd evaluate(const Eigen::Vector3d& barycentric) const;
  /// The directional derivative D_d p(λ) for a direction d in barycentric form (Σ d_i = 0),
  /// e.g. d = e_j − e_i.
  Eigen::VectorXd derivative(const Eigen::Vector3d& barycentric,
                             const Eigen::Vector3d& direction) const;

 private:
  Eigen::MatrixXd control_points_;  // n×10
};

}  // namespace tessera
