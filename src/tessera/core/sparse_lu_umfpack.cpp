// SPDX-License-Identifier: MIT
// SparseLu by SuiteSparse's UMFPACK (unsymmetric multifrontal LU; AMD/COLAMD ordering, dense
// frontal matrices factored with BLAS-3). Compiled only when CMake found UMFPACK.
#ifdef TESSERA_HAS_UMFPACK

#include <umfpack.h>

#include <vector>

#include "tessera/core/detail/sparse_lu_implementations.h"

namespace tessera::detail {
namespace {

SparseLuStatus status_of(int code) {
  if (code == UMFPACK_OK) {
    return SparseLuStatus::Success;
  }
  if (code == UMFPACK_WARNING_singular_matrix) {
    return SparseLuStatus::Singular;
  }
  if (code == UMFPACK_ERROR_out_of_memory) {
    return SparseLuStatus::OutOfMemory;
  }
  return SparseLuStatus::Failed;
}

class UmfpackSparseLu final : public SparseLu {
 public:
  UmfpackSparseLu() {
    umfpack_di_defaults(control_);
    // No iterative refinement: tessera's callers are Newton iterations that correct anyway, and
    // each refinement step costs a solve and a product with A (the default allows two).
    control_[UMFPACK_IRSTEP] = 0;
  }
  ~UmfpackSparseLu() override { release(); }

  SparseLuSolver solver() const override { return SparseLuSolver::Umfpack; }

  std::optional<long> factor_nonzeros() const override {
    if (!is_factored()) {
      return std::nullopt;
    }
    int lnz = 0, unz = 0, rows = 0, columns = 0, diagonal = 0;
    if (umfpack_di_get_lunz(&lnz, &unz, &rows, &columns, &diagonal, numeric_) != UMFPACK_OK) {
      return std::nullopt;
    }
    return static_cast<long>(lnz) + unz;
  }

 protected:
  SparseLuStatus do_analyze(const Eigen::SparseMatrix<double>& A) override {
    release();
    const int n = static_cast<int>(A.rows());
    const int code = umfpack_di_symbolic(n, n, A.outerIndexPtr(), A.innerIndexPtr(), A.valuePtr(),
                                         &symbolic_, control_, info_);
    if (code != UMFPACK_OK) {
      symbolic_ = nullptr;
      last_message_ = "UMFPACK symbolic analysis failed, status " + std::to_string(code);
      return status_of(code);
    }
    work_.resize(5 * static_cast<std::size_t>(n));
    work_indices_.resize(static_cast<std::size_t>(n));
    column_.resize(static_cast<std::size_t>(n));
    return SparseLuStatus::Success;
  }

  SparseLuStatus do_factorize(const Eigen::SparseMatrix<double>& A) override {
    if (numeric_ != nullptr) {
      umfpack_di_free_numeric(&numeric_);
      numeric_ = nullptr;
    }
    const int code = umfpack_di_numeric(A.outerIndexPtr(), A.innerIndexPtr(), A.valuePtr(),
                                        symbolic_, &numeric_, control_, info_);
    if (code == UMFPACK_OK) {
      return SparseLuStatus::Success;
    }
    // A singular matrix still has a Numeric object (with a zero pivot); it is of no use here.
    if (numeric_ != nullptr) {
      umfpack_di_free_numeric(&numeric_);
      numeric_ = nullptr;
    }
    last_message_ = code == UMFPACK_WARNING_singular_matrix
                        ? std::string("UMFPACK: matrix is singular (zero pivot)")
                        : "UMFPACK numeric factorisation failed, status " + std::to_string(code);
    return status_of(code);
  }

  void do_solve_in_place(Eigen::Ref<Eigen::MatrixXd> X) const override {
    // wsolve with preallocated workspace: no allocation per solve. A is not needed without
    // iterative refinement.
    for (Eigen::Index k = 0; k < X.cols(); ++k) {
      Eigen::Map<Eigen::VectorXd>(column_.data(), X.rows()) = X.col(k);
      umfpack_di_wsolve(UMFPACK_A, nullptr, nullptr, nullptr, X.col(k).data(), column_.data(),
                        numeric_, control_, info_, work_indices_.data(), work_.data());
    }
  }

 private:
  void release() {
    if (numeric_ != nullptr) {
      umfpack_di_free_numeric(&numeric_);
      numeric_ = nullptr;
    }
    if (symbolic_ != nullptr) {
      umfpack_di_free_symbolic(&symbolic_);
      symbolic_ = nullptr;
    }
  }

  double control_[UMFPACK_CONTROL];
  mutable double info_[UMFPACK_INFO];
  void* symbolic_ = nullptr;
  void* numeric_ = nullptr;
  mutable std::vector<double> work_;       // 5n, umfpack_di_wsolve's W
  mutable std::vector<int> work_indices_;  // n, its Wi
  mutable std::vector<double> column_;     // one right-hand side
};

}  // namespace

std::unique_ptr<SparseLu> make_umfpack_sparse_lu() { return std::make_unique<UmfpackSparseLu>(); }

}  // namespace tessera::detail

#endif  // TESSERA_HAS_UMFPACK
