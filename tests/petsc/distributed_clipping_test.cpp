// SPDX-License-Identifier: MIT
// The steps after a covering's build on a split mesh (the SPMD design of docs/cluster.md): every
// rank holds its rows of every vertex (TriangleMesh::set_space, Domain::distributed), and
// clipping to the domain, closing boundary notches and the edge swaps after clipping reduce
// through the DistributedSpace. They must make the one process's mesh, triangle for triangle, on
// any number of ranks.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "tessera/core/scaled_problem.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/methods/common/boundary_notches.h"
#include "tessera/methods/common/clip_to_domain.h"
#include "tessera/methods/covering_methods.h"
#include "tessera/methods/improvement/edge_swap.h"
#include "tessera/petsc/distributed_problem.h"
#include "tessera/petsc/petsc_bratu.h"
#include "tessera/problems/catalogue.h"
#include "petsc/split_support.h"

namespace tessera::petsc {
namespace {

// The atlas's step; its edges near ∂S are about this long.
constexpr double kStep = 0.5;

// bratu2d:N=6 twice: in one process (ScaledProblem, the coordinates run_covering works in) and
// on the ranks of PETSC_COMM_WORLD (ScaledPetscProblem, the same coordinates), with a covering
// of M ∩ S in those coordinates to start from.
class SplitBratu {
 public:
  SplitBratu()
      : setup_(make_catalogue_problem("bratu2d:N=6")),
        weights_(metric_weights(*setup_.problem)),
        serial_(*setup_.problem, weights_),
        bratu_(PETSC_COMM_WORLD, 2, 6),
        scaled_(bratu_),
        distributed_(scaled_),
        space_(distributed_.space()) {
    MethodSettings settings;
    settings.step = kStep;
    const CoveringResult covered = cover(setup_, find_covering_method("atlas"), settings);
    EXPECT_TRUE(covered.summary.is_complete()) << covered.summary.message;
    covering_ = covered.mesh;
    for (int v = 0; v < covering_.vertex_count(); ++v) {
      covering_.mutable_point(v) = weights_.cwiseProduct(covering_.point(v));
    }
  }

  const ImplicitProblem& serial() const { return serial_; }
  const ImplicitProblem& distributed() const { return distributed_; }
  const AmbientSpace& space() const { return *space_; }
  /// The covering, clipped to the catalogue's domain, in the metric's coordinates.
  const TriangleMesh& covering() const { return covering_; }

  /// The catalogue's domain cut by `extra` (in the problem's own coordinates), in the metric's.
  Domain domain(const Domain& extra = Domain()) const {
    Domain domain = setup_.domain;
    domain.intersect_with(extra);
    return scale_domain(domain, weights_);
  }
  Domain split_domain(const Domain& extra = Domain()) const {
    return domain(extra).distributed(space_);
  }

  /// This rank's rows of every vertex.
  TriangleMesh split(const TriangleMesh& mesh) const { return split_rows(mesh, space_); }

  int n() const { return static_cast<int>(weights_.size()); }

