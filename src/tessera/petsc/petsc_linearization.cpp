// SPDX-License-Identifier: MIT
#include "tessera/petsc/petsc_linearization.h"

#include <array>
#include <cmath>
#include <string>

#include "tessera/core/error.h"

namespace tessera::petsc {

namespace {

// A value and the global index where it was found, for MPI_MAXLOC: the largest value, the
// smallest index among equal values, so that the choice does not depend on the rank count.
struct ValueAndIndex {
  double value;
  int index;
};

ValueAndIndex largest_over_ranks(ValueAndIndex local, MPI_Comm communicator) {
  ValueAndIndex global{};
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE_INT, MPI_MAXLOC, communicator);
  return global;
}

// Distinct columns the border rows may have held before the matrix is made anew: each old
// column stays in the pattern as an explicit zero, and many would make the rows dense.
constexpr int kMaxBorderColumnChanges = 8;
// A border is kept while |det T([i, j], :)| is at least this fraction of the best pair's: the
// border only has to be regular (the tangent's accuracy is checked, and ReplicatedProblem's
// basis does not depend on it), and a linearisation reused for another chart would otherwise
// change its border, and MUMPS analyse the pattern again, at every other chart (bratu2d N = 32:
// 574 analyses for 6726 factorisations at 0.5, 246 at 0.1).
constexpr double kKeepBorderFraction = 0.1;

}  // namespace

void zero_border_entries(Vec v) {
  PetscInt n = 0;
  PetscInt first = 0;
  PetscInt end = 0;
  check(VecGetSize(v, &n), "VecGetSize");
  check(VecGetOwnershipRange(v, &first, &end), "VecGetOwnershipRange");
  if (end <= n - 2) {
    return;
  }
  PetscScalar* values = nullptr;
  check(VecGetArray(v, &values), "VecGetArray");
  for (PetscInt i = std::max(first, n - 2); i < end; ++i) {
    values[i - first] = 0.0;
  }
  check(VecRestoreArray(v, &values), "VecRestoreArray");
}

DistributedLinearization::DistributedLinearization(const PetscProblem& problem)
    : problem_(problem), n_(problem.ambient_dimension()) {
  TESSERA_CHECK(n_ >= 3, "DistributedLinearization: n = " << n_ << " must be >= 3");
}

DistributedLinearization::DistributedLinearization(const DistributedLinearization& other)
    : problem_(other.problem_), n_(other.n_) {
  if (!other.point_) {
    return;
  }
  const auto copy = [](Vec from, Owned<Vec>& to) {
    check(VecDuplicate(from, to.out()), "VecDuplicate");
    check(VecCopy(from, to), "VecCopy");
  };
  copy(other.point_, point_);
  copy(other.tangent_[0], tangent_[0]);
  copy(other.tangent_[1], tangent_[1]);
  check(VecDuplicate(other.unit_, unit_.out()), "VecDuplicate");
  check(VecDuplicate(other.rhs_, rhs_.out()), "VecDuplicate");
  has_basis_ = other.has_basis_;
  if (!other.bordered_) {
    return;
  }
  check(MatDuplicate(other.bordered_, MAT_COPY_VALUES, bordered_.out()), "MatDuplicate");
  border_i_ = other.border_i_;
  border_j_ = other.border_j_;
  border_changes_ = other.border_changes_;
  if (other.is_factored_) {
    make_solver();
    check(KSPSetOperators(solver_, bordered_, bordered_), "KSPSetOperators");
    check(KSPSetUp(solver_), "KSPSetUp");
    is_factored_ = true;
  }
}

