// SPDX-License-Identifier: MIT
#include "tessera/petsc/petsc_stability.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#if defined(TESSERA_HAS_SLEPC)
#include <slepceps.h>
#endif

#include "tessera/core/dynamics.h"
#include "tessera/core/error.h"

namespace tessera::petsc {

#if !defined(TESSERA_HAS_SLEPC)

bool has_slepc() { return false; }

StabilityResult compute_distributed_stability(const PetscProblem& /*problem*/,
                                              const TriangleMesh& /*mesh*/,
                                              const StabilityOptions& /*options*/) {
  throw InvalidArgument(
      "--stability on the PETSc backend needs SLEPc, and this tessera was built without it: "
      "install Debian's slepc-dev (scripts/install-dependencies.sh does) and build again, or "
      "run --stability on the serial backend");
}

#else

bool has_slepc() { return true; }

template <>
void Owned<EPS>::reset() {
  if (handle_ != nullptr) {
    EPSDestroy(&handle_);
  }
}

namespace {

using Complex = std::complex<double>;

VertexStability failed(std::string message) {
  VertexStability result;
  result.message = std::move(message);
  return result;
}

// As the serial computation: by decreasing real part, then decreasing imaginary part.
VertexStability from_eigenvalues(std::vector<Complex> values, bool is_certain, double radius) {
  std::sort(values.begin(), values.end(), [](const Complex& a, const Complex& b) {
    return a.real() != b.real() ? a.real() > b.real() : a.imag() > b.imag();
  });
  VertexStability result;
  result.unstable_count = static_cast<int>(std::count_if(
      values.begin(), values.end(), [](const Complex& mu) { return mu.real() > 0.0; }));
  result.leading_real_part =
      values.empty() ? std::numeric_limits<double>::quiet_NaN() : values.front().real();
  result.is_certain = is_certain;
  result.examined_radius = radius;
  result.eigenvalues = std::move(values);
  return result;
}

// A = s·D_uF and B at the vertices, on the rows of F each rank owns: rows [first, first + r) of
// the problem's layout that are equations (< n − 2), their state columns the same positions in
// the list of states, so that A is square with the same layout for rows and columns.
class DistributedPencil {
 public:
  DistributedPencil(const PetscProblem& problem, const Dynamics& dynamics)
      : problem_(problem), sign_(dynamics.sign) {
    const auto n = static_cast<int>(problem.ambient_dimension());
    state_count_ = n - 2;
    Owned<Vec> layout = problem.create_vector();
    PetscInt end = 0;
    check(VecGetOwnershipRange(layout, &first_, &end), "VecGetOwnershipRange");
    local_rows_ = static_cast<int>(end - first_);
    const PetscInt equations_end = std::min<PetscInt>(end, state_count_);
    equation_rows_ = static_cast<int>(std::max<PetscInt>(0, equations_end - first_));
    const std::vector<int> states = state_indices(dynamics, n);
    std::vector<PetscInt> columns(static_cast<std::size_t>(equation_rows_));
    for (int i = 0; i < equation_rows_; ++i) {
      columns[static_cast<std::size_t>(i)] = states[static_cast<std::size_t>(first_ + i)];
    }
    const MPI_Comm communicator = problem.communicator();
    check(ISCreateStride(communicator, equation_rows_, first_, 1, &rows_), "ISCreateStride");
    check(
        ISCreateGeneral(communicator, equation_rows_, columns.data(), PETSC_COPY_VALUES, &columns_),
        "ISCreateGeneral");
    jacobian_ = problem.create_jacobian();
    x_ = array_vector(communicator, local_rows_, n);

    mass_ = mass_matrix(dynamics, state_count_);
    has_identity_mass_ = dynamics.has_identity_mass();
    has_positive_diagonal_mass_ = true;
    for (int j = 0; j < mass_.outerSize(); ++j) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(mass_, j); it; ++it) {
        if (it.row() != it.col() ? it.value() != 0.0 : !(it.value() > 0.0)) {
          has_positive_diagonal_mass_ = false;
        }
      }
    }
    for (int i = 0; i < state_count_; ++i) {
      if (!(mass_.coeff(i, i) > 0.0)) {
        has_positive_diagonal_mass_ = false;
      }
    }
    if (!has_identity_mass_) {
      // B's rows here, as a distributed matrix of A's layout.
      const Eigen::SparseMatrix<double, Eigen::RowMajor> by_rows = mass_;
      check(MatCreate(communicator, B_.out()), "MatCreate");
      check(MatSetSizes(B_, equation_rows_, equation_rows_, state_count_, state_count_),
            "MatSetSizes");
      check(MatSetType(B_, MATAIJ), "MatSetType");
      check(MatSetUp(B_), "MatSetUp");
      check(MatSetOption(B_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE), "MatSetOption");
      for (PetscInt row = first_; row < first_ + equation_rows_; ++row) {
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(
                 by_rows, static_cast<Eigen::Index>(row));
             it; ++it) {
          const auto column = static_cast<PetscInt>(it.col());
          const double value = it.value();
          check(MatSetValues(B_, 1, &row, 1, &column, &value, INSERT_VALUES), "MatSetValues");
        }
      }
      check(MatAssemblyBegin(B_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
      check(MatAssemblyEnd(B_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    }
  }
  ~DistributedPencil() {
    MatDestroy(&A_);
    ISDestroy(&rows_);
    ISDestroy(&columns_);
  }
  DistributedPencil(const DistributedPencil&) = delete;
  DistributedPencil& operator=(const DistributedPencil&) = delete;

  int state_count() const { return state_count_; }
  PetscInt first_row() const { return first_; }
  int local_rows() const { return local_rows_; }
  int equation_rows() const { return equation_rows_; }
  Mat A() const { return A_; }
  /// Null for B = I.
  Mat B() const { return B_; }
  const Eigen::SparseMatrix<double>& mass() const { return mass_; }
  bool has_identity_mass() const { return has_identity_mass_; }
  bool has_positive_diagonal_mass() const { return has_positive_diagonal_mass_; }
  long jacobian_evaluations() const { return jacobian_evaluations_; }

  /// A at x (this rank's local_rows() rows of the point). False if A is not finite.
  bool evaluate(const double* x) {
    {
      const PlacedArray placed(x_, x);
      problem_.jacobian(x_, jacobian_);
    }
    ++jacobian_evaluations_;
    check(MatCreateSubMatrix(jacobian_, rows_, columns_,
                             A_ != nullptr ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, &A_),
          "MatCreateSubMatrix");
    if (sign_ != 1.0) {
      check(MatScale(A_, sign_), "MatScale");
    }
    check(MatNorm(A_, NORM_INFINITY, &norm_), "MatNorm");
    return std::isfinite(norm_);
  }

  /// A = Aᵀ to 10⁻¹² ‖A‖∞ (the serial test's tolerance, against the largest entry there).
  bool is_symmetric() const {
    PetscBool symmetric = PETSC_FALSE;
    check(MatIsSymmetric(A_, 1e-12 * norm_, &symmetric), "MatIsSymmetric");
    return symmetric == PETSC_TRUE;
  }

  /// A whole on every rank (few states: the dense eigenvalues).
  Eigen::MatrixXd gathered() const {
    const auto m = static_cast<std::size_t>(state_count_);
    std::vector<double> local(static_cast<std::size_t>(equation_rows_) * m, 0.0);
    for (int i = 0; i < equation_rows_; ++i) {
      const PetscInt row = first_ + i;
      PetscInt count = 0;
      const PetscInt* columns = nullptr;
      const PetscScalar* values = nullptr;
      check(MatGetRow(A_, row, &count, &columns, &values), "MatGetRow");
      for (PetscInt k = 0; k < count; ++k) {
        local[static_cast<std::size_t>(i) * m + static_cast<std::size_t>(columns[k])] = values[k];
      }
      check(MatRestoreRow(A_, row, &count, &columns, &values), "MatRestoreRow");
    }
    const MPI_Comm communicator = problem_.communicator();
    int ranks = 1;
    MPI_Comm_size(communicator, &ranks);
    const int sent = static_cast<int>(local.size());
    std::vector<int> counts(static_cast<std::size_t>(ranks));
    MPI_Allgather(&sent, 1, MPI_INT, counts.data(), 1, MPI_INT, communicator);
    std::vector<int> offsets(static_cast<std::size_t>(ranks), 0);
    for (std::size_t r = 1; r < offsets.size(); ++r) {
      offsets[r] = offsets[r - 1] + counts[r - 1];
    }
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> whole(state_count_,
                                                                                 state_count_);
    MPI_Allgatherv(local.data(), sent, MPI_DOUBLE, whole.data(), counts.data(), offsets.data(),
                   MPI_DOUBLE, communicator);
    return whole;
  }

 private:
  const PetscProblem& problem_;
  double sign_ = 1.0;
  int state_count_ = 0;
  PetscInt first_ = 0;
  int local_rows_ = 0;
  int equation_rows_ = 0;
  IS rows_ = nullptr;
  IS columns_ = nullptr;
  Owned<Mat> jacobian_;
  Owned<Vec> x_;
  Mat A_ = nullptr;  // MatCreateSubMatrix's, reused from vertex to vertex
  Owned<Mat> B_;
  Eigen::SparseMatrix<double> mass_;
  bool has_identity_mass_ = true;
  bool has_positive_diagonal_mass_ = true;
  double norm_ = 0.0;
  long jacobian_evaluations_ = 0;
};

// Shift-invert Krylov–Schur at target 0 on one pencil, its factorisation kept from vertex to
// vertex (the symbolic analysis once, a numerical factorisation per vertex).
class ShiftInvert {
 public:
  ShiftInvert(const DistributedPencil& pencil, bool is_symmetric, const StabilityOptions& options)
      : is_symmetric_(is_symmetric), options_(options) {
    const MPI_Comm communicator = PetscObjectComm(reinterpret_cast<PetscObject>(pencil.A()));
    const int m = pencil.state_count();
    eigenvalue_count_ = std::min(options.eigenvalue_count, is_symmetric ? m - 1 : m - 2);
    const int wanted = options.subspace_size > 0 ? options.subspace_size
                                                 : std::max(2 * options.eigenvalue_count + 1, 16);
    const int subspace = std::min(m, std::max(wanted, eigenvalue_count_ + 2));
    check(EPSCreate(communicator, eps_.out()), "EPSCreate");
    check(EPSSetOperators(eps_, pencil.A(), pencil.B()), "EPSSetOperators");
    const bool generalized = pencil.B() != nullptr;
    check(EPSSetProblemType(eps_, is_symmetric ? (generalized ? EPS_GHEP : EPS_HEP)
                                               : (generalized ? EPS_GNHEP : EPS_NHEP)),
          "EPSSetProblemType");
    check(EPSSetType(eps_, EPSKRYLOVSCHUR), "EPSSetType");
    check(EPSSetWhichEigenpairs(eps_, EPS_TARGET_MAGNITUDE), "EPSSetWhichEigenpairs");
    check(EPSSetTarget(eps_, 0.0), "EPSSetTarget");
    check(EPSSetDimensions(eps_, eigenvalue_count_, subspace, PETSC_DEFAULT), "EPSSetDimensions");
    check(EPSSetTolerances(eps_, options.tolerance, options.max_restarts), "EPSSetTolerances");
    ST st = nullptr;
    check(EPSGetST(eps_, &st), "EPSGetST");
    check(STSetType(st, STSINVERT), "STSetType");
    // In place: with the shift 0 the spectral transformation factors A itself, the matrix whose
    // MUMPS factor gives the inertia below (a copy would get a factor of its own).
    check(STSetMatMode(st, ST_MATMODE_INPLACE), "STSetMatMode");
    check(STGetKSP(st, &ksp_), "STGetKSP");
    check(KSPSetType(ksp_, KSPPREONLY), "KSPSetType");
    check(KSPGetPC(ksp_, &pc_), "KSPGetPC");
    check(PCSetType(pc_, is_symmetric ? PCCHOLESKY : PCLU), "PCSetType");
    check(PCFactorSetMatSolverType(pc_, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
    if (is_symmetric) {
      // MUMPS's LDLᵀ with the options its inertia needs on several ranks: no ScaLAPACK at the
      // root front (ICNTL 13), and null pivots detected (ICNTL 24) below 10⁻¹³ ‖A‖ (CNTL 3), as
      // the serial test of the pivots.
      check(KSPSetOperators(ksp_, pencil.A(), pencil.A()), "KSPSetOperators");
      check(PCFactorSetUpMatSolverType(pc_), "PCFactorSetUpMatSolverType");
      Mat factor = nullptr;
      check(PCFactorGetMatrix(pc_, &factor), "PCFactorGetMatrix");
      check(MatMumpsSetIcntl(factor, 13, 1), "MatMumpsSetIcntl");
      check(MatMumpsSetIcntl(factor, 24, 1), "MatMumpsSetIcntl");
      check(MatMumpsSetCntl(factor, 3, 1e-13), "MatMumpsSetCntl");
    }
    check(MatCreateVecs(pencil.A(), real_.out(), nullptr), "MatCreateVecs");
    check(VecDuplicate(real_, imaginary_.out()), "VecDuplicate");
    check(VecDuplicate(real_, start_.out()), "VecDuplicate");
  }

  long factorisations = 0;
  long solves = 0;

  /// Factors A (new values, same pattern). False if the factorisation failed (singular A).
  bool factor(const DistributedPencil& pencil) {
    check(EPSSetOperators(eps_, pencil.A(), pencil.B()), "EPSSetOperators");
    check(KSPSetOperators(ksp_, pencil.A(), pencil.A()), "KSPSetOperators");
    check(KSPSetUp(ksp_), "KSPSetUp");
    ++factorisations;
    PCFailedReason reason = PC_NOERROR;
    check(PCGetFailedReason(pc_, &reason), "PCGetFailedReason");
    return reason == PC_NOERROR;
  }

  /// After factor(), symmetric: the negative, zero and positive pivots of A's LDLᵀ.
  std::array<PetscInt, 3> inertia() const {
    Mat factor = nullptr;
    check(PCFactorGetMatrix(pc_, &factor), "PCFactorGetMatrix");
    std::array<PetscInt, 3> counts{};
    check(MatGetInertia(factor, &counts[0], &counts[1], &counts[2]), "MatGetInertia");
    return counts;
  }

  /// After factor(): the eigenvalues nearest 0, or a failure.
  VertexStability solve() {
    if (has_start_) {
      Vec start = start_;
      check(EPSSetInitialSpace(eps_, 1, &start), "EPSSetInitialSpace");
    }
    PetscInt before = 0;
    check(KSPGetTotalIterations(ksp_, &before), "KSPGetTotalIterations");
    check(EPSSolve(eps_), "EPSSolve");
    PetscInt after = 0;
    check(KSPGetTotalIterations(ksp_, &after), "KSPGetTotalIterations");
    solves += after - before;
    PetscInt converged = 0;
    check(EPSGetConverged(eps_, &converged), "EPSGetConverged");
    const char* method = is_symmetric_ ? "shift-invert Lanczos (SLEPc Krylov-Schur)"
                                       : "shift-invert Arnoldi (SLEPc Krylov-Schur)";
    if (converged < eigenvalue_count_) {
      has_start_ = false;
      return failed(std::string(method) + " did not converge to " +
                    std::to_string(eigenvalue_count_) + " eigenvalues in " +
                    std::to_string(options_.max_restarts) + " restarts");
    }
    std::vector<Complex> values;
    double radius = 0.0;
    check(VecSet(start_, 0.0), "VecSet");
    for (PetscInt i = 0; i < eigenvalue_count_; ++i) {
      PetscScalar real = 0.0;
      PetscScalar imaginary = 0.0;
      check(EPSGetEigenpair(eps_, i, &real, &imaginary, real_, imaginary_), "EPSGetEigenpair");
      const Complex mu(real, is_symmetric_ ? 0.0 : imaginary);
      if (!std::isfinite(mu.real()) || !std::isfinite(mu.imag())) {
        continue;  // an infinite eigenvalue (singular B)
      }
      values.push_back(mu);
      radius = std::max(radius, std::abs(mu));
      check(VecAXPY(start_, 1.0, real_), "VecAXPY");
      if (!is_symmetric_) {
        check(VecAXPY(start_, 1.0, imaginary_), "VecAXPY");
      }
    }
    complete_conjugate_pairs(values);
    PetscReal norm = 0.0;
    check(VecNorm(start_, NORM_2, &norm), "VecNorm");
    has_start_ = std::isfinite(norm) && norm > 0.0;
    return from_eigenvalues(std::move(values), /*is_certain=*/false, radius);
  }

 private:
  bool is_symmetric_;
  StabilityOptions options_;
  int eigenvalue_count_ = 0;
  Owned<EPS> eps_;
  KSP ksp_ = nullptr;  // the ST's
  PC pc_ = nullptr;
  Owned<Vec> real_;
  Owned<Vec> imaginary_;
  Owned<Vec> start_;  // the sum of the last vertex's eigenvectors: the next one's start
  bool has_start_ = false;
};

void check_options(const StabilityOptions& options) {
  TESSERA_CHECK(
      options.eigenvalue_count >= 1,
      "stability: the number of eigenvalues must be ≥ 1, got " << options.eigenvalue_count);
  TESSERA_CHECK(
      options.tolerance > 0.0 && options.tolerance < 1.0,
      "stability: the eigenvalue tolerance must lie in (0, 1), got " << options.tolerance);
  TESSERA_CHECK(options.max_restarts >= 1,
                "stability: the number of restarts must be ≥ 1, got " << options.max_restarts);
}

}  // namespace

StabilityResult compute_distributed_stability(const PetscProblem& problem, const TriangleMesh& mesh,
                                              const StabilityOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  check_options(options);
  const auto n = static_cast<int>(problem.ambient_dimension());
  const std::optional<Dynamics> declared = problem.dynamics();
  TESSERA_CHECK(declared.has_value(),
                "--stability: the PETSc problem '"
                    << problem.name()
                    << "' declares no dynamics (B·u' = ±F(u, p)): implement "
                       "petsc::PetscProblem::dynamics() (docs/cluster.md), as the catalogue's bvp "
                       "and bratu2d do");
  const Dynamics& dynamics = *declared;
  check_dynamics(dynamics, n, problem.name());
  if (SlepcInitializeCalled != PETSC_TRUE) {
    // PETSc was started without SLEPc (a Session of a build without it does not exist, but a
    // caller's own PetscInitialize may): SLEPc's packages register on this call.
    check(SlepcInitialize(nullptr, nullptr, nullptr, nullptr), "SlepcInitialize");
  }
  DistributedPencil pencil(problem, dynamics);
  const bool is_split = mesh.space().is_distributed();
  if (is_split) {
    TESSERA_CHECK(mesh.space().first_row() == pencil.first_row() &&
                      mesh.ambient_dimension() == pencil.local_rows(),
                  "stability: the split mesh holds rows "
                      << mesh.space().first_row() << " … "
                      << mesh.space().first_row() + mesh.ambient_dimension() - 1
                      << " of each vertex here, problem '" << problem.name() << "' rows "
                      << pencil.first_row() << " … "
                      << pencil.first_row() + pencil.local_rows() - 1);
  } else {
    TESSERA_CHECK(mesh.ambient_dimension() == n, "stability: the mesh lies in R^"
                                                     << mesh.ambient_dimension() << ", problem '"
                                                     << problem.name() << "' in R^" << n);
  }
  const int m = pencil.state_count();
  const bool is_dense = m <= options.dense_state_limit;
  StabilityResult result;
  result.eigenvalue_count = is_dense ? 0 : options.eigenvalue_count;
  result.vertices.resize(static_cast<std::size_t>(mesh.vertex_count()));
  std::unique_ptr<ShiftInvert> symmetric;
  std::unique_ptr<ShiftInvert> general;
  bool any_symmetric = false;
  bool any_general = false;
  Eigen::VectorXd local(pencil.local_rows());
  for (const int v : stability_vertex_order(mesh)) {
    VertexStability& vertex = result.vertices[static_cast<std::size_t>(v)];
    local = is_split
                ? Eigen::VectorXd(mesh.point(v))
                : Eigen::VectorXd(mesh.point(v).segment(pencil.first_row(), pencil.local_rows()));
    if (!pencil.evaluate(local.data())) {
      vertex = failed("DF is not finite here");
      continue;
    }
    if (is_dense) {
      vertex = dense_stability(pencil.gathered(), pencil.mass(), pencil.has_identity_mass());
      continue;
    }
    if (pencil.has_positive_diagonal_mass() && pencil.is_symmetric()) {
      if (!symmetric) {
        symmetric = std::make_unique<ShiftInvert>(pencil, /*is_symmetric=*/true, options);
      }
      // Sylvester: (A, B), B positive definite, has as many positive eigenvalues as A has
      // positive pivots in its LDLᵀ. A null pivot (a vertex on a fold to rounding) makes the
      // count unreliable: the general way then counts the computed eigenvalues.
      if (symmetric->factor(pencil)) {
        const std::array<PetscInt, 3> inertia = symmetric->inertia();
        if (inertia[1] == 0) {
          vertex = symmetric->solve();
          if (!vertex.has_failed()) {
            vertex.unstable_count = static_cast<int>(inertia[2]);
            vertex.is_certain = true;
            any_symmetric = true;
          }
          continue;
        }
      }
    }
    if (!general) {
      general = std::make_unique<ShiftInvert>(pencil, /*is_symmetric=*/false, options);
    }
    if (!general->factor(pencil)) {
      vertex = failed("s·D_uF is singular here (MUMPS's LU failed): a point of a fold to rounding");
      continue;
    }
    vertex = general->solve();
    any_general = any_general || !vertex.has_failed();
  }
  result.method = is_dense ? "dense"
                  : any_general && any_symmetric
                      ? "sparse symmetric (inertia, MUMPS LDLT), SLEPc shift-invert Krylov-Schur "
                        "where the LDLT failed"
                  : any_general ? "sparse (SLEPc shift-invert Krylov-Schur, MUMPS LU)"
                                : "sparse symmetric (inertia, MUMPS LDLT; SLEPc Krylov-Schur)";
  count_stability_classes(result);
  for (const ShiftInvert* solver : {symmetric.get(), general.get()}) {
    if (solver != nullptr) {
      result.factorisations += solver->factorisations;
      result.solves += solver->solves;
    }
  }
  result.jacobian_evaluations = pencil.jacobian_evaluations();
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

#endif

}  // namespace tessera::petsc
