// SPDX-License-Identifier: MIT
// The covering's later stages on a split mesh: every rank holds its rows of every vertex
// (TriangleMesh::set_space, Domain::distributed) and refinement to a tolerance, local repair,
// the start's projection and run_covering's checks reduce through the DistributedSpace (the
// SPMD design of docs/cluster.md). Each must do what one process does, on any number of ranks:
// the same edges split, the same triangles, the vertices to the solvers' rounding, the same
// verdicts and messages.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "tessera/core/error.h"
#include "tessera/core/scaled_problem.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/methods/common/local_repair.h"
#include "tessera/methods/common/refine_to_tolerance.h"
#include "tessera/methods/covering.h"
#include "tessera/methods/covering_methods.h"
#include "tessera/methods/start_point.h"
#include "tessera/petsc/distributed_problem.h"
#include "tessera/petsc/petsc_bratu.h"
#include "tessera/problems/catalogue.h"
#include "petsc/split_support.h"

namespace tessera::petsc {
namespace {

// Vertices computed through different linear solvers (MUMPS split over the ranks, the serial
// sparse LU) agree to about 1e-12 relative; 1e-9 leaves room for a few chord steps.
constexpr double kVertexTolerance = 1e-9;

// bratu2d:N=6 twice: the catalogue's serial problem in the metric's coordinates y = W x (as
// run_covering works), and the PETSc problem in the same coordinates, split over the ranks.
struct Bratu {
  ProblemSetup setup = make_catalogue_problem("bratu2d:N=6");
  Eigen::VectorXd weights = metric_weights(*setup.problem);
  ScaledProblem serial{*setup.problem, weights};
  PetscArrheniusBratu bratu{PETSC_COMM_WORLD, 2, 6};
  ScaledPetscProblem scaled{bratu};
  DistributedProblem distributed{scaled};
  std::shared_ptr<const AmbientSpace> space = distributed.space();

