// SPDX-License-Identifier: MIT
// Example manifolds with exact analytic Jacobians.
#include "tessera/problems/examples.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "tessera/core/bordered_jacobian.h"
#include "tessera/core/error.h"
#include "tessera/core/sparse_lu.h"
#include "tessera/problems/detail/arrhenius.h"

namespace tessera {

// ---------------------------------------------------------------------------------------------
// Plane: F = z.

void Plane::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                     Eigen::Ref<Eigen::VectorXd> F) const {
  F(0) = x(2);
}

void Plane::jacobian(const Eigen::Ref<const Eigen::VectorXd>& /*x*/,
                     Eigen::Ref<Eigen::MatrixXd> J) const {
  J << 0.0, 0.0, 1.0;
}

// ---------------------------------------------------------------------------------------------
// Sphere: F = |x|² − r².

Sphere::Sphere(double radius) : radius_(radius) {
  TESSERA_CHECK(std::isfinite(radius) && radius > 0.0,
                "Sphere radius = " << radius << " must be finite and > 0");
}

void Sphere::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                      Eigen::Ref<Eigen::VectorXd> F) const {
  F(0) = x.squaredNorm() - radius_ * radius_;
}

void Sphere::jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                      Eigen::Ref<Eigen::MatrixXd> J) const {
  J.row(0) = 2.0 * x.transpose();
}

// ---------------------------------------------------------------------------------------------
// Torus: F = s² − 4R²(y₂² + y₃²) with s = |y|² + R² − r².

Torus::Torus(double major_radius, double minor_radius)
    : major_radius_(major_radius), minor_radius_(minor_radius) {
  TESSERA_CHECK(
      std::isfinite(major_radius) && std::isfinite(minor_radius) && minor_radius > 0.0 &&
          minor_radius < major_radius,
      "Torus radii R = " << major_radius << ", r = " << minor_radius << " must satisfy 0 < r < R");
}

void Torus::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                     Eigen::Ref<Eigen::VectorXd> F) const {
  const double R2 = major_radius_ * major_radius_;
  const double s = x.squaredNorm() + R2 - minor_radius_ * minor_radius_;
  F(0) = s * s - 4.0 * R2 * (x(1) * x(1) + x(2) * x(2));
}

void Torus::jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                     Eigen::Ref<Eigen::MatrixXd> J) const {
  const double R2 = major_radius_ * major_radius_;
  const double s = x.squaredNorm() + R2 - minor_radius_ * minor_radius_;
  J(0, 0) = 4.0 * s * x(0);
  J(0, 1) = 4.0 * s * x(1) - 8.0 * R2 * x(1);
  J(0, 2) = 4.0 * s * x(2) - 8.0 * R2 * x(2);
}

// ---------------------------------------------------------------------------------------------
// Equipotential: F = 1/|y − p|² + 1/|y − q|² − c with p = 0, q = (0, q_y, 0).

Equipotential::Equipotential(double level, double separation)
    : level_(level), separation_(separation) {
  TESSERA_CHECK(std::isfinite(level) && level > 0.0,
                "Equipotential level c = " << level << " must be finite and > 0");
  TESSERA_CHECK(std::isfinite(separation),
                "Equipotential separation q_y = " << separation << " must be finite");
}

void Equipotential::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                             Eigen::Ref<Eigen::VectorXd> F) const {
  const double to_p = x.squaredNorm();
  const double dy = x(1) - separation_;
  const double to_q = x(0) * x(0) + dy * dy + x(2) * x(2);
  // At a charge the division gives +inf, which the solvers read as "outside the domain of F".
  F(0) = 1.0 / to_p + 1.0 / to_q - level_;
}

void Equipotential::jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                             Eigen::Ref<Eigen::MatrixXd> J) const {
  const double to_p = x.squaredNorm();
  const double dy = x(1) - separation_;
  const double to_q = x(0) * x(0) + dy * dy + x(2) * x(2);
  // ∇(1/|d|²) = −2 d / |d|⁴.
  const double wp = -2.0 / (to_p * to_p);
  const double wq = -2.0 / (to_q * to_q);
  J(0, 0) = (wp + wq) * x(0);
  J(0, 1) = wp * x(1) + wq * dy;
  J(0, 2) = (wp + wq) * x(2);
}

// ---------------------------------------------------------------------------------------------
// Whitney pleat: F = x³ − λx − μ.

void WhitneyPleat::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                            Eigen::Ref<Eigen::VectorXd> F) const {
  F(0) = x(0) * x(0) * x(0) - x(1) * x(0) - x(2);
}

