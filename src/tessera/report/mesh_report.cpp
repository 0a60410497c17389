// SPDX-License-Identifier: MIT
#include "tessera/report/mesh_report.h"

#include <algorithm>

namespace tessera {

namespace {

// From this n on, the report's distances to M are measured at kReportSamples vertices,
// centroids and edge midpoints each (the largest of 300 uniform samples exceeds the 99th
// percentile with probability 95 %); below it at every one.
constexpr int kSampledReportDimension = 500;
constexpr int kReportSamples = 300;
constexpr double kMinReportSeconds = 10.0;
constexpr double kReportTimeFraction = 0.1;

}  // namespace

MeshReport make_report(const TriangleMesh& mesh, const ProblemSetup& setup,
                       const std::string& problem_argument, const MeshValidation* known,
                       const ReportOptions& options) {
  MeshReport report;
  report.problem = problem_argument;  // as the user spelled it, e.g. "torus:R=2"
  report.ambient_dimension = setup.problem->ambient_dimension();
  // The geometric checks (orientation along M, overlaps on M, vertices in S) need the problem,
  // which every caller of make_report has.
  const bool is_known = known != nullptr && known->vertex_count == mesh.vertex_count() &&
                        known->triangle_count == mesh.triangle_count();
  report.validation =
      is_known ? *known : validate(mesh, *setup.problem, setup.domain, options.validation);
  // Distances are Gauss–Newton projections, a few factorisations each: at large n they are
  // measured on a uniform sample (the report says how many) instead of at every point.
  QualityOptions quality;
  const bool is_sampled =
      options.samples < 0 && report.ambient_dimension >= kSampledReportDimension;
  quality.max_samples = options.samples >= 0 ? options.samples : is_sampled ? kReportSamples : 0;
  if (is_sampled) {
    // The report is a check of the run, not a second run (bratu2d:N=316: 900 samples took
    // longer than the covering): a tenth of its time, at least kMinReportSeconds. Below n = 500
    // every point is measured, as --report-samples says: the budget cut the PETSc backend's
    // report after 356 of bratu2d:N=8's points on two ranks (a sample there is a collective
    // factorisation by MUMPS, a hundred times the serial one), until 2026-11-28.
    quality.max_seconds = std::max(kMinReportSeconds, kReportTimeFraction * options.run_seconds);
  }
  quality.stop_requested = options.stop_requested;
  quality.decide_together = options.decide_together;
  if (options.measure_distances) {
    report.quality = measure_quality(mesh, *setup.problem, quality);
  } else {
    report.quality = measure_shape(mesh, *setup.problem);  // in the metric, as measure_quality
    report.quality.vertex_residual.population = mesh.vertex_count();
    report.quality.vertex_distance.population = mesh.vertex_count();
    report.quality.centroid_distance.population = mesh.triangle_count();
    report.quality.midpoint_distance.population = report.validation.edge_count;
  }
  report.expected_euler_characteristic = setup.expected_euler_characteristic;
  report.exact_area = setup.exact_area;
  return report;
}

}  // namespace tessera
