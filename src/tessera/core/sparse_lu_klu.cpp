// SPDX-License-Identifier: MIT
// SparseLu by SuiteSparse's KLU (block triangular form, AMD ordering of the blocks, left-looking
// Gilbert–Peierls LU with partial pivoting). Compiled only when CMake found KLU.
#ifdef TESSERA_HAS_KLU

#include <klu.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "tessera/core/detail/sparse_lu_implementations.h"

namespace tessera::detail {
namespace {

// KLU's refactorisation reuses the pivot sequence of the last full factorisation, which is fast
// but unsafe when the values have drifted far. A refactorisation whose crude reciprocal
// condition (min/max |U_kk|) falls below this fraction of the full factorisation's is redone
// with pivoting.
constexpr double kRefactorConditionDrop = 1e-3;

// The symbolic analysis (BTF, AMD ordering) depends on the pattern only, and the bordered
// Jacobians have a few patterns: J's, with its two border rows at the coordinates the reference
// tangent picks, which alternate between a few pairs as a covering moves. The analyses of the
// last few patterns analysed on this thread are kept and shared by every factorisation with one
// of them (AMD alone was 28% of a factorisation's time on bvp at n = 1002, and with one pattern
// kept, re-analysis after a change of border was 3% of a covering at n = 10⁴). KLU's factor,
// refactor and solve only read it.
struct SymbolicDeleter {
  void operator()(klu_symbolic* symbolic) const {
    klu_common common;
    klu_defaults(&common);
    klu_free_symbolic(&symbolic, &common);
  }
};
using SharedSymbolic = std::shared_ptr<klu_symbolic>;

struct AnalysedPattern {
  std::vector<int> outer;
  std::vector<int> inner;
  SharedSymbolic symbolic;

  bool matches(const Eigen::SparseMatrix<double>& A) const {
    const auto n = static_cast<std::size_t>(A.cols());
    const auto nnz = static_cast<std::size_t>(A.nonZeros());
    return symbolic != nullptr && outer.size() == n + 1 && inner.size() == nnz &&
           std::equal(outer.begin(), outer.end(), A.outerIndexPtr()) &&
           std::equal(inner.begin(), inner.end(), A.innerIndexPtr());
  }
};

constexpr std::size_t kKeptPatterns = 8;

// Most recently used first.
std::vector<AnalysedPattern>& analysed_patterns() {
  thread_local std::vector<AnalysedPattern> patterns;
  return patterns;
}

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

  std::optional<std::size_t> factorisation_bytes() const override {
    if (!is_factored()) {
      return std::nullopt;
    }
    // klu_numeric's arrays: six of n ints (Pnum, Pinv, Lip, Uip, Llen, Ulen), two of n doubles
    // (Udiag, Rs), the off-diagonal blocks, the factors (LUsize in Units of a double) and the
    // permanent workspace, which alone is about as large as the factors of a banded matrix.
    const klu_numeric& numeric = *numeric_;
    const auto n = static_cast<std::size_t>(numeric.n);
    std::size_t bytes = numeric.worksize + n * (6 * sizeof(int) + 2 * sizeof(double)) +
                        (n + 1) * sizeof(int) +
                        static_cast<std::size_t>(numeric.nzoff) * (sizeof(int) + sizeof(double));
    for (int block = 0; block < numeric.nblocks; ++block) {
      // A singleton block has no LUbx (null) and its LUsize is never written.
      if (numeric.LUbx[block] != nullptr) {
        bytes += numeric.LUsize[block] * sizeof(double);
      }
    }
    return bytes;
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
    std::vector<AnalysedPattern>& patterns = analysed_patterns();
    for (std::size_t k = 0; k < patterns.size(); ++k) {
      if (patterns[k].matches(A)) {
        std::rotate(patterns.begin(), patterns.begin() + static_cast<std::ptrdiff_t>(k),
                    patterns.begin() + static_cast<std::ptrdiff_t>(k) + 1);
        symbolic_ = patterns.front().symbolic;
        return SparseLuStatus::Success;
      }
    }
    // klu_analyze takes non-const pointers but does not modify the pattern.
    klu_symbolic* symbolic = klu_analyze(static_cast<int>(A.rows()),
                                         const_cast<int*>(A.outerIndexPtr()),
                                         const_cast<int*>(A.innerIndexPtr()), &common_);
    if (symbolic == nullptr) {
      last_message_ = "KLU analysis failed, status " + std::to_string(common_.status);
      return common_.status == KLU_OUT_OF_MEMORY ? SparseLuStatus::OutOfMemory
                                                 : SparseLuStatus::Failed;
    }
    symbolic_ = SharedSymbolic(symbolic, SymbolicDeleter());
    if (patterns.size() == kKeptPatterns) {
      patterns.pop_back();
    }
    AnalysedPattern analysed;
    analysed.outer.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.cols() + 1);
    analysed.inner.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
    analysed.symbolic = symbolic_;
    patterns.insert(patterns.begin(), std::move(analysed));
    return SparseLuStatus::Success;
  }

  SparseLuStatus do_factorize(const Eigen::SparseMatrix<double>& A) override {
    int* outer = const_cast<int*>(A.outerIndexPtr());
    int* inner = const_cast<int*>(A.innerIndexPtr());
    double* values = const_cast<double*>(A.valuePtr());
    if (numeric_ != nullptr && FullPivotingScope::is_active()) {
      klu_free_numeric(&numeric_, &common_);
      numeric_ = nullptr;
    }
    if (numeric_ != nullptr) {
      if (klu_refactor(outer, inner, values, symbolic_.get(), numeric_, &common_) == 1 &&
          klu_rcond(symbolic_.get(), numeric_, &common_) == 1 && std::isfinite(common_.rcond) &&
          common_.rcond >= kRefactorConditionDrop * full_factor_rcond_) {
        return SparseLuStatus::Success;
      }
      klu_free_numeric(&numeric_, &common_);
      numeric_ = nullptr;
    }
    numeric_ = klu_factor(outer, inner, values, symbolic_.get(), &common_);
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
    klu_rcond(symbolic_.get(), numeric_, &common_);
    full_factor_rcond_ = common_.rcond;
    return SparseLuStatus::Success;
  }

  void do_solve_in_place(Eigen::Ref<Eigen::MatrixXd> X) const override {
    // klu_solve overwrites B (column-major, leading dimension ldim) with the solution.
    klu_solve(symbolic_.get(), numeric_, static_cast<int>(X.outerStride()),
              static_cast<int>(X.cols()), X.data(), &common_);
  }

 private:
  void release() {
    if (numeric_ != nullptr) {
      klu_free_numeric(&numeric_, &common_);
      numeric_ = nullptr;
    }
    symbolic_.reset();
  }

  mutable klu_common common_;
  SharedSymbolic symbolic_;  // shared with the other factorisations of the same pattern
  klu_numeric* numeric_ = nullptr;
  double full_factor_rcond_ = 0.0;
};

}  // namespace

std::unique_ptr<SparseLu> make_klu_sparse_lu() { return std::make_unique<KluSparseLu>(); }

}  // namespace tessera::detail

#endif  // TESSERA_HAS_KLU
