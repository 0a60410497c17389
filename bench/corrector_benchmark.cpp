// SPDX-License-Identifier: MIT
// Cost of the correctors and of the linearisation they rest on: dense (the sphere, n = 3) and
// sparse (the Arrhenius–Bratu BVP, n = N + 2 up to 10⁵), to show whether the sparse path scales
// linearly in n.
//
// Each sparse benchmark projects or factors at points of the catalogue's "bvp:points=N" problem:
// the start x₀ on M and a prediction x₀ + s·T·(cos θ, sin θ) scaled with the catalogue's
// suggested step h = 0.05·√N (distances along M grow like √N, so this is the same step on the
// continuous profile for every N). Gauss–Newton starts from s = h, θ = 0.3. The chord benchmark
// starts from s = h/4, θ = 2.0: at s = h the frozen-Jacobian chord contracts poorly for N ≥ 1000
// (θ_k up to 0.97, sometimes > 1: "Diverged"), and this benchmark measures the cost of the solves,
// not the reach of the chord; its corrector_iterations counter says how many solves were done.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <cmath>
#include <new>
#include <stdexcept>
#include <string>

#include "tessera/core/corrector.h"
#include "tessera/core/linearization.h"
#include "tessera/problems/catalogue.h"

namespace {

constexpr double kDirectionAngle = 0.3;  // radians in the tangent plane; any generic direction

// x₀ + s·T·(cos θ, sin θ): a point at distance O(s²) from M, as the front predicts new vertices.
Eigen::VectorXd predicted_point(const tessera::Linearization& frame, double step,
                                double angle = kDirectionAngle) {
  return frame.point() +
         step * frame.tangent_basis() * Eigen::Vector2d(std::cos(angle), std::sin(angle));
}

struct FactoredSetup {
  tessera::ProblemSetup setup;
  tessera::Linearization frame;  // factored at setup.start projected onto M
  Eigen::VectorXd predicted;     // a prediction at the suggested step from frame.point()
};

// The unit vectors of the last two coordinates as an n×2 reference tangent basis. For the BVP
// these are (λ, ε): the sparse backend then borders J with e_λᵀ, e_εᵀ, which is regular on the
// middle sheet of the fold where the start lies (∂F/∂u is invertible between the folds). The
// front always has such a reference (a neighbour's tangent) after its first vertex; without one
// the backend borders J with dense rows (BM_FirstFactor_Sparse_Bvp measures that case).
Eigen::MatrixXd last_coordinates(int n) {
  Eigen::MatrixXd basis = Eigen::MatrixXd::Zero(n, 2);
  basis(n - 2, 0) = 1.0;
  basis(n - 1, 1) = 1.0;
  return basis;
}

FactoredSetup factored_setup(const std::string& specification) {
  FactoredSetup result{tessera::make_catalogue_problem(specification), {}, {}};
  const tessera::ImplicitProblem& problem = *result.setup.problem;
  const Eigen::MatrixXd guide = last_coordinates(problem.ambient_dimension());
  Eigen::VectorXd x = result.setup.start;
  // The catalogue's starts are already on M to rounding; project anyway so that x₀ ∈ M exactly.
  // Pre-factoring the workspace gives the projection its reference tangent.
  tessera::Linearization workspace;
  workspace.factor(problem, x, &guide);
  tessera::project_gauss_newton(problem, x, {}, workspace);
  if (!result.frame.factor(problem, x, &guide)) {
    throw std::runtime_error("cannot factor DF at the start of " + specification);
  }
  result.predicted = predicted_point(result.frame, result.setup.suggested_step);
  return result;
}

// --- Dense: the sphere (n = 3) ---------------------------------------------------------------

// One factorisation: J = DF(x) evaluated and QR-factored, tangent basis extracted.
void BM_Factor_Dense(benchmark::State& state) {
  const FactoredSetup fixture = factored_setup("sphere");
  tessera::Linearization frame;
  for (auto _ : state) {
    benchmark::DoNotOptimize(frame.factor(*fixture.setup.problem, fixture.frame.point()));
  }
}
BENCHMARK(BM_Factor_Dense);

// One chord projection with the factorisation frozen at x_c (what the front does per new vertex),
// from x_c + h·t for h = 0.1 and 0.4 (range in thousandths).
void BM_Chord_Dense(benchmark::State& state) {
  const FactoredSetup fixture = factored_setup("sphere");
  const double step = static_cast<double>(state.range(0)) / 1000.0;
  const Eigen::VectorXd prediction = predicted_point(fixture.frame, step);
  Eigen::VectorXd x = prediction;
  tessera::CorrectorSummary summary;
  for (auto _ : state) {
    x = prediction;  // same size: no allocation
    summary = tessera::project_chord(*fixture.setup.problem, fixture.frame, x, {});
    benchmark::DoNotOptimize(x.data());
  }
  if (!summary.is_success()) {
    state.SkipWithError(("chord projection failed: " + summary.brief_report()).c_str());
  }
  state.counters["corrector_iterations"] = summary.iterations;
}
BENCHMARK(BM_Chord_Dense)->Arg(100)->Arg(400)->ArgName("h_thousandths");

// --- Sparse: the Arrhenius–Bratu BVP, n = N + 2 ------------------------------------------------

void sparse_sizes(benchmark::internal::Benchmark* benchmark) {
  for (int points : {100, 1000, 10000, 100000}) {
    benchmark->Arg(points);
  }
  // No ->Complexity(oN): Google Benchmark 1.7 fits errored runs too (and crashes when every run
  // of a family failed); run.sh prints the measured exponent between successive N instead.
  benchmark->ArgName("N")->Unit(benchmark::kMicrosecond);
}

std::string bvp_specification(const benchmark::State& state) {
  return "bvp:points=" + std::to_string(state.range(0));
}

// A sparse factorisation whose fill-in grows superlinearly can exhaust the machine's memory at
// N = 10⁵ (the kernel then kills the whole benchmark run). Below this limit on the address space
// an O(N) factorisation needs < 200 MB even at N = 10⁵, so hitting it means the fill-in is not
// O(N); the benchmark then reports an error instead of taking the machine down.
constexpr rlim_t kSparseAddressSpaceLimit = rlim_t{2} << 30;  // 2 GiB

// Lowers the soft RLIMIT_AS for its lifetime (never raises it).
class AddressSpaceLimit {
 public:
  explicit AddressSpaceLimit(rlim_t bytes) {
    getrlimit(RLIMIT_AS, &saved_);
    rlimit lowered = saved_;
    if (lowered.rlim_cur == RLIM_INFINITY || lowered.rlim_cur > bytes) {
      lowered.rlim_cur = bytes;
    }
    setrlimit(RLIMIT_AS, &lowered);
  }
  ~AddressSpaceLimit() { setrlimit(RLIMIT_AS, &saved_); }
  AddressSpaceLimit(const AddressSpaceLimit&) = delete;
  AddressSpaceLimit& operator=(const AddressSpaceLimit&) = delete;

