// SPDX-License-Identifier: MIT
#include "tessera/petsc/replicated_problem.h"

#include <algorithm>
#include <utility>

#include "tessera/core/bordered_jacobian.h"
#include "tessera/core/error.h"
#include "tessera/core/linearization_backend.h"
#include "tessera/petsc/petsc_linearization.h"

namespace tessera::petsc {

RowSplit::RowSplit(const PetscProblem& problem) : communicator_(problem.communicator()) {
  Owned<Vec> layout = problem.create_vector();
  PetscInt end = 0;
  check(VecGetOwnershipRange(layout, &first_, &end), "VecGetOwnershipRange");
  local_rows_ = end - first_;
  int ranks = 1;
  MPI_Comm_size(communicator_, &ranks);
  counts_.assign(static_cast<std::size_t>(ranks), 0);
  displacements_.assign(static_cast<std::size_t>(ranks), 0);
  const int mine = static_cast<int>(local_rows_);
  MPI_Allgather(&mine, 1, MPI_INT, counts_.data(), 1, MPI_INT, communicator_);
  for (std::size_t rank = 1; rank < counts_.size(); ++rank) {
    displacements_[rank] = displacements_[rank - 1] + counts_[rank - 1];
  }
}

void RowSplit::gather(const double* local, double* whole) const {
  MPI_Allgatherv(local, static_cast<int>(local_rows_), MPI_DOUBLE, whole, counts_.data(),
                 displacements_.data(), MPI_DOUBLE, communicator_);
}

void RowSplit::gather(Vec local, double* whole) const {
  const PetscScalar* values = nullptr;
  check(VecGetArrayRead(local, &values), "VecGetArrayRead");
  gather(values, whole);
  check(VecRestoreArrayRead(local, &values), "VecRestoreArrayRead");
}

bool any_rank(bool value, MPI_Comm communicator) {
  int local = value ? 1 : 0;
  int result = 0;
  MPI_Allreduce(&local, &result, 1, MPI_INT, MPI_LOR, communicator);
  return result != 0;
}

namespace {

// Linearization's backend for a ReplicatedProblem: DistributedLinearization on this rank's rows
// of the whole vectors it is given; tangent bases and solutions are gathered to every rank.
class ReplicatedBackend final : public LinearizationBackend {
 public:
  explicit ReplicatedBackend(const ReplicatedProblem& owner)
      : owner_(owner), linearization_(owner.take_linearization()) {
    make_array_vectors();
  }

  // A copy shares the factorisation (solves do not change it) until either factors again.
  ReplicatedBackend(const ReplicatedBackend& other)
      : LinearizationBackend(other),
        owner_(other.owner_),
        linearization_(other.linearization_),
        last_tangent_(other.last_tangent_) {
    make_array_vectors();
  }

  ~ReplicatedBackend() override {
    if (linearization_.use_count() == 1) {
      owner_.give_back(std::move(linearization_));
    }
  }
  ReplicatedBackend& operator=(const ReplicatedBackend&) = delete;

  std::unique_ptr<LinearizationBackend> clone() const override {
    return std::make_unique<ReplicatedBackend>(*this);
  }
  // As the serial sparse backend: a kept factorisation (release_assembly) is not copied. The
  // factors stay in MUMPS either way; what matters is that the covering takes the same steps
  // (a copy that is not factored is factored again by its user) as with the serial backend.
  bool clones_factorisation() const override { return !released_; }
  void release_assembly() override { released_ = true; }

  bool factor(const ImplicitProblem& /*problem*/, const Eigen::Ref<const Eigen::VectorXd>& x,
              const Eigen::MatrixXd* reference, Eigen::MatrixXd& tangent,
              double& reciprocal_condition) override {
    const PetscProblem& problem = owner_.petsc_problem();
    const RowSplit& rows = owner_.rows();
    TangentPair guide;
    if (reference != nullptr) {
      for (int c = 0; c < 2; ++c) {
        Owned<Vec>& column = guide[static_cast<std::size_t>(c)];
        column = problem.create_vector();
        PetscScalar* values = nullptr;
        check(VecGetArray(column, &values), "VecGetArray");
        Eigen::Map<Eigen::VectorXd>(values, rows.local_rows()) =
            reference->col(c).segment(rows.first(), rows.local_rows());
        check(VecRestoreArray(column, &values), "VecRestoreArray");
      }
    }
    released_ = false;
    if (linearization_.use_count() > 1) {
      linearization_ = owner_.take_linearization();  // the copies keep the shared one
    }
    const long before = linearization_->factorisations();
    bool is_factored = false;
    {
      const PlacedArray placed(x_, x.data() + rows.first());
      is_factored = linearization_->factor(x_, reference != nullptr ? &guide : nullptr);
    }
    factorisations_ += linearization_->factorisations() - before;
    ++own_jacobian_evaluations_;
    if (!is_factored) {
      return false;
    }
    tangent.resize(problem.ambient_dimension(), 2);
    for (int c = 0; c < 2; ++c) {
      rows.gather(linearization_->tangent_basis()[static_cast<std::size_t>(c)], tangent.col(c).data());
    }
    // The basis tessera's sparse backend would give (its border's), whatever border MUMPS
    // factored with: the covering draws in tangent coordinates.
    if (!coordinate_tangent_basis(tangent, reference, last_tangent_)) {
      return false;
    }
    reciprocal_condition = 1.0;  // the tangent's accuracy was checked against ‖DF‖ instead
    return true;
  }

