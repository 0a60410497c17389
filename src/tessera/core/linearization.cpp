// SPDX-License-Identifier: MIT
#include "tessera/core/linearization.h"

#include <chrono>

#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <string_view>

#include "tessera/core/ambient_space.h"
#include "tessera/core/bordered_jacobian.h"
#include "tessera/core/counted_problem.h"
#include "tessera/core/error.h"
#include "tessera/core/jacobian_product.h"
#include "tessera/core/linearization_backend.h"
#include "tessera/core/sparse_lu.h"

namespace tessera {

// Relative threshold below which |R_ii| counts as zero: J is then treated as rank deficient.
// 1e-10 leaves ample room above rounding (1e-16) for Jacobians of moderate condition.
constexpr double kRankThreshold = 1e-10;

namespace {

// ‖J‖_F over the stored values as one array: SparseMatrix::norm() walks them by inner
// iterators, 3 % of a front run at n = 10⁴ (bvp), where it is taken at every vertex.
double frobenius_norm(const Eigen::SparseMatrix<double>& J) {
  if (!J.isCompressed()) {
    return J.norm();
  }
  return Eigen::Map<const Eigen::VectorXd>(J.valuePtr(), J.nonZeros()).norm();
}

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
    if (m == 1) {
      return factor_gradient(tangent, reciprocal_condition);
    }
    qr_.compute(jacobian_.transpose());
    is_qr_computed_ = true;
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
    if (jacobian_.rows() == 1) {
      // H [r/β; 0] = (r/β)(e₀ − τ v), as minimum_norm_from_qr computes it (v₀ = 1).
      const double z = rhs(0) / beta_;
      dx = (-z * tau_) * reflector_;
      dx(0) += z;
      return;
    }
    minimum_norm_from_qr(qr_, rhs, dx);
  }

  std::size_t memory_bytes() const override {
    // (qr_ only where it was computed: Eigen asserts on an uncomputed one.)
    const Eigen::Index qr_doubles =
        is_qr_computed_ ? qr_.matrixQR().size() + qr_.hCoeffs().size() : 0;
    return sizeof(double) *
           static_cast<std::size_t>(jacobian_.size() + qr_doubles + reflector_.size());
  }

 private:
  // One equation (a surface in R³): the QR of the gradient g (n×1) is a single Householder
  // reflection H = I − τ v vᵀ with H g = β e₀, formed here as Eigen's makeHouseholder forms it,
  // so that the basis and the solves equal the general path's to rounding, without its
  // allocations and column pivoting (at n = 3 they cost more than F: issue 35).
  bool factor_gradient(Eigen::MatrixXd& tangent, double& reciprocal_condition) {
    const int n = static_cast<int>(jacobian_.cols());
    const double c0 = jacobian_(0, 0);
    const double tail = jacobian_.row(0).tail(n - 1).squaredNorm();
    ++factorisations_;
    reflector_.resize(n);
    reflector_(0) = 1.0;
    if (tail <= std::numeric_limits<double>::min()) {
      tau_ = 0.0;
      beta_ = c0;
      reflector_.tail(n - 1).setZero();
    } else {
      beta_ = std::sqrt(c0 * c0 + tail);
      if (c0 >= 0.0) {
        beta_ = -beta_;
      }
      reflector_.tail(n - 1) = jacobian_.row(0).tail(n - 1).transpose() / (c0 - beta_);
      tau_ = (beta_ - c0) / beta_;
    }
    reciprocal_condition = beta_ != 0.0 ? 1.0 : 0.0;
    if (beta_ == 0.0) {
      return false;
    }
    // ker g: columns 1 and 2 of H, e_k − τ v v_k.
    tangent.resize(n, 2);
    for (int k = 0; k < 2; ++k) {
      tangent.col(k) = (-tau_ * reflector_(k + 1)) * reflector_;
      tangent(k + 1, k) += 1.0;
    }
    return true;
  }

