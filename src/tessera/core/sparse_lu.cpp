// SPDX-License-Identifier: MIT
#include "tessera/core/sparse_lu.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <mutex>
#include <sstream>

#include "tessera/core/detail/sparse_lu_implementations.h"
#include "tessera/core/error.h"

namespace tessera {
namespace {

std::string available_names() {
  std::ostringstream out;
  const auto solvers = available_sparse_lu_solvers();
  for (std::size_t k = 0; k < solvers.size(); ++k) {
    out << (k ? ", " : "") << name(solvers[k]);
  }
  return out.str();
}

}  // namespace

const std::vector<SparseLuSolver>& all_sparse_lu_solvers() {
  static const std::vector<SparseLuSolver> solvers = {
      SparseLuSolver::Eigen, SparseLuSolver::Umfpack, SparseLuSolver::Klu, SparseLuSolver::SuperLu};
  return solvers;
}

bool is_available(SparseLuSolver solver) {
  switch (solver) {
    case SparseLuSolver::Eigen:
      return true;
    case SparseLuSolver::Umfpack:
#ifdef TESSERA_HAS_UMFPACK
      return true;
#else
      return false;
#endif
    case SparseLuSolver::Klu:
#ifdef TESSERA_HAS_KLU
      return true;
#else
      return false;
#endif
    case SparseLuSolver::SuperLu:
#ifdef TESSERA_HAS_SUPERLU
      return true;
#else
      return false;
#endif
  }
  return false;
}

std::vector<SparseLuSolver> available_sparse_lu_solvers() {
  std::vector<SparseLuSolver> solvers;
  for (SparseLuSolver solver : all_sparse_lu_solvers()) {
    if (is_available(solver)) {
      solvers.push_back(solver);
    }
  }
  return solvers;
}

std::string_view name(SparseLuSolver solver) {
  switch (solver) {
    case SparseLuSolver::Eigen:
      return "eigen";
    case SparseLuSolver::Umfpack:
      return "umfpack";
    case SparseLuSolver::Klu:
      return "klu";
    case SparseLuSolver::SuperLu:
      return "superlu";
  }
  return "unknown";
}

std::optional<SparseLuSolver> sparse_lu_solver_named(std::string_view solver_name) {
  for (SparseLuSolver solver : all_sparse_lu_solvers()) {
    if (name(solver) == solver_name) {
      return solver;
    }
  }
  return std::nullopt;
}

SparseLuSolver default_sparse_lu_solver() {
  const char* requested = std::getenv("TESSERA_SPARSE_LU");
  if (requested != nullptr && *requested != '\0') {
    const auto solver = sparse_lu_solver_named(requested);
    TESSERA_CHECK(solver.has_value(), "TESSERA_SPARSE_LU = '"
                                          << requested << "' names no sparse LU solver; this "
                                          << "build has: " << available_names());
    TESSERA_CHECK(is_available(*solver),
                  "TESSERA_SPARSE_LU = '"
                      << requested << "': this build has no " << requested
                      << " (configure found no library for it); it has: " << available_names());
    return *solver;
  }
  return SparseLuSolver::Eigen;
}

namespace {
thread_local bool full_pivoting = false;
}  // namespace

FullPivotingScope::FullPivotingScope() : previous_(full_pivoting) { full_pivoting = true; }
FullPivotingScope::~FullPivotingScope() { full_pivoting = previous_; }
bool FullPivotingScope::is_active() { return full_pivoting; }

SparseLuSolver sparse_lu_solver_for(const Eigen::SparseMatrix<double>& A) {
  const char* requested = std::getenv("TESSERA_SPARSE_LU");
  if ((requested != nullptr && *requested != '\0') || !is_available(SparseLuSolver::Klu)) {
    return default_sparse_lu_solver();
  }
  // Measured (bench/history/RESULTS-log.md section 9): KLU is the fastest where the fill is low,
  // nnz(L + U) ≤ 5.5·nnz(A) (bvp at every n, bratu2d up to N = 32), and 1.7–10× slower than Eigen's
  // supernodal SparseLU where it is high (bratu2d N = 100: 12×, N = 316: 26×). The map keeps one
  // entry per pattern a run factors (a handful: the borders differ in two rows).
  constexpr double kLowFill = 6.0;
  static std::mutex mutex;
  static std::map<std::pair<long, std::uint64_t>, SparseLuSolver> decided;
  // The pattern's hash (FNV-1a over the compressed indices, O(nnz)): the fill depends on more
  // than the size (one border row elsewhere can change it by half).
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  const auto mix = [&hash](const int* first, Eigen::Index count) {
    for (Eigen::Index k = 0; k < count; ++k) {
      hash = (hash ^ static_cast<std::uint32_t>(first[k])) * 0x100000001b3ULL;
    }
  };
  if (A.isCompressed()) {
    mix(A.outerIndexPtr(), A.outerSize() + 1);
    mix(A.innerIndexPtr(), A.nonZeros());
  }
  const std::pair<long, std::uint64_t> key{static_cast<long>(A.rows()), hash};
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (const auto found = decided.find(key); found != decided.end()) {
      return found->second;
    }
  }
  SparseLuSolver choice = SparseLuSolver::Eigen;
  if (A.rows() == A.cols() && A.rows() > 0 && A.isCompressed()) {
    const std::unique_ptr<SparseLu> klu = make_sparse_lu(SparseLuSolver::Klu);
    if (klu->analyze(A) == SparseLuStatus::Success) {
      const std::optional<long> predicted = klu->predicted_factor_nonzeros();
      if (predicted.has_value() && *predicted <= kLowFill * static_cast<double>(A.nonZeros())) {
        choice = SparseLuSolver::Klu;
      }
    }
  }
  const std::lock_guard<std::mutex> lock(mutex);
  decided.emplace(key, choice);
  return choice;
}