void DistributedLinearization::make_solver() {
  check(KSPCreate(problem_.communicator(), solver_.out()), "KSPCreate");
  check(KSPSetType(solver_, KSPPREONLY), "KSPSetType");
  PC preconditioner = nullptr;
  check(KSPGetPC(solver_, &preconditioner), "KSPGetPC");
  check(PCSetType(preconditioner, PCLU), "PCSetType");
  // On one rank SuiteSparse's KLU (the serial backend's solver for these matrices), on more
  // MUMPS: bench/history/RESULTS-log.md section 13b. KLU's analysis costs 1–2 factorisations where
  // MUMPS's costs 10–40, and its solves are 1.5–5× faster at n = 10⁴–10⁵.
  int ranks = 1;
  MPI_Comm_size(problem_.communicator(), &ranks);
  const char* package = nullptr;
#if defined(PETSC_HAVE_MUMPS)
  package = MATSOLVERMUMPS;
#endif
#if defined(PETSC_HAVE_SUITESPARSE)
  if (ranks == 1) {
    package = MATSOLVERKLU;
  }
#endif
  if (package != nullptr) {
    check(PCFactorSetMatSolverType(preconditioner, package), "PCFactorSetMatSolverType");
  }
  // PETSc's command-line options (-ksp_type, -pc_type, -mat_mumps_…) win over these defaults.
  check(KSPSetFromOptions(solver_), "KSPSetFromOptions");
  // SuperLU_dist pivots statically: the border rows' zero diagonal needs its MC64 row
  // permutation, which Debian's build leaves out (non-free), and its other permutation (AWPM)
  // needs a square process grid; it then aborts the whole job ("pivotL() encounters zero
  // diagonal") instead of returning an error. Refused here with the reason, before any work.
  PCType chosen = nullptr;
  check(PCGetType(preconditioner, &chosen), "PCGetType");
  const char* chosen_package = nullptr;
  if (chosen != nullptr && (std::string(chosen) == PCLU || std::string(chosen) == PCCHOLESKY)) {
    check(PCFactorGetMatSolverType(preconditioner, &chosen_package), "PCFactorGetMatSolverType");
  }
  TESSERA_CHECK(chosen_package == nullptr || std::string(chosen_package) != MATSOLVERSUPERLU_DIST,
                "-pc_factor_mat_solver_type superlu_dist cannot factor tessera's bordered Jacobians: "
                "their border rows have a zero diagonal, which SuperLU_dist's static pivoting "
                "needs its MC64 row permutation for, and Debian's SuperLU_dist is built without "
                "it; use mumps (the default on several ranks) or an iterative -ksp_type");
}

bool DistributedLinearization::factor(Vec x, const TangentPair* reference) {
  is_factored_ = false;
  last_failure_.clear();
  if (!point_) {
    point_ = problem_.create_vector();
    unit_ = problem_.create_vector();
    rhs_ = problem_.create_vector();
    tangent_[0] = problem_.create_vector();
    tangent_[1] = problem_.create_vector();
  }
  check(VecCopy(x, point_), "VecCopy");
  if (!bordered_ || border_changes_ >= kMaxBorderColumnChanges) {
    bordered_ = problem_.create_jacobian();
    border_i_ = border_j_ = -1;
    border_changes_ = 0;
  }
  problem_.jacobian(x, bordered_);
  PetscReal norm = 0.0;
  check(MatNorm(bordered_, NORM_FROBENIUS, &norm), "MatNorm");
  if (!std::isfinite(norm)) {
    last_failure_ = "DF(x) is not finite";
    return false;
  }
  // The border: PITCON's coordinate rows from the reference (or the last basis), else the last
  // two coordinates (the parameters).
  const TangentPair* guide = reference != nullptr ? reference : (has_basis_ ? &tangent_ : nullptr);
  PetscInt i = n_ - 2;
  PetscInt j = n_ - 1;
  PetscInt best_i = i;
  PetscInt best_j = j;
  if (guide != nullptr) {
    choose_border(*guide, i, j, best_i, best_j);
  }
  bool is_regular = factor_with_border(i, j);
  if (is_regular && (i != best_i || j != best_j)) {
    // A kept border gives another basis of the same plane; the basis is the frame of the
    // atlas's charts (their polygons, the directions of their radius probes), so it must not
    // depend on which border the factorisation kept: it is made the serial backend's.
    is_regular = express_in_coordinates(best_i, best_j);
  }
  if (!is_regular && (i != n_ - 2 || j != n_ - 1)) {
    is_regular = factor_with_border(n_ - 2, n_ - 1);
  }
  has_basis_ = is_regular;
  if (!is_regular) {
    if (last_failure_.empty()) {
      last_failure_ = "the bordered Jacobian is singular for every border tried";
    }
    return false;
  }
  if (reference != nullptr) {
    // det(Tᵀ Tᵣ) > 0: neighbouring frames keep one orientation.
    PetscScalar a = 0, b = 0, c = 0, d = 0;
    check(VecDot(tangent_[0], (*reference)[0], &a), "VecDot");
    check(VecDot(tangent_[0], (*reference)[1], &b), "VecDot");
    check(VecDot(tangent_[1], (*reference)[0], &c), "VecDot");
    check(VecDot(tangent_[1], (*reference)[1], &d), "VecDot");
    if (a * d - b * c < 0.0) {
      check(VecScale(tangent_[1], -1.0), "VecScale");
    }
  }
  is_factored_ = true;
  return true;
}

