// SPDX-License-Identifier: MIT
// Sparse LU factorisation of a square matrix behind one narrow interface: the symbolic analysis
// of a pattern once, numerical factorisations of matrices with that pattern many times, solves
// with one or several right-hand sides. Implementations: Eigen's SparseLU (always), SuiteSparse's
// UMFPACK and KLU, SuperLU (when the build found them). Their headers stay in the .cpp files.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tessera {

/// While one lives on the calling thread, every SparseLu::factorize makes a full factorisation
/// with pivoting (KLU does not refactor with the pivot sequence of the object's last one): a
/// factorisation then depends on the matrix alone, not on what the same object factored
/// before. The atlas builds under one, so that a build continued from a checkpoint (whose
/// factorisations are new objects) repeats the uninterrupted build's arithmetic bit for bit.
class FullPivotingScope {
 public:
  FullPivotingScope();
  ~FullPivotingScope();
  FullPivotingScope(const FullPivotingScope&) = delete;
  FullPivotingScope& operator=(const FullPivotingScope&) = delete;
  static bool is_active();

 private:
  bool previous_;
};

/// The sparse direct solvers. Which ones a build has depends on the libraries found when it was
/// configured (`is_available`); Eigen is always there. bench/history/RESULTS-log.md section 9
/// compares them on tessera's bordered Jacobians.
enum class SparseLuSolver {
  Eigen,    ///< Eigen's SparseLU: supernodal, partial pivoting, ordered by nested dissection
            ///< (METIS) where the build has it, else (or TESSERA_SPARSE_LU_ORDERING=colamd) COLAMD
  Umfpack,  ///< SuiteSparse UMFPACK: multifrontal, AMD/COLAMD ordering, BLAS-3 on dense fronts
  Klu,      ///< SuiteSparse KLU: BTF + AMD ordering, left-looking; refactors without re-pivoting
  SuperLu,  ///< SuperLU: supernodal, COLAMD ordering (through Eigen's SuperLUSupport)
};

/// Every solver, available or not, in a fixed order.
const std::vector<SparseLuSolver>& all_sparse_lu_solvers();
/// The solvers this build has, Eigen always among them.
std::vector<SparseLuSolver> available_sparse_lu_solvers();
bool is_available(SparseLuSolver solver);
/// "eigen", "umfpack", "klu", "superlu": the names accepted by TESSERA_SPARSE_LU.
std::string_view name(SparseLuSolver solver);
/// The solver of that name (case-sensitive), or nothing.
std::optional<SparseLuSolver> sparse_lu_solver_named(std::string_view name);

/// The solver the environment asks for: TESSERA_SPARSE_LU when it is set and not empty,
/// otherwise Eigen's SparseLU. Read at every call, so that a test or a benchmark can switch
/// solvers with setenv. `Linearization` asks `sparse_lu_solver_for` instead.
/// \throw InvalidArgument if TESSERA_SPARSE_LU names no solver or one this build does not have
///        (the message lists the available ones).
SparseLuSolver default_sparse_lu_solver();

/// The solver `Linearization` uses for matrices with A's pattern: TESSERA_SPARSE_LU when set;
/// otherwise KLU where its symbolic analysis predicts little fill, nnz(L + U) at most
/// 6·nnz(A) (1-D and small 2-D problems, where it is 2–7× faster than the others: no
/// supernodes to set up, and a refactorisation that keeps the pivots), else Eigen's SparseLU,
/// the fastest on 2-D problems at n ≥ 10⁴ (bench/history/RESULTS-log.md section 9). The choice
/// depends on the pattern only, so it is deterministic; it is remembered per (n, nnz(A)), so the
/// analysis that decides is paid once per pattern size, not per factorisation.
SparseLuSolver sparse_lu_solver_for(const Eigen::SparseMatrix<double>& A);

/// The outcome of an analysis or a factorisation. Numerical outcomes are values, not exceptions.
enum class SparseLuStatus {
  Success,
  Singular,     ///< a zero (or, for KLU, non-finite) pivot: A is numerically singular
  OutOfMemory,  ///< the solver could not allocate its factors
  Failed,       ///< anything else the solver reports (the message says what)
};