  Eigen::MatrixXd jacobian_;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr_;
  Eigen::VectorXd reflector_;  // v of the one-equation case
  bool is_qr_computed_ = false;
  double tau_ = 0.0;
  double beta_ = 0.0;
};

class SparseBackend final : public LinearizationBackend {
 public:
  // The solver is chosen at the first factorisation, from the bordered matrix's pattern
  // (sparse_lu_solver_for: TESSERA_SPARSE_LU, else by the fill), and kept.
  SparseBackend() = default;
  explicit SparseBackend(SparseLuSolver solver) : lu_(make_sparse_lu(solver)) {}

  std::unique_ptr<LinearizationBackend> clone() const override {
    // Factorisations are not copyable; a copy refactors from the stored bordered matrix.
    auto copy = lu_ ? std::make_unique<SparseBackend>(lu_->solver())
                    : std::make_unique<SparseBackend>();
    copy->bordered_ = bordered_;
    copy->last_tangent_ = last_tangent_;
    if (lu_ && lu_->is_factored() && !assembly_released_ &&
        copy->lu_->analyze(copy->bordered_) == SparseLuStatus::Success) {
      copy->lu_->factorize(copy->bordered_);
    }
    return copy;
  }

  void release_assembly() override {
    // Swapped out, not assigned: an assignment keeps the storage (Eigen's CompressedStorage
    // never shrinks), and the atlas's kept factorisations held DF and the bordered matrix after
    // all, ~1.4 MB each at n = 10⁴, uncounted.
    Eigen::SparseMatrix<double>().swap(jacobian_);
    Eigen::SparseMatrix<double>().swap(bordered_);
    assembly_released_ = true;
  }

  bool clones_factorisation() const override { return !assembly_released_; }

  Eigen::MatrixXd border_guide() const override { return last_tangent_; }
  void set_border_guide(const Eigen::MatrixXd& guide) override { last_tangent_ = guide; }

  bool factor(const ImplicitProblem& problem, const Eigen::Ref<const Eigen::VectorXd>& x,
              const Eigen::MatrixXd* reference, Eigen::MatrixXd& tangent,
              double& reciprocal_condition) override {
    const int n = problem.ambient_dimension();
    assembly_released_ = false;
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
    // probability one, but they fill the LU (O(n²); bench/history/RESULTS-log.md section 6).
    const Eigen::MatrixXd* guide = reference != nullptr        ? reference
                                   : last_tangent_.rows() == n ? &last_tangent_
                                                               : nullptr;
    // Without a guide, try the last two coordinates first: in parameter-dependent problems
    // x = (u, λ, μ) the two parameters usually parametrise M locally (away from folds).
    const JacobianBorder last_two{{n - 2, n - 2, 1.0}, {n - 1, n - 1, 1.0}};
    if (guide != nullptr && factor_bordered(coordinate_border(*guide), tangent)) {
      last_tangent_ = tangent;
    } else if (guide == nullptr && factor_bordered(last_two, tangent)) {
      last_tangent_ = tangent;
    } else if (factor_bordered(random_border(n), tangent)) {
      last_tangent_ = tangent;
    } else {
      return false;
    }
    // Cheap conditioning proxy: residual of J·T relative to ‖J‖ (exact kernels give ~1e-16).
    const double jacobian_norm = frobenius_norm(jacobian_);
    const double kernel_residual = (jacobian_ * tangent).norm();
    reciprocal_condition =
        jacobian_norm > 0 ? std::max(1e-300, 1.0 - kernel_residual / jacobian_norm) : 0.0;
    return jacobian_norm > 0 && kernel_residual <= 1e-8 * jacobian_norm;
  }

  void solve(const Eigen::Ref<const Eigen::VectorXd>& rhs, const Eigen::MatrixXd& tangent,
             Eigen::Ref<Eigen::VectorXd> dx) const override {
    solve_columns(rhs, tangent, dx);
  }

