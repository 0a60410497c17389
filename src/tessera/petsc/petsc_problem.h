// SPDX-License-Identifier: MIT
// The problem interface of the PETSc backend: F: R^n → R^(n−2) and its Jacobian on distributed
// PETSc vectors and matrices, the counterpart of ImplicitProblem for n beyond one machine.
#pragma once

#include <petscmat.h>

#include <optional>
#include <string>
#include <vector>

#include "tessera/core/counted_problem.h"
#include "tessera/core/dynamics.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/petsc/petsc_support.h"

namespace tessera::petsc {

/// An implicitly defined surface M = {x ∈ R^n : F(x) = 0} whose vectors are distributed over the
/// ranks of a communicator.
///
/// Layout: x and the residual are PETSc vectors of global size n with the layout of
/// `create_vector` (each rank owns a contiguous range of rows). The residual is an n-vector:
/// entries 0 … n−3 are F(x), entries n−2 and n−1 are the two rows the linearisation borders F
/// with, and the problem sets them to 0. Likewise the Jacobian is an n×n parallel AIJ matrix
/// (`create_jacobian`): rows 0 … n−3 are DF(x), rows n−2 and n−1 belong to the linearisation.
/// Keeping one layout for x, F and the bordered matrix makes every solve square.
///
/// Implement the protected `compute_*` functions; callers use `evaluate` and `jacobian`, which
/// count the work (the currency of continuation at large n). All functions are collective.
class PetscProblem {
 public:
  virtual ~PetscProblem() = default;

  virtual MPI_Comm communicator() const = 0;
  /// n, the dimension of the ambient space.
  virtual PetscInt ambient_dimension() const = 0;
  /// A new vector with the problem's layout, entries unset.
  virtual Owned<Vec> create_vector() const = 0;
  /// A new n×n matrix with the layout of `create_vector`, preallocated for DF's pattern in rows
  /// 0 … n−3 and for at least one entry in each of rows n−2 and n−1.
  virtual Owned<Mat> create_jacobian() const = 0;

  /// F(x) into `F` (entries n−2, n−1 set to 0). Non-finite values mean "x is outside F's domain".
  void evaluate(Vec x, Vec F) const {
    ++counts_.function_evaluations;
    compute_residual(x, F);
  }
  /// DF(x) into rows 0 … n−3 of `J` (INSERT_VALUES), then assembles J. Rows n−2, n−1 are left
  /// as they are. \pre J came from create_jacobian.
  void jacobian(Vec x, Mat J) const {
    ++counts_.jacobian_evaluations;
    compute_jacobian(x, J);
  }

  /// Short identifier, e.g. "bratu2d".
  virtual std::string name() const { return "problem"; }
  /// Named coordinate ranges and their weights in the metric, as in ImplicitProblem.
  virtual std::vector<CoordinateBlock> coordinate_blocks() const { return {}; }
  /// The dynamics B·u' = ±F(u, p) whose steady states M is, as ImplicitProblem::dynamics (the
  /// mass matrix as an Eigen vector or matrix of n − 2 rows: each rank reads its rows). Nothing
  /// (the default): `mesh --stability` is refused.
  virtual std::optional<Dynamics> dynamics() const { return std::nullopt; }

  /// Evaluations of F and DF so far; factorisations are counted by the linearisation.
  const WorkCounts& counts() const { return counts_; }
  WorkCounts& counts() { return counts_; }

 protected:
  virtual void compute_residual(Vec x, Vec F) const = 0;
  virtual void compute_jacobian(Vec x, Mat J) const = 0;

 private:
  mutable WorkCounts counts_;
};

/// F̃(y) = F(W⁻¹ y), W = diag(weights from the inner problem's coordinate blocks): the problem in
/// the coordinates of its metric, like ScaledProblem, so that Euclidean lengths of y are the
/// problem's weighted lengths of x. The inner problem must outlive this one.
class ScaledPetscProblem final : public PetscProblem {
 public:
  /// \throw InvalidArgument if the inner problem's blocks are invalid (see metric_weights).
  explicit ScaledPetscProblem(const PetscProblem& inner);

  MPI_Comm communicator() const override { return inner_.communicator(); }
  PetscInt ambient_dimension() const override { return inner_.ambient_dimension(); }
  Owned<Vec> create_vector() const override { return inner_.create_vector(); }
  Owned<Mat> create_jacobian() const override { return inner_.create_jacobian(); }
  std::string name() const override { return inner_.name(); }
  /// The inner blocks with weight 1: in y the metric is Euclidean.
  std::vector<CoordinateBlock> coordinate_blocks() const override;

  /// y = W x and x = W⁻¹ y, in place.
  void to_scaled(Vec x) const;
  void from_scaled(Vec y) const;

 protected:
  void compute_residual(Vec y, Vec F) const override;
  void compute_jacobian(Vec y, Mat J) const override;

 private:
  const PetscProblem& inner_;
  Owned<Vec> weights_;          // W's diagonal
  Owned<Vec> inverse_weights_;  // W⁻¹'s diagonal
  Owned<Vec> unscaled_;         // scratch: x = W⁻¹ y
};

}  // namespace tessera::petsc
