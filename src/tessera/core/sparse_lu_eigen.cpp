// SPDX-License-Identifier: MIT
// SparseLu by Eigen's SparseLU (supernodal, COLAMD column ordering, partial pivoting).
#include <Eigen/SparseLU>
#include <new>

#include "tessera/core/detail/sparse_lu_implementations.h"

namespace tessera::detail {
namespace {

class EigenSparseLu final : public SparseLu {
 public:
  SparseLuSolver solver() const override { return SparseLuSolver::Eigen; }

  std::optional<long> factor_nonzeros() const override {
    if (!is_factored()) {
      return std::nullopt;
    }
    return static_cast<long>(lu_.nnzL() + lu_.nnzU());
  }

 protected:
  SparseLuStatus do_analyze(const Eigen::SparseMatrix<double>& A) override {
    lu_.analyzePattern(A);
    return SparseLuStatus::Success;
  }

  SparseLuStatus do_factorize(const Eigen::SparseMatrix<double>& A) override {
    // Eigen's SparseLU does not throw when an allocation fails inside the factorisation (it can
    // crash in SparseLUImpl::expand; bench/RESULTS.md section 6), so OutOfMemory is only seen
    // when it reports it.
    try {
      lu_.factorize(A);
    } catch (const std::bad_alloc&) {
      last_message_ = "Eigen::SparseLU: out of memory";
      return SparseLuStatus::OutOfMemory;
    }
    if (lu_.info() == Eigen::Success) {
      return SparseLuStatus::Success;
    }
    last_message_ = "Eigen::SparseLU: " + lu_.lastErrorMessage();
    return lu_.info() == Eigen::NumericalIssue ? SparseLuStatus::Singular : SparseLuStatus::Failed;
  }

  void do_solve_in_place(Eigen::Ref<Eigen::MatrixXd> X) const override {
    // SparseLU's solve reads B after writing X, so it needs its own right-hand side.
    scratch_ = X;
    X = lu_.solve(scratch_);
  }

 private:
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu_;
  mutable Eigen::MatrixXd scratch_;
};

}  // namespace

std::unique_ptr<SparseLu> make_eigen_sparse_lu() { return std::make_unique<EigenSparseLu>(); }

}  // namespace tessera::detail