void DistributedLinearization::choose_border(const TangentPair& guide, PetscInt& i, PetscInt& j,
                                             PetscInt& best_i, PetscInt& best_j) const {
  PetscInt first = 0;
  PetscInt end = 0;
  check(VecGetOwnershipRange(guide[0], &first, &end), "VecGetOwnershipRange");
  const PetscScalar* t0 = nullptr;
  const PetscScalar* t1 = nullptr;
  check(VecGetArrayRead(guide[0], &t0), "VecGetArrayRead");
  check(VecGetArrayRead(guide[1], &t1), "VecGetArrayRead");
  // i: the row of T of largest norm.
  ValueAndIndex best{-1.0, 0};
  for (PetscInt k = first; k < end; ++k) {
    const double norm2 = t0[k - first] * t0[k - first] + t1[k - first] * t1[k - first];
    if (norm2 > best.value) {
      best = {norm2, static_cast<int>(k)};
    }
  }
  const MPI_Comm communicator = problem_.communicator();
  i = largest_over_ranks(best, communicator).index;
  const bool owns_i = i >= first && i < end;
  const double ti0 = sum_over_ranks(owns_i ? t0[i - first] : 0.0, communicator);
  const double ti1 = sum_over_ranks(owns_i ? t1[i - first] : 0.0, communicator);
  // j: maximises |det T([i, j], :)|.
  best = {-1.0, 0};
  for (PetscInt k = first; k < end; ++k) {
    const double det = std::abs(ti0 * t1[k - first] - ti1 * t0[k - first]);
    if (k != i && det > best.value) {
      best = {det, static_cast<int>(k)};
    }
  }
  const ValueAndIndex best_pair = largest_over_ranks(best, communicator);
  j = best_pair.index;
  best_i = i;
  best_j = j;
  // Keep the current border while it is not much worse conditioned than the best one: a
  // new border column is a new pattern, and MUMPS's analysis of it costs several numerical
  // factorisations (bratu2d N = 316: 5–17 s against 0.24 s).
  if (border_i_ >= 0) {
    const auto entry = [&](const PetscScalar* t, PetscInt row) {
      return sum_over_ranks(row >= first && row < end ? t[row - first] : 0.0, communicator);
    };
    const double current = std::abs(entry(t0, border_i_) * entry(t1, border_j_) -
                                    entry(t1, border_i_) * entry(t0, border_j_));
    if (current >= kKeepBorderFraction * best_pair.value) {
      i = border_i_;
      j = border_j_;
    }
  }
  check(VecRestoreArrayRead(guide[0], &t0), "VecRestoreArrayRead");
  check(VecRestoreArrayRead(guide[1], &t1), "VecRestoreArrayRead");
}

// The basis of the same plane whose rows i and j are those of the identity, orthonormalised as
// factor_with_border does (coordinate_tangent_basis in one process): what the border (e_i, e_j)
// would have given, without its factorisation.
// Modified Gram–Schmidt, twice for stability.
bool DistributedLinearization::orthonormalise_tangent() {
  for (int pass = 0; pass < 2; ++pass) {
    PetscReal length = 0.0;
    check(VecNormalize(tangent_[0], &length), "VecNormalize");
    if (!std::isfinite(length) || length == 0.0) {
      last_failure_ = "the tangent is not finite";
      return false;
    }
    PetscScalar overlap = 0.0;
    check(VecDot(tangent_[0], tangent_[1], &overlap), "VecDot");
    check(VecAXPY(tangent_[1], -overlap, tangent_[0]), "VecAXPY");
    check(VecNormalize(tangent_[1], &length), "VecNormalize");
    if (!std::isfinite(length) || length == 0.0) {
      last_failure_ = "the tangent basis is degenerate";
      return false;
    }
  }
  return true;
}

