// SPDX-License-Identifier: MIT
#include "tessera/methods/stability/vertex_stability.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <Spectra/GenEigsSolver.h>
#include <Spectra/SymEigsSolver.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <memory>

#include "tessera/core/error.h"
#include "tessera/core/sparse_lu.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/methods/stability/state_jacobian.h"

namespace tessera {

namespace {

using Complex = std::complex<double>;

// By decreasing real part, then decreasing imaginary part: deterministic, conjugates adjacent.
void sort_by_real_part(std::vector<Complex>& values) {
  std::sort(values.begin(), values.end(), [](const Complex& a, const Complex& b) {
    return a.real() != b.real() ? a.real() > b.real() : a.imag() > b.imag();
  });
}

int count_unstable(const std::vector<Complex>& values) {
  return static_cast<int>(std::count_if(values.begin(), values.end(),
                                        [](const Complex& mu) { return mu.real() > 0.0; }));
}

VertexStability failed(std::string message) {
  VertexStability result;
  result.message = std::move(message);
  return result;
}

// The count and leading real part of a set of computed eigenvalues.
VertexStability from_eigenvalues(std::vector<Complex> values, bool is_certain, double radius) {
  VertexStability result;
  sort_by_real_part(values);
  result.unstable_count = count_unstable(values);
  result.leading_real_part =
      values.empty() ? std::numeric_limits<double>::quiet_NaN() : values.front().real();
  result.is_certain = is_certain;
  result.examined_radius = radius;
  result.eigenvalues = std::move(values);
  return result;
}

// All finite eigenvalues: QR (B = I) or QZ, an eigenvalue infinite when |β| ≤ 10⁻¹³(|α| + |β|)
// (the rows of B that vanish: algebraic equations).
VertexStability dense_stability_of(const StateJacobian& jacobian) {
  return dense_stability(jacobian.as_dense(), jacobian.mass(), jacobian.has_identity_mass());
}

}  // namespace

VertexStability dense_stability(const Eigen::MatrixXd& A, const Eigen::SparseMatrix<double>& mass,
                                bool has_identity_mass) {
  std::vector<Complex> values;
  if (has_identity_mass) {
    Eigen::EigenSolver<Eigen::MatrixXd> solver(A, /*computeEigenvectors=*/false);
    if (solver.info() != Eigen::Success) {
      return failed("the QR algorithm did not converge");
    }
    for (Eigen::Index i = 0; i < solver.eigenvalues().size(); ++i) {
      values.push_back(solver.eigenvalues()(i));
    }
  } else {
    const Eigen::MatrixXd B(mass);
    Eigen::GeneralizedEigenSolver<Eigen::MatrixXd> solver(A, B, /*computeEigenvectors=*/false);
    if (solver.info() != Eigen::Success) {
      return failed("the QZ algorithm did not converge");
    }
    for (Eigen::Index i = 0; i < solver.betas().size(); ++i) {
      const Complex alpha = solver.alphas()(i);
      const double beta = solver.betas()(i);
      if (std::abs(beta) > 1e-13 * (std::abs(alpha) + std::abs(beta))) {
        values.push_back(alpha / beta);
      }
    }
  }
  return from_eigenvalues(std::move(values), /*is_certain=*/true,
                          std::numeric_limits<double>::infinity());
}

namespace {

// y = D^½ A⁻¹ D^½ x, D = B (positive diagonal): symmetric, with eigenvalues 1/μ for the
// eigenvalues μ of the pencil (A, B), A symmetric.
class SymmetricShiftInvert {
 public:
  using Scalar = double;
  SymmetricShiftInvert(const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>& ldlt,
                       Eigen::VectorXd sqrt_mass, long& solves)
      : ldlt_(ldlt), sqrt_mass_(std::move(sqrt_mass)), solves_(solves) {}
  Eigen::Index rows() const { return sqrt_mass_.size(); }
  Eigen::Index cols() const { return sqrt_mass_.size(); }
  void perform_op(const double* x_in, double* y_out) const {
    const Eigen::Map<const Eigen::VectorXd> x(x_in, rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, rows());
    y = sqrt_mass_.cwiseProduct(ldlt_.solve(Eigen::VectorXd(sqrt_mass_.cwiseProduct(x))));
    ++solves_;
  }

 private:
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>& ldlt_;
  Eigen::VectorXd sqrt_mass_;
  long& solves_;
};

// y = A⁻¹ B x: eigenvalues 1/μ for the finite eigenvalues μ of (A, B), 0 for the infinite ones.
class GeneralShiftInvert {
 public:
  using Scalar = double;
  GeneralShiftInvert(const SparseLu& lu, const Eigen::SparseMatrix<double>& mass, long& solves)
      : lu_(lu), mass_(mass), solves_(solves), work_(mass.rows(), 1) {}
  Eigen::Index rows() const { return mass_.rows(); }
  Eigen::Index cols() const { return mass_.rows(); }
  void perform_op(const double* x_in, double* y_out) const {
    const Eigen::Map<const Eigen::VectorXd> x(x_in, rows());
    work_.col(0) = mass_ * x;
    lu_.solve(work_, work_);
    Eigen::Map<Eigen::VectorXd>(y_out, rows()) = work_.col(0);
    ++solves_;
  }

