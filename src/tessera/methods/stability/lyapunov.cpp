// SPDX-License-Identifier: MIT
#include "tessera/methods/stability/lyapunov.h"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <complex>
#include <limits>

#include "tessera/methods/stability/state_jacobian.h"

namespace tessera {

namespace {

using Complex = std::complex<double>;

// The state Jacobian A(x) = M⁻¹·s·D_uF(x) and its derivatives along state directions, by
// differences of DF.
class StateDerivatives {
 public:
  StateDerivatives(const ImplicitProblem& problem, const Eigen::VectorXd& x,
                   const Eigen::VectorXd& inverse_mass)
      : jacobian_(problem, "first Lyapunov coefficient"), x_(x), inverse_mass_(inverse_mass) {
    step_ = 1e-4 * (1.0 + x.lpNorm<Eigen::Infinity>());
  }

  bool at(const Eigen::VectorXd& x, Eigen::MatrixXd& A) {
    if (!jacobian_.evaluate(x)) {
      return false;
    }
    A = inverse_mass_.asDiagonal() * jacobian_.as_dense();
    return true;
  }

  // x + Σ hᵢ uᵢ with the state directions uᵢ embedded among the n coordinates.
  Eigen::VectorXd shifted(const std::vector<std::pair<double, const Eigen::VectorXd*>>& moves) const {
    Eigen::VectorXd y = x_;
    const auto& states = jacobian_.states();
    for (const auto& [h, u] : moves) {
      for (std::size_t i = 0; i < states.size(); ++i) {
        y(states[i]) += h * (*u)(static_cast<Eigen::Index>(i));
      }
    }
    return y;
  }

  // B(u, v) = D_u A · v (central difference, O(h²)).
  bool second(const Eigen::VectorXd& u, const Eigen::VectorXd& v, Eigen::VectorXd& result) {
    Eigen::MatrixXd plus;
    Eigen::MatrixXd minus;
    const double h = step_ / std::max(u.norm(), 1e-300);
    if (!at(shifted({{h, &u}}), plus) || !at(shifted({{-h, &u}}), minus)) {
      return false;
    }
    result = (plus - minus) * v / (2 * h);
    return result.allFinite();
  }

  // C(u, v, w) = D_u D_v A · w (central differences in both directions).
  bool third(const Eigen::VectorXd& u, const Eigen::VectorXd& v, const Eigen::VectorXd& w,
             Eigen::VectorXd& result) {
    const double hu = step_ / std::max(u.norm(), 1e-300);
    const double hv = step_ / std::max(v.norm(), 1e-300);
    Eigen::MatrixXd pp, pm, mp, mm;
    if (!at(shifted({{hu, &u}, {hv, &v}}), pp) || !at(shifted({{hu, &u}, {-hv, &v}}), pm) ||
        !at(shifted({{-hu, &u}, {hv, &v}}), mp) || !at(shifted({{-hu, &u}, {-hv, &v}}), mm)) {
      return false;
    }
    result = (pp - pm - mp + mm) * w / (4 * hu * hv);
    return result.allFinite();
  }

  // The complex-bilinear B(x, y) from the real one.
  bool second(const Eigen::VectorXcd& x, const Eigen::VectorXcd& y, Eigen::VectorXcd& result) {
    const Eigen::VectorXd xr = x.real(), xi = x.imag(), yr = y.real(), yi = y.imag();
    Eigen::VectorXd rr, ii, ri, ir;
    if (!second(xr, yr, rr) || !second(xi, yi, ii) || !second(xr, yi, ri) || !second(xi, yr, ir)) {
      return false;
    }
    result = (rr - ii).cast<Complex>() + Complex(0.0, 1.0) * (ri + ir).cast<Complex>();
    return true;
  }

  const StateJacobian& jacobian() const { return jacobian_; }