void WhitneyPleat::jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                            Eigen::Ref<Eigen::MatrixXd> J) const {
  J(0, 0) = 3.0 * x(0) * x(0) - x(1);
  J(0, 1) = -x(0);
  J(0, 2) = -1.0;
}

// ---------------------------------------------------------------------------------------------
// Trough: F = a²b²z³ − a²z⁵ − x²z + ε.

Trough::Trough(double a, double b, double epsilon) : a_(a), b_(b), epsilon_(epsilon) {
  TESSERA_CHECK(std::isfinite(a) && a > 0.0, "Trough a = " << a << " must be finite and > 0");
  TESSERA_CHECK(std::isfinite(b) && b > 0.0, "Trough b = " << b << " must be finite and > 0");
  TESSERA_CHECK(std::isfinite(epsilon), "Trough epsilon = " << epsilon << " must be finite");
}

void Trough::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                      Eigen::Ref<Eigen::VectorXd> F) const {
  const double z = x(2);
  F(0) = z * (a_ * a_ * z * z * (b_ * b_ - z * z) - x(0) * x(0)) + epsilon_;
}

void Trough::jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                      Eigen::Ref<Eigen::MatrixXd> J) const {
  const double z = x(2);
  const double a2 = a_ * a_;
  J(0, 0) = -2.0 * x(0) * z;
  J(0, 1) = 0.0;
  J(0, 2) = 3.0 * a2 * b_ * b_ * z * z - 5.0 * a2 * z * z * z * z - x(0) * x(0);
}

// ---------------------------------------------------------------------------------------------
// Stirred tank reactor.

StirredTankReactor::StirredTankReactor(double beta) : beta_(beta) {
  TESSERA_CHECK(std::isfinite(beta) && beta > -1.0,
                "StirredTankReactor beta = " << beta << " must be finite and > -1");
}

void StirredTankReactor::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                                  Eigen::Ref<Eigen::VectorXd> F) const {
  // x = (x1, x2, Da, B); rate = Da (1 − x1) exp(x2) is the reaction term of both equations.
  const double rate = x(2) * (1.0 - x(0)) * std::exp(x(1));
  F(0) = -x(0) + rate;
  F(1) = -(1.0 + beta_) * x(1) + x(3) * rate;
}

void StirredTankReactor::jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                                  Eigen::Ref<Eigen::MatrixXd> J) const {
  const double e = std::exp(x(1));
  const double rate = x(2) * (1.0 - x(0)) * e;
  const double B = x(3);
  J(0, 0) = -1.0 - x(2) * e;
  J(0, 1) = rate;
  J(0, 2) = (1.0 - x(0)) * e;
  J(0, 3) = 0.0;
  J(1, 0) = -B * x(2) * e;
  J(1, 1) = -(1.0 + beta_) + B * rate;
  J(1, 2) = B * (1.0 - x(0)) * e;
  J(1, 3) = rate;
}

Eigen::VectorXd StirredTankReactor::point_on_manifold(double x1, double B) const {
  TESSERA_CHECK(x1 < 1.0, "StirredTankReactor::point_on_manifold: x1 = " << x1 << " must be < 1");
  // f₂ − B f₁ = 0 gives x₂ = B x₁/(1 + β); then f₁ = 0 gives Da.
  const double x2 = B * x1 / (1.0 + beta_);
  Eigen::VectorXd x(4);
  x << x1, x2, x1 * std::exp(-x2) / (1.0 - x1), B;
  return x;
}

// ---------------------------------------------------------------------------------------------
// Arrhenius–Bratu boundary value problem.

namespace {

using detail::Arrhenius;
using detail::arrhenius;

// Solves A v = rhs in place for the tridiagonal A with unit off-diagonals and the given diagonal,
// by the Thomas algorithm. There is no pivoting: A = ∂F/∂u is singular only exactly at a fold,
// and the bordered Newton step below only needs A to be regular at the iterates, not uniformly.
// `scratch` has the size of `diagonal`.
void solve_unit_tridiagonal(const Eigen::VectorXd& diagonal, Eigen::VectorXd& rhs,
                            Eigen::VectorXd& scratch) {
  const Eigen::Index n = diagonal.size();
  scratch(0) = 1.0 / diagonal(0);
  rhs(0) *= scratch(0);
  for (Eigen::Index i = 1; i < n; ++i) {
    const double pivot = diagonal(i) - scratch(i - 1);
    scratch(i) = 1.0 / pivot;
    rhs(i) = (rhs(i) - rhs(i - 1)) * scratch(i);
  }
  // scratch(i) holds 1/pivot_i, which is also the eliminated super-diagonal c'_i = 1/pivot_i.
  for (Eigen::Index i = n - 2; i >= 0; --i) {
    rhs(i) -= scratch(i) * rhs(i + 1);
  }
}

}  // namespace

