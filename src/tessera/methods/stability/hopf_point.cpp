// SPDX-License-Identifier: MIT
#include "tessera/methods/stability/hopf_point.h"

#include <Eigen/Dense>
#include <Eigen/SparseLU>
#include <cmath>
#include <complex>
#include <memory>
#include <optional>

#include "tessera/core/linearization.h"
#include "tessera/core/metric_problem.h"
#include "tessera/methods/stability/state_jacobian.h"

namespace tessera {

namespace {

using Complex = std::complex<double>;
using SparseComplex = Eigen::SparseMatrix<Complex>;

enum class PencilKind { Hopf, NeutralSaddle, ZeroHopf };

Eigen::SparseMatrix<double> sparse_of(const StateJacobian& jacobian) {
  if (jacobian.is_sparse()) {
    return jacobian.sparse();
  }
  Eigen::SparseMatrix<double> A = jacobian.dense().sparseView();
  A.makeCompressed();
  return A;
}

// The complex bordered matrix [A − σB, b; cᴴ, 0], factored, with the solves that give g and the
// null vectors: [A − σB, b; cᴴ, 0]·[v; g] = [0; 1] and its adjoint, ·ᴴ[w; h] = [0; 1]. Without
// borders (b, c empty) it is A − σB alone, for inverse iteration.
class BorderedPencil {
 public:
  bool factor(const Eigen::SparseMatrix<double>& A, const Eigen::SparseMatrix<double>& B,
              Complex sigma, const Eigen::VectorXcd& b, const Eigen::VectorXcd& c) {
    const int m = static_cast<int>(A.rows());
    const bool bordered = b.size() > 0;
    const int size = bordered ? m + 1 : m;
    std::vector<Eigen::Triplet<Complex>> entries;
    entries.reserve(static_cast<std::size_t>(A.nonZeros() + B.nonZeros() + 2 * m));
    for (int k = 0; k < A.outerSize(); ++k) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
        entries.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
      }
    }
    if (sigma != Complex(0.0)) {
      for (int k = 0; k < B.outerSize(); ++k) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(B, k); it; ++it) {
          entries.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), -sigma * it.value());
        }
      }
    }
    if (bordered) {
      for (int i = 0; i < m; ++i) {
        entries.emplace_back(i, m, b(i));
        entries.emplace_back(m, i, std::conj(c(i)));
      }
    }
    matrix_.resize(size, size);
    matrix_.setFromTriplets(entries.begin(), entries.end());
    matrix_.makeCompressed();
    lu_.compute(matrix_);
    ++factorisations;
    return lu_.info() == Eigen::Success;
  }
  Eigen::VectorXcd solve(const Eigen::VectorXcd& rhs) const { return lu_.solve(rhs); }
  Eigen::VectorXcd solve_adjoint(const Eigen::VectorXcd& rhs) {
    return lu_.adjoint().solve(rhs);
  }
  long factorisations = 0;

 private:
  SparseComplex matrix_;
  Eigen::SparseLU<SparseComplex> lu_;
};

// DF(x) (full, (n−2)×n), dense or sparse.
class FullJacobian {
 public:
  void evaluate(const ImplicitProblem& problem, const Eigen::Ref<const Eigen::VectorXd>& x) {
    is_sparse_ = problem.has_sparse_jacobian();
    if (is_sparse_) {
      problem.sparse_jacobian(x, sparse_);
    } else {
      dense_.resize(problem.equation_count(), problem.ambient_dimension());
      problem.jacobian(x, dense_);
    }
  }
  Eigen::VectorXd transpose_times(const Eigen::VectorXd& u) const {
    return is_sparse_ ? Eigen::VectorXd(sparse_.transpose() * u)
                      : Eigen::VectorXd(dense_.transpose() * u);
  }

 private:
  bool is_sparse_ = false;
  Eigen::SparseMatrix<double> sparse_;
  Eigen::MatrixXd dense_;
};

// The Newton iterations of both systems on the problem seen in its metric (ScaledProblem), as
// the fold solver: y = W x, minimum-norm corrections and tolerances in the metric.
class AugmentedNewton {
 public:
  AugmentedNewton(const ImplicitProblem& problem, const HopfOptions& options)
      : options_(options),
        metric_(problem),
        original_(problem),
        jacobian_(original_, "Hopf curves"),
        mass_(jacobian_.mass()) {}

