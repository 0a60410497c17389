// SPDX-License-Identifier: MIT
#include "tessera/core/linearization.h"

#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <random>

#include "tessera/core/counted_problem.h"
#include "tessera/core/error.h"

namespace tessera {

// Relative threshold below which |R_ii| counts as zero: J is then treated as rank deficient.
// 1e-10 leaves ample room above rounding (1e-16) for Jacobians of moderate condition.
constexpr double kRankThreshold = 1e-10;

class LinearizationBackend {
 public:
  virtual ~LinearizationBackend() = default;
  virtual std::unique_ptr<LinearizationBackend> clone() const = 0;
  /// Factors; fills the (unnormalised, unoriented) tangent basis. Returns false if singular.
  virtual bool factor(const ImplicitProblem& problem, const Eigen::Ref<const Eigen::VectorXd>& x,
                      const Eigen::MatrixXd* reference, Eigen::MatrixXd& tangent,
                      double& reciprocal_condition) = 0;
  virtual void solve(const Eigen::Ref<const Eigen::VectorXd>& rhs, const Eigen::MatrixXd& tangent,
                     Eigen::Ref<Eigen::VectorXd> dx) const = 0;
  /// Numerical factorisations made so far (a sparse factor() may try more than one border).
  long factorisations() const { return factorisations_; }

 protected:
  long factorisations_ = 0;
};

namespace {

// Jᵀ P = Q R  ⇒  J = P Rᵀ Qᵀ; the minimum-norm solution of J dx = r is Q1 R⁻ᵀ Pᵀ r.
void minimum_norm_from_qr(const Eigen::ColPivHouseholderQR<Eigen::MatrixXd>& qr,
                          const Eigen::Ref<const Eigen::VectorXd>& rhs,
                          Eigen::Ref<Eigen::VectorXd> dx) {
  const int m = static_cast<int>(rhs.size());
  const int n = static_cast<int>(dx.size());
  // Scratch kept between calls: the chord corrector solves here at every iteration, and at
  // small n the allocations would cost more than the arithmetic.
  thread_local Eigen::VectorXd z;
  thread_local Eigen::VectorXd padded;
  z = qr.colsPermutation().transpose() * rhs;
  qr.matrixR().topLeftCorner(m, m).transpose().triangularView<Eigen::Lower>().solveInPlace(z);
  padded.setZero(n);
  padded.head(m) = z;
  dx.noalias() = qr.householderQ() * padded;
}

class DenseBackend final : public LinearizationBackend {
 public:
  std::unique_ptr<LinearizationBackend> clone() const override {
    return std::make_unique<DenseBackend>(*this);
  }

  bool factor(const ImplicitProblem& problem, const Eigen::Ref<const Eigen::VectorXd>& x,
              const Eigen::MatrixXd*, Eigen::MatrixXd& tangent,
              double& reciprocal_condition) override {
    const int n = problem.ambient_dimension();
    const int m = n - 2;
    jacobian_.resize(m, n);
    problem.jacobian(x, jacobian_);
    if (!jacobian_.allFinite()) {
      return false;
    }
    qr_.compute(jacobian_.transpose());
    ++factorisations_;
    const auto& R = qr_.matrixR();
    double largest = 0.0;
    double smallest = std::numeric_limits<double>::infinity();
    for (int i = 0; i < m; ++i) {
      largest = std::max(largest, std::abs(R(i, i)));
      smallest = std::min(smallest, std::abs(R(i, i)));
    }
    reciprocal_condition = m == 0 ? 1.0 : (largest > 0 ? smallest / largest : 0.0);
    if (m > 0 && reciprocal_condition < kRankThreshold) {
      return false;
    }
    // Q2: the last two columns of Q span the orthogonal complement of range Jᵀ, i.e. ker J.
    Eigen::MatrixXd selector = Eigen::MatrixXd::Zero(n, 2);
    selector(m, 0) = 1.0;
    selector(m + 1, 1) = 1.0;
    tangent = qr_.householderQ() * selector;
    return true;
  }

  void solve(const Eigen::Ref<const Eigen::VectorXd>& rhs, const Eigen::MatrixXd&,
             Eigen::Ref<Eigen::VectorXd> dx) const override {
    minimum_norm_from_qr(qr_, rhs, dx);
  }

