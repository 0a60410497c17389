// SPDX-License-Identifier: MIT
// Throughput of the advancing front (method `front`) on the unit sphere and the cut sphere of
// Brodzik & Rheinboldt's figure 5.1, as a function of the step h.
//
// Counters (per triangulation; rates per second of CPU time):
//   vertices             vertices of the result mesh
//   vertices_per_second  vertices produced per second
//   F_evals_per_vertex   evaluations of F per result vertex (summary.function_evaluations / V)
//   DF_evals_per_vertex  Jacobian evaluations per result vertex (one per factorisation)
//   bytes_per_vertex     storage of the result mesh per vertex: 8n bytes of coordinates plus
//                        12 bytes per triangle (three ints), i.e. 8n + 12·T/V (≈ 48 for n = 3).
//                        Peak memory of a run is measured by tessera_front_memory instead.
#include <benchmark/benchmark.h>

#include <string>

#include "tessera/methods/front/advancing_front.h"
#include "tessera/problems/catalogue.h"

namespace {

// h ∈ {0.4, 0.2, 0.1, 0.05, 0.025}, passed in thousandths because ranges are integers.
void front_steps(benchmark::internal::Benchmark* benchmark) {
  for (int step_thousandths : {400, 200, 100, 50, 25}) {
    benchmark->Arg(step_thousandths);
  }
  benchmark->ArgName("h_thousandths")->Unit(benchmark::kMillisecond);
}

void run_front(benchmark::State& state, const std::string& problem_name) {
  const tessera::ProblemSetup setup = tessera::make_catalogue_problem(problem_name);  // built once
  tessera::FrontOptions options;  // assigned, not designated: -Wextra flags the unset callback
  options.step = static_cast<double>(state.range(0)) / 1000.0;
  tessera::CoveringSummary summary;
  for (auto _ : state) {
    tessera::CoveringResult result =
        tessera::triangulate_by_front(*setup.problem, setup.start, setup.domain, options);
    benchmark::DoNotOptimize(result.mesh.points().data());
    summary = result.summary;
    if (!summary.is_complete()) {
      state.SkipWithError(("front did not complete: " + summary.message).c_str());
      break;
    }
  }
  if (summary.vertex_count == 0) {
    return;
  }
  const double vertices = summary.vertex_count;
  const double n = setup.problem->ambient_dimension();
  state.counters["vertices"] = vertices;
  state.counters["triangles"] = summary.triangle_count;
  state.counters["vertices_per_second"] = benchmark::Counter(
      vertices * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["F_evals_per_vertex"] =
      static_cast<double>(summary.function_evaluations) / vertices;
  state.counters["DF_evals_per_vertex"] =
      static_cast<double>(summary.jacobian_evaluations) / vertices;
  state.counters["step_reductions"] = summary.step_reductions;
  state.counters["bytes_per_vertex"] =
      (8.0 * n * vertices + 12.0 * summary.triangle_count) / vertices;
}

void BM_Front_Sphere(benchmark::State& state) { run_front(state, "sphere"); }
BENCHMARK(BM_Front_Sphere)->Apply(front_steps);

// The sphere cut by z ≥ −0.8: the front is clipped to the half-space at the end.
void BM_Front_CutSphere(benchmark::State& state) { run_front(state, "sphere_cut"); }
BENCHMARK(BM_Front_CutSphere)->Apply(front_steps);

}  // namespace