  WorkCounts work() const {
    WorkCounts work = metric_.work();
    work.function_evaluations += original_.function_evaluations();
    work.jacobian_evaluations += original_.jacobian_evaluations();
    work.factorisations += pencil_.factorisations;
    return work;
  }

  // Newton on F = 0 and the pencil condition of `kind` with its parameter p (ω for a Hopf point:
  // A − iωB singular, the real and imaginary parts of one complex g; κ for a neutral saddle:
  // A − κB and A + κB singular, two real g's).
  HopfPoint pencil_point(PencilKind kind, const Eigen::VectorXd& x_start, double parameter,
                         double max_displacement) {
    HopfPoint point;
    Eigen::VectorXd y = to_metric(x_start);
    const Eigen::VectorXd start = y;
    const bool is_hopf = kind != PencilKind::NeutralSaddle;
    // The shifts σ_j(p) of the pencils, dσ_j/dp, and whether a pencil's g is complex (two
    // equations: its real and imaginary part) or real (one). Zero-Hopf: the Hopf pencil and A
    // itself (a fold).
    auto shifts = [&](double p) {
      switch (kind) {
        case PencilKind::Hopf:
          return std::vector<Complex>{Complex(0.0, p)};
        case PencilKind::NeutralSaddle:
          return std::vector<Complex>{p, -p};
        case PencilKind::ZeroHopf:
          break;
      }
      return std::vector<Complex>{Complex(0.0, p), 0.0};
    };
    const std::vector<Complex> shift_derivatives =
        kind == PencilKind::Hopf            ? std::vector<Complex>{Complex(0.0, 1.0)}
        : kind == PencilKind::NeutralSaddle ? std::vector<Complex>{1.0, -1.0}
                                            : std::vector<Complex>{Complex(0.0, 1.0), 0.0};
    const std::vector<bool> is_complex = kind == PencilKind::Hopf            ? std::vector<bool>{true}
                                         : kind == PencilKind::NeutralSaddle ? std::vector<bool>{false, false}
                                                                             : std::vector<bool>{true, false};
    const std::size_t pencils = shift_derivatives.size();
    const int rows = kind == PencilKind::ZeroHopf ? 3 : 2;
    std::vector<Eigen::VectorXcd> v(pencils);
    std::vector<Eigen::VectorXcd> w(pencils);
    for (std::size_t j = 0; j < pencils; ++j) {
      if (!start_vectors(from_metric(y), shifts(parameter)[j], v[j], w[j])) {
        point.x = x_start;
        return point;
      }
      if (!is_complex[j]) {  // real shifts: real null vectors
        v[j] = v[j].real().cast<Complex>().normalized();
        w[j] = w[j].real().cast<Complex>().normalized();
      }
    }
    for (int iteration = 1; iteration <= options_.max_iterations; ++iteration) {
      point.iterations = iteration;
      Eigen::VectorXd F;
      Eigen::MatrixXd T;
      Eigen::VectorXd dy_p;
      if (!manifold_step(y, F, T, dy_p)) {
        break;
      }
      // Rows of the system in (a₁, a₂, dp): Re and Im of a complex g, a real g once.
      Eigen::MatrixXd J(rows, 3);
      Eigen::VectorXd rhs(rows);
      Eigen::Index row = 0;
      bool ok = true;
      for (std::size_t j = 0; j < pencils && ok; ++j) {
        Complex g;
        if (!bordered_solve(from_metric(y), shifts(parameter)[j], v[j], w[j], g)) {
          ok = false;
          break;
        }
        // dg[δy] = −wᴴ·s·D²F[ṽ, δx], δx = δy/W; dg/dσ = wᴴBv.
        const Eigen::VectorXcd gradient = g_gradient(from_metric(y), v[j], w[j]);
        const Complex g_p = shift_derivatives[j] * w[j].dot(mass_ * v[j]);
        const Complex q_p = gradient.dot(dy_p);
        const Complex q_1 = gradient.dot(Eigen::VectorXd(T.col(0)));
        const Complex q_2 = gradient.dot(Eigen::VectorXd(T.col(1)));
        J.row(row) << q_1.real(), q_2.real(), g_p.real();
        rhs(row++) = -(g + q_p).real();
        if (is_complex[j]) {
          J.row(row) << q_1.imag(), q_2.imag(), g_p.imag();
          rhs(row++) = -(g + q_p).imag();
        }
      }
      if (!ok) {
        break;
      }
      Eigen::Vector3d z;
      if (rows == 3) {  // a point: the square system
        if (!J.allFinite() || !(std::abs(J.determinant()) > 0.0)) {
          break;
        }
        z = J.partialPivLu().solve(rhs);
        point.curve_tangent.resize(0);
      } else {
        const Eigen::Matrix2d JJt = J * J.transpose();
        if (!J.allFinite() || !(std::abs(JJt.determinant()) > 0.0)) {
          break;
        }
        z = J.transpose() * JJt.ldlt().solve(rhs);
        // The curve's direction: the null vector of J (a cross product of its rows), its
        // tangent part.
        const Eigen::Vector3d null = Eigen::Vector3d(J.row(0)).cross(Eigen::Vector3d(J.row(1)));
        point.curve_tangent = T * null.head<2>();
        if (point.curve_tangent.norm() > 0.0) {
          point.curve_tangent = from_metric(point.curve_tangent).normalized();
        }
      }
      const Eigen::VectorXd dy = dy_p + T * z.head<2>();
      y += dy;
      parameter += z(2);
      if (!y.allFinite() || !std::isfinite(parameter) || (y - start).norm() > max_displacement) {
        break;
      }
      if (dy.norm() <= options_.tolerance * (1.0 + y.norm()) &&
          std::abs(z(2)) <= options_.tolerance * (1.0 + std::abs(parameter)) &&
          F.norm() <= options_.residual_tolerance) {
        finish(y, shifts(parameter)[0], v[0], w[0], point);
        if (!is_hopf) {
          // The residual of the condition: the Rayleigh quotients should be ±κ.
          point.condition_residual = rayleigh_residual(point.x, shifts(parameter), v, w);
        }
        (is_hopf ? point.omega : point.kappa) = std::abs(parameter);
        point.is_neutral_saddle = !is_hopf;
        point.is_zero_hopf = kind == PencilKind::ZeroHopf;
        return point;
      }
    }
    point.x = x_start;
    return point;
  }