 private:
  Eigen::MatrixXd jacobian_;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr_;
};

class SparseBackend final : public LinearizationBackend {
 public:
  std::unique_ptr<LinearizationBackend> clone() const override {
    // SparseLU is not copyable; a copy refactors lazily from the stored bordered matrix.
    auto copy = std::make_unique<SparseBackend>();
    copy->bordered_ = bordered_;
    copy->last_tangent_ = last_tangent_;
    if (bordered_.rows() > 0) {
      copy->lu_.analyzePattern(copy->bordered_);
      copy->lu_.factorize(copy->bordered_);
      copy->analyzed_outer_ = analyzed_outer_;
      copy->analyzed_inner_ = analyzed_inner_;
    }
    return copy;
  }

  bool factor(const ImplicitProblem& problem, const Eigen::Ref<const Eigen::VectorXd>& x,
              const Eigen::MatrixXd* reference, Eigen::MatrixXd& tangent,
              double& reciprocal_condition) override {
    const int n = problem.ambient_dimension();
    problem.sparse_jacobian(x, jacobian_);
    for (int k = 0; k < jacobian_.nonZeros(); ++k) {
      if (!std::isfinite(jacobian_.valuePtr()[k])) {
        return false;
      }
    }
    // Border J with two coordinate rows e_iᵀ, e_jᵀ (a local parametrisation by x_i, x_j, as in
    // PITCON): A stays as sparse as J and its LU costs O(n) for banded J. (i, j) maximises
    // |det| of the reference tangent's rows i, j, so A is as well conditioned as the reference
    // allows. The last resort is two dense pseudo-random rows: transversal to ker J with
    // probability one, but they fill the LU (O(n²); bench/RESULTS.md).
    const Eigen::MatrixXd* guide = reference != nullptr ? reference
                                   : last_tangent_.rows() == n ? &last_tangent_
                                                               : nullptr;
    // Without a guide, try the last two coordinates first: in parameter-dependent problems
    // x = (u, λ, μ) the two parameters usually parametrise M locally (away from folds).
    const Border last_two{{n - 2, n - 2, 1.0}, {n - 1, n - 1, 1.0}};
    if (guide != nullptr && factor_bordered(n, coordinate_border(*guide), tangent)) {
      last_tangent_ = tangent;
    } else if (guide == nullptr && factor_bordered(n, last_two, tangent)) {
      last_tangent_ = tangent;
    } else if (factor_bordered(n, random_border(n), tangent)) {
      last_tangent_ = tangent;
    } else {
      return false;
    }
    // Cheap conditioning proxy: residual of J·T relative to ‖J‖ (exact kernels give ~1e-16).
    const double jacobian_norm = jacobian_.norm();
    const double kernel_residual = (jacobian_ * tangent).norm();
    reciprocal_condition =
        jacobian_norm > 0 ? std::max(1e-300, 1.0 - kernel_residual / jacobian_norm) : 0.0;
    return jacobian_norm > 0 && kernel_residual <= 1e-8 * jacobian_norm;
  }

  void solve(const Eigen::Ref<const Eigen::VectorXd>& rhs, const Eigen::MatrixXd& tangent,
             Eigen::Ref<Eigen::VectorXd> dx) const override {
    const int n = static_cast<int>(dx.size());
    Eigen::VectorXd extended = Eigen::VectorXd::Zero(n);
    extended.head(n - 2) = rhs;
    Eigen::VectorXd solution = lu_.solve(extended);
    // Remove the ker-J component: what remains is the minimum-norm solution.
    solution -= tangent * (tangent.transpose() * solution);
    dx = solution;
  }

 private:
  // Border rows as triplets (row index n−2+j, column, value).
  using Border = std::vector<Eigen::Triplet<double>>;

  static Border coordinate_border(const Eigen::MatrixXd& T) {
    const int n = static_cast<int>(T.rows());
    int i = 0;
    T.rowwise().squaredNorm().maxCoeff(&i);
    int j = i == 0 ? 1 : 0;
    double best = -1.0;
    for (int k = 0; k < n; ++k) {
      const double det = std::abs(T(i, 0) * T(k, 1) - T(i, 1) * T(k, 0));
      if (k != i && det > best) {
        best = det;
        j = k;
      }
    }
    return {{n - 2, i, 1.0}, {n - 1, j, 1.0}};
  }