ArrheniusBratu::ArrheniusBratu(int point_count) : point_count_(point_count) {
  TESSERA_CHECK(point_count >= 1,
                "ArrheniusBratu point_count = " << point_count << " must be >= 1");
}

void ArrheniusBratu::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                              Eigen::Ref<Eigen::VectorXd> F) const {
  const int N = point_count_;
  const double h = 1.0 / (N + 1);
  const double lambda = x(N);
  const double epsilon = x(N + 1);
  for (int i = 0; i < N; ++i) {
    const double left = i > 0 ? x(i - 1) : 0.0;
    const double right = i + 1 < N ? x(i + 1) : 0.0;
    const double u = x(i);
    F(i) = left - 2.0 * u + right + h * h * lambda * std::exp(u / (1.0 + epsilon * u));
  }
}

void ArrheniusBratu::jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                              Eigen::Ref<Eigen::MatrixXd> J) const {
  const int N = point_count_;
  const double h2 = 1.0 / ((N + 1.0) * (N + 1.0));
  const double lambda = x(N);
  const double epsilon = x(N + 1);
  J.setZero();
  for (int i = 0; i < N; ++i) {
    const Arrhenius term = arrhenius(x(i), epsilon);
    if (i > 0) {
      J(i, i - 1) = 1.0;
    }
    J(i, i) = -2.0 + h2 * lambda * term.derivative_u;
    if (i + 1 < N) {
      J(i, i + 1) = 1.0;
    }
    J(i, N) = h2 * term.value;
    J(i, N + 1) = h2 * lambda * term.derivative_epsilon;
  }
}

void ArrheniusBratu::sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                                     Eigen::SparseMatrix<double>& J) const {
  const int N = point_count_;
  const double h2 = 1.0 / ((N + 1.0) * (N + 1.0));
  const double lambda = x(N);
  const double epsilon = x(N + 1);
  const Eigen::Index nonzeros = 3 * static_cast<Eigen::Index>(N) - 2 + 2 * N;

  // Write the compressed column arrays directly: resize() keeps the outer index array when the
  // shape is unchanged and resizeNonZeros() keeps the value/inner arrays when their capacity
  // suffices, so a J reused across calls is filled without allocating.
  J.resize(N, N + 2);
  J.resizeNonZeros(nonzeros);
  int* outer = J.outerIndexPtr();
  int* inner = J.innerIndexPtr();
  double* values = J.valuePtr();

  // Columns 0 … N−1 (u_j): rows j−1, j, j+1 of the tridiagonal block, in increasing row order.
  int k = 0;
  for (int j = 0; j < N; ++j) {
    outer[j] = k;
    if (j > 0) {
      inner[k] = j - 1;
      values[k++] = 1.0;
    }
    inner[k] = j;
    values[k++] = -2.0 + h2 * lambda * arrhenius(x(j), epsilon).derivative_u;
    if (j + 1 < N) {
      inner[k] = j + 1;
      values[k++] = 1.0;
    }
  }
  // Columns N (λ) and N+1 (ε) are dense.
  outer[N] = k;
  outer[N + 1] = k + N;
  outer[N + 2] = k + 2 * N;
  for (int i = 0; i < N; ++i) {
    const Arrhenius term = arrhenius(x(i), epsilon);
    inner[k + i] = i;
    values[k + i] = h2 * term.value;
    inner[k + N + i] = i;
    values[k + N + i] = h2 * lambda * term.derivative_epsilon;
  }
  TESSERA_ASSERT(k + 2 * N == nonzeros);
}

std::vector<std::string> ArrheniusBratu::coordinate_names() const {
  std::vector<std::string> names;
  names.reserve(point_count_ + 2);
  for (int i = 1; i <= point_count_; ++i) {
    names.push_back("u" + std::to_string(i));
  }
  names.push_back("lambda");
  names.push_back("epsilon");
  return names;
}

std::vector<CoordinateBlock> ArrheniusBratu::coordinate_blocks() const {
  return {{"u", 0, point_count_, std::sqrt(1.0 / (point_count_ + 1.0))}};
}