 private:
  rlimit saved_{};
};

// Runs `body` under the address-space limit; running out of memory becomes a benchmark error.
template <typename Body>
void run_sparse(benchmark::State& state, Body body) {
  const AddressSpaceLimit limit(kSparseAddressSpaceLimit);
  try {
    body();
  } catch (const std::bad_alloc&) {
    state.SkipWithError(
        "out of memory under the 2 GiB address-space limit (an O(N) "
        "factorisation needs < 200 MB even at N = 1e5)");
  }
}

// One factorisation as the front does it, with a neighbour's tangent basis as reference: sparse J,
// bordered, sparse LU, tangent basis. The same Linearization is reused, as in Gauss–Newton.
void BM_Factor_Sparse_Bvp(benchmark::State& state) {
  run_sparse(state, [&] {
    const FactoredSetup fixture = factored_setup(bvp_specification(state));
    const Eigen::MatrixXd reference = fixture.frame.tangent_basis();
    tessera::Linearization frame;
    // Warm-up outside the timed loop: the first call also does the symbolic analysis (ordering),
    // which later calls with the same sparsity pattern skip.
    frame.factor(*fixture.setup.problem, fixture.predicted, &reference);
    for (auto _ : state) {
      benchmark::DoNotOptimize(frame.factor(*fixture.setup.problem, fixture.predicted, &reference));
    }
  });
}
BENCHMARK(BM_Factor_Sparse_Bvp)->Apply(sparse_sizes);

// The first factorisation of a run, with no reference tangent (project_start_point does this):
// a fresh Linearization, so the symbolic analysis is included, as it is at the start.
void BM_FirstFactor_Sparse_Bvp(benchmark::State& state) {
  run_sparse(state, [&] {
    const FactoredSetup fixture = factored_setup(bvp_specification(state));
    for (auto _ : state) {
      tessera::Linearization frame;
      benchmark::DoNotOptimize(frame.factor(*fixture.setup.problem, fixture.frame.point()));
    }
  });
}
BENCHMARK(BM_FirstFactor_Sparse_Bvp)->Apply(sparse_sizes);

// Full Gauss–Newton from the prediction at the suggested step: one factorisation per iteration.
// seconds_per_factorisation = CPU time / (iterations × Gauss–Newton iterations).
void BM_GaussNewton_Sparse_Bvp(benchmark::State& state) {
  run_sparse(state, [&] {
    const FactoredSetup fixture = factored_setup(bvp_specification(state));
    tessera::Linearization workspace = fixture.frame;
    Eigen::VectorXd x = fixture.predicted;
    tessera::CorrectorSummary summary;
    double factorisations = 0.0;
    for (auto _ : state) {
      x = fixture.predicted;
      summary = tessera::project_gauss_newton(*fixture.setup.problem, x, {}, workspace);
      factorisations += summary.iterations;
      benchmark::DoNotOptimize(x.data());
    }
    if (!summary.is_success()) {
      state.SkipWithError(("Gauss-Newton failed: " + summary.brief_report()).c_str());
    }
    state.counters["corrector_iterations"] = summary.iterations;
    state.counters["seconds_per_factorisation"] = benchmark::Counter(
        factorisations, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  });
}
BENCHMARK(BM_GaussNewton_Sparse_Bvp)->Apply(sparse_sizes);

// One chord projection frozen at x₀ (the front's per-vertex corrector): only solves, no factoring.
void BM_Chord_Sparse_Bvp(benchmark::State& state) {
  run_sparse(state, [&] {
    const FactoredSetup fixture = factored_setup(bvp_specification(state));
    const Eigen::VectorXd prediction =
        predicted_point(fixture.frame, 0.25 * fixture.setup.suggested_step, /*angle=*/2.0);
    Eigen::VectorXd x = prediction;
    tessera::CorrectorSummary summary;
    for (auto _ : state) {
      x = prediction;
      summary = tessera::project_chord(*fixture.setup.problem, fixture.frame, x, {});
      benchmark::DoNotOptimize(x.data());
    }
    if (!summary.is_success()) {
      state.SkipWithError(("chord projection failed: " + summary.brief_report()).c_str());
    }
    state.counters["corrector_iterations"] = summary.iterations;
  });
}
BENCHMARK(BM_Chord_Sparse_Bvp)->Apply(sparse_sizes);

}  // namespace