  static Border random_border(int n) {
    // A fixed seed keeps runs deterministic.
    std::mt19937_64 generator(20261121);
    std::normal_distribution<double> normal;
    Border border;
    for (int j = 0; j < 2; ++j) {
      for (int i = 0; i < n; ++i) {
        border.emplace_back(n - 2 + j, i, normal(generator));
      }
    }
    return border;
  }

  // Factors A = [J; border] and computes the orthonormal kernel basis of J; false if A is
  // singular or the basis is not accurate (the border was nearly tangent-blind).
  bool factor_bordered(int n, const Border& border, Eigen::MatrixXd& tangent) {
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(jacobian_.nonZeros() + border.size());
    for (int k = 0; k < jacobian_.outerSize(); ++k) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(jacobian_, k); it; ++it) {
        entries.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
      }
    }
    entries.insert(entries.end(), border.begin(), border.end());
    bordered_.resize(n, n);
    bordered_.setFromTriplets(entries.begin(), entries.end());
    bordered_.makeCompressed();
    // The symbolic analysis (ordering) is redone only when the pattern changes.
    if (!has_same_pattern(bordered_)) {
      lu_.analyzePattern(bordered_);
      analyzed_outer_.assign(bordered_.outerIndexPtr(), bordered_.outerIndexPtr() + n + 1);
      analyzed_inner_.assign(bordered_.innerIndexPtr(),
                             bordered_.innerIndexPtr() + bordered_.nonZeros());
    }
    lu_.factorize(bordered_);
    ++factorisations_;
    if (lu_.info() != Eigen::Success) {
      return false;
    }
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 2);
    rhs(n - 2, 0) = 1.0;
    rhs(n - 1, 1) = 1.0;
    tangent = lu_.solve(rhs);
    if (!tangent.allFinite()) {
      return false;
    }
    // Orthonormalise (modified Gram–Schmidt, twice for stability).
    for (int pass = 0; pass < 2; ++pass) {
      tangent.col(0).normalize();
      tangent.col(1) -= tangent.col(0).dot(tangent.col(1)) * tangent.col(0);
      tangent.col(1).normalize();
    }
    return tangent.allFinite() &&
           (jacobian_ * tangent).norm() <= 1e-8 * std::max(1.0, jacobian_.norm());
  }

  bool has_same_pattern(const Eigen::SparseMatrix<double>& A) const {
    return static_cast<std::size_t>(A.outerSize()) + 1 == analyzed_outer_.size() &&
           static_cast<std::size_t>(A.nonZeros()) == analyzed_inner_.size() &&
           std::equal(analyzed_outer_.begin(), analyzed_outer_.end(), A.outerIndexPtr()) &&
           std::equal(analyzed_inner_.begin(), analyzed_inner_.end(), A.innerIndexPtr());
  }

  Eigen::SparseMatrix<double> jacobian_;
  Eigen::SparseMatrix<double> bordered_;
  std::vector<int> analyzed_outer_;  // pattern of the last symbolic analysis
  std::vector<int> analyzed_inner_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu_;
  Eigen::MatrixXd last_tangent_;  // guides the border of the next factorisation
};

}  // namespace

Linearization::Linearization() = default;
Linearization::~Linearization() = default;
Linearization::Linearization(Linearization&&) noexcept = default;
Linearization& Linearization::operator=(Linearization&&) noexcept = default;
Linearization::Linearization(const Linearization& other)
    : backend_(other.backend_ ? other.backend_->clone() : nullptr),
      point_(other.point_),
      tangent_(other.tangent_),
      reciprocal_condition_(other.reciprocal_condition_),
      factored_(other.factored_) {}
Linearization& Linearization::operator=(const Linearization& other) {
  if (this != &other) {
    Linearization copy(other);
    *this = std::move(copy);
  }
  return *this;
}