Eigen::VectorXd ArrheniusBratu::point_with_amplitude(double amplitude, double epsilon) const {
  TESSERA_CHECK(
      std::isfinite(amplitude) && amplitude >= 0.0,
      "ArrheniusBratu::point_with_amplitude: amplitude = " << amplitude << " must be >= 0");
  TESSERA_CHECK(std::isfinite(epsilon) && epsilon >= 0.0,
                "ArrheniusBratu::point_with_amplitude: epsilon = " << epsilon << " must be >= 0");
  const int N = point_count_;
  const double h2 = 1.0 / ((N + 1.0) * (N + 1.0));
  const int middle = (N - 1) / 2;  // 0-based index of u_{⌊(N+1)/2⌋}, where u is largest

  // Continuation in the amplitude α: (u, λ) solve F(u, λ, ε) = 0 and u_middle = α. This bordered
  // system is regular through the folds of λ ↦ u because (α, ε) parametrise M. Steps of 0.25 in α
  // keep the scaled previous profile inside Newton's region of quadratic convergence.
  Eigen::VectorXd u(N);
  for (int i = 0; i < N; ++i) {
    const double t = (i + 1.0) / (N + 1.0);
    const double t_middle = (middle + 1.0) / (N + 1.0);
    u(i) = t * (1.0 - t) / (t_middle * (1.0 - t_middle));  // unit-amplitude parabola
  }
  double lambda = 0.0;
  double previous_amplitude = 1.0;
  const int steps = std::max(1, static_cast<int>(std::ceil(amplitude / 0.25)));
  Eigen::VectorXd diagonal(N), y(N), z(N), scratch(N);
  for (int step = 1; step <= steps; ++step) {
    const double target = amplitude * step / steps;
    u *= target / previous_amplitude;  // predictor: same shape, new amplitude
    previous_amplitude = target > 0.0 ? target : 1.0;
    // Stop on the residual, not on the size of the correction: the correction cannot fall below
    // cond(∂F/∂u)·(rounding) ~ N²·1e-16, which exceeds any fixed threshold for large N, while
    // the residual of the h²-scaled equations sits at ~1e-15·max u for every N.
    const double tolerance = 1e-13 * (1.0 + target);
    bool converged = false;
    for (int iteration = 0; iteration < 50; ++iteration) {
      for (int i = 0; i < N; ++i) {
        const Arrhenius term = arrhenius(u(i), epsilon);
        const double left = i > 0 ? u(i - 1) : 0.0;
        const double right = i + 1 < N ? u(i + 1) : 0.0;
        y(i) = -(left - 2.0 * u(i) + right + h2 * lambda * term.value);  // −F
        z(i) = h2 * term.value;                                          // ∂F/∂λ
        diagonal(i) = -2.0 + h2 * lambda * term.derivative_u;
      }
      const double residual = std::max(y.lpNorm<Eigen::Infinity>(), std::abs(u(middle) - target));
      if (!std::isfinite(residual)) {
        break;
      }
      if (residual <= tolerance) {
        converged = true;
        break;
      }
      solve_unit_tridiagonal(diagonal, y, scratch);
      solve_unit_tridiagonal(diagonal, z, scratch);
      // du = y − dλ z, and the border row requires u_middle + du_middle = target.
      const double dlambda = (y(middle) - (target - u(middle))) / z(middle);
      u += y - dlambda * z;
      lambda += dlambda;
    }
    if (!converged) {
      std::ostringstream message;
      message << "ArrheniusBratu::point_with_amplitude: Newton's method did not converge at "
                 "amplitude "
              << target << " (target " << amplitude << "), epsilon " << epsilon;
      throw ComputationFailed(message.str());
    }
  }
  Eigen::VectorXd x(N + 2);
  x << u, lambda, epsilon;
  return x;
}

// ---------------------------------------------------------------------------------------------
// Arrhenius–Bratu problem on the unit square.

ArrheniusBratu2D::ArrheniusBratu2D(int grid_size) : grid_size_(grid_size) {
  TESSERA_CHECK(
      grid_size >= 1 && grid_size <= kMaxGridSize,
      "ArrheniusBratu2D grid_size = " << grid_size << " must be in [1, " << kMaxGridSize << "]");
}

int ArrheniusBratu2D::centre_index() const {
  const int middle = (grid_size_ - 1) / 2;  // 0-based row and column of ⌊(N+1)/2⌋
  return middle * grid_size_ + middle;
}

