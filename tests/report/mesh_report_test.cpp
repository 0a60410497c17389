// SPDX-License-Identifier: MIT
// The report of a mesh: measured in the problem's metric whether or not it measures the
// distances, every point below n = 500 with the default samples, exactly K with K asked for.
#include "tessera/report/mesh_report.h"

#include <gtest/gtest.h>

#include <string>

#include "tessera/methods/covering_methods.h"
#include "tessera/problems/catalogue.h"

namespace tessera {
namespace {

// bratu2d's grid values are weighted by the mesh width h in its metric: a problem whose report
// differs in x and in the metric (area 10454 against 128.65 at N = 32).
struct Covered {
  ProblemSetup setup = make_catalogue_problem("bratu2d:N=8");
  CoveringResult result = cover(setup, covering_methods().front(), {});
};

const Covered& covered() {
  static const Covered run;
  return run;
}

void expect_same_shape(const MeshQuality& a, const MeshQuality& b) {
  EXPECT_EQ(a.min_angle_degrees, b.min_angle_degrees);
  EXPECT_EQ(a.max_angle_degrees, b.max_angle_degrees);
  EXPECT_EQ(a.fraction_angles_below_30, b.fraction_angles_below_30);
  EXPECT_EQ(a.min_edge_length, b.min_edge_length);
  EXPECT_EQ(a.max_edge_length, b.max_edge_length);
  EXPECT_EQ(a.area, b.area);
}

// `tessera mesh` writes its summary once before the distances (minutes at large n), so that a
// run killed during them leaves one: that summary measured the shape in x, not in the metric,
// until 2026-11-28.
TEST(MeshReport, MeasuresTheShapeInTheMetricWithOrWithoutTheDistances) {
  const auto& [setup, result] = covered();
  ASSERT_TRUE(result.summary.is_complete()) << result.summary.message;
  ASSERT_GT(metric_weights(*setup.problem).size(), 0);
  const MeshReport full = make_report(result.mesh, setup, "bratu2d:N=8");
  const MeshReport before = make_report(result.mesh, setup, "bratu2d:N=8", &full.validation,
                                        {.measure_distances = false});
  expect_same_shape(before.quality, measure_quality(result.mesh, *setup.problem));
  expect_same_shape(before.quality, full.quality);
  // In x the same triangles have another area: the metric is what is measured.
  EXPECT_GT(measure_shape(result.mesh).area, 10 * full.quality.area);
  // Before: nothing measured of the populations there are.
  EXPECT_EQ(before.quality.centroid_distance.count, 0);
  EXPECT_EQ(before.quality.centroid_distance.population, result.mesh.triangle_count());
  EXPECT_EQ(before.quality.midpoint_distance.population, full.validation.edge_count);
}

// The help of --report-samples: all of them below n = 500 (within the time budget, which this
// small mesh is far from).
TEST(MeshReport, DefaultSamplesMeasureEveryPointBelowNOf500) {
  const auto& [setup, result] = covered();
  ASSERT_LT(setup.problem->ambient_dimension(), 500);
  const MeshReport report = make_report(result.mesh, setup, "bratu2d:N=8");
  for (const Statistic* statistic :
       {&report.quality.vertex_distance, &report.quality.centroid_distance,
        &report.quality.midpoint_distance}) {
    EXPECT_EQ(statistic->count, statistic->population);
    EXPECT_GT(statistic->population, 0);
  }
  EXPECT_EQ(report.quality.failed_projections, 0);
  EXPECT_TRUE(report.validation.is_valid()) << report.validation.report();
  EXPECT_EQ(report.problem, "bratu2d:N=8");
  EXPECT_EQ(report.ambient_dimension, 66);
}

TEST(MeshReport, AsksForExactlyTheSamplesGiven) {
  const auto& [setup, result] = covered();
  const MeshReport report = make_report(result.mesh, setup, "bratu2d:N=8", nullptr, {.samples = 7});
  EXPECT_EQ(report.quality.vertex_distance.count, 7);
  EXPECT_EQ(report.quality.centroid_distance.count, 7);
  EXPECT_EQ(report.quality.midpoint_distance.count, 7);
  EXPECT_EQ(report.quality.vertex_distance.population, result.mesh.vertex_count());
}

}  // namespace
}  // namespace tessera
