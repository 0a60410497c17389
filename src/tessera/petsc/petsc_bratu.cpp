// SPDX-License-Identifier: MIT
#include "tessera/petsc/petsc_bratu.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "tessera/core/error.h"
#include "tessera/problems/detail/arrhenius.h"

namespace tessera::petsc {

using detail::Arrhenius;
using detail::arrhenius;

PetscArrheniusBratu::PetscArrheniusBratu(MPI_Comm communicator, int spatial_dimension,
                                         PetscInt grid_size)
    : communicator_(communicator), spatial_dimension_(spatial_dimension), grid_size_(grid_size) {
  TESSERA_CHECK(spatial_dimension == 1 || spatial_dimension == 2,
                "PetscArrheniusBratu: spatial_dimension = " << spatial_dimension
                                                            << " must be 1 or 2");
  const PetscInt max_grid = spatial_dimension == 1 ? 10'000'000 : 10'000;
  TESSERA_CHECK(grid_size >= 1 && grid_size <= max_grid,
                "PetscArrheniusBratu: grid size N = " << grid_size << " must be in [1, " << max_grid
                                                      << "] for dimension " << spatial_dimension);
  grid_values_ = spatial_dimension == 1 ? grid_size : grid_size * grid_size;
  const double h = 1.0 / (static_cast<double>(grid_size) + 1.0);
  h2_ = h * h;

  check(VecCreate(communicator_, layout_.out()), "VecCreate");
  check(VecSetSizes(layout_, PETSC_DECIDE, grid_values_ + 2), "VecSetSizes");
  check(VecSetType(layout_, VECMPI), "VecSetType");
  check(VecGetOwnershipRange(layout_, &first_, &end_), "VecGetOwnershipRange");

  // The neighbourhood: the stencil reaches `reach` grid values beyond the rank's rows.
  const PetscInt reach = spatial_dimension == 1 ? 1 : grid_size;
  const PetscInt last_grid_row = std::min(end_, grid_values_);
  ghost_first_ = std::max<PetscInt>(0, std::min(first_, last_grid_row) - reach);
  ghost_end_ = std::min(grid_values_, last_grid_row + reach);
  if (first_ >= grid_values_) {
    ghost_first_ = ghost_end_ = 0;  // only border rows here: no grid values needed
  }
  std::vector<PetscInt> indices(static_cast<std::size_t>(ghost_end_ - ghost_first_));
  std::iota(indices.begin(), indices.end(), ghost_first_);
  indices.push_back(grid_values_);      // λ
  indices.push_back(grid_values_ + 1);  // ε
  const PetscInt count = static_cast<PetscInt>(indices.size());
  IS from = nullptr;
  check(ISCreateGeneral(PETSC_COMM_SELF, count, indices.data(), PETSC_COPY_VALUES, &from),
        "ISCreateGeneral");
  check(VecCreateSeq(PETSC_COMM_SELF, count, local_.out()), "VecCreateSeq");
  const PetscErrorCode code = VecScatterCreate(layout_, from, local_, nullptr, to_local_.out());
  ISDestroy(&from);
  check(code, "VecScatterCreate");
}

Owned<Vec> PetscArrheniusBratu::create_vector() const {
  Owned<Vec> x;
  check(VecDuplicate(layout_, x.out()), "VecDuplicate");
  return x;
}

Owned<Mat> PetscArrheniusBratu::create_jacobian() const {
  const PetscInt n = grid_values_ + 2;
  const PetscInt rows = end_ - first_;
  // Per row: the stencil (3 or 5) in or near the diagonal block, λ and ε (owned by the last
  // rank). Counted exactly for the diagonal block would save little; this bounds both blocks.
  std::vector<PetscInt> diagonal(static_cast<std::size_t>(rows));
  std::vector<PetscInt> off_diagonal(static_cast<std::size_t>(rows));
  const PetscInt stencil = spatial_dimension_ == 1 ? 3 : 5;
  for (PetscInt row = first_; row < end_; ++row) {
    const auto k = static_cast<std::size_t>(row - first_);
    if (row < grid_values_) {
      diagonal[k] = std::min(rows, stencil + 2);
      off_diagonal[k] = std::min(n - rows, stencil + 2);
    } else {
      diagonal[k] = std::min<PetscInt>(rows, 2);  // a border row: its entries
      off_diagonal[k] = std::min<PetscInt>(n - rows, 2);
    }
  }
  Owned<Mat> J;
  check(MatCreate(communicator_, J.out()), "MatCreate");
  check(MatSetSizes(J, rows, rows, n, n), "MatSetSizes");
  check(MatSetType(J, MATAIJ), "MatSetType");
  check(MatSeqAIJSetPreallocation(J, 0, diagonal.data()), "MatSeqAIJSetPreallocation");
  check(MatMPIAIJSetPreallocation(J, 0, diagonal.data(), 0, off_diagonal.data()),
        "MatMPIAIJSetPreallocation");
  // The border rows' columns are chosen later (from the tangent) and may move.
  check(MatSetOption(J, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE), "MatSetOption");
  return J;
}

std::vector<CoordinateBlock> PetscArrheniusBratu::coordinate_blocks() const {
  const double h = 1.0 / (static_cast<double>(grid_size_) + 1.0);
  return {{"u", 0, static_cast<int>(grid_values_), spatial_dimension_ == 1 ? std::sqrt(h) : h}};
}

std::optional<Dynamics> PetscArrheniusBratu::dynamics() const {
  Dynamics dynamics;
  const auto m = static_cast<int>(grid_values_);
  dynamics.parameters = {m, m + 1};
  dynamics.mass_diagonal = Eigen::VectorXd::Constant(m, h2_);
  return dynamics;
}

void PetscArrheniusBratu::gather_neighbourhood(Vec x) const {
  check(VecScatterBegin(to_local_, x, local_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
  check(VecScatterEnd(to_local_, x, local_, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
}

void PetscArrheniusBratu::compute_residual(Vec x, Vec F) const {
  gather_neighbourhood(x);
  const PetscScalar* u = nullptr;
  check(VecGetArrayRead(local_, &u), "VecGetArrayRead");
  const PetscInt ghosts = ghost_end_ - ghost_first_;
  const double lambda = u[ghosts];
  const double epsilon = u[ghosts + 1];
  const auto value = [&](PetscInt i) { return u[i - ghost_first_]; };
  PetscScalar* f = nullptr;
  check(VecGetArray(F, &f), "VecGetArray");
  const PetscInt N = grid_size_;
  for (PetscInt row = first_; row < end_; ++row) {
    if (row >= grid_values_) {
      f[row - first_] = 0.0;  // the border rows
      continue;
    }
    double neighbours = 0.0;
    double centre_weight = 2.0;
    if (spatial_dimension_ == 1) {
      neighbours = (row > 0 ? value(row - 1) : 0.0) + (row + 1 < N ? value(row + 1) : 0.0);
    } else {
      const PetscInt i = row / N;
      const PetscInt j = row % N;
      neighbours = (i > 0 ? value(row - N) : 0.0) + (i + 1 < N ? value(row + N) : 0.0) +
                   (j > 0 ? value(row - 1) : 0.0) + (j + 1 < N ? value(row + 1) : 0.0);
      centre_weight = 4.0;
    }
    const double centre = value(row);
    f[row - first_] = neighbours - centre_weight * centre +
                      h2_ * lambda * std::exp(centre / (1.0 + epsilon * centre));
  }
  check(VecRestoreArray(F, &f), "VecRestoreArray");
  check(VecRestoreArrayRead(local_, &u), "VecRestoreArrayRead");
}

void PetscArrheniusBratu::compute_jacobian(Vec x, Mat J) const {
  gather_neighbourhood(x);
  const PetscScalar* u = nullptr;
  check(VecGetArrayRead(local_, &u), "VecGetArrayRead");
  const PetscInt ghosts = ghost_end_ - ghost_first_;
  const double lambda = u[ghosts];
  const double epsilon = u[ghosts + 1];
  const PetscInt N = grid_size_;
  const PetscInt m = grid_values_;
  PetscInt columns[7];
  PetscScalar values[7];
  for (PetscInt row = first_; row < std::min(end_, m); ++row) {
    const Arrhenius term = arrhenius(u[row - ghost_first_], epsilon);
    int k = 0;
    const auto add = [&](PetscInt column, double value) {
      columns[k] = column;
      values[k++] = value;
    };
    if (spatial_dimension_ == 1) {
      if (row > 0) add(row - 1, 1.0);
      add(row, -2.0 + h2_ * lambda * term.derivative_u);
      if (row + 1 < N) add(row + 1, 1.0);
    } else {
      const PetscInt i = row / N;
      const PetscInt j = row % N;
      if (i > 0) add(row - N, 1.0);
      if (j > 0) add(row - 1, 1.0);
      add(row, -4.0 + h2_ * lambda * term.derivative_u);
      if (j + 1 < N) add(row + 1, 1.0);
      if (i + 1 < N) add(row + N, 1.0);
    }
    add(m, h2_ * term.value);
    add(m + 1, h2_ * lambda * term.derivative_epsilon);
    check(MatSetValues(J, 1, &row, k, columns, values, INSERT_VALUES), "MatSetValues");
  }
  check(VecRestoreArrayRead(local_, &u), "VecRestoreArrayRead");
  check(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
}

}  // namespace tessera::petsc
