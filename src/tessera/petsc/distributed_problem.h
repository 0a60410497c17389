// SPDX-License-Identifier: MIT
// A PETSc problem seen through tessera's ImplicitProblem interface, on the local rows of every
// rank: the covering code (SPMD, the same on every rank) and the correctors run on it unchanged,
// reducing through its AmbientSpace and factoring through its PETSc linearisation.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "tessera/core/ambient_space.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/core/jacobian_product.h"
#include "tessera/petsc/petsc_problem.h"

namespace tessera::petsc {

/// The ranks' split of R^n for a PETSc layout: each rank the contiguous rows PETSc gave it,
/// F in the same rows (the last two, the border rows, zero). Sums gather the ranks' partial
/// values and add them in rank order, so that every rank gets the same bits (an MPI_Allreduce
/// may add in a different order on different ranks) and the result does not depend on timing.
class DistributedSpace final : public AmbientSpace {
 public:
  DistributedSpace(MPI_Comm communicator, int dimension, int first_row, int local_rows);
  bool is_distributed() const override { return true; }
  void sum(double* values, int count) const override;
  double maximum(double value) const override;
  void maximum(double* values, int count) const override;
  bool is_root() const override { return rank_ == 0; }
  /// MPI_Gatherv of the ranks' blocks to rank 0, which puts each at the rank's first row.
  void gather_to_root(const double* local, int count, double* whole) const override;
  /// Calls of sum and maximum so far (each one collective call): the covering logic's
  /// communication, next to the solver's own.
  long reductions() const { return reductions_; }

 private:
  MPI_Comm communicator_;
  int rank_ = 0;
  int ranks_ = 1;
  mutable long reductions_ = 0;
};

/// An ImplicitProblem over the local rows of a PetscProblem (which must outlive it).
///
/// x is this rank's rows of a point (space()->local_rows() entries), F(x) its rows of the
/// residual (as many; the border rows are 0). Jacobians are never formed as Eigen matrices:
/// Linearization factors through make_linearization_backend (MUMPS by default), and
/// `jacobian`/`sparse_jacobian` throw. The metric's weights are the PetscProblem's business
/// (wrap it in a ScaledPetscProblem first): tessera's ScaledProblem refuses distributed problems.
class DistributedProblem final : public ImplicitProblem, public JacobianProduct {
 public:
  /// `coordinate_names`: one per coordinate (the serial problem's, for views and messages);
  /// empty: x0 … x{n−1}.
  explicit DistributedProblem(const PetscProblem& problem,
                              std::vector<std::string> coordinate_names = {});

  int ambient_dimension() const override { return static_cast<int>(problem_.ambient_dimension()); }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override;
  /// \throw InvalidArgument always: a distributed Jacobian is not an Eigen matrix.
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override;
  bool has_sparse_jacobian() const override { return true; }
  /// \throw InvalidArgument always: a distributed Jacobian is not an Eigen matrix.
  void sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                       Eigen::SparseMatrix<double>& J) const override;
  std::string name() const override { return problem_.name(); }
  std::vector<CoordinateBlock> coordinate_blocks() const override;
  std::vector<std::string> coordinate_names() const override;
  /// The PetscProblem's (none for a ScaledPetscProblem, as ScaledProblem forwards none).
  std::optional<Dynamics> dynamics() const override { return problem_.dynamics(); }
  std::shared_ptr<const AmbientSpace> space() const override { return space_; }
  std::unique_ptr<LinearizationBackend> make_linearization_backend() const override;

  const PetscProblem& petsc_problem() const { return problem_; }
  const JacobianProduct* as_jacobian_product() const override { return this; }
  /// The problem in its metric's coordinates, if set_metric_problem gave it.
  const ImplicitProblem* metric_problem() const override { return metric_problem_; }
  /// `scaled`: this problem in y = W x on the same split (a DistributedProblem over a
  /// ScaledPetscProblem of the same PetscProblem), which must outlive this one.
  void set_metric_problem(const ImplicitProblem* scaled) { metric_problem_ = scaled; }
  /// DF(y)·V by MatMult on PETSc's Jacobian (its border rows left empty), for
  /// tangent_basis_near: a split mesh's tangent planes from a neighbour's factorisation.
  double evaluate_jacobian_at(const Eigen::Ref<const Eigen::VectorXd>& y) const override;
  void multiply_jacobian(const Eigen::Ref<const Eigen::MatrixXd>& V,
                         Eigen::MatrixXd& JV) const override;

 private:
  const PetscProblem& problem_;
  std::vector<std::string> coordinate_names_;
  const ImplicitProblem* metric_problem_ = nullptr;
  std::shared_ptr<const DistributedSpace> space_;
  Owned<Vec> x_;  // wrappers of the caller's arrays (VecPlaceArray)
  Owned<Vec> F_;
  mutable Owned<Mat> jacobian_;  // for jacobian_product; made at its first use
};

}  // namespace tessera::petsc
