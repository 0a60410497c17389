// SPDX-License-Identifier: MIT
#include "tessera/petsc/distributed_problem.h"

#include <vector>

#include "tessera/core/error.h"
#include "tessera/core/linearization_backend.h"
#include "tessera/petsc/petsc_linearization.h"

namespace tessera::petsc {

DistributedSpace::DistributedSpace(MPI_Comm communicator, int dimension, int first_row,
                                   int local_rows)
    : AmbientSpace(dimension, first_row, local_rows, local_rows), communicator_(communicator) {
  MPI_Comm_size(communicator_, &ranks_);
}

void DistributedSpace::sum(double* values, int count) const {
  thread_local std::vector<double> gathered;
  gathered.resize(static_cast<std::size_t>(count) * static_cast<std::size_t>(ranks_));
  MPI_Allgather(values, count, MPI_DOUBLE, gathered.data(), count, MPI_DOUBLE, communicator_);
  for (int k = 0; k < count; ++k) {
    double total = 0.0;
    for (int rank = 0; rank < ranks_; ++rank) {
      total += gathered[static_cast<std::size_t>(rank) * count + k];
    }
    values[k] = total;
  }
}

double DistributedSpace::maximum(double value) const {
  double result = value;
  MPI_Allreduce(&value, &result, 1, MPI_DOUBLE, MPI_MAX, communicator_);  // exact: no rounding
  return result;
}

namespace {

// Linearization's backend for a DistributedProblem: DistributedLinearization on the placed
// local rows; the tangent basis is copied back into Eigen's local rows × 2.
class DistributedBackend final : public LinearizationBackend {
 public:
  explicit DistributedBackend(const PetscProblem& problem)
      : problem_(problem), linearization_(problem) {
    PetscInt rows = 0;
    Owned<Vec> layout = problem.create_vector();
    check(VecGetLocalSize(layout, &rows), "VecGetLocalSize");
    local_rows_ = static_cast<int>(rows);
    x_ = array_vector(problem.communicator(), local_rows_, problem.ambient_dimension());
    rhs_ = array_vector(problem.communicator(), local_rows_, problem.ambient_dimension());
    dx_ = array_vector(problem.communicator(), local_rows_, problem.ambient_dimension());
  }

  std::unique_ptr<LinearizationBackend> clone() const override {
    // A distributed factorisation is not copied: the copy factors again at its next use.
    return std::make_unique<DistributedBackend>(problem_);
  }

  bool factor(const ImplicitProblem& /*problem*/, const Eigen::Ref<const Eigen::VectorXd>& x,
              const Eigen::MatrixXd* reference, Eigen::MatrixXd& tangent,
              double& reciprocal_condition) override {
    const Eigen::VectorXd point = x;  // contiguous for VecPlaceArray
    TangentPair guide;
    if (reference != nullptr) {
      for (int c = 0; c < 2; ++c) {
        guide[static_cast<std::size_t>(c)] = problem_.create_vector();
        PetscScalar* values = nullptr;
        check(VecGetArray(guide[static_cast<std::size_t>(c)], &values), "VecGetArray");
        Eigen::Map<Eigen::VectorXd>(values, local_rows_) = reference->col(c);
        check(VecRestoreArray(guide[static_cast<std::size_t>(c)], &values), "VecRestoreArray");
      }
    }
    const long before = linearization_.factorisations();
    bool is_factored = false;
    {
      const PlacedArray placed(x_, point.data());
      is_factored = linearization_.factor(x_, reference != nullptr ? &guide : nullptr);
    }
    factorisations_ += linearization_.factorisations() - before;
    ++own_jacobian_evaluations_;
    if (!is_factored) {
      return false;
    }
    tangent.resize(local_rows_, 2);
    for (int c = 0; c < 2; ++c) {
      const PetscScalar* values = nullptr;
      Vec t = linearization_.tangent_basis()[static_cast<std::size_t>(c)];
      check(VecGetArrayRead(t, &values), "VecGetArrayRead");
      tangent.col(c) = Eigen::Map<const Eigen::VectorXd>(values, local_rows_);
      check(VecRestoreArrayRead(t, &values), "VecRestoreArrayRead");
    }
    reciprocal_condition = 1.0;  // the tangent's accuracy was checked against ‖DF‖ instead
    return true;
  }

  void solve(const Eigen::Ref<const Eigen::VectorXd>& rhs, const Eigen::MatrixXd& /*tangent*/,
             Eigen::Ref<Eigen::VectorXd> dx) const override {
    const Eigen::VectorXd right = rhs;
    Eigen::VectorXd solution(local_rows_);
    {
      const PlacedArray placed_rhs(rhs_, right.data());
      const PlacedArray placed_dx(dx_, solution.data());
      linearization_.solve_minimum_norm(rhs_, dx_);
    }
    dx = solution;
  }