  void solve_columns(const Eigen::Ref<const Eigen::MatrixXd>& rhs, const Eigen::MatrixXd& tangent,
                     Eigen::Ref<Eigen::MatrixXd> dx) const override {
    const Eigen::Index n = dx.rows();
    // Scratch kept between calls: the chord iterations solve here at every step.
    thread_local Eigen::MatrixXd solution;
    solution.resize(n, rhs.cols());
    solution.topRows(n - 2) = rhs;
    solution.bottomRows(2).setZero();
    lu_->solve(solution, solution);
    // Remove the ker-J component: what remains is the minimum-norm solution.
    const Eigen::MatrixXd along = tangent.transpose() * solution;
    dx.noalias() = solution - tangent * along;
  }

  std::size_t memory_bytes() const override {
    // A compressed sparse matrix: a value and an index per entry, an index per column.
    const auto matrix = [](const Eigen::SparseMatrix<double>& A) {
      return static_cast<std::size_t>(A.nonZeros()) * (sizeof(double) + sizeof(int)) +
             static_cast<std::size_t>(A.outerSize() + 1) * sizeof(int);
    };
    std::size_t factors = 0;
    if (lu_ && lu_->is_factored()) {
      factors = lu_->factorisation_bytes().value_or(
          static_cast<std::size_t>(lu_->factor_nonzeros().value_or(2 * bordered_.nonZeros())) *
          (sizeof(double) + sizeof(int)));
    }
    return matrix(jacobian_) + matrix(bordered_) + factors +
           sizeof(double) * static_cast<std::size_t>(last_tangent_.size());
  }

 private:
  // Factors A = [J; border] and computes the orthonormal kernel basis of J; false if A is
  // singular or the basis is not accurate (the border was nearly tangent-blind).
  bool factor_bordered(const JacobianBorder& border, Eigen::MatrixXd& tangent) {
    const int n = static_cast<int>(jacobian_.cols());
    bordered_jacobian(jacobian_, border, bordered_);
    if (!lu_) {
      lu_ = make_sparse_lu(sparse_lu_solver_for(bordered_));
    }
    // The symbolic analysis (ordering) is redone only when the pattern changes.
    if (!lu_->is_analyzed_for(bordered_) && lu_->analyze(bordered_) != SparseLuStatus::Success) {
      return false;
    }
    const SparseLuStatus status = lu_->factorize(bordered_);
    ++factorisations_;
    if (status != SparseLuStatus::Success) {
      return false;
    }
    if (const std::optional<long> nonzeros = lu_->factor_nonzeros(); nonzeros) {
      fill_ = static_cast<double>(*nonzeros) / static_cast<double>(bordered_.nonZeros());
    }
    tangent = Eigen::MatrixXd::Zero(n, 2);
    tangent(n - 2, 0) = 1.0;
    tangent(n - 1, 1) = 1.0;
    lu_->solve(tangent, tangent);
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
           (jacobian_ * tangent).norm() <= 1e-8 * std::max(1.0, frobenius_norm(jacobian_));
  }

  Eigen::SparseMatrix<double> jacobian_;
  Eigen::SparseMatrix<double> bordered_;
  std::unique_ptr<SparseLu> lu_;
  Eigen::MatrixXd last_tangent_;  // guides the border of the next factorisation
  bool assembly_released_ = false;  // jacobian_ and bordered_ freed after factoring
  double fill_ = 0.0;               // nnz(L + U) / nnz(A) of the last factorisation

 public:
  double fill_ratio() const override { return fill_; }
};

}  // namespace

