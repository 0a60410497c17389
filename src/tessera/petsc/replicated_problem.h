// SPDX-License-Identifier: MIT
// A PETSc problem seen as an ordinary ImplicitProblem whose points every rank holds whole: the
// whole of tessera (every method, clipping, refinement, validation, the report, the output)
// runs on it unchanged and identically on every rank, while F, DF and the factorisations of the
// bordered Jacobian are distributed (MUMPS). `tessera mesh --backend petsc` covers with it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "tessera/core/implicit_problem.h"
#include "tessera/petsc/petsc_problem.h"

namespace tessera::petsc {

class DistributedLinearization;

/// How the rows of a PETSc vector are split over the ranks, for gathering a distributed vector
/// into a whole one on every rank (MPI_Allgatherv: every rank gets the same bits).
class RowSplit {
 public:
  explicit RowSplit(const PetscProblem& problem);
  PetscInt first() const { return first_; }
  PetscInt local_rows() const { return local_rows_; }
  /// `local` (this rank's rows) into all n entries of `whole`, on every rank. Collective.
  void gather(const double* local, double* whole) const;
  /// The same for a distributed vector.
  void gather(Vec local, double* whole) const;

 private:
  MPI_Comm communicator_;
  PetscInt first_ = 0;
  PetscInt local_rows_ = 0;
  std::vector<int> counts_;         // rows per rank
  std::vector<int> displacements_;  // first row per rank
};

/// An ImplicitProblem over a PetscProblem (which must outlive it) whose points, tangent bases
/// and solutions are whole n-vectors on every rank.
///
/// Every rank runs the same covering code on the same data and so takes the same decisions;
/// the collective calls (evaluate, sparse_jacobian, the linearisation's factor and solves) are
/// therefore made in the same order on every rank. Each rank evaluates and factors its own
/// rows, and the results are gathered to all: a solve costs one distributed triangular solve
/// and one all-gather of n doubles.
///
/// What this does not distribute: the vertices' states, 8n bytes per vertex on every rank (the
/// SPMD design of petsc::DistributedProblem, where each rank keeps its rows only, is the next
/// step: see docs/cluster.md). What runs on one rank must not decide anything on its own: the
/// CLI agrees on stops and time budgets over all ranks (`any_rank`).
///
/// The metric: coordinate_blocks() are the PetscProblem's, so the covering scales the problem
/// as it scales a serial one (ScaledProblem wraps the distributed factorisation).
class ReplicatedProblem final : public ImplicitProblem {
 public:
  /// `coordinate_names`: one per coordinate (the serial problem's, for views and output);
  /// empty: x0, x1, ….
  explicit ReplicatedProblem(const PetscProblem& problem,
                             std::vector<std::string> coordinate_names = {});
  ~ReplicatedProblem() override;

  int ambient_dimension() const override { return static_cast<int>(problem_.ambient_dimension()); }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override;
  /// Dense DF from the gathered sparse one (small n: the dense methods and tests).
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override;
  bool has_sparse_jacobian() const override { return true; }
  /// DF(x) gathered to every rank: O(nonzeros) memory and traffic. The covering factors
  /// through make_linearization_backend instead; this serves the few places that multiply by
  /// DF (tangent updates, fold curves).
  void sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                       Eigen::SparseMatrix<double>& J) const override;
  std::string name() const override { return problem_.name(); }
  std::vector<std::string> coordinate_names() const override;
  std::vector<CoordinateBlock> coordinate_blocks() const override {
    return problem_.coordinate_blocks();
  }
  std::optional<Dynamics> dynamics() const override { return problem_.dynamics(); }
  /// The distributed factorisation (DistributedLinearization, MUMPS by default), its tangent
  /// bases and solutions gathered to every rank.
  std::unique_ptr<LinearizationBackend> make_linearization_backend() const override;

  const PetscProblem& petsc_problem() const { return problem_; }
  const RowSplit& rows() const { return rows_; }

  /// For this problem's linearisation backends: a linearisation left by a backend that is gone
  /// (its solver's symbolic analysis is reused while the border stays: MUMPS's analysis costs
  /// 7–60 numerical factorisations), else a new one.
  std::shared_ptr<DistributedLinearization> take_linearization() const;
  /// Keeps a backend's linearisation for the next one (up to kIdleLinearizations; each holds
  /// its factors). \pre no other backend shares it.
  void give_back(std::shared_ptr<DistributedLinearization> linearization) const;
  static constexpr std::size_t kIdleLinearizations = 64;

 private:
  const PetscProblem& problem_;
  std::vector<std::string> coordinate_names_;
  RowSplit rows_;
  Owned<Vec> x_;  // array vectors: the local rows of the caller's x, lent for a call
  Owned<Vec> F_;
  mutable Owned<Mat> jacobian_;  // for sparse_jacobian, made at its first call
  mutable std::vector<std::shared_ptr<DistributedLinearization>> idle_;
};

/// Whether `value` is true on any rank of `communicator` (collective): stops and time budgets
/// that one rank notices become every rank's decision.
bool any_rank(bool value, MPI_Comm communicator);

}  // namespace tessera::petsc
