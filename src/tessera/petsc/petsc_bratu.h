// SPDX-License-Identifier: MIT
// The catalogue's Arrhenius–Bratu problems (bvp and bratu2d) on distributed PETSc vectors.
#pragma once

#include "tessera/petsc/petsc_problem.h"

namespace tessera::petsc {

/// u'' + λ exp(u / (1 + ε u)) = 0 on (0, 1) (`spatial_dimension` 1, the catalogue's `bvp`, N
/// interior points) or Δu + λ exp(u / (1 + ε u)) = 0 on (0, 1)² (2, `bratu2d`, an N×N grid),
/// u = 0 on the boundary: the same equations, coordinates, scaling by h² and metric blocks as
/// tessera::ArrheniusBratu and tessera::ArrheniusBratu2D, so that the two backends describe the
/// same M (tests/petsc compares them entry by entry).
///
/// Distribution: PETSc's default split of the n = m + 2 rows (m = N or N² grid values) into
/// contiguous ranges; the last rank also owns λ and ε. A rank needs the grid values one row of
/// the stencil (1 or N entries) beyond its range, and λ and ε: one scatter per evaluation.
class PetscArrheniusBratu final : public PetscProblem {
 public:
  /// \throw InvalidArgument unless spatial_dimension is 1 or 2 and 1 ≤ grid_size (≤ 10⁷ in 1-D,
  ///        ≤ 10⁴ in 2-D, so that n fits PETSc's 32-bit indices).
  PetscArrheniusBratu(MPI_Comm communicator, int spatial_dimension, PetscInt grid_size);

  MPI_Comm communicator() const override { return communicator_; }
  PetscInt ambient_dimension() const override { return grid_values_ + 2; }
  Owned<Vec> create_vector() const override;
  Owned<Mat> create_jacobian() const override;
  std::string name() const override { return spatial_dimension_ == 1 ? "bvp" : "bratu2d"; }
  /// One block "u" of weight √h (1-D) or h (2-D), as the serial problems.
  std::vector<CoordinateBlock> coordinate_blocks() const override;
  /// The serial problems' dynamics: parameters λ, ε (the last two coordinates), sign +1,
  /// B = h²·I.
  std::optional<Dynamics> dynamics() const override;

  int spatial_dimension() const { return spatial_dimension_; }
  PetscInt grid_size() const { return grid_size_; }

 protected:
  void compute_residual(Vec x, Vec F) const override;
  void compute_jacobian(Vec x, Mat J) const override;

 private:
  // The grid values this rank needs, scattered from x: [ghost_first_, ghost_end_) of u, then λ, ε.
  void gather_neighbourhood(Vec x) const;
  double neighbour(PetscInt index) const;  // u at a global grid index, 0 outside the grid

  MPI_Comm communicator_;
  int spatial_dimension_;
  PetscInt grid_size_;
  PetscInt grid_values_;  // m = N or N²
  double h2_;             // h² = 1/(N + 1)²
  PetscInt first_ = 0;    // this rank's rows [first_, end_)
  PetscInt end_ = 0;
  PetscInt ghost_first_ = 0;  // grid values [ghost_first_, ghost_end_) are in local_
  PetscInt ghost_end_ = 0;
  Owned<Vec> layout_;
  Owned<Vec> local_;  // sequential: the neighbourhood, then λ, ε
  Owned<VecScatter> to_local_;
};

}  // namespace tessera::petsc