bool Linearization::factor(const ImplicitProblem& problem,
                           const Eigen::Ref<const Eigen::VectorXd>& x,
                           const Eigen::MatrixXd* reference_tangent) {
  const int n = problem.ambient_dimension();
  TESSERA_CHECK(x.size() == n, "point has " << x.size() << " coordinates, problem '"
                                            << problem.name() << "' has n = " << n);
  TESSERA_CHECK(reference_tangent == nullptr ||
                    (reference_tangent->rows() == n && reference_tangent->cols() == 2),
                "reference tangent basis must be " << n << "×2");
  factored_ = false;
  if (!x.allFinite()) {
    return false;
  }
  if (!backend_) {
    if (problem.has_sparse_jacobian()) {
      backend_ = std::make_unique<SparseBackend>();
    } else {
      backend_ = std::make_unique<DenseBackend>();
    }
  }
  point_ = x;
  const long before = backend_->factorisations();
  const bool is_factored =
      backend_->factor(problem, x, reference_tangent, tangent_, reciprocal_condition_);
  // Factorisations are the currency of continuation at large n: the run's counter sees them.
  if (const auto* counted = dynamic_cast<const CountedProblem*>(&problem)) {
    counted->record_factorisations(backend_->factorisations() - before);
  }
  if (!is_factored) {
    return false;
  }
  if (reference_tangent != nullptr) {
    align_tangent_basis(tangent_, *reference_tangent);
  }
  factored_ = true;
  return true;
}

void Linearization::solve_minimum_norm(const Eigen::Ref<const Eigen::VectorXd>& rhs,
                                       Eigen::Ref<Eigen::VectorXd> dx) const {
  TESSERA_ASSERT(factored_);
  backend_->solve(rhs, tangent_, dx);
}

bool tangent_basis_near(const ImplicitProblem& problem, const Linearization& near,
                        const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::MatrixXd& T,
                        double tolerance, int max_iterations) {
  TESSERA_ASSERT(near.is_factored());
  const int n = problem.ambient_dimension();
  const int m = n - 2;
  // J(y)·T, from the sparse or the dense Jacobian as the problem prefers.
  Eigen::SparseMatrix<double> sparse;
  Eigen::MatrixXd dense;
  double jacobian_norm = 0.0;
  if (problem.has_sparse_jacobian()) {
    problem.sparse_jacobian(y, sparse);
    jacobian_norm = sparse.norm();
  } else {
    dense.resize(m, n);
    problem.jacobian(y, dense);
    jacobian_norm = dense.norm();
  }
  if (!std::isfinite(jacobian_norm) || jacobian_norm == 0.0) {
    return false;
  }
  const auto residual = [&](const Eigen::MatrixXd& basis) -> Eigen::MatrixXd {
    return problem.has_sparse_jacobian() ? Eigen::MatrixXd(sparse * basis)
                                         : Eigen::MatrixXd(dense * basis);
  };
  T = near.tangent_basis();
  Eigen::VectorXd correction(n);
  for (int iteration = 0; iteration <= max_iterations; ++iteration) {
    const Eigen::MatrixXd JT = residual(T);
    if (JT.norm() <= tolerance * jacobian_norm) {
      return true;
    }
    if (iteration == max_iterations) {
      break;
    }
    for (int j = 0; j < 2; ++j) {
      near.solve_minimum_norm(JT.col(j), correction);
      T.col(j) -= correction;
    }
    // Orthonormalise (modified Gram–Schmidt): ker J(y) is spanned either way.
    T.col(0).normalize();
    T.col(1) -= T.col(0).dot(T.col(1)) * T.col(0);
    T.col(1).normalize();
    if (!T.allFinite()) {
      return false;
    }
  }
  return false;
}

bool solve_minimum_norm_dense(const Eigen::Ref<const Eigen::MatrixXd>& J,
                              const Eigen::Ref<const Eigen::VectorXd>& rhs,
                              Eigen::Ref<Eigen::VectorXd> dx) {
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(J.transpose());
  if (qr.rank() < J.rows()) {
    return false;
  }
  minimum_norm_from_qr(qr, rhs, dx);
  return true;
}

void align_tangent_basis(Eigen::MatrixXd& T, const Eigen::MatrixXd& reference) {
  const Eigen::Matrix2d overlap = T.transpose() * reference;
  if (overlap.determinant() < 0) {
    T.col(1) *= -1.0;
  }
}

}  // namespace tessera