  // The mesh (in the problem's own coordinates) in the metric's.
  TriangleMesh scaled_mesh(const TriangleMesh& mesh) const {
    Eigen::MatrixXd points(mesh.ambient_dimension(), mesh.vertex_count());
    for (int v = 0; v < mesh.vertex_count(); ++v) {
      points.col(v) = weights.cwiseProduct(mesh.point(v));
    }
    return TriangleMesh(points, mesh.triangles());
  }
  // This rank's rows of a mesh in the metric's coordinates.
  TriangleMesh split(const TriangleMesh& mesh) const { return split_rows(mesh, space); }
  Eigen::VectorXd rows_of(const Eigen::VectorXd& x) const {
    return x.segment(space->first_row(), space->local_rows());
  }
  // The largest difference, over all ranks, between a split mesh's vertices and the rows of a
  // whole one's, relative to the largest coordinate.
  double vertex_difference(const TriangleMesh& split_mesh, const TriangleMesh& whole) const {
    double difference = 0.0;
    double scale = 0.0;
    for (int v = 0; v < whole.vertex_count(); ++v) {
      difference = std::max(
          difference, (split_mesh.point(v) - rows_of(whole.point(v))).lpNorm<Eigen::Infinity>());
      scale = std::max(scale, whole.point(v).lpNorm<Eigen::Infinity>());
    }
    return space->maximum(difference) / std::max(scale, 1.0);
  }
};

// A coarse covering of bratu2d:N=6 (388 vertices, its samples within 0.06 of M; the atlas
// itself bisects only one edge for the tolerance 10): refinement has a few rounds to do.
TriangleMesh coarse_covering(const ProblemSetup& setup) {
  MethodSettings settings;
  settings.step = 1.0;
  settings.tolerance = 10.0;
  const CoveringResult covered = cover(setup, find_covering_method("atlas"), settings);
  EXPECT_TRUE(covered.summary.is_complete()) << covered.summary.message;
  return covered.mesh;
}

// The catalogue's domain with every face moved out by `margin` (in the problem's coordinates):
// the covering lies strictly inside it, so no edge lies on a face.
Domain widened(const Domain& domain, double margin) {
  Domain wider(domain.ambient_dimension());
  for (const HalfSpace& h : domain.half_spaces()) {
    wider.add_half_space(h.normal, h.point - margin * h.normal, h.label);
  }
  return wider;
}

// An interior vertex with a full fan of at least five triangles, far from the boundary.
int interior_hub(const TriangleMesh& mesh) {
  const MeshTopology topology(mesh.vertex_count(), mesh.triangles());
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    const auto around = topology.vertex_triangles(v);
    bool interior = around.size() >= 5;
    for (int t : around) {
      for (int w : mesh.triangle(t)) {
        for (int s : topology.vertex_triangles(w)) {
          for (int e : topology.triangle_edges(s)) {
            interior = interior && topology.edge_triangles(e).size() == 2;
          }
        }
      }
    }
    if (interior) {
      return v;
    }
  }
  return -1;
}

// The mesh with a fold put in: a hub vertex and one of its neighbours trade places (both stay
// on M, the triangles between them fold over).
TriangleMesh folded(TriangleMesh mesh, int hub) {
  const MeshTopology topology(mesh.vertex_count(), mesh.triangles());
  const Triangle& first = mesh.triangle(topology.vertex_triangles(hub)[0]);
  const int neighbour = first[0] != hub ? first[0] : first[1];
  const Eigen::VectorXd a = mesh.point(hub);
  mesh.mutable_point(hub) = mesh.point(neighbour);
  mesh.mutable_point(neighbour) = a;
  return mesh;
}

TEST(DistributedRefinement, ASplitMeshIsRefinedAsInOneProcess) {
  Bratu b;
  const TriangleMesh coarse = b.scaled_mesh(coarse_covering(b.setup));
  const Domain domain = scale_domain(widened(b.setup.domain, 0.1), b.weights);
  // Not finer: at 8e-3 one midpoint's Gauss–Newton projection (with its factorisation kept,
  // CorrectorOptions::reuse_factorisation) ends on steps at the rounding floor, where the
  // serial LU and MUMPS see different noise and decide differently whether it contracts.
  ToleranceRefinementOptions options;
  options.tolerance = 1e-2;

  TriangleMesh serial = coarse;
  const ToleranceRefinement expected = refine_to_tolerance(b.serial, domain, serial, {}, options);
  ASSERT_GT(expected.split_edges, 0);
  ASSERT_GE(expected.rounds, 2);

  TriangleMesh split = b.split(coarse);
  const ToleranceRefinement result =
      refine_to_tolerance(b.distributed, domain.distributed(b.space), split, {}, options);

  EXPECT_EQ(result.rounds, expected.rounds);
  EXPECT_EQ(result.split_edges, expected.split_edges);
  EXPECT_EQ(result.remaining, expected.remaining);
  EXPECT_FALSE(result.interrupted);
  EXPECT_NEAR(result.max_distance, expected.max_distance, 1e-6 * expected.max_distance);
  EXPECT_EQ(split.triangles(), serial.triangles());
  ASSERT_EQ(split.vertex_count(), serial.vertex_count());
  EXPECT_LE(b.vertex_difference(split, serial), kVertexTolerance);
}

// Refinement of chosen triangles only, and a tolerance it cannot reach in the rounds allowed:
// the triangles left and the farthest sample are reported alike.
TEST(DistributedRefinement, TrianglesStillTooFarAreReportedAsInOneProcess) {
  Bratu b;
  const TriangleMesh coarse = b.scaled_mesh(coarse_covering(b.setup));
  const Domain domain = scale_domain(widened(b.setup.domain, 0.1), b.weights);
  ToleranceRefinementOptions options;
  options.tolerance = 1e-2;
  options.max_rounds = 1;
  std::vector<int> candidates;
  for (int t = 0; t < coarse.triangle_count(); t += 3) {
    candidates.push_back(t);
  }

  TriangleMesh serial = coarse;
  const ToleranceRefinement expected =
      refine_to_tolerance(b.serial, domain, serial, candidates, options);
  ASSERT_GT(expected.remaining, 0);

  TriangleMesh split = b.split(coarse);
  const ToleranceRefinement result =
      refine_to_tolerance(b.distributed, domain.distributed(b.space), split, candidates, options);

  EXPECT_EQ(result.split_edges, expected.split_edges);
  EXPECT_EQ(result.remaining, expected.remaining);
  EXPECT_NEAR(result.max_distance, expected.max_distance, 1e-6 * expected.max_distance);
  EXPECT_EQ(split.triangles(), serial.triangles());
  ASSERT_EQ(split.vertex_count(), serial.vertex_count());
  EXPECT_LE(b.vertex_difference(split, serial), kVertexTolerance);
  ASSERT_EQ(result.worst_point.size(), b.space->local_rows());
  EXPECT_LE(b.space->maximum((result.worst_point - b.rows_of(expected.worst_point))
                                 .lpNorm<Eigen::Infinity>()),
            kVertexTolerance * (1.0 + expected.worst_point.lpNorm<Eigen::Infinity>()));
}

// A stop request on one rank stops every rank, between two triangles, with the mesh as it was.
TEST(DistributedRefinement, AStopRequestOnOneRankStopsEveryRank) {
  Bratu b;
  const TriangleMesh coarse = b.scaled_mesh(coarse_covering(b.setup));
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  ToleranceRefinementOptions options;
  options.tolerance = 2e-3;
  int polls = 0;
  options.stop_requested = [&] { return rank == 0 && ++polls > 3; };
  TriangleMesh split = b.split(coarse);
  const ToleranceRefinement result =
      refine_to_tolerance(b.distributed, Domain(), split, {}, options);
  EXPECT_TRUE(result.interrupted);
  EXPECT_EQ(result.split_edges, 0);
  EXPECT_EQ(split.triangles(), coarse.triangles());
}

TEST(DistributedRepair, ASplitMeshIsRepairedAsInOneProcess) {
  Bratu b;
  const TriangleMesh coarse = b.scaled_mesh(coarse_covering(b.setup));
  const int hub = interior_hub(coarse);
  ASSERT_GE(hub, 0);
  const TriangleMesh defective = folded(coarse, hub);
  const Domain domain = scale_domain(b.setup.domain, b.weights);
  const MeshValidation validation = validate(defective, b.serial, domain);
  ASSERT_GE(validation.flipped_triangle_count, 1);
  for (int rings : {1, 2}) {
    TriangleMesh serial = defective;
    const LocalRepair expected =
        repair_locally(b.serial, serial, validation.flipped_triangles, rings);
    ASSERT_TRUE(expected.is_repaired) << expected.message;
    ASSERT_GT(expected.added_triangles, 0);

    TriangleMesh split = b.split(defective);
    const LocalRepair result =
        repair_locally(b.distributed, split, validation.flipped_triangles, rings);
    EXPECT_EQ(result.is_repaired, expected.is_repaired) << result.message;
    EXPECT_EQ(result.removed_triangles, expected.removed_triangles);
    EXPECT_EQ(result.filled_holes, expected.filled_holes);
    EXPECT_EQ(result.added_triangles, expected.added_triangles);
    EXPECT_EQ(split.triangles(), serial.triangles());
    ASSERT_EQ(split.vertex_count(), serial.vertex_count());
    EXPECT_LE(b.vertex_difference(split, serial), 0.0);  // vertices are only dropped
    EXPECT_EQ(validate(split, b.distributed, domain.distributed(b.space)).is_valid(),
              validate(serial, b.serial, domain).is_valid());
  }
}

// A hole that cannot be filled (the whole mesh removed: no triangle around it tells M's
// orientation) is refused with the same message, its place gathered from the ranks.
TEST(DistributedRepair, AHoleThatCannotBeFilledIsRefusedWithTheSameMessage) {
  Bratu b;
  const TriangleMesh coarse = b.scaled_mesh(coarse_covering(b.setup));
  std::vector<int> all(static_cast<std::size_t>(coarse.triangle_count()));
  for (int t = 0; t < coarse.triangle_count(); ++t) {
    all[static_cast<std::size_t>(t)] = t;
  }
  TriangleMesh serial = coarse;
  const LocalRepair expected = repair_locally(b.serial, serial, all);
  ASSERT_FALSE(expected.is_repaired);
  ASSERT_FALSE(expected.message.empty());
  TriangleMesh split = b.split(coarse);
  const LocalRepair result = repair_locally(b.distributed, split, all);
  EXPECT_FALSE(result.is_repaired);
  EXPECT_EQ(result.message, expected.message);
  EXPECT_EQ(split.triangles(), coarse.triangles());
}

TEST(DistributedStartPoint, TheStartIsProjectedAsInOneProcess) {
  Bratu b;
  const Domain domain = scale_domain(b.setup.domain, b.weights);
  const Eigen::VectorXd guess = b.weights.cwiseProduct(b.setup.start);
  const StartPoint expected = project_start_point(b.serial, guess, domain, 10.0);
  const StartPoint result =
      project_start_point(b.distributed, b.rows_of(guess), domain.distributed(b.space), 10.0);
  EXPECT_EQ(result.corrector.termination, expected.corrector.termination);
  EXPECT_EQ(result.corrector.iterations, expected.corrector.iterations);
  ASSERT_EQ(result.x.size(), b.space->local_rows());
  EXPECT_LE(b.space->maximum((result.x - b.rows_of(expected.x)).lpNorm<Eigen::Infinity>()),
            kVertexTolerance * (1.0 + expected.x.lpNorm<Eigen::Infinity>()));
  EXPECT_TRUE(result.linearization.is_factored());
}

// A start that projects onto M outside the domain fails with the same message (its
// coordinates gathered from the ranks); a start of the wrong size is refused.
TEST(DistributedStartPoint, AStartOutsideTheDomainFailsWithTheSameMessage) {
  Bratu b;
  const Eigen::VectorXd guess = b.weights.cwiseProduct(b.setup.start);
  const StartPoint on_m =
      project_start_point(b.serial, guess, scale_domain(b.setup.domain, b.weights), 10.0);
  // The domain λ ≥ λ(start) + 1 (in the metric's coordinates; λ has weight 1).
  const int n = static_cast<int>(guess.size());
  const Eigen::VectorXd normal = Eigen::VectorXd::Unit(n, n - 2);
  const Eigen::VectorXd point = (on_m.x(n - 2) + 1.0) * normal;
  Domain domain(n);
  domain.add_half_space(normal, point, "lambda >= start + 1");
  std::string expected;
  try {
    project_start_point(b.serial, guess, domain, 10.0);
  } catch (const ComputationFailed& failure) {
    expected = failure.what();
  }
  ASSERT_NE(expected.find("outside the domain"), std::string::npos) << expected;
  std::string message;
  try {
    project_start_point(b.distributed, b.rows_of(guess), domain.distributed(b.space), 10.0);
  } catch (const ComputationFailed& failure) {
    message = failure.what();
  }
  EXPECT_EQ(message, expected);
  EXPECT_THROW(project_start_point(b.distributed, guess.head(b.space->local_rows() + 1),
                                   domain.distributed(b.space), 10.0),
               InvalidArgument);
}

// run_covering's skeleton around a build that hands over a given mesh (no clipping: the mesh
// is already inside S): validation with local repair, the tolerance check, the coverage
// checks, the summary, on the serial problem and on the split one.
CoveringResult run_with_mesh(const ImplicitProblem& problem, const Eigen::VectorXd& start,
                             const Domain& domain, const TriangleMesh& mesh, double tolerance) {
  CoveringOptions options;
  options.step = 0.3;
  options.tolerance = tolerance;
  return run_covering("given", problem, start, domain, options,
                      [&](CoveringContext&, CoveringResult& result) { result.mesh = mesh; });
}

void expect_same_run(const Bratu& b, const CoveringResult& result, const CoveringResult& expected) {
  EXPECT_EQ(result.summary.termination, expected.summary.termination);
  EXPECT_EQ(result.summary.message, expected.summary.message);
  EXPECT_EQ(result.summary.notes, expected.summary.notes);
  EXPECT_EQ(result.summary.refined_edges, expected.summary.refined_edges);
  EXPECT_EQ(result.summary.removed_triangles, expected.summary.removed_triangles);
  EXPECT_EQ(result.summary.repaired_holes, expected.summary.repaired_holes);
  EXPECT_NEAR(result.summary.max_sampled_distance, expected.summary.max_sampled_distance,
              1e-6 * std::abs(expected.summary.max_sampled_distance));
  EXPECT_EQ(result.mesh.triangles(), expected.mesh.triangles());
  ASSERT_EQ(result.mesh.vertex_count(), expected.mesh.vertex_count());
  ASSERT_TRUE(result.mesh.space().is_distributed());
  // The serial run returns its points in the problem's own coordinates.
  EXPECT_LE(b.vertex_difference(result.mesh, b.scaled_mesh(expected.mesh)), kVertexTolerance);
}

TEST(DistributedCovering, TheSkeletonRepairsAndChecksASplitMeshAsInOneProcess) {
  Bratu b;
  const TriangleMesh coarse = b.scaled_mesh(coarse_covering(b.setup));
  const int hub = interior_hub(coarse);
  ASSERT_GE(hub, 0);
  const TriangleMesh defective = folded(coarse, hub);
  const Eigen::VectorXd start = b.weights.cwiseProduct(b.setup.start);
  // A tolerance the coarse mesh meets: the fold is validated and repaired as built, and the
  // repair's triangles are held to the tolerance.
  const double tolerance = 0.1;
  const CoveringResult expected =
      run_with_mesh(*b.setup.problem, b.setup.start, b.setup.domain, defective, tolerance);
  ASSERT_TRUE(expected.summary.is_complete()) << expected.summary.message;
  ASSERT_GT(expected.summary.repaired_holes, 0);
  // The domain given whole: run_covering cuts it to the rows (AHoleIsFoundAsInOneProcess
  // gives it as rows).
  const CoveringResult result = run_with_mesh(b.distributed, b.rows_of(start),
                                              scale_domain(b.setup.domain, b.weights),
                                              b.split(defective), tolerance);
  expect_same_run(b, result, expected);
}

// A mesh with a hole inside (an interior triangle removed) fails the coverage check with the
// same message, the edge's ends gathered from the ranks.
TEST(DistributedCovering, AHoleIsFoundAsInOneProcess) {
  Bratu b;
  TriangleMesh coarse = b.scaled_mesh(coarse_covering(b.setup));
  const int hub = interior_hub(coarse);
  ASSERT_GE(hub, 0);
  const MeshTopology topology(coarse.vertex_count(), coarse.triangles());
  std::vector<Triangle> triangles = coarse.triangles();
  triangles.erase(triangles.begin() + topology.vertex_triangles(hub)[0]);
  coarse.set_triangles(triangles);
  const Eigen::VectorXd start = b.weights.cwiseProduct(b.setup.start);
  const CoveringResult expected =
      run_with_mesh(*b.setup.problem, b.setup.start, b.setup.domain, coarse, 0.0);
  ASSERT_EQ(expected.summary.termination, CoveringTermination::TriangulationFailed);
  ASSERT_NE(expected.summary.message.find("the mesh has a hole"), std::string::npos)
      << expected.summary.message;
  const CoveringResult result =
      run_with_mesh(b.distributed, b.rows_of(start),
                    scale_domain(b.setup.domain, b.weights).distributed(b.space), b.split(coarse),
                    0.0);
  expect_same_run(b, result, expected);
}

// The inputs of a distributed run: the start holds this rank's rows, and a problem with a
// metric must present its coordinates itself (ScaledPetscProblem), not be scaled again.
TEST(DistributedCovering, InputsThatDoNotFitASplitRunAreRefused) {
  Bratu b;
  const Eigen::VectorXd start = b.weights.cwiseProduct(b.setup.start);
  const Domain domain = scale_domain(b.setup.domain, b.weights);
  const TriangleMesh none;
  EXPECT_THROW(run_with_mesh(b.distributed, start.head(b.space->local_rows() + 1), domain, none,
                             0.0),
               InvalidArgument);
  const DistributedProblem unscaled(b.bratu);
  ASSERT_GT(metric_weights(unscaled).size(), 0);
  try {
    run_with_mesh(unscaled, b.rows_of(b.setup.start), b.setup.domain, none, 0.0);
    ADD_FAILURE() << "a distributed problem with a metric was accepted";
  } catch (const InvalidArgument& refusal) {
    EXPECT_NE(std::string(refusal.what()).find("ScaledPetscProblem"), std::string::npos)
        << refusal.what();
  }
}

}  // namespace
}  // namespace tessera::petsc