void ArrheniusBratu2D::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                                Eigen::Ref<Eigen::VectorXd> F) const {
  const int N = grid_size_;
  const int m = N * N;
  const double h = 1.0 / (N + 1);
  const double lambda = x(m);
  const double epsilon = x(m + 1);
  for (int row = 0; row < N; ++row) {
    for (int column = 0; column < N; ++column) {
      const int i = row * N + column;
      const double u = x(i);
      const double below = row > 0 ? x(i - N) : 0.0;
      const double above = row + 1 < N ? x(i + N) : 0.0;
      const double left = column > 0 ? x(i - 1) : 0.0;
      const double right = column + 1 < N ? x(i + 1) : 0.0;
      F(i) = below + above + left + right - 4.0 * u +
             h * h * lambda * std::exp(u / (1.0 + epsilon * u));
    }
  }
}

void ArrheniusBratu2D::jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                                Eigen::Ref<Eigen::MatrixXd> J) const {
  Eigen::SparseMatrix<double> sparse;
  sparse_jacobian(x, sparse);
  J = Eigen::MatrixXd(sparse);
}

void ArrheniusBratu2D::sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                                       Eigen::SparseMatrix<double>& J) const {
  const int N = grid_size_;
  const int m = N * N;
  const double h2 = 1.0 / ((N + 1.0) * (N + 1.0));
  const double lambda = x(m);
  const double epsilon = x(m + 1);
  const Eigen::Index nonzeros = 5 * static_cast<Eigen::Index>(m) - 4 * N + 2 * m;

  // The compressed column arrays are written directly, as in ArrheniusBratu::sparse_jacobian:
  // a J reused across calls keeps its storage.
  J.resize(m, m + 2);
  J.resizeNonZeros(nonzeros);
  int* outer = J.outerIndexPtr();
  int* inner = J.innerIndexPtr();
  double* values = J.valuePtr();

  // Column j (u_j) holds rows j−N, j−1, j, j+1, j+N of the stencil, in increasing row order.
  int k = 0;
  for (int j = 0; j < m; ++j) {
    const int row = j / N;
    const int column = j % N;
    outer[j] = k;
    if (row > 0) {
      inner[k] = j - N;
      values[k++] = 1.0;
    }
    if (column > 0) {
      inner[k] = j - 1;
      values[k++] = 1.0;
    }
    inner[k] = j;
    values[k++] = -4.0 + h2 * lambda * arrhenius(x(j), epsilon).derivative_u;
    if (column + 1 < N) {
      inner[k] = j + 1;
      values[k++] = 1.0;
    }
    if (row + 1 < N) {
      inner[k] = j + N;
      values[k++] = 1.0;
    }
  }
  // Columns m (λ) and m+1 (ε) are dense.
  outer[m] = k;
  outer[m + 1] = k + m;
  outer[m + 2] = k + 2 * m;
  for (int i = 0; i < m; ++i) {
    const Arrhenius term = arrhenius(x(i), epsilon);
    inner[k + i] = i;
    values[k + i] = h2 * term.value;
    inner[k + m + i] = i;
    values[k + m + i] = h2 * lambda * term.derivative_epsilon;
  }
  TESSERA_ASSERT(k + 2 * m == nonzeros);
}

std::vector<std::string> ArrheniusBratu2D::coordinate_names() const {
  std::vector<std::string> names;
  names.reserve(static_cast<std::size_t>(grid_size_) * grid_size_ + 2);
  for (int row = 1; row <= grid_size_; ++row) {
    for (int column = 1; column <= grid_size_; ++column) {
      names.push_back("u_" + std::to_string(row) + "_" + std::to_string(column));
    }
  }
  names.push_back("lambda");
  names.push_back("epsilon");
  return names;
}

std::vector<CoordinateBlock> ArrheniusBratu2D::coordinate_blocks() const {
  return {{"u", 0, grid_size_ * grid_size_, 1.0 / (grid_size_ + 1.0)}};
}

