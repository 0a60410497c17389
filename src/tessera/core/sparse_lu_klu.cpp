// SPDX-License-Identifier: MIT
// SparseLu by SuiteSparse's KLU (block triangular form, AMD ordering of the blocks, left-looking
// Gilbert–Peierls LU with partial pivoting). Compiled only when CMake found KLU.
#ifdef TESSERA_HAS_KLU

#include <klu.h>

#include <cmath>

#include "tessera/core/detail/sparse_lu_implementations.h"

namespace tessera::detail {
namespace {

// KLU's refactorisation reuses the pivot sequence of the last full factorisation, which is fast
// but unsafe when the values have drifted far. A refactorisation whose crude reciprocal
// condition (min/max |U_kk|) falls below this fraction of the full factorisation's is redone
// with pivoting.
constexpr double kRefactorConditionDrop = 1e-3;

class KluSparseLu final : public SparseLu {
 public:
  KluSparseLu() {
    klu_defaults(&common_);
    common_.halt_if_singular = 1;
  }
  ~KluSparseLu() override { release(); }

  SparseLuSolver solver() const override { return SparseLuSolver::Klu; }

  std::optional<long> factor_nonzeros() const override {
    if (!is_factored()) {
      return std::nullopt;
    }
    return static_cast<long>(numeric_->lnz) + numeric_->unz + numeric_->nzoff;
  }

  std::optional<long> predicted_factor_nonzeros() const override {
    if (symbolic_ == nullptr) {
      return std::nullopt;
    }
    return static_cast<long>(symbolic_->lnz + symbolic_->unz) + symbolic_->nzoff;
  }

 protected:
  SparseLuStatus do_analyze(const Eigen::SparseMatrix<double>& A) override {
    release();
    // klu_analyze takes non-const pointers but does not modify the pattern.
    symbolic_ = klu_analyze(static_cast<int>(A.rows()), const_cast<int*>(A.outerIndexPtr()),
                            const_cast<int*>(A.innerIndexPtr()), &common_);
    if (symbolic_ == nullptr) {
      last_message_ = "KLU analysis failed, status " + std::to_string(common_.status);
      return common_.status == KLU_OUT_OF_MEMORY ? SparseLuStatus::OutOfMemory
                                                 : SparseLuStatus::Failed;
    }
    return SparseLuStatus::Success;
  }

  SparseLuStatus do_factorize(const Eigen::SparseMatrix<double>& A) override {
    int* outer = const_cast<int*>(A.outerIndexPtr());
    int* inner = const_cast<int*>(A.innerIndexPtr());
    double* values = const_cast<double*>(A.valuePtr());
    if (numeric_ != nullptr) {
      if (klu_refactor(outer, inner, values, symbolic_, numeric_, &common_) == 1 &&
          klu_rcond(symbolic_, numeric_, &common_) == 1 && std::isfinite(common_.rcond) &&
          common_.rcond >= kRefactorConditionDrop * full_factor_rcond_) {
        return SparseLuStatus::Success;
      }
      klu_free_numeric(&numeric_, &common_);
      numeric_ = nullptr;
    }
    numeric_ = klu_factor(outer, inner, values, symbolic_, &common_);
    if (numeric_ == nullptr) {
      if (common_.status == KLU_SINGULAR) {
        last_message_ = "KLU: matrix is singular (zero pivot in column " +
                        std::to_string(common_.singular_col) + ")";
        return SparseLuStatus::Singular;
      }
      last_message_ = "KLU factorisation failed, status " + std::to_string(common_.status);
      return common_.status == KLU_OUT_OF_MEMORY ? SparseLuStatus::OutOfMemory
                                                 : SparseLuStatus::Failed;
    }
    klu_rcond(symbolic_, numeric_, &common_);
    full_factor_rcond_ = common_.rcond;
    return SparseLuStatus::Success;
  }

  void do_solve_in_place(Eigen::Ref<Eigen::MatrixXd> X) const override {
    // klu_solve overwrites B (column-major, leading dimension ldim) with the solution.
    klu_solve(symbolic_, numeric_, static_cast<int>(X.outerStride()), static_cast<int>(X.cols()),
              X.data(), &common_);
  }

 private:
  void release() {
    if (numeric_ != nullptr) {
      klu_free_numeric(&numeric_, &common_);
      numeric_ = nullptr;
    }
    if (symbolic_ != nullptr) {
      klu_free_symbolic(&symbolic_, &common_);
      symbolic_ = nullptr;
    }
  }

  mutable klu_common common_;
  klu_symbolic* symbolic_ = nullptr;
  klu_numeric* numeric_ = nullptr;
  double full_factor_rcond_ = 0.0;
};

}  // namespace

std::unique_ptr<SparseLu> make_klu_sparse_lu() { return std::make_unique<KluSparseLu>(); }

}  // namespace tessera::detail

#endif  // TESSERA_HAS_KLU