  HopfPoint bogdanov_takens(const Eigen::VectorXd& x_start, double max_displacement) {
    HopfPoint point;
    Eigen::VectorXd y = to_metric(x_start);
    const Eigen::VectorXd start = y;
    Eigen::VectorXcd v;
    Eigen::VectorXcd w;
    if (!start_vectors(from_metric(y), Complex(0.0), v, w)) {
      point.x = x_start;
      return point;
    }
    v = v.real().cast<Complex>().normalized();
    w = w.real().cast<Complex>().normalized();
    for (int iteration = 1; iteration <= options_.max_iterations; ++iteration) {
      point.iterations = iteration;
      Eigen::VectorXd F;
      Eigen::MatrixXd T;
      Eigen::VectorXd dy_p;
      if (!manifold_step(y, F, T, dy_p)) {
        break;
      }
      Complex g1;
      Eigen::VectorXcd v_new = v;
      Eigen::VectorXcd w_new = w;
      if (!bordered_solve(from_metric(y), Complex(0.0), v_new, w_new, g1)) {
        break;
      }
      const double g2 = jordan_condition(v_new, w_new);
      const Eigen::VectorXcd gradient = g_gradient(from_metric(y), v_new, w_new);
      // g₂'s derivatives by forward differences along dy_p, T₁ and T₂ (borders kept).
      auto g2_at = [&](const Eigen::VectorXd& direction) {
        const double h = options_.difference_step * (1.0 + y.norm()) / std::max(direction.norm(), 1e-300);
        Eigen::VectorXcd v_h = v;
        Eigen::VectorXcd w_h = w;
        Complex unused;
        if (!bordered_solve(from_metric(Eigen::VectorXd(y + h * direction)), Complex(0.0), v_h, w_h, unused)) {
          return std::numeric_limits<double>::quiet_NaN();
        }
        return (jordan_condition(v_h, w_h) - g2) / h;
      };
      const Eigen::VectorXd t1 = T.col(0);
      const Eigen::VectorXd t2 = T.col(1);
      Eigen::Matrix2d J;
      J << gradient.dot(t1).real(), gradient.dot(t2).real(), g2_at(t1), g2_at(t2);
      const double dg2_p = dy_p.norm() > 0.0 ? g2_at(dy_p) : 0.0;
      const Eigen::Vector2d rhs(-(g1 + gradient.dot(dy_p)).real(), -(g2 + dg2_p));
      if (!J.allFinite() || !std::isfinite(dg2_p) || !(std::abs(J.determinant()) > 0.0)) {
        break;
      }
      const Eigen::Vector2d a = J.partialPivLu().solve(rhs);
      const Eigen::VectorXd dy = dy_p + T * a;
      y += dy;
      v = v_new.normalized();
      w = w_new.normalized();
      if (!y.allFinite() || (y - start).norm() > max_displacement) {
        break;
      }
      if (dy.norm() <= options_.tolerance * (1.0 + y.norm()) &&
          F.norm() <= options_.residual_tolerance) {
        finish(y, Complex(0.0), v, w, point);
        point.omega = 0.0;
        point.curve_tangent.resize(0);
        return point;
      }
    }
    point.x = x_start;
    return point;
  }

