// SPDX-License-Identifier: MIT
// The sparse LU solvers of core/sparse_lu.h on the matrices tessera actually factors: the
// bordered Jacobian A = [J; e_iᵀ; e_jᵀ] of the sparse linearisation, at a point of M, bordered
// with the coordinates that the tangent there picks (core/bordered_jacobian.h, as Linearization
// does with a neighbour's tangent).
//
// Problems: `bvp:points=N` (1-D, n = N + 2: tridiagonal plus two dense columns) at
// N = 10², 10³, 10⁴, 10⁵ and `bratu2d:N=N` (2-D five-point stencil plus two dense columns,
// n = N² + 2) at N = 10, 32, 100, 316, each at its catalogue start.
//
// Families, each per solver and matrix:
//   BM_Analyze            symbolic analysis (ordering) of A's pattern
//   BM_AnalyzeFactorize   a fresh analysis and factorisation (what a change of border costs;
//                         for KLU a full factorisation with pivoting)
//   BM_Factorize          a numerical factorisation on the analysed pattern, repeated (for KLU a
//                         refactorisation that reuses the pivot sequence)
//   BM_Solve              one solve with one right-hand side
// Counters: n, nnz(A) and fill = nnz(L) + nnz(U) as the solver reports it. "eigen" is ordered by
// nested dissection where the build has METIS; "eigen-colamd" is the same LU ordered by COLAMD.
// One vertex of a covering costs about one factorisation and 20–40 solves.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <map>
#include <memory>
#include <string>

#include "tessera/core/bordered_jacobian.h"
#include "tessera/core/detail/nested_dissection.h"
#include "tessera/core/linearization.h"
#include "tessera/core/sparse_lu.h"
#include "tessera/problems/catalogue.h"

namespace {

// The bordered Jacobian at the catalogue start of `specification`, built once per process.
const Eigen::SparseMatrix<double>& bordered_matrix(const std::string& specification) {
  static std::map<std::string, Eigen::SparseMatrix<double>> matrices;
  auto found = matrices.find(specification);
  if (found != matrices.end()) {
    return found->second;
  }
  const tessera::ProblemSetup setup = tessera::make_catalogue_problem(specification);
  const tessera::ImplicitProblem& problem = *setup.problem;
  tessera::Linearization linearization;
  if (!linearization.factor(problem, setup.start)) {
    throw std::runtime_error("cannot factor at the start of " + specification);
  }
  Eigen::SparseMatrix<double> J, A;
  problem.sparse_jacobian(setup.start, J);
  tessera::bordered_jacobian(J, tessera::coordinate_border(linearization.tangent_basis()), A);
  return matrices.emplace(specification, std::move(A)).first->second;
}

void set_counters(benchmark::State& state, const Eigen::SparseMatrix<double>& A,
                  const tessera::SparseLu& lu) {
  state.counters["n"] = static_cast<double>(A.rows());
  state.counters["nnz_A"] = static_cast<double>(A.nonZeros());
  if (const auto fill = lu.factor_nonzeros()) {
    state.counters["fill"] = static_cast<double>(*fill);
  }
}

std::unique_ptr<tessera::SparseLu> factored(tessera::SparseLuSolver solver,
                                            const Eigen::SparseMatrix<double>& A,
                                            benchmark::State& state) {
  auto lu = tessera::make_sparse_lu(solver);
  if (lu->analyze(A) != tessera::SparseLuStatus::Success ||
      lu->factorize(A) != tessera::SparseLuStatus::Success) {
    state.SkipWithError(("factorisation failed: " + lu->last_message()).c_str());
  }
  return lu;
}

void analyze(benchmark::State& state, tessera::SparseLuSolver solver, std::string specification) {
  const auto& A = bordered_matrix(specification);
  auto lu = tessera::make_sparse_lu(solver);
  for (auto _ : state) {
    benchmark::DoNotOptimize(lu->analyze(A));
  }
  lu->factorize(A);
  set_counters(state, A, *lu);
}

void analyze_factorize(benchmark::State& state, tessera::SparseLuSolver solver,
                       std::string specification) {
  const auto& A = bordered_matrix(specification);
  auto lu = tessera::make_sparse_lu(solver);
  for (auto _ : state) {
    lu->analyze(A);
    if (lu->factorize(A) != tessera::SparseLuStatus::Success) {
      state.SkipWithError(("factorisation failed: " + lu->last_message()).c_str());
      break;
    }
  }
  set_counters(state, A, *lu);
}

void factorize(benchmark::State& state, tessera::SparseLuSolver solver, std::string specification) {
  const auto& A = bordered_matrix(specification);
  auto lu = factored(solver, A, state);
  for (auto _ : state) {
    if (lu->factorize(A) != tessera::SparseLuStatus::Success) {
      state.SkipWithError(("factorisation failed: " + lu->last_message()).c_str());
      break;
    }
  }
  set_counters(state, A, *lu);
}

void solve(benchmark::State& state, tessera::SparseLuSolver solver, std::string specification) {
  const auto& A = bordered_matrix(specification);
  auto lu = factored(solver, A, state);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 1.0);
  Eigen::VectorXd x(A.rows());
  for (auto _ : state) {
    lu->solve(b, x);
    benchmark::DoNotOptimize(x.data());
  }
  // The residual says the solve is worth timing: ‖Ax − b‖/(‖A‖‖x‖) near rounding.
  state.counters["relative_residual"] = (A * x - b).norm() / (A.norm() * x.norm());
  set_counters(state, A, *lu);
}

// Registered before main: every available solver × every matrix × every family.
const bool registered = [] {
  const std::vector<std::string> specifications = {
      "bvp:points=100", "bvp:points=1000", "bvp:points=10000", "bvp:points=100000",
      "bratu2d:N=10",   "bratu2d:N=32",    "bratu2d:N=100",    "bratu2d:N=316"};
  using Family = void (*)(benchmark::State&, tessera::SparseLuSolver, std::string);
  const std::vector<std::pair<std::string, Family>> families = {
      {"BM_Analyze", analyze},
      {"BM_AnalyzeFactorize", analyze_factorize},
      {"BM_Factorize", factorize},
      {"BM_Solve", solve}};
  for (const auto& [family, function] : families) {
    for (const std::string& specification : specifications) {
      for (tessera::SparseLuSolver solver : tessera::available_sparse_lu_solvers()) {
        const std::string name =
            family + "/" + std::string(tessera::name(solver)) + "/" + specification;
        benchmark::RegisterBenchmark(name.c_str(), function, solver, specification)
            ->Unit(benchmark::kMicrosecond);
      }
      // Eigen's SparseLU with COLAMD, its ordering before nested dissection (and where the
      // build has no METIS), for the comparison of bench/history/RESULTS-log.md section 9.
      if (tessera::detail::has_nested_dissection()) {
        const std::string name = family + "/eigen-colamd/" + specification;
        benchmark::RegisterBenchmark(
            name.c_str(),
            [function = function](benchmark::State& state, std::string matrix) {
              setenv("TESSERA_SPARSE_LU_ORDERING", "colamd", 1);
              function(state, tessera::SparseLuSolver::Eigen, std::move(matrix));
              unsetenv("TESSERA_SPARSE_LU_ORDERING");
            },
            specification)
            ->Unit(benchmark::kMicrosecond);
      }
    }
  }
  return true;
}();

}  // namespace