Eigen::VectorXd ArrheniusBratu2D::point_with_amplitude(double amplitude, double epsilon) const {
  TESSERA_CHECK(
      std::isfinite(amplitude) && amplitude >= 0.0,
      "ArrheniusBratu2D::point_with_amplitude: amplitude = " << amplitude << " must be >= 0");
  TESSERA_CHECK(std::isfinite(epsilon) && epsilon >= 0.0,
                "ArrheniusBratu2D::point_with_amplitude: epsilon = " << epsilon << " must be >= 0");
  const int n = ambient_dimension();
  const int m = n - 2;
  const int centre = centre_index();

  // Newton's method on F(u, λ, ε) = 0, u_c = α, ε fixed: the bordered matrix
  // A = [J; e_cᵀ; e_εᵀ] is tessera's own (core/bordered_jacobian.h), regular wherever (u_c, ε)
  // parametrise M, folds of λ ↦ u included. Its pattern does not change: one analysis.
  const JacobianBorder border{{m, centre, 1.0}, {m + 1, m + 1, 1.0}};
  std::unique_ptr<SparseLu> lu;
  Eigen::SparseMatrix<double> J, A;
  Eigen::VectorXd F(m), rhs(n), tangent(n);
  const auto factor_at = [&](const Eigen::VectorXd& x) {
    sparse_jacobian(x, J);
    bordered_jacobian(J, border, A);
    if (!lu) {
      lu = make_sparse_lu(sparse_lu_solver_for(A));
    }
    if (!lu->is_analyzed_for(A) && lu->analyze(A) != SparseLuStatus::Success) {
      return false;
    }
    return lu->factorize(A) == SparseLuStatus::Success;
  };
  // Newton from x towards u_c = target; x is left at the last iterate. Stops on the residual of
  // the h²-scaled equations, which sits at ~1e-15·max u for every N, not on the size of the
  // correction (that cannot fall below cond(A)·rounding ~ N²·1e-16).
  const auto newton = [&](Eigen::VectorXd& x, double target) {
    const double tolerance = 1e-13 * (1.0 + target);
    for (int iteration = 0; iteration < 30; ++iteration) {
      evaluate(x, F);
      const double residual = std::max(F.lpNorm<Eigen::Infinity>(), std::abs(x(centre) - target));
      if (!std::isfinite(residual) || !factor_at(x)) {
        return false;
      }
      if (residual <= tolerance) {
        return true;  // and A is factored at x, for the next tangent
      }
      rhs << -F, target - x(centre), 0.0;
      lu->solve(rhs, rhs);
      x += rhs;
    }
    return false;
  };

  // Continuation in the amplitude α from u = 0, λ = 0 (a solution for every ε), predicting
  // along the tangent d(u, λ)/dα = A⁻¹ e_c (ε fixed). Steps of at most 0.5 in α converge in 2–4
  // Newton iterations; a step that does not is halved.
  constexpr double kLargestStep = 0.5;
  constexpr double kSmallestStep = 1e-3;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  x(m + 1) = epsilon;
  if (!newton(x, 0.0)) {
    throw ComputationFailed("ArrheniusBratu2D::point_with_amplitude: cannot factor at u = 0");
  }
  double reached = 0.0;
  double step = kLargestStep;
  while (reached < amplitude) {
    tangent.setZero();
    tangent(m) = 1.0;
    lu->solve(tangent, tangent);
    const double target = std::min(amplitude, reached + step);
    Eigen::VectorXd candidate = x + (target - reached) * tangent;
    if (newton(candidate, target)) {
      x = candidate;
      reached = target;
      step = std::min(kLargestStep, 2.0 * step);
      continue;
    }
    step /= 2.0;
    if (step < kSmallestStep || !factor_at(x)) {
      std::ostringstream message;
      message << "ArrheniusBratu2D::point_with_amplitude: Newton's method did not converge "
                 "beyond amplitude "
              << reached << " (target " << amplitude << "), epsilon " << epsilon;
      throw ComputationFailed(message.str());
    }
  }
  return x;
}

std::optional<Dynamics> WhitneyPleat::dynamics() const {
  Dynamics dynamics;
  dynamics.parameters = {1, 2};
  dynamics.sign = -1.0;
  return dynamics;
}

std::optional<Dynamics> StirredTankReactor::dynamics() const {
  Dynamics dynamics;
  dynamics.parameters = {2, 3};
  return dynamics;
}

std::optional<Dynamics> ArrheniusBratu::dynamics() const {
  const double h = 1.0 / (point_count_ + 1);
  Dynamics dynamics;
  dynamics.parameters = {point_count_, point_count_ + 1};
  dynamics.mass_diagonal = Eigen::VectorXd::Constant(point_count_, h * h);
  return dynamics;
}

std::optional<Dynamics> ArrheniusBratu2D::dynamics() const {
  const double h = 1.0 / (grid_size_ + 1);
  const int states = grid_size_ * grid_size_;
  Dynamics dynamics;
  dynamics.parameters = {states, states + 1};
  dynamics.mass_diagonal = Eigen::VectorXd::Constant(states, h * h);
  return dynamics;
}

}  // namespace tessera