 private:
  const SparseLu& lu_;
  const Eigen::SparseMatrix<double>& mass_;
  long& solves_;
  mutable Eigen::MatrixXd work_;
};

bool is_symmetric(const Eigen::SparseMatrix<double>& A) {
  const Eigen::SparseMatrix<double> difference = A - Eigen::SparseMatrix<double>(A.transpose());
  double scale = 0.0;
  for (int k = 0; k < A.nonZeros(); ++k) {
    scale = std::max(scale, std::abs(A.valuePtr()[k]));
  }
  for (int k = 0; k < difference.nonZeros(); ++k) {
    if (std::abs(difference.valuePtr()[k]) > 1e-12 * scale) {
      return false;
    }
  }
  return true;
}

// The sparse computations at one vertex, with the warm start carried from vertex to vertex.
class SparseStability {
 public:
  explicit SparseStability(const StabilityOptions& options) : options_(options) {}

  long factorisations = 0;
  long solves = 0;

  VertexStability compute(const StateJacobian& jacobian) {
    const Eigen::SparseMatrix<double>& A = jacobian.sparse();
    if (jacobian.has_positive_diagonal_mass() && is_symmetric(A)) {
      return symmetric(jacobian);
    }
    return general(jacobian);
  }

 private:
  int subspace_size(int m) const {
    const int wanted = options_.subspace_size > 0 ? options_.subspace_size
                                                  : std::max(2 * options_.eigenvalue_count + 1, 16);
    return std::min(m, std::max(wanted, options_.eigenvalue_count + 2));
  }

  // Sylvester: the pencil (A, B), B positive definite, has as many positive eigenvalues as A has
  // positive pivots in P A Pᵀ = L D Lᵀ. The same factorisation drives shift-invert Lanczos.
  VertexStability symmetric(const StateJacobian& jacobian) {
    const Eigen::SparseMatrix<double>& A = jacobian.sparse();
    const int m = jacobian.state_count();
    // The ordering and the symbolic factorisation once per pattern (the Jacobians of one
    // problem share it), the numerical one per vertex.
    if (!has_same_pattern(A, ldlt_pattern_)) {
      ldlt_.analyzePattern(A);
      ldlt_pattern_ = A;
    }
    ldlt_.factorize(A);
    ++factorisations;
    if (ldlt_.info() != Eigen::Success) {
      return general(jacobian);
    }
    const Eigen::VectorXd& D = ldlt_.vectorD();
    const double largest = D.cwiseAbs().maxCoeff();
    // A pivot at rounding level makes the inertia unreliable (and A is nearly singular: a
    // vertex on a fold); the LU path then counts the computed eigenvalues.
    if (!D.allFinite() || !(D.cwiseAbs().minCoeff() > 1e-13 * largest)) {
      return general(jacobian);
    }
    const int inertia = static_cast<int>((D.array() > 0.0).count());
    Eigen::VectorXd sqrt_mass = Eigen::VectorXd::Ones(m);
    if (!jacobian.has_identity_mass()) {
      for (int i = 0; i < m; ++i) {
        sqrt_mass(i) = std::sqrt(jacobian.mass().coeff(i, i));
      }
    }
    SymmetricShiftInvert op(ldlt_, sqrt_mass, solves);
    const int k = std::min(options_.eigenvalue_count, m - 1);
    Spectra::SymEigsSolver<SymmetricShiftInvert> eigs(op, k, subspace_size(m));
    init(eigs, m);
    eigs.compute(Spectra::SortRule::LargestMagn, options_.max_restarts, options_.tolerance,
                 Spectra::SortRule::LargestMagn);
    if (eigs.info() != Spectra::CompInfo::Successful) {
      has_start_ = false;
      return failed("shift-invert Lanczos did not converge to " + std::to_string(k) +
                    " eigenvalues in " + std::to_string(options_.max_restarts) + " restarts");
    }
    std::vector<Complex> values;
    double radius = 0.0;
    for (Eigen::Index i = 0; i < eigs.eigenvalues().size(); ++i) {
      const double mu = 1.0 / eigs.eigenvalues()(i);
      values.emplace_back(mu, 0.0);
      radius = std::max(radius, std::abs(mu));
    }
    remember(eigs.eigenvectors().real(), Eigen::MatrixXd(), sqrt_mass);
    VertexStability result = from_eigenvalues(std::move(values), /*is_certain=*/true, radius);
    result.unstable_count = inertia;
    return result;
  }