 private:
  StateJacobian jacobian_;
  Eigen::VectorXd x_;
  Eigen::VectorXd inverse_mass_;
  double step_ = 1e-4;
};

}  // namespace

double first_lyapunov_coefficient(const ImplicitProblem& problem, const Eigen::VectorXd& x,
                                  double omega, int dense_state_limit) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  const Dynamics dynamics = required_dynamics(problem, "first Lyapunov coefficient");
  const int m = problem.ambient_dimension() - 2;
  if (m > dense_state_limit || !(omega > 0.0)) {
    return nan;
  }
  Eigen::VectorXd inverse_mass = Eigen::VectorXd::Ones(m);
  if (dynamics.mass_diagonal.size() > 0) {
    if (!(dynamics.mass_diagonal.array() > 0.0).all()) {
      return nan;  // algebraic equations: the reduction to an ODE is not done here
    }
    inverse_mass = dynamics.mass_diagonal.cwiseInverse();
  } else if (dynamics.mass_matrix.size() > 0) {
    return nan;
  }
  StateDerivatives derivatives(problem, x, inverse_mass);
  Eigen::MatrixXd A;
  if (!derivatives.at(x, A)) {
    return nan;
  }
  // q: the eigenvector of the eigenvalue nearest iω; p: Aᵀp = −iωp, normalised p̄ᵀq = 1.
  const Eigen::ComplexEigenSolver<Eigen::MatrixXcd> right(A.cast<Complex>());
  const Eigen::ComplexEigenSolver<Eigen::MatrixXcd> left(A.transpose().cast<Complex>());
  if (right.info() != Eigen::Success || left.info() != Eigen::Success) {
    return nan;
  }
  const Complex iw(0.0, omega);
  Eigen::Index k_right = 0;
  Eigen::Index k_left = 0;
  (right.eigenvalues().array() - iw).abs().minCoeff(&k_right);
  (left.eigenvalues().array() + iw).abs().minCoeff(&k_left);
  if (std::abs(right.eigenvalues()(k_right) - iw) > 1e-6 * (1.0 + omega)) {
    return nan;  // not a Hopf point to the accuracy this needs
  }
  Eigen::VectorXcd q = right.eigenvectors().col(k_right).normalized();
  Eigen::VectorXcd p = left.eigenvectors().col(k_left);
  const Complex pq = p.dot(q);  // p̄ᵀq
  if (std::abs(pq) == 0.0) {
    return nan;
  }
  p /= std::conj(pq);  // now p.dot(q) = 1
  Eigen::VectorXcd Bqq, Bqqbar;
  if (!derivatives.second(q, q, Bqq) || !derivatives.second(q, q.conjugate().eval(), Bqqbar)) {
    return nan;
  }
  const Eigen::VectorXd a = q.real();
  const Eigen::VectorXd b = q.imag();
  // C(q, q, q̄) = C(a,a,a) + C(a,b,b) + i(C(a,a,b) + C(b,b,b)) for symmetric C.
  Eigen::VectorXd aaa, abb, aab, bbb;
  if (!derivatives.third(a, a, a, aaa) || !derivatives.third(a, b, b, abb) ||
      !derivatives.third(a, a, b, aab) || !derivatives.third(b, b, b, bbb)) {
    return nan;
  }
  const Eigen::VectorXcd Cqqqbar =
      (aaa + abb).cast<Complex>() + Complex(0.0, 1.0) * (aab + bbb).cast<Complex>();
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(A);
  const Eigen::VectorXcd r = lu.solve(Bqqbar.real()).cast<Complex>();  // B(q, q̄) is real
  const Eigen::MatrixXcd shifted =
      Complex(0.0, 2 * omega) * Eigen::MatrixXcd::Identity(m, m) - A.cast<Complex>();
  const Eigen::VectorXcd s = shifted.partialPivLu().solve(Bqq);
  Eigen::VectorXcd Bqr, Bqbars;
  if (!derivatives.second(q, r, Bqr) || !derivatives.second(q.conjugate().eval(), s, Bqbars)) {
    return nan;
  }
  const Complex value = p.dot(Cqqqbar) - 2.0 * p.dot(Bqr) + p.dot(Bqbars);
  return value.real() / (2 * omega);
}

}  // namespace tessera