bool DistributedLinearization::express_in_coordinates(PetscInt i, PetscInt j) {
  PetscInt first = 0;
  PetscInt end = 0;
  check(VecGetOwnershipRange(tangent_[0], &first, &end), "VecGetOwnershipRange");
  std::array<double, 4> rows{};  // T(i, 0), T(i, 1), T(j, 0), T(j, 1)
  for (int k = 0; k < 2; ++k) {
    const PetscScalar* t = nullptr;
    check(VecGetArrayRead(tangent_[static_cast<std::size_t>(k)], &t), "VecGetArrayRead");
    rows[static_cast<std::size_t>(k)] = i >= first && i < end ? t[i - first] : 0.0;
    rows[static_cast<std::size_t>(2 + k)] = j >= first && j < end ? t[j - first] : 0.0;
    check(VecRestoreArrayRead(tangent_[static_cast<std::size_t>(k)], &t), "VecRestoreArrayRead");
  }
  for (double& value : rows) {
    value = sum_over_ranks(value, problem_.communicator());
  }
  const double det = rows[0] * rows[3] - rows[1] * rows[2];
  if (!(std::abs(det) > 1e-12)) {  // T is orthonormal: the pair is (nearly) blind to the plane
    last_failure_ = "the tangent plane is not a graph over the border's coordinates";
    return false;
  }
  // T (rows of (i, j))⁻¹, column by column, into unit_ and rhs_ (free here).
  const double inverse[2][2] = {{rows[3] / det, -rows[1] / det}, {-rows[2] / det, rows[0] / det}};
  Vec basis[2] = {unit_, rhs_};
  for (int c = 0; c < 2; ++c) {
    check(VecAXPBY(basis[c], inverse[0][c], 0.0, tangent_[0]), "VecAXPBY");
    check(VecAXPY(basis[c], inverse[1][c], tangent_[1]), "VecAXPY");
  }
  check(VecSetValue(basis[0], i, 1.0, INSERT_VALUES), "VecSetValue");
  check(VecSetValue(basis[0], j, 0.0, INSERT_VALUES), "VecSetValue");
  check(VecSetValue(basis[1], i, 0.0, INSERT_VALUES), "VecSetValue");
  check(VecSetValue(basis[1], j, 1.0, INSERT_VALUES), "VecSetValue");
  for (Vec v : basis) {
    check(VecAssemblyBegin(v), "VecAssemblyBegin");
    check(VecAssemblyEnd(v), "VecAssemblyEnd");
  }
  check(VecCopy(basis[0], tangent_[0]), "VecCopy");
  check(VecCopy(basis[1], tangent_[1]), "VecCopy");
  return orthonormalise_tangent();
}