  VertexStability general(const StateJacobian& jacobian) {
    const Eigen::SparseMatrix<double>& A = jacobian.sparse();
    const int m = jacobian.state_count();
    if (!lu_ || !lu_->is_analyzed_for(A)) {
      lu_ = make_sparse_lu(sparse_lu_solver_for(A));
      if (lu_->analyze(A) != SparseLuStatus::Success) {
        lu_.reset();
        return failed("the sparse LU of s·D_uF could not analyse its pattern");
      }
    }
    ++factorisations;
    if (lu_->factorize(A) != SparseLuStatus::Success) {
      return failed("s·D_uF is singular here (" + lu_->last_message() +
                    "): a point of a fold to rounding");
    }
    GeneralShiftInvert op(*lu_, jacobian.mass(), solves);
    const int k = std::min(options_.eigenvalue_count, m - 2);
    Spectra::GenEigsSolver<GeneralShiftInvert> eigs(op, k, std::max(subspace_size(m), k + 2));
    init(eigs, m);
    eigs.compute(Spectra::SortRule::LargestMagn, options_.max_restarts, options_.tolerance,
                 Spectra::SortRule::LargestMagn);
    if (eigs.info() != Spectra::CompInfo::Successful) {
      has_start_ = false;
      return failed("shift-invert Arnoldi did not converge to " + std::to_string(k) +
                    " eigenvalues in " + std::to_string(options_.max_restarts) + " restarts");
    }
    std::vector<Complex> values;
    double radius = 0.0;
    for (Eigen::Index i = 0; i < eigs.eigenvalues().size(); ++i) {
      const Complex nu = eigs.eigenvalues()(i);
      if (std::abs(nu) == 0.0) {
        continue;  // an infinite eigenvalue (singular B)
      }
      const Complex mu = 1.0 / nu;
      values.push_back(mu);
      radius = std::max(radius, std::abs(mu));
    }
    complete_conjugate_pairs(values);
    const Eigen::MatrixXcd vectors = eigs.eigenvectors();
    remember(vectors.real(), vectors.imag(), Eigen::VectorXd::Ones(m));
    return from_eigenvalues(std::move(values), /*is_certain=*/false, radius);
  }

  // The next vertex starts from the sum of this one's eigenvectors (mapped back by D^-½ where
  // the operator was symmetrised): a start rich in every wanted direction.
  void remember(const Eigen::MatrixXd& real, const Eigen::MatrixXd& imaginary,
                const Eigen::VectorXd& scale) {
    start_ = real.rowwise().sum();
    if (imaginary.size() > 0) {
      start_ += imaginary.rowwise().sum();
    }
    start_ = start_.cwiseQuotient(scale);
    has_start_ = start_.allFinite() && start_.norm() > 0.0;
  }

  template <typename Solver>
  void init(Solver& eigs, int m) {
    if (has_start_ && start_.size() == m) {
      eigs.init(start_.data());
    } else {
      eigs.init();
    }
  }

  static bool has_same_pattern(const Eigen::SparseMatrix<double>& A,
                               const Eigen::SparseMatrix<double>& pattern) {
    return A.rows() == pattern.rows() && A.cols() == pattern.cols() &&
           A.nonZeros() == pattern.nonZeros() &&
           std::equal(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1,
                      pattern.outerIndexPtr()) &&
           std::equal(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros(), pattern.innerIndexPtr());
  }

  StabilityOptions options_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
  Eigen::SparseMatrix<double> ldlt_pattern_;  // the pattern ldlt_ was analysed for
  std::unique_ptr<SparseLu> lu_;
  Eigen::VectorXd start_;
  bool has_start_ = false;
};

}  // namespace

std::vector<int> stability_vertex_order(const TriangleMesh& mesh) {
  const int vertex_count = mesh.vertex_count();
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(vertex_count));
  for (const Triangle& t : mesh.triangles()) {
    for (int k = 0; k < 3; ++k) {
      neighbours[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])].push_back(
          t[static_cast<std::size_t>((k + 1) % 3)]);
      neighbours[static_cast<std::size_t>(t[static_cast<std::size_t>((k + 1) % 3)])].push_back(
          t[static_cast<std::size_t>(k)]);
    }
  }
  std::vector<int> order;
  order.reserve(static_cast<std::size_t>(vertex_count));
  std::vector<char> seen(static_cast<std::size_t>(vertex_count), 0);
  for (int root = 0; root < vertex_count; ++root) {
    if (seen[static_cast<std::size_t>(root)]) {
      continue;
    }
    std::deque<int> queue{root};
    seen[static_cast<std::size_t>(root)] = 1;
    while (!queue.empty()) {
      const int v = queue.front();
      queue.pop_front();
      order.push_back(v);
      for (const int w : neighbours[static_cast<std::size_t>(v)]) {
        if (!seen[static_cast<std::size_t>(w)]) {
          seen[static_cast<std::size_t>(w)] = 1;
          queue.push_back(w);
        }
      }
    }
  }
  return order;
}