struct SparsePattern;

/// An LU factorisation P A Q = L U of a sparse square n×n matrix A.
///
/// Use: `analyze(A)` once per sparsity pattern (fill-reducing ordering, symbolic factorisation),
/// then `factorize(A)` for each matrix with that pattern, then `solve` as often as needed. The
/// pattern is A's compressed column structure (outer and inner indices); values may change
/// freely between factorisations, the pattern may not (`is_analyzed_for` tells).
///
/// Objects are not copyable (the solvers' factors are not); make a new one with
/// make_sparse_lu(solver()) and factor again. One thread at a time per object.
class SparseLu {
 public:
  virtual ~SparseLu();
  SparseLu(const SparseLu&) = delete;
  SparseLu& operator=(const SparseLu&) = delete;

  virtual SparseLuSolver solver() const = 0;

  /// Symbolic analysis of A's pattern; forgets any earlier factorisation.
  /// \pre A is square, n ≥ 1, compressed (A.isCompressed()).
  /// \throw InvalidArgument if a precondition fails (the message names the shape).
  SparseLuStatus analyze(const Eigen::SparseMatrix<double>& A);

  /// True if the last `analyze` saw exactly A's pattern (same n, outer and inner indices).
  bool is_analyzed_for(const Eigen::SparseMatrix<double>& A) const;

  /// Numerical factorisation of A. On failure the object holds no factorisation (is_factored()
  /// is false) until the next success.
  /// \pre is_analyzed_for(A).
  /// \throw InvalidArgument if the precondition fails.
  SparseLuStatus factorize(const Eigen::SparseMatrix<double>& A);

  bool is_factored() const { return is_factored_; }

  /// X = A⁻¹ B for B n×k, k ≥ 1; X may be B itself (the same memory) but must not overlap it
  /// otherwise. No iterative refinement: the callers are Newton-type iterations, which correct.
  /// \pre is_factored(); B and X are n×k.
  /// \throw InvalidArgument if a precondition fails.
  void solve(const Eigen::Ref<const Eigen::MatrixXd>& B, Eigen::Ref<Eigen::MatrixXd> X) const;

  /// nnz(L) + nnz(U) of the current factorisation as the solver counts them (diagonals
  /// included; KLU adds the off-diagonal blocks of its block triangular form); nothing when the
  /// solver does not say (SuperLU) or there is no factorisation.
  virtual std::optional<long> factor_nonzeros() const = 0;
  /// nnz(L) + nnz(U) as the symbolic analysis predicts it, where the solver predicts one (KLU).
  virtual std::optional<long> predicted_factor_nonzeros() const { return std::nullopt; }
  /// The bytes the current factorisation holds (factors, permutations, scaling and the solves'
  /// workspace; a shared symbolic analysis not counted), where the solver says (KLU); else
  /// nothing, and callers estimate from factor_nonzeros().
  virtual std::optional<std::size_t> factorisation_bytes() const { return std::nullopt; }

  /// The solver's own words about the last failure, empty after a success.
  const std::string& last_message() const { return last_message_; }

 protected:
  SparseLu() = default;
  /// Implementations: the three steps, with the preconditions already checked.
  virtual SparseLuStatus do_analyze(const Eigen::SparseMatrix<double>& A) = 0;
  virtual SparseLuStatus do_factorize(const Eigen::SparseMatrix<double>& A) = 0;
  /// X holds B on entry and A⁻¹B on return.
  virtual void do_solve_in_place(Eigen::Ref<Eigen::MatrixXd> X) const = 0;

  std::string last_message_;

 private:
  // The pattern of the last analysis, one copy shared by the objects of a thread analysed for
  // it: each of the atlas's kept factorisations held its own, nnz + n + 1 ints (320 KB at
  // n = 10⁴, a hundred of them).
  std::shared_ptr<const SparsePattern> pattern_;
  bool is_analyzed_ = false;
  bool is_factored_ = false;
};

/// A new, empty factorisation object of that solver.
/// \throw InvalidArgument if this build does not have the solver (the message lists those it has).
std::unique_ptr<SparseLu> make_sparse_lu(SparseLuSolver solver);

}  // namespace tessera