  std::size_t memory_bytes() const override {
    return 0;  // MUMPS holds its factors; PETSc does not say how much (see docs/cluster.md)
  }

 private:
  const PetscProblem& problem_;
  DistributedLinearization linearization_;
  int local_rows_ = 0;
  Owned<Vec> x_;
  Owned<Vec> rhs_;
  Owned<Vec> dx_;
};

}  // namespace

DistributedProblem::DistributedProblem(const PetscProblem& problem) : problem_(problem) {
  Owned<Vec> layout = problem.create_vector();
  PetscInt first = 0;
  PetscInt end = 0;
  check(VecGetOwnershipRange(layout, &first, &end), "VecGetOwnershipRange");
  space_ = std::make_shared<DistributedSpace>(problem.communicator(),
                                              static_cast<int>(problem.ambient_dimension()),
                                              static_cast<int>(first), static_cast<int>(end - first));
  x_ = array_vector(problem.communicator(), space_->local_rows(), problem.ambient_dimension());
  F_ = array_vector(problem.communicator(), space_->local_rows(), problem.ambient_dimension());
}

void DistributedProblem::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                                  Eigen::Ref<Eigen::VectorXd> F) const {
  TESSERA_ASSERT(x.size() == space_->local_rows() && F.size() == space_->local_rows());
  const Eigen::VectorXd point = x;  // contiguous
  Eigen::VectorXd residual(space_->local_rows());
  {
    const PlacedArray placed_x(x_, point.data());
    const PlacedArray placed_F(F_, residual.data());
    problem_.evaluate(x_, F_);
  }
  F = residual;
}

void DistributedProblem::jacobian(const Eigen::Ref<const Eigen::VectorXd>& /*x*/,
                                  Eigen::Ref<Eigen::MatrixXd> /*J*/) const {
  throw InvalidArgument("problem '" + name() +
                        "' is distributed (PETSc): its Jacobian is not an Eigen matrix; "
                        "this method needs a serial problem");
}

void DistributedProblem::sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                                         Eigen::SparseMatrix<double>& /*J*/) const {
  Eigen::MatrixXd unused;
  jacobian(x, unused);
}

void DistributedProblem::jacobian_product(const Eigen::Ref<const Eigen::VectorXd>& y,
                                          const Eigen::Ref<const Eigen::MatrixXd>& V,
                                          Eigen::MatrixXd& JV,
                                          double& squared_frobenius_part) const {
  const int rows = space_->local_rows();
  TESSERA_ASSERT(y.size() == rows && V.rows() == rows);
  // A matrix of its own: PetscProblem::jacobian sets DF's rows only, so the border rows (n − 2,
  // n − 1) of a matrix no linearisation has bordered stay empty, and J·V is DF·V with 0 there.
  if (!jacobian_) {
    jacobian_ = problem_.create_jacobian();
  }
  const Eigen::VectorXd point = y;  // contiguous
  {
    const PlacedArray placed(x_, point.data());
    problem_.jacobian(x_, jacobian_);
  }
  PetscInt first = 0;
  PetscInt end = 0;
  check(MatGetOwnershipRange(jacobian_, &first, &end), "MatGetOwnershipRange");
  squared_frobenius_part = 0.0;
  for (PetscInt row = first; row < end; ++row) {
    PetscInt count = 0;
    const PetscScalar* values = nullptr;
    check(MatGetRow(jacobian_, row, &count, nullptr, &values), "MatGetRow");
    for (PetscInt k = 0; k < count; ++k) {
      squared_frobenius_part += values[k] * values[k];
    }
    check(MatRestoreRow(jacobian_, row, &count, nullptr, &values), "MatRestoreRow");
  }
  JV.resize(rows, V.cols());
  Eigen::VectorXd column(rows);
  Eigen::VectorXd product(rows);
  for (Eigen::Index c = 0; c < V.cols(); ++c) {
    column = V.col(c);
    {
      const PlacedArray placed_in(x_, column.data());
      const PlacedArray placed_out(F_, product.data());
      check(MatMult(jacobian_, x_, F_), "MatMult");
    }
    JV.col(c) = product;
  }
}

std::vector<CoordinateBlock> DistributedProblem::coordinate_blocks() const {
  return problem_.coordinate_blocks();
}

std::unique_ptr<LinearizationBackend> DistributedProblem::make_linearization_backend() const {
  return std::make_unique<DistributedBackend>(problem_);
}

}  // namespace tessera::petsc