namespace {

VertexStability stability_with(StateJacobian& jacobian, SparseStability& sparse,
                               const Eigen::VectorXd& x, const StabilityOptions& options) {
  if (!jacobian.evaluate(x)) {
    return failed("DF is not finite here");
  }
  if (!jacobian.is_sparse() || jacobian.state_count() <= options.dense_state_limit) {
    return dense_stability_of(jacobian);
  }
  return sparse.compute(jacobian);
}

void check_options(const StabilityOptions& options) {
  TESSERA_CHECK(options.eigenvalue_count >= 1,
                "stability: the number of eigenvalues must be ≥ 1, got " << options.eigenvalue_count);
  TESSERA_CHECK(options.tolerance > 0.0 && options.tolerance < 1.0,
                "stability: the eigenvalue tolerance must lie in (0, 1), got " << options.tolerance);
  TESSERA_CHECK(options.max_restarts >= 1,
                "stability: the number of restarts must be ≥ 1, got " << options.max_restarts);
}

}  // namespace

VertexStability stability_at(const ImplicitProblem& problem, const Eigen::VectorXd& x,
                             const StabilityOptions& options) {
  check_options(options);
  StateJacobian jacobian(problem, "stability");
  TESSERA_CHECK(x.size() == problem.ambient_dimension(),
                "stability: the point has " << x.size() << " coordinates, problem '"
                                            << problem.name() << "' has n = "
                                            << problem.ambient_dimension());
  SparseStability sparse(options);
  return stability_with(jacobian, sparse, x, options);
}

StabilityResult compute_stability(const ImplicitProblem& problem, const TriangleMesh& mesh,
                                  const StabilityOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  check_options(options);
  StateJacobian jacobian(problem, "stability");
  TESSERA_CHECK(mesh.ambient_dimension() == problem.ambient_dimension(),
                "stability: the mesh lies in R^" << mesh.ambient_dimension() << ", problem '"
                                                 << problem.name() << "' in R^"
                                                 << problem.ambient_dimension());
  StabilityResult result;
  const bool is_dense =
      !jacobian.is_sparse() || jacobian.state_count() <= options.dense_state_limit;
  result.eigenvalue_count = is_dense ? 0 : options.eigenvalue_count;
  result.vertices.resize(static_cast<std::size_t>(mesh.vertex_count()));
  SparseStability sparse(options);
  bool any_symmetric = false;
  bool any_general = false;
  for (const int v : stability_vertex_order(mesh)) {
    VertexStability& vertex = result.vertices[static_cast<std::size_t>(v)];
    vertex = stability_with(jacobian, sparse, mesh.point(v), options);
    if (!is_dense && !vertex.has_failed()) {
      (vertex.is_certain ? any_symmetric : any_general) = true;
    }
  }
  result.method = is_dense ? "dense"
                  : any_general && any_symmetric
                      ? "sparse symmetric (inertia), shift-invert Arnoldi where LDLT failed"
                  : any_general ? "sparse (shift-invert Arnoldi)"
                                : "sparse symmetric (inertia)";
  count_stability_classes(result);
  result.factorisations = sparse.factorisations;
  result.solves = sparse.solves;
  result.jacobian_evaluations = jacobian.jacobian_evaluations();
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

void complete_conjugate_pairs(std::vector<std::complex<double>>& values) {
  const std::size_t found = values.size();
  for (std::size_t i = 0; i < found; ++i) {
    if (values[i].imag() == 0.0) {
      continue;
    }
    const Complex conjugate = std::conj(values[i]);
    const bool has = std::any_of(values.begin(), values.end(), [&](const Complex& other) {
      return std::abs(other - conjugate) <= 1e-8 * std::abs(conjugate);
    });
    if (!has) {
      values.push_back(conjugate);
    }
  }
}

void count_stability_classes(StabilityResult& result) {
  result.index_counts.clear();
  result.failed_count = 0;
  result.uncertain_count = 0;
  for (const VertexStability& vertex : result.vertices) {
    if (vertex.has_failed()) {
      ++result.failed_count;
      continue;
    }
    if (!vertex.is_certain) {
      ++result.uncertain_count;
    }
    const auto index = static_cast<std::size_t>(vertex.unstable_count);
    if (result.index_counts.size() <= index) {
      result.index_counts.resize(index + 1, 0);
    }
    ++result.index_counts[index];
  }
  result.stable_count = result.index_counts.empty() ? 0 : result.index_counts[0];
}

}  // namespace tessera