Linearization::Linearization() = default;
Linearization::~Linearization() = default;
Linearization::Linearization(Linearization&&) noexcept = default;
Linearization& Linearization::operator=(Linearization&&) noexcept = default;
Linearization::Linearization(const Linearization& other)
    : backend_(other.is_borrowed() ? other.backend_
               : other.backend_    ? std::shared_ptr<LinearizationBackend>(other.backend_->clone())
                                   : nullptr),
      point_(other.point_),
      tangent_(other.tangent_),
      solver_tangent_(other.solver_tangent_),
      solver_point_(other.solver_point_),
      oblique_(other.oblique_),
      space_(other.space_),
      reciprocal_condition_(other.reciprocal_condition_),
      factored_(other.factored_ && other.backend_ &&
                (other.is_borrowed() || other.backend_->clones_factorisation())),
      counted_(other.counted_) {}
Linearization& Linearization::operator=(const Linearization& other) {
  if (this != &other) {
    Linearization copy(other);
    *this = std::move(copy);
  }
  return *this;
}

double Linearization::fill_ratio() const { return backend_ ? backend_->fill_ratio() : 0.0; }

std::size_t Linearization::memory_bytes() const {
  return (backend_ ? backend_->memory_bytes() : 0) +
         sizeof(double) * static_cast<std::size_t>(point_.size() + tangent_.size());
}

void Linearization::release_assembly() {
  if (backend_) {
    backend_->release_assembly();
  }
}

void Linearization::make_backend(const ImplicitProblem& problem) {
  if (backend_ && (is_borrowed() || backend_.use_count() > 1)) {
    backend_.reset();  // others solve with it: a new factorisation goes into a new backend
  }
  solver_tangent_.resize(0, 0);
  solver_point_.resize(0);
  space_.reset();
  if (!backend_) {
    backend_ = problem.make_linearization_backend();
  }
  if (!backend_) {
    if (problem.has_sparse_jacobian()) {
      backend_ = std::make_shared<SparseBackend>();
    } else {
      backend_ = std::make_shared<DenseBackend>();
    }
  }
}

Eigen::MatrixXd Linearization::border_guide() const {
  return backend_ ? backend_->border_guide() : Eigen::MatrixXd();
}

void Linearization::set_border_guide(const ImplicitProblem& problem,
                                     const Eigen::MatrixXd& guide) {
  make_backend(problem);
  backend_->set_border_guide(guide);
}

bool Linearization::factor(const ImplicitProblem& problem,
                           const Eigen::Ref<const Eigen::VectorXd>& x,
                           const Eigen::MatrixXd* reference_tangent) {
  // The local rows of the problem's space: all n in one process (see AmbientSpace).
  const std::shared_ptr<const AmbientSpace> space = problem.space();
  const int n = space->local_rows();
  TESSERA_CHECK(x.size() == n, "point has " << x.size() << " coordinates, problem '"
                                            << problem.name() << "' has n = " << n);
  TESSERA_CHECK(reference_tangent == nullptr ||
                    (reference_tangent->rows() == n && reference_tangent->cols() == 2),
                "reference tangent basis must be " << n << "×2");
  factored_ = false;
  if (!space->all_finite(x)) {
    return false;
  }
  make_backend(problem);
  point_ = x;
  const long before = backend_->factorisations();
  const long jacobians_before = backend_->own_jacobian_evaluations();
  // Factorisations are the currency of continuation at large n: the run's counter sees them,
  // and their time, so that a run states its cost per vertex in factorisations' worth. Where
  // one takes under kTimedBelow (n = 3: less than reading the clock twice, which was 3 % of a
  // torus's run) only every kTimingStride-th is timed, its time counted for all of them. Per
  // thread, not per object: the loops that factor make a Linearization per point.
  const auto* counted = dynamic_cast<const CountedProblem*>(&problem);
  counted_ = counted;
  constexpr double kTimedBelow = 20e-6;
  constexpr int kTimingStride = 16;
  thread_local int untimed = 0;
  thread_local double last_seconds = 1.0;
  const bool timed = counted != nullptr && (last_seconds >= kTimedBelow || untimed == 0);
  using Clock = std::chrono::steady_clock;
  const Clock::time_point started = timed ? Clock::now() : Clock::time_point();
  const bool is_factored =
      backend_->factor(problem, x, reference_tangent, tangent_, reciprocal_condition_);
  if (counted != nullptr) {
    double seconds = 0.0;
    if (timed) {
      last_seconds = std::chrono::duration<double>(Clock::now() - started).count();
      seconds = last_seconds < kTimedBelow ? kTimingStride * last_seconds : last_seconds;
      untimed = kTimingStride - 1;
    } else {
      --untimed;
    }
    counted->record_factorisations(backend_->factorisations() - before, seconds);
    counted->record_jacobian_evaluations(backend_->own_jacobian_evaluations() - jacobians_before);
  }
  if (!is_factored) {
    return false;
  }
  if (reference_tangent != nullptr) {
    align_tangent_basis(tangent_, *reference_tangent, *space);
  }
  factored_ = true;
  return true;
}

