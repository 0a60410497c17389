// SPDX-License-Identifier: MIT
// The atlas's continuation on split points: every rank holds its rows of every chart's centre
// and tangent basis, and the charts' geometry (distances, tangent coordinates, the radius
// probes' norms) is reduced over the ranks (the SPMD design of docs/cluster.md). The charts and
// their triangulation must be the one process's on any number of ranks.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "tessera/core/counted_problem.h"
#include "tessera/core/scaled_problem.h"
#include "tessera/methods/atlas/atlas_builder.h"
#include "tessera/methods/atlas/atlas_triangulation.h"
#include "tessera/methods/covering_methods.h"
#include "tessera/methods/start_point.h"
#include "tessera/petsc/distributed_problem.h"
#include "tessera/petsc/petsc_bratu.h"
#include "tessera/problems/catalogue.h"
#include "petsc/split_support.h"

namespace tessera::petsc {
namespace {

using detail::AtlasBuilder;

AtlasTriangulation triangulate(const AtlasBuilder& builder) {
  return triangulate_atlas(builder.cells());
}

// The small square in the metric's coordinates, charts of radius up to 0.2: the serial problem and the PETSc one split over the ranks build the same
// charts (radii to rounding, centres to the corrector's tolerance) and the same triangles.
TEST(DistributedAtlas, SplitChartsAreTheOneProcessCharts) {
  const ProblemSetup setup = around_start("bratu2d:N=6", 0.1);
  const Eigen::VectorXd weights = metric_weights(*setup.problem);
  ASSERT_GT(weights.size(), 0);
  const ScaledProblem scaled_serial(*setup.problem, weights);
  const Domain serial_domain = scale_domain(setup.domain, weights);
  const StartPoint start =
      project_start_point(scaled_serial, weights.cwiseProduct(setup.start), serial_domain, 3.0);

  AtlasOptions options;
  options.step = 0.2;
  options.tolerance = 0.01;
  options.boundary_snap = 0.0;  // face projections are not the builder's (clipping's test)
  AtlasBuilder serial(scaled_serial, serial_domain, options);
  CoveringSummary serial_summary;
  serial.run(start.x, serial_summary);
  ASSERT_TRUE(serial_summary.is_complete()) << serial_summary.message;
  ASSERT_GT(serial.chart_count(), 20);
  const AtlasTriangulation serial_mesh = triangulate(serial);
  ASSERT_TRUE(serial_mesh.message.empty()) << serial_mesh.message;

  PetscArrheniusBratu bratu(PETSC_COMM_WORLD, 2, 6);
  const ScaledPetscProblem scaled(bratu);
  const DistributedProblem distributed(scaled);
  const std::shared_ptr<const AmbientSpace> space = distributed.space();
  const int first = space->first_row();
  const int rows = space->local_rows();
  const CountedProblem counted(distributed);  // as run_covering wraps it
  const Domain split_domain = serial_domain.distributed(space);
  AtlasBuilder split(counted, split_domain, options);
  CoveringSummary split_summary;
  const long reductions_before = distributed_space(*space).reductions();
  split.run(start.x.segment(first, rows), split_summary);
  ASSERT_TRUE(split_summary.is_complete()) << split_summary.message;
  // The covering logic's collective calls (the solver's own are PETSc's): a few hundred per
  // chart, each of a few numbers.
  const double per_chart = static_cast<double>(distributed_space(*space).reductions() -
                                               reductions_before) /
                           split.chart_count();
  RecordProperty("reductions_per_chart", std::to_string(per_chart));
  EXPECT_LE(per_chart, 400.0);

  ASSERT_EQ(split.chart_count(), serial.chart_count());
  for (int c = 0; c < serial.chart_count(); ++c) {
    EXPECT_NEAR(split.chart(c).radius, serial.chart(c).radius, 1e-9) << "chart " << c;
    // The frame: the serial backend's basis whatever border the distributed LU kept.
    EXPECT_LE(space->frobenius_norm(split.tangent(c) - serial.tangent(c).middleRows(first, rows)),
              1e-9)
        << "chart " << c;
    EXPECT_EQ(split.chart(c).parent, serial.chart(c).parent) << "chart " << c;
    const Eigen::VectorXd difference = split.center(c) - serial.center(c).segment(first, rows);
    EXPECT_LE(space->norm(difference), 1e-8) << "chart " << c;
  }
  EXPECT_EQ(split_summary.charts, serial_summary.charts);
  EXPECT_EQ(split_summary.sheet_rejections, serial_summary.sheet_rejections);
  EXPECT_EQ(split_summary.notes, serial_summary.notes);

  const AtlasTriangulation split_mesh = triangulate(split);
  EXPECT_TRUE(split_mesh.message.empty()) << split_mesh.message;
  EXPECT_EQ(split_mesh.mesh.triangles(), serial_mesh.mesh.triangles());
  EXPECT_EQ(split_mesh.filled_holes, serial_mesh.filled_holes);
  ASSERT_EQ(split_mesh.mesh.vertex_count(), serial_mesh.mesh.vertex_count());
  EXPECT_TRUE(split_mesh.mesh.space().is_distributed() == space->is_distributed());
  EXPECT_EQ(split_mesh.mesh.ambient_dimension(), rows);
}

// The whole pipeline (start, atlas, clipping, notches, swaps, refinement to the tolerance,
// validation, the checks) on split states gives the one process's mesh, in y = W x.
TEST(DistributedAtlas, TheCoveringOfSplitStatesIsTheOneProcessMesh) {
  const ProblemSetup serial = around_start("bratu2d:N=6", 0.1);
  const Eigen::VectorXd weights = metric_weights(*serial.problem);
  MethodSettings settings;
  settings.step = 0.2;
  const CoveringMethod& atlas = find_covering_method("atlas");
  const CoveringResult expected = cover(serial, atlas, settings);
  ASSERT_TRUE(expected.summary.is_complete()) << expected.summary.message;

  PetscArrheniusBratu bratu(PETSC_COMM_WORLD, 2, 6);
  const ScaledPetscProblem scaled(bratu);
  const CoveringResult result = cover(split_setup(serial, scaled), atlas, settings);
  ASSERT_TRUE(result.summary.is_complete()) << result.summary.message;
  expect_same_covering(result, expected, weights);
}

}  // namespace
}  // namespace tessera::petsc