bool DistributedLinearization::factor_with_border(PetscInt i, PetscInt j) {
  PetscInt first = 0;
  PetscInt end = 0;
  check(MatGetOwnershipRange(bordered_, &first, &end), "MatGetOwnershipRange");
  const PetscInt row_i = n_ - 2;
  const PetscInt row_j = n_ - 1;
  const auto set_entry = [&](PetscInt row, PetscInt column, double value) {
    if (row >= first && row < end) {
      check(MatSetValue(bordered_, row, column, value, INSERT_VALUES), "MatSetValue");
    }
  };
  if (border_i_ >= 0 && (border_i_ != i || border_j_ != j)) {
    set_entry(row_i, border_i_, 0.0);  // the old border column stays as an explicit zero
    set_entry(row_j, border_j_, 0.0);
  }
  // The border rows' diagonal entries are in the pattern (explicit zeros unless the border is
  // there): incomplete factorisations (-pc_type ilu, bjacobi) need every diagonal entry, and
  // -pc_factor_shift_type nonzero then shifts these zero pivots.
  set_entry(row_i, row_i, 0.0);
  set_entry(row_j, row_j, 0.0);
  set_entry(row_i, i, 1.0);
  set_entry(row_j, j, 1.0);
  check(MatAssemblyBegin(bordered_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(bordered_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  if (border_i_ != i || border_j_ != j) {
    ++analyses_;  // a new pattern: the solver analyses it again
    ++border_changes_;
  }
  border_i_ = i;
  border_j_ = j;

  if (!solver_) {
    make_solver();
  }
  check(KSPSetOperators(solver_, bordered_, bordered_), "KSPSetOperators");
  ++factorisations_;
  const PetscErrorCode code = KSPSetUp(solver_);
  PC preconditioner = nullptr;
  check(KSPGetPC(solver_, &preconditioner), "KSPGetPC");
  PCFailedReason reason = PC_NOERROR;
  check(PCGetFailedReason(preconditioner, &reason), "PCGetFailedReason");
  if (code != 0 || reason != PC_NOERROR) {
    const char* text = nullptr;
    if (code != 0) {
      PetscErrorMessage(code, &text, nullptr);
    }
    last_failure_ = std::string("the factorisation failed: ") +
                    (code != 0 ? (text != nullptr ? text : "PETSc error") : PCFailedReasons[reason]);
    return false;
  }
  last_failure_.clear();
  // ker DF = span A⁻¹ e_{n−2}, A⁻¹ e_{n−1}.
  for (int k = 0; k < 2; ++k) {
    check(VecSet(unit_, 0.0), "VecSet");
    check(VecSetValue(unit_, n_ - 2 + k, 1.0, INSERT_VALUES), "VecSetValue");
    check(VecAssemblyBegin(unit_), "VecAssemblyBegin");
    check(VecAssemblyEnd(unit_), "VecAssemblyEnd");
    check(KSPSolve(solver_, unit_, tangent_[static_cast<std::size_t>(k)]), "KSPSolve");
    KSPConvergedReason converged = KSP_CONVERGED_ITERATING;
    check(KSPGetConvergedReason(solver_, &converged), "KSPGetConvergedReason");
    if (converged < 0) {
      last_failure_ = std::string("the tangent solve did not converge: ") +
                      KSPConvergedReasons[converged];
      return false;
    }
  }
  if (!orthonormalise_tangent()) {
    return false;
  }
  // The basis must lie in ker DF to 1e-8 relative to ‖DF‖ (a border nearly blind to the tangent
  // plane gives an inaccurate one). ‖DF‖²_F = ‖A‖²_F − 2: the border holds two ones.
  PetscReal bordered_norm = 0.0;
  check(MatNorm(bordered_, NORM_FROBENIUS, &bordered_norm), "MatNorm");
  const double jacobian_norm = std::sqrt(std::max(0.0, bordered_norm * bordered_norm - 2.0));
  double residual2 = 0.0;
  for (int k = 0; k < 2; ++k) {
    check(MatMult(bordered_, tangent_[static_cast<std::size_t>(k)], unit_), "MatMult");
    zero_border_entries(unit_);
    PetscReal residual = 0.0;
    check(VecNorm(unit_, NORM_2, &residual), "VecNorm");
    residual2 += residual * residual;
  }
  if (!(std::sqrt(residual2) <= 1e-8 * std::max(1.0, jacobian_norm))) {
    last_failure_ = "the tangent basis is not accurate (|DF T| = " +
                    std::to_string(std::sqrt(residual2)) + ")";
    return false;
  }
  return true;
}

std::size_t DistributedLinearization::memory_bytes() const {
  if (!bordered_) {
    return 0;
  }
  int ranks = 1;
  MPI_Comm_size(problem_.communicator(), &ranks);
  MatInfo info{};
  check(MatGetInfo(bordered_, MAT_GLOBAL_SUM, &info), "MatGetInfo");
  // A CSR entry: its value and its column index.
  double bytes = info.nz_allocated * (sizeof(PetscScalar) + sizeof(PetscInt));
#if defined(PETSC_HAVE_MUMPS)
  if (solver_ && is_factored_) {
    PC preconditioner = nullptr;
    check(KSPGetPC(solver_, &preconditioner), "KSPGetPC");
    PCType type = nullptr;
    check(PCGetType(preconditioner, &type), "PCGetType");
    MatSolverType package = nullptr;
    if (type != nullptr && std::string(type) == PCLU) {
      check(PCFactorGetMatSolverType(preconditioner, &package), "PCFactorGetMatSolverType");
    }
    if (package != nullptr && std::string(package) == MATSOLVERMUMPS) {
      Mat factors = nullptr;
      check(PCFactorGetMatrix(preconditioner, &factors), "PCFactorGetMatrix");
      // INFOG(9), INFOG(10): real and integer entries of the factors over all ranks; a negative
      // value counts millions.
      const auto entries = [&](PetscInt index) {
        PetscInt value = 0;
        check(MatMumpsGetInfog(factors, index, &value), "MatMumpsGetInfog");
        return value < 0 ? -1e6 * static_cast<double>(value) : static_cast<double>(value);
      };
      bytes += entries(9) * sizeof(PetscScalar) + entries(10) * sizeof(PetscInt);
    }
  }
#endif
  return static_cast<std::size_t>(bytes / ranks);
}

void DistributedLinearization::solve_bordered_columns(Mat B, Mat X) const {
  TESSERA_CHECK(is_factored_, "DistributedLinearization::solve_bordered_columns: not factored");
  check(KSPMatSolve(solver_, B, X), "KSPMatSolve");
}

void DistributedLinearization::solve_minimum_norm(Vec rhs, Vec dx) const {
  TESSERA_CHECK(is_factored_, "DistributedLinearization::solve_minimum_norm: not factored");
  check(VecCopy(rhs, rhs_), "VecCopy");
  zero_border_entries(rhs_);
  check(KSPSolve(solver_, rhs_, dx), "KSPSolve");
  // Remove the ker-DF component: what remains is the minimum-norm solution.
  Vec basis[2] = {tangent_[0], tangent_[1]};
  PetscScalar dots[2] = {0.0, 0.0};
  check(VecMDot(dx, 2, basis, dots), "VecMDot");
  dots[0] = -dots[0];
  dots[1] = -dots[1];
  check(VecMAXPY(dx, 2, dots, basis), "VecMAXPY");
}

}  // namespace tessera::petsc