namespace {
// borrow_factorisation: the tangent iteration's angle and steps, and the fill above which
// factorisations are shared (worth_sharing).
constexpr double kBorrowAngle = 1e-7;
constexpr int kBorrowIterations = 8;
constexpr double kShareAboveFill = 2.0;
// borrow_nearby: how many edge lengths away a factorisation is worth trying (the tolerance
// check's anchors serve two rings; corners of ∂S come as neighbours).
constexpr double kBorrowReachEdges = 4.0;
}  // namespace

bool worth_sharing(const Linearization& factored) {
  // TESSERA_SHARE_FACTORISATIONS=off: never (the mesh a PETSc run gives, whose backend does not
  // share yet; comparisons).
  static const bool is_off = [] {
    const char* value = std::getenv("TESSERA_SHARE_FACTORISATIONS");
    return value != nullptr && (std::string_view(value) == "off" || std::string_view(value) == "0");
  }();
  return !is_off && factored.is_factored() && factored.fill_ratio() > kShareAboveFill;
}

bool borrow_factorisation(const ImplicitProblem& problem, const Linearization& near,
                          const Eigen::Ref<const Eigen::VectorXd>& y, Linearization& out) {
  // (Judged by its steps, not by ‖DF(y)·T‖ against ‖DF‖: on bvp at n = 10⁴, ‖DF‖ ≈ 10¹⁰, and a
  // residual of 10⁻¹⁰‖DF‖ left T 10⁻³ off, which the atlas's radius probes read as a curvature
  // of 2·10⁻³/r: the radii collapsed. An angle δ moves a point at distance r by δr: 10⁻⁸ at
  // r = 0.1, against the atlas probes' accuracy of 10⁻³ ε. 10⁻⁹ took two more steps a chart and
  // let fewer charts borrow: bratu2d:N=100 in 161 s instead of 147.)
  Eigen::MatrixXd T;
  if (!near.is_factored() ||
      !tangent_basis_near(problem, near, y, T, 0.0, kBorrowIterations, kBorrowAngle)) {
    return false;
  }
  // The iteration's basis drifts from point to point; the atlas's polygons start as squares in
  // tangent coordinates, and a drifting basis packed its charts less regularly (1–5 % more
  // vertices on bratu2d:N=8 and 12).
  const Eigen::MatrixXd& guide = near.tangent_basis();
  if (!coordinate_tangent_basis(T, &guide)) {
    return false;
  }
  align_tangent_basis(T, guide, *problem.space());
  return out.borrow(problem, near, y, T);
}

bool borrow_nearby(const ImplicitProblem& problem, const Linearization& near,
                   const Eigen::Ref<const Eigen::VectorXd>& y, double edge_length,
                   Linearization& out) {
  return worth_sharing(near) &&
         problem.space()->distance(near.factored_point(), y) <= kBorrowReachEdges * edge_length &&
         borrow_factorisation(problem, near, y, out);
}