 private:
  Eigen::VectorXd to_metric(const Eigen::VectorXd& x) const { return metric_.to_metric(x); }
  Eigen::VectorXd from_metric(const Eigen::VectorXd& y) const { return metric_.from_metric(y); }

  // F(y), M's tangent basis T at y and the normal correction dy_p = −DF⁺F.
  bool manifold_step(const Eigen::VectorXd& y, Eigen::VectorXd& F, Eigen::MatrixXd& T,
                     Eigen::VectorXd& dy_p) {
    F.resize(metric_.counted().equation_count());
    metric_.counted().evaluate(y, F);
    if (!F.allFinite() || !linearization_.factor(metric_.counted(), y)) {
      return false;
    }
    T = linearization_.tangent_basis();
    dy_p.resize(y.size());
    linearization_.solve_minimum_norm(-F, dy_p);
    return dy_p.allFinite();
  }

  // Two steps of inverse iteration with A − σB from fixed vectors: right (v) and left (w) null
  // vectors of the pencil near σ, the borders of the first bordered system.
  bool start_vectors(const Eigen::VectorXd& x, Complex sigma, Eigen::VectorXcd& v,
                     Eigen::VectorXcd& w) {
    if (!jacobian_.evaluate(x)) {
      return false;
    }
    const int m = jacobian_.state_count();
    const Eigen::SparseMatrix<double> A = sparse_of(jacobian_);
    Eigen::VectorXcd u(m);
    for (int i = 0; i < m; ++i) {
      u(i) = Complex(1.0 + 0.1 * (i % 7), i % 2 == 0 ? 0.5 : -0.5);
    }
    // σ may be an eigenvalue to rounding (an estimate on the curve): the factorisation then
    // fails or its solves overflow. Any vector is as good a start there, so move σ off it, by
    // 10⁻⁸ relative to the pencil's scale, in a complex direction.
    const double scale = 1.0 + std::abs(sigma) + A.norm();
    for (const double offset : {0.0, 1e-8, 1e-6}) {
      const Complex shift = sigma + offset * scale * Complex(1.0, 1.0);
      if (!pencil_.factor(A, mass_, shift, {}, {})) {
        continue;
      }
      v = u;
      w = u;
      for (int step = 0; step < 2; ++step) {
        v = pencil_.solve(Eigen::VectorXcd(mass_ * v));
        w = pencil_.solve_adjoint(Eigen::VectorXcd(mass_.transpose() * w));
        const double v_norm = v.norm();
        const double w_norm = w.norm();
        if (!(v_norm > 0.0) || !(w_norm > 0.0) || !std::isfinite(v_norm) || !std::isfinite(w_norm)) {
          break;
        }
        v /= v_norm;
        w /= w_norm;
      }
      if (v.allFinite() && w.allFinite() && std::abs(v.norm() - 1.0) < 1e-8 &&
          std::abs(w.norm() - 1.0) < 1e-8) {
        return true;
      }
    }
    return false;
  }