 private:
  ProblemSetup setup_;
  Eigen::VectorXd weights_;
  ScaledProblem serial_;
  PetscArrheniusBratu bratu_;
  ScaledPetscProblem scaled_;
  DistributedProblem distributed_;
  std::shared_ptr<const AmbientSpace> space_;
  TriangleMesh covering_;
};

// The same triangles, and this rank's rows of every vertex those of the serial vertex to 1e-9
// relative (the backends factor differently: MUMPS against Eigen's sparse LU).
void expect_same_mesh(const TriangleMesh& split, const TriangleMesh& serial,
                      const AmbientSpace& space) {
  EXPECT_EQ(split.triangles(), serial.triangles());
  EXPECT_EQ(split.vertex_count(), serial.vertex_count());
  if (split.vertex_count() != serial.vertex_count()) {
    return;
  }
  double worst = 0.0;
  for (int v = 0; v < serial.vertex_count(); ++v) {
    const Eigen::VectorXd rows = serial.point(v).segment(space.first_row(), space.local_rows());
    worst = std::max(worst, (split.point(v) - rows).lpNorm<Eigen::Infinity>() /
                                (1.0 + serial.point(v).lpNorm<Eigen::Infinity>()));
  }
  EXPECT_LE(worst, 1e-9);
}

void expect_same_summary(const ClipSummary& split, const ClipSummary& serial) {
  EXPECT_EQ(split.half_spaces_crossed, serial.half_spaces_crossed);
  EXPECT_EQ(split.snapped_vertices, serial.snapped_vertices);
  EXPECT_EQ(split.cut_edges, serial.cut_edges);
  EXPECT_EQ(split.collapsed_edges, serial.collapsed_edges);
  EXPECT_EQ(split.message, serial.message);
  EXPECT_EQ(split.interrupted, serial.interrupted);
}

// Faces that cut through the covering: two bounds on the parameters, which meet M ∩ S in a
// corner, and one slanted face across all of u (not a coordinate face: its vertices are placed
// along its normal, whose rows lie on every rank, so that every rank's part of a distance
// counts).
Domain smaller_domain(int n) {
  Domain extra(n);
  Eigen::VectorXd normal = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd point = Eigen::VectorXd::Zero(n);
  normal(n - 2) = 1.0;  // λ ≥ 3
  point(n - 2) = 3.0;
  extra.add_half_space(normal, point, "lambda >= 3");
  normal.setZero();
  point.setZero();
  normal(n - 1) = -1.0;  // ε ≤ 0.2
  point(n - 1) = 0.2;
  extra.add_half_space(normal, point, "eps <= 0.2");
  normal.setZero();
  point.setZero();
  normal.head(n - 2).setConstant(-1.0);  // mean u ≤ 3: its normal has rows on every rank
  point.head(n - 2).setConstant(3.0);
  extra.add_half_space(normal, point, "mean u <= 3");
  return extra;
}

ClipOptions clip_options() {
  ClipOptions options;
  options.snap_distance = 0.35 * kStep;  // run_covering's boundary_snap_fraction
  options.min_boundary_edge = 0.2 * kStep;
  return options;
}

TEST(DistributedClipping, ASplitMeshIsClippedAsInOneProcess) {
  const SplitBratu bratu;
  const Domain extra = smaller_domain(bratu.n());
  TriangleMesh serial = bratu.covering();
  const ClipSummary expected = clip_to_domain(bratu.serial(), bratu.domain(extra), serial,
                                              clip_options());
  // The faces are crossed, vertices snapped and edges cut: every step of the clipping runs.
  EXPECT_EQ(expected.half_spaces_crossed, 3);
  EXPECT_GT(expected.snapped_vertices, 0);
  EXPECT_GT(expected.cut_edges, 0);
  EXPECT_TRUE(expected.message.empty()) << expected.message;

  TriangleMesh split = bratu.split(bratu.covering());
  const ClipSummary result = clip_to_domain(bratu.distributed(), bratu.split_domain(extra), split,
                                            clip_options());
  expect_same_summary(result, expected);
  expect_same_mesh(split, serial, bratu.space());
}

// A stop request seen by one rank stops every rank at the same projection (the ranks agree on
// it by a reduction), and the faces left are cut by dropping what lies outside them.
TEST(DistributedClipping, AStopRequestOnOneRankStopsEveryRankWhereOneProcessStops) {
  const SplitBratu bratu;
  const Domain extra = smaller_domain(bratu.n());
  constexpr int kPollsBeforeStop = 5;
  int serial_polls = 0;
  ClipOptions options = clip_options();
  options.stop_requested = [&] { return ++serial_polls > kPollsBeforeStop; };
  TriangleMesh serial = bratu.covering();
  const ClipSummary expected = clip_to_domain(bratu.serial(), bratu.domain(extra), serial, options);
  EXPECT_TRUE(expected.interrupted);

  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  int polls = 0;
  options.stop_requested = [&] { return rank == 0 && ++polls > kPollsBeforeStop; };
  TriangleMesh split = bratu.split(bratu.covering());
  const ClipSummary result =
      clip_to_domain(bratu.distributed(), bratu.split_domain(extra), split, options);
  expect_same_summary(result, expected);
  expect_same_mesh(split, serial, bratu.space());
}

// Ears cut off the clipped covering's boundary (a triangle with a boundary edge and its third
// vertex inside S) leave notches, which are closed again as in one process.
TEST(DistributedBoundaryNotches, ASplitMeshHasItsNotchesClosedAsInOneProcess) {
  const SplitBratu bratu;
  const TriangleMesh& covering = bratu.covering();
  const MeshTopology topology(covering);
  std::vector<bool> on_boundary(covering.vertex_count(), false);
  for (int e : topology.boundary_edges()) {
    on_boundary[topology.edge(e)[0]] = on_boundary[topology.edge(e)[1]] = true;
  }
  // Up to three ears far apart (no shared vertex), each one boundary edge and an inner apex.
  std::vector<bool> keep(covering.triangle_count(), true);
  std::vector<bool> used(covering.vertex_count(), false);
  int removed = 0;
  for (int e : topology.boundary_edges()) {
    const int t = topology.edge_triangles(e)[0];
    const Triangle& triangle = covering.triangle(t);
    int inner = 0;
    bool is_free = true;
    for (int v : triangle) {
      inner += on_boundary[v] ? 0 : 1;
      is_free = is_free && !used[v];
    }
    if (inner != 1 || !is_free || removed == 3) {
      continue;
    }
    for (int v : triangle) {
      used[v] = true;
      for (int w : triangle) {
        used[w] = true;
      }
    }
    keep[t] = false;
    ++removed;
  }
  ASSERT_EQ(removed, 3);
  TriangleMesh notched = covering;
  notched.keep_triangles(keep);

  TriangleMesh serial = notched;
  const NotchClosing expected =
      close_boundary_notches(bratu.serial(), bratu.domain(), serial, 5.0 * kStep);
  EXPECT_GT(expected.added_triangles, 0);

  TriangleMesh split = bratu.split(notched);
  const NotchClosing result =
      close_boundary_notches(bratu.distributed(), bratu.split_domain(), split, 5.0 * kStep);
  EXPECT_EQ(result.added_triangles, expected.added_triangles);
  expect_same_mesh(split, serial, bratu.space());
}

// Makes `attempts` random swaps that check_edge_swap allows, whatever they do to the shape, so
// that the improvement has something to do.
void scramble(TriangleMesh& mesh, const ImplicitProblem& problem, int attempts) {
  std::mt19937 random(7);
  for (int i = 0; i < attempts; ++i) {
    const int t = static_cast<int>(random() % static_cast<unsigned>(mesh.triangle_count()));
    const int k = static_cast<int>(random() % 3);
    const Triangle triangle = mesh.triangle(t);
    swap_edge(mesh, problem, triangle[k], triangle[(k + 1) % 3]);
  }
}

void expect_same_swaps(const ImprovementSummary& split, const ImprovementSummary& serial) {
  EXPECT_EQ(split.swaps, serial.swaps);
  EXPECT_EQ(split.sweeps, serial.sweeps);
  EXPECT_EQ(split.converged, serial.converged);
  EXPECT_EQ(split.interrupted, serial.interrupted);
  EXPECT_EQ(split.interior_edges, serial.interior_edges);
  EXPECT_EQ(split.rejected_non_convex, serial.rejected_non_convex);
  EXPECT_EQ(split.rejected_existing_edge, serial.rejected_existing_edge);
  EXPECT_EQ(split.rejected_projection_failed, serial.rejected_projection_failed);
  EXPECT_NEAR(split.min_angle_degrees_before, serial.min_angle_degrees_before, 1e-9);
  EXPECT_NEAR(split.min_angle_degrees_after, serial.min_angle_degrees_after, 1e-9);
  EXPECT_EQ(split.fraction_angles_below_30_after, serial.fraction_angles_below_30_after);
}

// The swaps after clipping (the angle criterion, as run_covering makes them) on a clipped
// covering, and the angle and normal criteria on one whose edges were first swapped at random.
// (The distance criterion projects two midpoints per edge: too slow for the 2-rank run here.)
TEST(DistributedEdgeSwaps, ASplitMeshGetsTheSameSwapsAsInOneProcess) {
  const SplitBratu bratu;
  TriangleMesh clipped = bratu.covering();
  clip_to_domain(bratu.serial(), bratu.domain(smaller_domain(bratu.n())), clipped,
                 clip_options());
  TriangleMesh scrambled = clipped;
  scramble(scrambled, bratu.serial(), 60);
  struct Case {
    ImprovementCriterion criterion;
    const TriangleMesh* start;
  };
  for (const Case& run : {Case{ImprovementCriterion::MaxMinAngle, &clipped},
                          Case{ImprovementCriterion::MaxMinAngle, &scrambled},
                          Case{ImprovementCriterion::NormalAngle, &scrambled}}) {
    SCOPED_TRACE(std::string(to_string(run.criterion)) +
                 (run.start == &clipped ? " after clipping" : " after scrambling"));
    ImprovementOptions options;
    options.criterion = run.criterion;
    TriangleMesh serial = *run.start;
    const ImprovementSummary expected = improve_by_edge_swaps(serial, bratu.serial(), options);
    EXPECT_GT(expected.swaps, 0);
    TriangleMesh split = bratu.split(*run.start);
    const ImprovementSummary result = improve_by_edge_swaps(split, bratu.distributed(), options);
    expect_same_swaps(result, expected);
    expect_same_mesh(split, serial, bratu.space());
  }
}

}  // namespace
}  // namespace tessera::petsc