bool Linearization::borrow(const ImplicitProblem& problem, const Linearization& near,
                           const Eigen::Ref<const Eigen::VectorXd>& y,
                           const Eigen::MatrixXd& tangent, double min_cosine) {
  if (!near.is_factored()) {
    return false;
  }
  std::shared_ptr<const AmbientSpace> space = problem.space();
  const Eigen::MatrixXd& solver_tangent =
      near.is_borrowed() ? near.solver_tangent_ : near.tangent_;
  const Eigen::Matrix2d cosines = space->products(tangent, solver_tangent);
  if (!(std::abs(cosines.determinant()) >= min_cosine)) {
    return false;
  }
  backend_ = near.backend_;
  counted_ = dynamic_cast<const CountedProblem*>(&problem);
  solver_tangent_ = solver_tangent;
  solver_point_ = near.factored_point();
  oblique_ = cosines.inverse();
  space_ = std::move(space);
  point_ = y;
  tangent_ = tangent;
  reciprocal_condition_ = near.reciprocal_condition_;
  factored_ = true;
  return true;
}

// dx ← dx − T_s (Tᵀ T_s)⁻¹ Tᵀ dx, column by column: J_s·dx is unchanged (T_s spans ker J_s) and
// Tᵀ dx becomes zero.
void Linearization::make_orthogonal_to_tangent(Eigen::Ref<Eigen::MatrixXd> dx) const {
  const Eigen::MatrixXd along = space_->products(tangent_, dx);  // 2 × k
  dx.noalias() -= solver_tangent_ * (oblique_ * along);
}

void Linearization::solve_minimum_norm(const Eigen::Ref<const Eigen::VectorXd>& rhs,
                                       Eigen::Ref<Eigen::VectorXd> dx) const {
  TESSERA_ASSERT(factored_);
  count_solves(1);
  if (is_borrowed()) {
    backend_->solve(rhs, solver_tangent_, dx);
    make_orthogonal_to_tangent(dx);
    return;
  }
  backend_->solve(rhs, tangent_, dx);
}

void Linearization::count_solves(long columns) const {
  if (counted_ != nullptr) {
    counted_->record_solves(columns);
  }
}

void Linearization::solve_minimum_norm_columns(const Eigen::Ref<const Eigen::MatrixXd>& rhs,
                                               Eigen::Ref<Eigen::MatrixXd> dx) const {
  TESSERA_ASSERT(factored_);
  TESSERA_ASSERT(rhs.cols() == dx.cols());
  count_solves(rhs.cols());
  if (is_borrowed()) {
    backend_->solve_columns(rhs, solver_tangent_, dx);
    make_orthogonal_to_tangent(dx);
    return;
  }
  backend_->solve_columns(rhs, tangent_, dx);
}