  // Factors the bordered pencil at x with borders b = w, c = v and solves: on return v, w are the
  // new null vectors (normalised) and g the bordered system's last entry.
  bool bordered_solve(const Eigen::VectorXd& x, Complex sigma, Eigen::VectorXcd& v,
                      Eigen::VectorXcd& w, Complex& g) {
    if (!jacobian_.evaluate(x)) {
      return false;
    }
    const int m = jacobian_.state_count();
    const Eigen::VectorXcd b = w.normalized();
    const Eigen::VectorXcd c = v.normalized();
    if (!pencil_.factor(sparse_of(jacobian_), mass_, sigma, b, c)) {
      return false;
    }
    Eigen::VectorXcd e = Eigen::VectorXcd::Zero(m + 1);
    e(m) = 1.0;
    const Eigen::VectorXcd vg = pencil_.solve(e);
    const Eigen::VectorXcd wh = pencil_.solve_adjoint(e);
    if (!vg.allFinite() || !wh.allFinite()) {
      return false;
    }
    v = vg.head(m);
    w = wh.head(m);
    g = vg(m);
    return true;
  }

  // The gradient of g over y (conjugated, so that gradient.dot(δy) = dg[δy]):
  // dg[δx] = −wᴴ·s·D²F[ṽ, δx] with ṽ = v in the state coordinates, by central differences of DF
  // along Re ṽ and Im ṽ; then δx = δy/W.
  Eigen::VectorXcd g_gradient(const Eigen::VectorXd& x, const Eigen::VectorXcd& v,
                              const Eigen::VectorXcd& w) {
    const int n = static_cast<int>(x.size());
    const double s = jacobian_.dynamics().sign;
    const auto& states = jacobian_.states();
    Eigen::VectorXcd row = Eigen::VectorXcd::Zero(n);  // dg[δx] = Σ row_j δx_j
    const double h = options_.difference_step * (1.0 + x.lpNorm<Eigen::Infinity>());
    const Eigen::VectorXcd w_conj = w.conjugate();
    for (int part = 0; part < 2; ++part) {
      Eigen::VectorXd direction = Eigen::VectorXd::Zero(n);
      for (std::size_t i = 0; i < states.size(); ++i) {
        const Complex vi = v(static_cast<Eigen::Index>(i));
        direction(states[i]) = part == 0 ? vi.real() : vi.imag();
      }
      const double norm = direction.lpNorm<Eigen::Infinity>();
      if (norm == 0.0) {
        continue;
      }
      const double step = h / norm;
      plus_.evaluate(original_, x + step * direction);
      minus_.evaluate(original_, x - step * direction);
      // (wᴴ K)_j = Σ_i conj(w_i) K_ij = (Kᵀ conj(w))_j, K = D²F[direction, ·], real.
      const Eigen::VectorXd re = (plus_.transpose_times(w_conj.real()) -
                                  minus_.transpose_times(w_conj.real())) / (2 * step);
      const Eigen::VectorXd im = (plus_.transpose_times(w_conj.imag()) -
                                  minus_.transpose_times(w_conj.imag())) / (2 * step);
      const Complex factor = part == 0 ? Complex(1.0) : Complex(0.0, 1.0);
      row += -s * factor * (re.cast<Complex>() + Complex(0.0, 1.0) * im.cast<Complex>());
    }
    // In y: dg[δy] = Σ row_j δy_j / W_j; returned conjugated for Eigen's dot.
    if (metric_.weights().size() > 0) {
      row = row.cwiseQuotient(metric_.weights().cast<Complex>());
    }
    return row.conjugate();
  }

  // wᵀBv relative to ‖w‖‖v‖ (real vectors at a real singular A).
  double jordan_condition(const Eigen::VectorXcd& v, const Eigen::VectorXcd& w) const {
    return (w.real().dot(mass_ * v.real())) / (w.real().norm() * v.real().norm());
  }

