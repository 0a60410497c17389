// SPDX-License-Identifier: MIT
#include "tessera/petsc/distributed_problem.h"

#include <algorithm>
#include <vector>

#include "tessera/core/error.h"
#include "tessera/core/linearization_backend.h"
#include "tessera/petsc/petsc_linearization.h"

namespace tessera::petsc {

DistributedSpace::DistributedSpace(MPI_Comm communicator, int dimension, int first_row,
                                   int local_rows)
    : AmbientSpace(dimension, first_row, local_rows, local_rows), communicator_(communicator) {
  MPI_Comm_rank(communicator_, &rank_);
  MPI_Comm_size(communicator_, &ranks_);
}

void DistributedSpace::sum(double* values, int count) const {
  ++reductions_;
  thread_local std::vector<double> gathered;
  gathered.resize(static_cast<std::size_t>(count) * static_cast<std::size_t>(ranks_));
  MPI_Allgather(values, count, MPI_DOUBLE, gathered.data(), count, MPI_DOUBLE, communicator_);
  for (int k = 0; k < count; ++k) {
    // −0.0, the exact identity of floating addition (0.0 is not: 0.0 + −0.0 = 0.0): a value
    // held by one rank and summed with the others' −0.0 comes back bit for bit (a view's
    // coordinates of a split mesh).
    double total = -0.0;
    for (int rank = 0; rank < ranks_; ++rank) {
      total += gathered[static_cast<std::size_t>(rank) * count + k];
    }
    values[k] = total;
  }
}

double DistributedSpace::maximum(double value) const {
  ++reductions_;
  double result = value;
  MPI_Allreduce(&value, &result, 1, MPI_DOUBLE, MPI_MAX, communicator_);  // exact: no rounding
  return result;
}

void DistributedSpace::maximum(double* values, int count) const {
  ++reductions_;
  MPI_Allreduce(MPI_IN_PLACE, values, count, MPI_DOUBLE, MPI_MAX, communicator_);
}

void DistributedSpace::gather_to_root(const double* local, int count, double* whole) const {
  // Where each rank's rows go: its first row and its number of rows (any split, even empty).
  const int layout[2] = {first_row(), local_rows()};
  const auto ranks = static_cast<std::size_t>(ranks_);
  std::vector<int> layouts(is_root() ? 2 * ranks : 0);
  MPI_Gather(layout, 2, MPI_INT, layouts.data(), 2, MPI_INT, 0, communicator_);
  std::vector<int> counts(is_root() ? ranks : 0);
  std::vector<int> offsets(is_root() ? ranks : 0);
  thread_local std::vector<double> gathered;
  if (is_root()) {
    int offset = 0;
    for (std::size_t r = 0; r < ranks; ++r) {
      counts[r] = layouts[2 * r + 1] * count;
      offsets[r] = offset;
      offset += counts[r];
    }
    gathered.resize(static_cast<std::size_t>(offset));
  }
  MPI_Gatherv(local, local_rows() * count, MPI_DOUBLE, gathered.data(), counts.data(),
              offsets.data(), MPI_DOUBLE, 0, communicator_);
  if (!is_root()) {
    return;
  }
  // Rank r sent its rows of the `count` columns, column-major (rows × count).
  const auto n = static_cast<std::size_t>(dimension());
  for (std::size_t r = 0; r < ranks; ++r) {
    const auto first = static_cast<std::size_t>(layouts[2 * r]);
    const auto rows = static_cast<std::size_t>(layouts[2 * r + 1]);
    const double* block = gathered.data() + offsets[r];
    for (std::size_t column = 0; column < static_cast<std::size_t>(count); ++column) {
      std::copy_n(block + column * rows, rows, whole + column * n + first);
    }
  }
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
  // ...so a copied Linearization must not call itself factored (it did: the front's
  // continuation then solved with an empty factorisation).
  bool clones_factorisation() const override { return false; }

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

DistributedProblem::DistributedProblem(const PetscProblem& problem,
                                       std::vector<std::string> coordinate_names)
    : problem_(problem), coordinate_names_(std::move(coordinate_names)) {
  TESSERA_CHECK(coordinate_names_.empty() ||
                    coordinate_names_.size() == static_cast<std::size_t>(problem.ambient_dimension()),
                "DistributedProblem: " << coordinate_names_.size() << " coordinate names for n = "
                                       << problem.ambient_dimension());
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

double DistributedProblem::evaluate_jacobian_at(const Eigen::Ref<const Eigen::VectorXd>& y) const {
  const int rows = space_->local_rows();
  TESSERA_ASSERT(y.size() == rows);
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
  double squared_frobenius_part = 0.0;
  for (PetscInt row = first; row < end; ++row) {
    PetscInt count = 0;
    const PetscScalar* values = nullptr;
    check(MatGetRow(jacobian_, row, &count, nullptr, &values), "MatGetRow");
    for (PetscInt k = 0; k < count; ++k) {
      squared_frobenius_part += values[k] * values[k];
    }
    check(MatRestoreRow(jacobian_, row, &count, nullptr, &values), "MatRestoreRow");
  }
  return squared_frobenius_part;
}

void DistributedProblem::multiply_jacobian(const Eigen::Ref<const Eigen::MatrixXd>& V,
                                           Eigen::MatrixXd& JV) const {
  const int rows = space_->local_rows();
  TESSERA_ASSERT(jacobian_ && V.rows() == rows);
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

std::vector<std::string> DistributedProblem::coordinate_names() const {
  return coordinate_names_.empty() ? ImplicitProblem::coordinate_names() : coordinate_names_;
}

std::unique_ptr<LinearizationBackend> DistributedProblem::make_linearization_backend() const {
  return std::make_unique<DistributedBackend>(problem_);
}

}  // namespace tessera::petsc