namespace {

// The tangent iteration's stop by its steps (tangent_basis_near's angle_tolerance): a linear
// iteration contracting by θ (the largest ratio of successive corrections) is within
// θ/(1 − θ)·‖correction‖ of its limit after a correction. The first correction gives no θ.
bool converged_by_steps(double size, double& previous, double& contraction,
                        double angle_tolerance) {
  const bool has_ratio = previous > 0;
  if (has_ratio) {
    contraction = std::max(contraction, size / previous);
  }
  previous = size;
  return size == 0.0 || (has_ratio && contraction < 1.0 &&
                         contraction / (1.0 - contraction) * size <= angle_tolerance);
}

// tangent_basis_near on the local rows of a distributed problem: the same iteration, with DF(y)·T
// from the problem's JacobianProduct and every norm and inner product reduced over the ranks
// (the serial one's Eigen expressions are left untouched).
bool tangent_basis_near_distributed(const ImplicitProblem& problem, const AmbientSpace& space,
                                    const Linearization& near,
                                    const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::MatrixXd& T,
                                    double tolerance, int max_iterations,
                                    double angle_tolerance) {
  const JacobianProduct* product = problem.as_jacobian_product();
  if (product == nullptr) {
    return false;  // J(y)·T is not available: the caller factors at y instead
  }
  Eigen::MatrixXd JT;
  double squared_norm = product->evaluate_jacobian_at(y);
  space.sum(&squared_norm, 1);
  const double jacobian_norm = std::sqrt(squared_norm);
  if (!std::isfinite(jacobian_norm) || jacobian_norm == 0.0) {
    return false;
  }
  T = near.tangent_basis();
  Eigen::MatrixXd correction(T.rows(), 2);
  double previous = -1.0;
  double contraction = 0.0;
  for (int iteration = 0; iteration <= max_iterations; ++iteration) {
    product->multiply_jacobian(T, JT);
    if (space.frobenius_norm(JT) <= tolerance * jacobian_norm) {
      return true;
    }
    if (iteration == max_iterations) {
      break;
    }
    near.solve_minimum_norm_columns(JT, correction);
    T -= correction;
    const bool converged =
        angle_tolerance > 0 && converged_by_steps(space.frobenius_norm(correction), previous,
                                                  contraction, angle_tolerance);
    // Orthonormalise (modified Gram–Schmidt): ker J(y) is spanned either way.
    T.col(0) /= space.norm(T.col(0));
    T.col(1) -= space.dot(T.col(0), T.col(1)) * T.col(0);
    T.col(1) /= space.norm(T.col(1));
    if (!space.all_finite(T)) {
      return false;
    }
    if (converged) {
      return true;
    }
  }
  return false;
}

}  // namespace

bool tangent_basis_near(const ImplicitProblem& problem, const Linearization& near,
                        const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::MatrixXd& T,
                        double tolerance, int max_iterations, double angle_tolerance) {
  TESSERA_ASSERT(near.is_factored());
  if (const std::shared_ptr<const AmbientSpace> space = problem.space(); space->is_distributed()) {
    return tangent_basis_near_distributed(problem, *space, near, y, T, tolerance, max_iterations,
                                          angle_tolerance);
  }
  const int n = problem.ambient_dimension();
  const int m = n - 2;
  // J(y)·T, from the sparse or the dense Jacobian as the problem prefers.
  Eigen::SparseMatrix<double> sparse;
  Eigen::MatrixXd dense;
  double jacobian_norm = 0.0;
  if (problem.has_sparse_jacobian()) {
    problem.sparse_jacobian(y, sparse);
    jacobian_norm = frobenius_norm(sparse);
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
  Eigen::MatrixXd correction(n, 2);
  double previous = -1.0;
  double contraction = 0.0;
  for (int iteration = 0; iteration <= max_iterations; ++iteration) {
    const Eigen::MatrixXd JT = residual(T);
    if (JT.norm() <= tolerance * jacobian_norm) {
      return true;
    }
    if (iteration == max_iterations) {
      break;
    }
    near.solve_minimum_norm_columns(JT, correction);
    T -= correction;
    const bool converged =
        angle_tolerance > 0 &&
        converged_by_steps(correction.norm(), previous, contraction, angle_tolerance);
    // Orthonormalise (modified Gram–Schmidt): ker J(y) is spanned either way.
    T.col(0).normalize();
    T.col(1) -= T.col(0).dot(T.col(1)) * T.col(0);
    T.col(1).normalize();
    if (!T.allFinite()) {
      return false;
    }
    if (converged) {
      return true;
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
  align_tangent_basis(T, reference, AmbientSpace(static_cast<int>(T.rows())));
}

void align_tangent_basis(Eigen::MatrixXd& T, const Eigen::MatrixXd& reference,
                         const AmbientSpace& space) {
  const Eigen::Matrix2d overlap = space.products(T, reference);
  if (overlap.determinant() < 0) {
    T.col(1) *= -1.0;
  }
}

}  // namespace tessera
