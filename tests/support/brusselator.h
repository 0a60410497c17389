// SPDX-License-Identifier: MIT
// The Brusselator on N grid points with no-flux ends and equal diffusion D for both species,
//     u' = D u_xx + a − (b + 1) u + u² v,   v' = D v_xx + b u − u² v,
// coordinates (u_1, v_1, …, u_N, v_N, a, b): a sparse problem whose D_uF is not symmetric. Its
// homogeneous steady states u = a, v = b/a form M (a graph over (a, b)); there the uniform mode
// has trace b − 1 − a² and determinant a², so a Hopf bifurcation happens on b = 1 + a² with
// frequency ω = a; the other modes only shift the trace and determinant by D q_k, q_k > 0, so
// with equal diffusion they never go unstable first.
#pragma once

#include <Eigen/SparseCore>
#include <optional>
#include <string>
#include <vector>

#include "tessera/core/implicit_problem.h"

namespace tessera::test {

class Brusselator final : public ImplicitProblem {
 public:
  explicit Brusselator(int points = 40, double diffusion = 0.02)
      : points_(points), coupling_(diffusion * (points - 1.0) * (points - 1.0)) {}

  int ambient_dimension() const override { return 2 * points_ + 2; }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override {
    const double a = x(2 * points_);
    const double b = x(2 * points_ + 1);
    for (int i = 0; i < points_; ++i) {
      const double u = x(2 * i);
      const double v = x(2 * i + 1);
      F(2 * i) = coupling_ * laplacian(x, i, 0) + a - (b + 1) * u + u * u * v;
      F(2 * i + 1) = coupling_ * laplacian(x, i, 1) + b * u - u * u * v;
    }
  }
  bool has_sparse_jacobian() const override { return true; }
  void sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                       Eigen::SparseMatrix<double>& J) const override {
    const int m = 2 * points_;
    const double b = x(m + 1);
    std::vector<Eigen::Triplet<double>> entries;
    for (int i = 0; i < points_; ++i) {
      const double u = x(2 * i);
      const double v = x(2 * i + 1);
      for (int s = 0; s < 2; ++s) {
        const int row = 2 * i + s;
        const int left = i > 0 ? i - 1 : i + 1;  // no flux: a mirrored neighbour
        const int right = i + 1 < points_ ? i + 1 : i - 1;
        entries.emplace_back(row, 2 * left + s, coupling_);
        entries.emplace_back(row, 2 * right + s, coupling_);
        entries.emplace_back(row, row, -2 * coupling_);
      }
      entries.emplace_back(2 * i, 2 * i, -(b + 1) + 2 * u * v);
      entries.emplace_back(2 * i, 2 * i + 1, u * u);
      entries.emplace_back(2 * i + 1, 2 * i, b - 2 * u * v);
      entries.emplace_back(2 * i + 1, 2 * i + 1, -u * u);
      entries.emplace_back(2 * i, m, 1.0);
      entries.emplace_back(2 * i, m + 1, -u);
      entries.emplace_back(2 * i + 1, m + 1, u);
    }
    J.resize(m, m + 2);
    J.setFromTriplets(entries.begin(), entries.end());
    J.makeCompressed();
  }
  std::string name() const override { return "brusselator"; }
  std::optional<Dynamics> dynamics() const override {
    Dynamics dynamics;
    dynamics.parameters = {2 * points_, 2 * points_ + 1};
    return dynamics;
  }
  /// The homogeneous steady state at (a, b).
  Eigen::VectorXd steady_state(double a, double b) const {
    Eigen::VectorXd x(ambient_dimension());
    for (int i = 0; i < points_; ++i) {
      x(2 * i) = a;
      x(2 * i + 1) = b / a;
    }
    x(2 * points_) = a;
    x(2 * points_ + 1) = b;
    return x;
  }

 private:
  double laplacian(const Eigen::Ref<const Eigen::VectorXd>& x, int i, int s) const {
    const int left = i > 0 ? i - 1 : i + 1;
    const int right = i + 1 < points_ ? i + 1 : i - 1;
    return x(2 * left + s) + x(2 * right + s) - 2 * x(2 * i + s);
  }

  int points_;
  double coupling_;  // D/h², h = 1/(N − 1)
};

}  // namespace tessera::test