  // max_j |μ_j − σ_j|/max(1, |σ_j|) for the Rayleigh quotients μ_j of the pencils' null vectors.
  double rayleigh_residual(const Eigen::VectorXd& x, const std::vector<Complex>& sigmas,
                           std::vector<Eigen::VectorXcd> v, std::vector<Eigen::VectorXcd> w) {
    double worst = 0.0;
    for (std::size_t j = 0; j < sigmas.size(); ++j) {
      Complex g;
      if (!bordered_solve(x, sigmas[j], v[j], w[j], g)) {
        return std::numeric_limits<double>::quiet_NaN();
      }
      const Eigen::SparseMatrix<double> A = sparse_of(jacobian_);
      const Complex mu = w[j].dot(A * v[j]) / w[j].dot(mass_ * v[j]);
      worst = std::max(worst, std::abs(mu - sigmas[j]) / std::max(1.0, std::abs(sigmas[j])));
    }
    return worst;
  }

  // The converged point: its residual and the Rayleigh quotient μ = wᴴAv / wᴴBv of the final
  // null vectors, whose real part is the Hopf condition's residual.
  void finish(const Eigen::VectorXd& y, Complex sigma, Eigen::VectorXcd v, Eigen::VectorXcd w,
              HopfPoint& point) {
    point.x = from_metric(y);
    Eigen::VectorXd F(metric_.counted().equation_count());
    metric_.counted().evaluate(y, F);
    point.residual = F.norm();
    Complex g;
    if (bordered_solve(point.x, sigma, v, w, g)) {
      const Eigen::SparseMatrix<double> A = sparse_of(jacobian_);
      const Complex mu = w.dot(A * v) / w.dot(mass_ * v);
      point.condition_residual = std::abs(mu.real()) / std::max(std::abs(mu), 1e-300);
      if (sigma == Complex(0.0)) {
        point.condition_residual = std::abs(mu) / std::max(1.0, A.norm());
      }
    }
    point.is_refined = F.allFinite() && point.residual <= options_.residual_tolerance;
  }

  HopfOptions options_;
  MetricProblem metric_;
  CountedProblem original_;  // in the problem's own coordinates: the dynamics' Jacobians
  StateJacobian jacobian_;
  Eigen::SparseMatrix<double> mass_;
  Linearization linearization_;
  BorderedPencil pencil_;
  FullJacobian plus_;
  FullJacobian minus_;
};

}  // namespace

HopfPoint refine_hopf_point(const ImplicitProblem& problem, const Eigen::VectorXd& x, double omega,
                            double max_displacement, const HopfOptions& options, WorkCounts& work) {
  AugmentedNewton newton(problem, options);
  HopfPoint point = newton.pencil_point(PencilKind::Hopf, x, omega, max_displacement);
  work += newton.work();
  return point;
}

HopfPoint refine_zero_hopf_point(const ImplicitProblem& problem, const Eigen::VectorXd& x,
                                 double omega, double max_displacement, const HopfOptions& options,
                                 WorkCounts& work) {
  AugmentedNewton newton(problem, options);
  HopfPoint point = newton.pencil_point(PencilKind::ZeroHopf, x, omega, max_displacement);
  work += newton.work();
  return point;
}

HopfPoint refine_neutral_saddle_point(const ImplicitProblem& problem, const Eigen::VectorXd& x,
                                      double kappa, double max_displacement,
                                      const HopfOptions& options, WorkCounts& work) {
  AugmentedNewton newton(problem, options);
  HopfPoint point = newton.pencil_point(PencilKind::NeutralSaddle, x, kappa, max_displacement);
  work += newton.work();
  return point;
}

HopfPoint refine_bogdanov_takens_point(const ImplicitProblem& problem, const Eigen::VectorXd& x,
                                       double max_displacement, const HopfOptions& options,
                                       WorkCounts& work) {
  AugmentedNewton newton(problem, options);
  HopfPoint point = newton.bogdanov_takens(x, max_displacement);
  work += newton.work();
  return point;
}

}  // namespace tessera
