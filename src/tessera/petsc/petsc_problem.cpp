// SPDX-License-Identifier: MIT
#include "tessera/petsc/petsc_problem.h"

#include <cmath>

#include "tessera/core/error.h"

namespace tessera::petsc {

ScaledPetscProblem::ScaledPetscProblem(const PetscProblem& inner) : inner_(inner) {
  weights_ = inner.create_vector();
  check(VecSet(weights_, 1.0), "VecSet");
  const PetscInt n = inner.ambient_dimension();
  PetscInt first = 0;
  PetscInt end = 0;
  check(VecGetOwnershipRange(weights_, &first, &end), "VecGetOwnershipRange");
  PetscScalar* w = nullptr;
  check(VecGetArray(weights_, &w), "VecGetArray");
  for (const CoordinateBlock& block : inner.coordinate_blocks()) {
    TESSERA_CHECK(block.first >= 0 && block.size >= 1 && block.first + block.size <= n,
                  "coordinate block '" << block.name << "' (" << block.first << " … "
                                       << block.first + block.size - 1 << ") lies outside 0 … "
                                       << n - 1);
    TESSERA_CHECK(std::isfinite(block.weight) && block.weight > 0.0,
                  "coordinate block '" << block.name << "' has weight " << block.weight
                                       << ", must be finite and > 0");
    for (PetscInt i = std::max<PetscInt>(first, block.first);
         i < std::min<PetscInt>(end, block.first + block.size); ++i) {
      w[i - first] = block.weight;
    }
  }
  check(VecRestoreArray(weights_, &w), "VecRestoreArray");
  check(VecDuplicate(weights_, inverse_weights_.out()), "VecDuplicate");
  check(VecCopy(weights_, inverse_weights_), "VecCopy");
  check(VecReciprocal(inverse_weights_), "VecReciprocal");
  check(VecDuplicate(weights_, unscaled_.out()), "VecDuplicate");
}

std::vector<CoordinateBlock> ScaledPetscProblem::coordinate_blocks() const {
  std::vector<CoordinateBlock> blocks = inner_.coordinate_blocks();
  for (CoordinateBlock& block : blocks) {
    block.weight = 1.0;
  }
  return blocks;
}

void ScaledPetscProblem::to_scaled(Vec x) const {
  check(VecPointwiseMult(x, x, weights_), "VecPointwiseMult");
}

void ScaledPetscProblem::from_scaled(Vec y) const {
  check(VecPointwiseMult(y, y, inverse_weights_), "VecPointwiseMult");
}

void ScaledPetscProblem::compute_residual(Vec y, Vec F) const {
  check(VecPointwiseMult(unscaled_, y, inverse_weights_), "VecPointwiseMult");
  inner_.evaluate(unscaled_, F);
}

void ScaledPetscProblem::compute_jacobian(Vec y, Mat J) const {
  check(VecPointwiseMult(unscaled_, y, inverse_weights_), "VecPointwiseMult");
  inner_.jacobian(unscaled_, J);
  // DF̃(y) = DF(x) W⁻¹: columns scaled. The border rows are scaled too; the linearisation sets
  // them afterwards.
  check(MatDiagonalScale(J, nullptr, inverse_weights_), "MatDiagonalScale");
}

}  // namespace tessera::petsc