  void solve(const Eigen::Ref<const Eigen::VectorXd>& rhs, const Eigen::MatrixXd& /*tangent*/,
             Eigen::Ref<Eigen::VectorXd> dx) const override {
    const RowSplit& rows = owner_.rows();
    const PetscInt equations = owner_.petsc_problem().ambient_dimension() - 2;
    // This rank's rows of the square system's right-hand side (rhs; 0, 0).
    right_.setZero(rows.local_rows());
    const PetscInt shared = std::max<PetscInt>(0, std::min(rows.local_rows(), equations - rows.first()));
    right_.head(shared) = rhs.segment(rows.first(), shared);
    solution_.resize(rows.local_rows());
    {
      const PlacedArray placed_rhs(rhs_, right_.data());
      const PlacedArray placed_dx(dx_, solution_.data());
      linearization_->solve_minimum_norm(rhs_, dx_);
    }
    rows.gather(solution_.data(), dx.data());
  }

  void solve_columns(const Eigen::Ref<const Eigen::MatrixXd>& rhs, const Eigen::MatrixXd& tangent,
                     Eigen::Ref<Eigen::MatrixXd> dx) const override {
    const Eigen::Index k = rhs.cols();
    if (k == 1) {
      solve(rhs.col(0), tangent, dx.col(0));
      return;
    }
    const RowSplit& rows = owner_.rows();
    const PetscProblem& problem = owner_.petsc_problem();
    const PetscInt equations = problem.ambient_dimension() - 2;
    right_columns_.setZero(rows.local_rows(), k);
    const PetscInt shared = std::max<PetscInt>(0, std::min(rows.local_rows(), equations - rows.first()));
    right_columns_.topRows(shared) = rhs.middleRows(rows.first(), shared);
    solution_columns_.resize(rows.local_rows(), k);
    Owned<Mat> B;
    Owned<Mat> X;
    check(MatCreateDense(problem.communicator(), rows.local_rows(), PETSC_DECIDE,
                         problem.ambient_dimension(), static_cast<PetscInt>(k),
                         right_columns_.data(), B.out()),
          "MatCreateDense");
    check(MatCreateDense(problem.communicator(), rows.local_rows(), PETSC_DECIDE,
                         problem.ambient_dimension(), static_cast<PetscInt>(k),
                         solution_columns_.data(), X.out()),
          "MatCreateDense");
    linearization_->solve_bordered_columns(B, X);
    for (Eigen::Index j = 0; j < k; ++j) {
      rows.gather(solution_columns_.col(j).data(), dx.col(j).data());
    }
    // Remove the ker-DF components: what remains are the minimum-norm solutions.
    dx -= tangent * (tangent.transpose() * dx);
  }

  std::size_t memory_bytes() const override { return linearization_->memory_bytes(); }

 private:
  void make_array_vectors() {
    const PetscProblem& problem = owner_.petsc_problem();
    const PetscInt rows = owner_.rows().local_rows();
    x_ = array_vector(problem.communicator(), rows, problem.ambient_dimension());
    rhs_ = array_vector(problem.communicator(), rows, problem.ambient_dimension());
    dx_ = array_vector(problem.communicator(), rows, problem.ambient_dimension());
  }

  const ReplicatedProblem& owner_;
  std::shared_ptr<DistributedLinearization> linearization_;
  Owned<Vec> x_;
  Owned<Vec> rhs_;
  Owned<Vec> dx_;
  Eigen::MatrixXd last_tangent_;      // guides the basis of the next factorisation
  bool released_ = false;             // release_assembly since the last factor
  mutable Eigen::VectorXd right_;     // scratch: this rank's rows of a right-hand side
  mutable Eigen::VectorXd solution_;  // and of its solution
  mutable Eigen::MatrixXd right_columns_;     // the same for several right-hand sides
  mutable Eigen::MatrixXd solution_columns_;
};

}  // namespace

ReplicatedProblem::ReplicatedProblem(const PetscProblem& problem,
                                     std::vector<std::string> coordinate_names)
    : problem_(problem), coordinate_names_(std::move(coordinate_names)), rows_(problem) {
  TESSERA_CHECK(coordinate_names_.empty() ||
                    coordinate_names_.size() == static_cast<std::size_t>(problem.ambient_dimension()),
                "ReplicatedProblem: " << coordinate_names_.size() << " coordinate names for n = "
                                      << problem.ambient_dimension());
  x_ = array_vector(problem.communicator(), rows_.local_rows(), problem.ambient_dimension());
  F_ = array_vector(problem.communicator(), rows_.local_rows(), problem.ambient_dimension());
}

ReplicatedProblem::~ReplicatedProblem() = default;

std::vector<std::string> ReplicatedProblem::coordinate_names() const {
  return coordinate_names_.empty() ? ImplicitProblem::coordinate_names() : coordinate_names_;
}

void ReplicatedProblem::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                                 Eigen::Ref<Eigen::VectorXd> F) const {
  const int n = ambient_dimension();
  TESSERA_ASSERT(x.size() == n && F.size() == n - 2);
  thread_local Eigen::VectorXd local;
  thread_local Eigen::VectorXd whole;
  local.resize(rows_.local_rows());
  whole.resize(n);
  {
    const PlacedArray placed_x(x_, x.data() + rows_.first());
    const PlacedArray placed_F(F_, local.data());
    problem_.evaluate(x_, F_);
  }
  rows_.gather(local.data(), whole.data());
  F = whole.head(n - 2);
}

