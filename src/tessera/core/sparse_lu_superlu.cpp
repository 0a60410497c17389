// SPDX-License-Identifier: MIT
// SparseLu by SuperLU (supernodal LU, COLAMD ordering, row equilibration), through Eigen's
// SuperLUSupport. Compiled only when CMake found SuperLU.
#ifdef TESSERA_HAS_SUPERLU

#include <Eigen/SuperLUSupport>
#include <new>

#include "tessera/core/detail/sparse_lu_implementations.h"

namespace tessera::detail {
namespace {

// Eigen's wrapper keeps SuperLU's factors protected; they are needed only to count their
// nonzeros.
class CountingSuperLu : public Eigen::SuperLU<Eigen::SparseMatrix<double>> {
 public:
  long factor_nonzeros() const {
    if (m_sluL.Store == nullptr || m_sluU.Store == nullptr) {
      return -1;
    }
    return static_cast<long>(static_cast<const SCformat*>(m_sluL.Store)->nnz) +
           static_cast<const NCformat*>(m_sluU.Store)->nnz;
  }
};

class SuperLuSparseLu final : public SparseLu {
 public:
  SparseLuSolver solver() const override { return SparseLuSolver::SuperLu; }

  std::optional<long> factor_nonzeros() const override {
    if (!is_factored()) {
      return std::nullopt;
    }
    const long count = lu_.factor_nonzeros();
    return count >= 0 ? std::optional<long>(count) : std::nullopt;
  }

 protected:
  SparseLuStatus do_analyze(const Eigen::SparseMatrix<double>& A) override {
    lu_.analyzePattern(A);
    return SparseLuStatus::Success;
  }

  SparseLuStatus do_factorize(const Eigen::SparseMatrix<double>& A) override {
    try {
      lu_.factorize(A);
    } catch (const std::bad_alloc&) {
      last_message_ = "SuperLU: out of memory";
      return SparseLuStatus::OutOfMemory;
    }
    if (lu_.info() == Eigen::Success) {
      return SparseLuStatus::Success;
    }
    // SuperLU's info > 0 is either a zero pivot (info ≤ n) or a failed allocation (info > n);
    // Eigen reports both as NumericalIssue.
    last_message_ = "SuperLU: factorisation failed (zero pivot or out of memory)";
    return lu_.info() == Eigen::NumericalIssue ? SparseLuStatus::Singular : SparseLuStatus::Failed;
  }

  void do_solve_in_place(Eigen::Ref<Eigen::MatrixXd> X) const override {
    scratch_ = X;
    X = lu_.solve(scratch_);
  }

 private:
  CountingSuperLu lu_;
  mutable Eigen::MatrixXd scratch_;
};

}  // namespace

std::unique_ptr<SparseLu> make_superlu_sparse_lu() { return std::make_unique<SuperLuSparseLu>(); }

}  // namespace tessera::detail

#endif  // TESSERA_HAS_SUPERLU