std::unique_ptr<SparseLu> make_sparse_lu(SparseLuSolver solver) {
  TESSERA_CHECK(is_available(solver),
                "sparse LU solver '" << name(solver)
                                     << "' is not in this build; it has: " << available_names());
  switch (solver) {
    case SparseLuSolver::Eigen:
      return detail::make_eigen_sparse_lu();
#ifdef TESSERA_HAS_UMFPACK
    case SparseLuSolver::Umfpack:
      return detail::make_umfpack_sparse_lu();
#endif
#ifdef TESSERA_HAS_KLU
    case SparseLuSolver::Klu:
      return detail::make_klu_sparse_lu();
#endif
#ifdef TESSERA_HAS_SUPERLU
    case SparseLuSolver::SuperLu:
      return detail::make_superlu_sparse_lu();
#endif
    default:
      break;
  }
  TESSERA_ASSERT(false);
  return nullptr;
}

// A compressed column pattern (outer and inner indices).
struct SparsePattern {
  std::vector<int> outer;
  std::vector<int> inner;

  bool matches(const Eigen::SparseMatrix<double>& A) const {
    return A.isCompressed() && A.rows() == A.cols() &&
           static_cast<std::size_t>(A.outerSize()) + 1 == outer.size() &&
           static_cast<std::size_t>(A.nonZeros()) == inner.size() &&
           std::equal(outer.begin(), outer.end(), A.outerIndexPtr()) &&
           std::equal(inner.begin(), inner.end(), A.innerIndexPtr());
  }
};

namespace {

// A's pattern, shared with the objects of this thread that hold the same one: the patterns in
// use are few (J with its border rows at a few coordinate pairs), the objects many.
std::shared_ptr<const SparsePattern> shared_pattern(const Eigen::SparseMatrix<double>& A) {
  thread_local std::vector<std::weak_ptr<const SparsePattern>> in_use;
  std::erase_if(in_use, [](const auto& pattern) { return pattern.expired(); });
  for (const auto& weak : in_use) {
    if (auto pattern = weak.lock(); pattern && pattern->matches(A)) {
      return pattern;
    }
  }
  auto pattern = std::make_shared<SparsePattern>();
  pattern->outer.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1);
  pattern->inner.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
  in_use.push_back(pattern);
  return pattern;
}

}  // namespace

SparseLu::~SparseLu() = default;

SparseLuStatus SparseLu::analyze(const Eigen::SparseMatrix<double>& A) {
  TESSERA_CHECK(A.rows() == A.cols() && A.rows() >= 1, "SparseLu::analyze: A is "
                                                           << A.rows() << "×" << A.cols()
                                                           << ", must be square and non-empty");
  TESSERA_CHECK(A.isCompressed(), "SparseLu::analyze: A must be compressed (makeCompressed())");
  is_analyzed_ = false;
  is_factored_ = false;
  last_message_.clear();
  const SparseLuStatus status = do_analyze(A);
  if (status != SparseLuStatus::Success) {
    return status;
  }
  pattern_ = shared_pattern(A);
  is_analyzed_ = true;
  return status;
}

bool SparseLu::is_analyzed_for(const Eigen::SparseMatrix<double>& A) const {
  return is_analyzed_ && pattern_->matches(A);
}

SparseLuStatus SparseLu::factorize(const Eigen::SparseMatrix<double>& A) {
  TESSERA_CHECK(is_analyzed_for(A), "SparseLu::factorize: the pattern of A ("
                                        << A.rows() << "×" << A.cols() << ", " << A.nonZeros()
                                        << " nonzeros) was not analysed");
  is_factored_ = false;
  last_message_.clear();
  const SparseLuStatus status = do_factorize(A);
  is_factored_ = status == SparseLuStatus::Success;
  return status;
}

void SparseLu::solve(const Eigen::Ref<const Eigen::MatrixXd>& B,
                     Eigen::Ref<Eigen::MatrixXd> X) const {
  TESSERA_CHECK(is_factored_, "SparseLu::solve: no factorisation (factorize failed or not called)");
  const Eigen::Index n = static_cast<Eigen::Index>(pattern_->outer.size()) - 1;
  TESSERA_CHECK(B.rows() == n && X.rows() == n && B.cols() == X.cols() && B.cols() >= 1,
                "SparseLu::solve: B is " << B.rows() << "×" << B.cols() << " and X is " << X.rows()
                                         << "×" << X.cols() << ", both must be " << n << "×k");
  if (X.data() != B.data() || X.outerStride() != B.outerStride()) {
    X = B;
  }
  do_solve_in_place(X);
}

}  // namespace tessera