void ReplicatedProblem::jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                                 Eigen::Ref<Eigen::MatrixXd> J) const {
  Eigen::SparseMatrix<double> sparse;
  sparse_jacobian(x, sparse);
  J = Eigen::MatrixXd(sparse);
}

void ReplicatedProblem::sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                                        Eigen::SparseMatrix<double>& J) const {
  const int n = ambient_dimension();
  if (!jacobian_) {
    jacobian_ = problem_.create_jacobian();
  }
  {
    const PlacedArray placed_x(x_, x.data() + rows_.first());
    problem_.jacobian(x_, jacobian_);
  }
  // This rank's rows of DF (not the border rows n − 2, n − 1), then everybody's.
  std::vector<PetscInt> rows;
  std::vector<PetscInt> columns;
  std::vector<double> values;
  const PetscInt end = std::min<PetscInt>(rows_.first() + rows_.local_rows(), n - 2);
  for (PetscInt row = rows_.first(); row < end; ++row) {
    PetscInt count = 0;
    const PetscInt* row_columns = nullptr;
    const PetscScalar* row_values = nullptr;
    check(MatGetRow(jacobian_, row, &count, &row_columns, &row_values), "MatGetRow");
    for (PetscInt k = 0; k < count; ++k) {
      rows.push_back(row);
      columns.push_back(row_columns[k]);
      values.push_back(row_values[k]);
    }
    check(MatRestoreRow(jacobian_, row, &count, &row_columns, &row_values), "MatRestoreRow");
  }
  const MPI_Comm communicator = problem_.communicator();
  int ranks = 1;
  MPI_Comm_size(communicator, &ranks);
  const int mine = static_cast<int>(rows.size());
  std::vector<int> counts(static_cast<std::size_t>(ranks));
  std::vector<int> displacements(static_cast<std::size_t>(ranks), 0);
  MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, communicator);
  for (std::size_t rank = 1; rank < counts.size(); ++rank) {
    displacements[rank] = displacements[rank - 1] + counts[rank - 1];
  }
  const int total = displacements.back() + counts.back();
  std::vector<PetscInt> all_rows(static_cast<std::size_t>(total));
  std::vector<PetscInt> all_columns(static_cast<std::size_t>(total));
  std::vector<double> all_values(static_cast<std::size_t>(total));
  MPI_Allgatherv(rows.data(), mine, MPIU_INT, all_rows.data(), counts.data(), displacements.data(),
                 MPIU_INT, communicator);
  MPI_Allgatherv(columns.data(), mine, MPIU_INT, all_columns.data(), counts.data(),
                 displacements.data(), MPIU_INT, communicator);
  MPI_Allgatherv(values.data(), mine, MPI_DOUBLE, all_values.data(), counts.data(),
                 displacements.data(), MPI_DOUBLE, communicator);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(total));
  for (int k = 0; k < total; ++k) {
    triplets.emplace_back(static_cast<int>(all_rows[static_cast<std::size_t>(k)]),
                          static_cast<int>(all_columns[static_cast<std::size_t>(k)]),
                          all_values[static_cast<std::size_t>(k)]);
  }
  J.resize(n - 2, n);
  J.setFromTriplets(triplets.begin(), triplets.end());
}

std::shared_ptr<DistributedLinearization> ReplicatedProblem::take_linearization() const {
  if (idle_.empty()) {
    return std::make_shared<DistributedLinearization>(problem_);
  }
  std::shared_ptr<DistributedLinearization> linearization = std::move(idle_.back());
  idle_.pop_back();
  return linearization;
}

void ReplicatedProblem::give_back(std::shared_ptr<DistributedLinearization> linearization) const {
  if (linearization && idle_.size() < kIdleLinearizations) {
    idle_.push_back(std::move(linearization));
  }
}

std::unique_ptr<LinearizationBackend> ReplicatedProblem::make_linearization_backend() const {
  return std::make_unique<ReplicatedBackend>(*this);
}

}  // namespace tessera::petsc
