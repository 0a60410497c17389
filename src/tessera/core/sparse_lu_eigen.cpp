// SPDX-License-Identifier: MIT
// SparseLu by Eigen's SparseLU (supernodal, partial pivoting), with a nested-dissection column
// ordering where the build has METIS and COLAMD otherwise.
#include <Eigen/SparseLU>
#include <cstdlib>
#include <new>
#include <string_view>
#include <vector>

#include "tessera/core/detail/nested_dissection.h"
#include "tessera/core/detail/sparse_lu_implementations.h"

namespace tessera::detail {
namespace {

// Eigen's SparseLU reserves its L and U storage for 20× the nonzeros of A before it factors,
// and grows it by half when that is not enough. The bordered Jacobians of discretised PDEs fill
// far less (a 1-D problem about 2×, a 2-D one about 5–10×), and a covering keeps the
// factorisations of all its boundary charts: at n = 10³ the reserve was 2 MB per factorisation
// and half of the atlas's peak memory, and allocating and zeroing it a tenth of its time.
// Reserving 4× and letting the rare larger fill grow costs a few copies there instead.
constexpr int kReservedFill = 4;

// Eigen's ordering hook (default-constructed inside analyzePattern): nested dissection
// (detail/nested_dissection.h: half of COLAMD's fill on 2-D PDEs), COLAMD where METIS is absent
// or fails, or where TESSERA_SPARSE_LU_ORDERING=colamd asks for it (benchmarks compare the two).
struct FillReducingOrdering {
  using PermutationType = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;
  template <typename MatrixType>
  void operator()(const MatrixType& A, PermutationType& permutation) {
    const char* requested = std::getenv("TESSERA_SPARSE_LU_ORDERING");
    const bool wants_colamd = requested != nullptr && std::string_view(requested) == "colamd";
    const std::vector<int> order = wants_colamd ? std::vector<int>() : nested_dissection_ordering(A);
    if (order.empty()) {
      Eigen::COLAMDOrdering<int>()(A, permutation);
      return;
    }
    permutation.resize(static_cast<Eigen::Index>(order.size()));
    for (int k = 0; k < static_cast<int>(order.size()); ++k) {
      permutation.indices()(order[k]) = k;  // Eigen's convention: indices()(old) = new
    }
  }
};

class LeanSparseLU : public Eigen::SparseLU<Eigen::SparseMatrix<double>, FillReducingOrdering> {
 public:
  LeanSparseLU() { this->m_perfv.fillfactor = kReservedFill; }
};

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
    // crash in SparseLUImpl::expand; bench/history/RESULTS-log.md section 6), so OutOfMemory is
    // only seen when it reports it.
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
  LeanSparseLU lu_;
  mutable Eigen::MatrixXd scratch_;
};

}  // namespace

std::unique_ptr<SparseLu> make_eigen_sparse_lu() { return std::make_unique<EigenSparseLu>(); }

}  // namespace tessera::detail
