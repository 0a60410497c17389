// SPDX-License-Identifier: MIT
// Discretised PDEs (issue 9): the work per vertex, counted in factorisations and Jacobian
// evaluations (deterministic, so bounded here; timings live in bench/), vertices on M, and a
// surface that does not depend on the grid.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "tessera/core/process_memory.h"
#include "tessera/core/scaled_problem.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/methods/atlas/atlas.h"
#include "tessera/methods/covering_methods.h"
#include "tessera/problems/catalogue.h"

namespace {

tessera::CoveringResult cover(const tessera::ProblemSetup& setup, const std::string& method,
                              const tessera::MethodSettings& settings = {}) {
  return tessera::cover(setup, tessera::find_covering_method(method), settings);
}

double largest_residual(const tessera::TriangleMesh& mesh, const tessera::ImplicitProblem& F) {
  Eigen::VectorXd value(F.equation_count());
  double largest = 0.0;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    F.evaluate(mesh.point(v), value);
    largest = std::max(largest, value.norm());
  }
  return largest;
}

struct PerVertex {
  double factorisations;
  double jacobians;
};

PerVertex per_vertex(const tessera::CoveringSummary& summary) {
  const double V = summary.vertex_count;
  return {summary.factorisations / V, summary.jacobian_evaluations / V};
}

// The target is 2 factorisations and 4 Jacobians per vertex of the final mesh. The atlas
// meets it on bvp (1.61 and 2.8 measured), the front too (1.11 and 3.07: one factorisation per
// processed vertex, the tangents of new vertices by the chord from their creator's); the bounds hold
// that, so that a change that spends more fails here. Evaluations of F (the chord's steps)
// are bounded too: 40 per vertex for the atlas (each distance bound takes at least three chord
// steps: θ is trusted from two ratios), 6 for the front.
TEST(LargeN, AtlasWorkPerVertexIsBounded) {
  const auto setup = tessera::make_catalogue_problem("bvp:points=60");
  const auto result = cover(setup, "atlas");
  ASSERT_TRUE(result.summary.is_complete()) << result.summary.message;
  const PerVertex work = per_vertex(result.summary);
  EXPECT_LE(work.factorisations, 1.7);
  EXPECT_LE(work.jacobians, 3.0);
  EXPECT_LE(result.summary.function_evaluations, 42.0 * result.summary.vertex_count);
  // The summary splits the work by step, and the steps add up to the whole.
  tessera::WorkCounts total;
  for (const auto& phase : result.summary.work_by_phase) {
    total += phase.counts;
  }
  EXPECT_EQ(total.factorisations, result.summary.factorisations);
  EXPECT_EQ(total.jacobian_evaluations, result.summary.jacobian_evaluations);
  EXPECT_EQ(total.function_evaluations, result.summary.function_evaluations);
  EXPECT_EQ(total.solves, result.summary.solves);
  // Every factorisation is used: a projection solves at least once with it.
  EXPECT_GT(result.summary.solves, result.summary.factorisations);
  // It samples its resident memory (between stages, every 64 charts of the atlas) and reports
  // the largest sample, and the largest less the atlas's open boundary at that moment: the
  // figure issue 9 bounds. Where the system tells (Linux), both are there and ordered.
  if (tessera::resident_bytes() > 0) {
    EXPECT_GT(result.summary.resident_beyond_boundary_peak_bytes, 0.0);
    EXPECT_LE(result.summary.resident_beyond_boundary_peak_bytes,
              result.summary.resident_peak_bytes);
  }
}

// The 2-D problem: a larger stencil and a surface that meets the box on more faces (more
// clipping). Its LU fills in (nnz(L + U) about twice nnz(A)), so charts share factorisations
// (issue 30): measured 0.64 factorisations per vertex at N = 8 (0.86 before the steps after the
// build and the atlas's lenders shared too) and 4.11 Jacobians, against 1.78 and 3.56 each chart
// factoring its own (a
// borrowed chart evaluates DF for its tangent iteration, and one whose iteration does not
// converge evaluates it again to factor).
TEST(LargeN, AtlasWorkPerVertexIsBoundedOnTheSquare) {
  const auto setup = tessera::make_catalogue_problem("bratu2d:N=8");
  const auto result = cover(setup, "atlas");
  ASSERT_TRUE(result.summary.is_complete()) << result.summary.message;
  const PerVertex work = per_vertex(result.summary);
  EXPECT_LE(work.factorisations, 0.7);
  EXPECT_LE(work.jacobians, 4.3);  // 4.11: a borrow that does not converge costs a DF
  EXPECT_GT(result.summary.borrowed_factorisations, result.summary.charts / 2);
  // The steps after the build visit points along M and borrow from the nearest kept
  // factorisation (issue 30, second step): clipping with its swaps, the tolerance check and
  // validation factored 0.505 per vertex when each point factored or borrowed from the last one
  // only, 0.344 now.
  long after_build = 0;
  for (const auto& phase : result.summary.work_by_phase) {
    if (phase.phase == "clip" || phase.phase == "refine" || phase.phase == "validate") {
      after_build += phase.counts.factorisations;
    }
  }
  EXPECT_LE(after_build, 0.4 * result.summary.vertex_count);
  // Where factorisations are shared, solves are the rest of the cost: 73 per vertex measured
  // (37 in the build: tangent iterations, chords from borrowed factorisations, radius probes).
  EXPECT_LE(result.summary.solves, 80 * result.summary.vertex_count);
}

// Shared factorisations change the work, not what is covered: without them the same region
// gets a mesh of nearly the same size (the radii are measured from other chords), both within
// the tolerance and valid, and the factorisations per vertex go back to one per chart and more.
TEST(LargeN, SharedFactorisationsChangeTheWorkNotTheCovering) {
  const auto setup = tessera::make_catalogue_problem("bratu2d:N=8");
  tessera::AtlasOptions options;
  options.step = setup.suggested_step;
  options.tolerance = 0.01;
  const auto shared = tessera::cover_by_atlas(*setup.problem, setup.start, setup.domain, options);
  options.share_factorisations = false;
  const auto own = tessera::cover_by_atlas(*setup.problem, setup.start, setup.domain, options);
  ASSERT_TRUE(shared.summary.is_complete()) << shared.summary.message;
  ASSERT_TRUE(own.summary.is_complete()) << own.summary.message;
  EXPECT_EQ(own.summary.borrowed_factorisations, 0);
  EXPECT_GT(shared.summary.borrowed_factorisations, 0);
  EXPECT_NEAR(shared.mesh.vertex_count(), own.mesh.vertex_count(), 0.05 * own.mesh.vertex_count());
  EXPECT_LT(per_vertex(shared.summary).factorisations,
            0.75 * per_vertex(own.summary).factorisations);
  for (const auto* result : {&shared, &own}) {
    EXPECT_LE(result->summary.max_sampled_distance, options.tolerance);
    EXPECT_LE(largest_residual(result->mesh, *setup.problem), 1e-9);
    EXPECT_TRUE(tessera::validate(result->mesh, *setup.problem, setup.domain).is_valid());
  }
}

TEST(LargeN, FrontWorkPerVertexIsBounded) {
  const auto setup = tessera::make_catalogue_problem("bvp:points=60");
  const auto result = cover(setup, "front");
  ASSERT_TRUE(result.summary.is_complete()) << result.summary.message;
  const PerVertex work = per_vertex(result.summary);
  EXPECT_LE(work.factorisations, 1.3);
  EXPECT_LE(work.jacobians, 3.1);
  EXPECT_LE(result.summary.function_evaluations, 6.5 * result.summary.vertex_count);
}

// The atlas keeps the factorisations of the charts waiting in its queue within a memory budget;
// over it, the newest are dropped and factored again when their turn comes. The covering is the
// same (the same charts, in the same order), it only costs more factorisations, and says why.
TEST(LargeN, AtlasFactorisationBudgetChangesTheWorkNotTheMesh) {
  const auto setup = tessera::make_catalogue_problem("bvp:points=40");
  tessera::AtlasOptions options;
  options.step = 2.0 * setup.suggested_step;
  options.tolerance = 0.01;
  const auto unbounded = tessera::cover_by_atlas(*setup.problem, setup.start, setup.domain, options);
  options.max_factorisation_bytes = 1.0;  // keeps only the chart being processed
  const auto bounded = tessera::cover_by_atlas(*setup.problem, setup.start, setup.domain, options);
  ASSERT_TRUE(unbounded.summary.is_complete()) << unbounded.summary.message;
  ASSERT_TRUE(bounded.summary.is_complete()) << bounded.summary.message;
  EXPECT_EQ(bounded.summary.charts, unbounded.summary.charts);
  ASSERT_EQ(bounded.mesh.vertex_count(), unbounded.mesh.vertex_count());
  EXPECT_EQ(bounded.mesh.triangles(), unbounded.mesh.triangles());
  EXPECT_LT((bounded.mesh.points() - unbounded.mesh.points()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_GT(bounded.summary.factorisations, unbounded.summary.factorisations);
  // The open boundary's memory (kept factorisations and the bases of charts not retired) is
  // reported, and the budget lowers it: at least one tangent basis (2n numbers) is held.
  const double basis_bytes = 16.0 * setup.problem->ambient_dimension();
  EXPECT_GE(bounded.summary.boundary_peak_bytes, basis_bytes);
  EXPECT_LT(bounded.summary.boundary_peak_bytes, unbounded.summary.boundary_peak_bytes);
  const auto& notes = bounded.summary.notes;
  EXPECT_TRUE(std::any_of(notes.begin(), notes.end(), [](const std::string& note) {
    return note.find("max_factorisation_bytes") != std::string::npos;
  }));
}

TEST(LargeN, BratuSquareVerticesLieOnM) {
  const auto setup = tessera::make_catalogue_problem("bratu2d:N=6");
  tessera::MethodSettings settings;
  settings.tolerance = 0.01;
  const auto result = cover(setup, "atlas", settings);
  ASSERT_TRUE(result.summary.is_complete()) << result.summary.message;
  EXPECT_LE(largest_residual(result.mesh, *setup.problem), 1e-9);
  EXPECT_LE(result.summary.max_sampled_distance, 0.01);
}

// The image of a vertex in (λ, ε, ‖u‖) with the metric's norm of the grid function u, the
// discrete L² norm: how these surfaces are plotted, and 1-Lipschitz in the metric.
Eigen::Vector3d image(const tessera::ImplicitProblem& problem, const Eigen::VectorXd& x) {
  const Eigen::VectorXd weights = tessera::metric_weights(problem);
  const int N = problem.ambient_dimension() - 2;
  return {x(N), x(N + 1), weights.head(N).cwiseProduct(x.head(N)).norm()};
}

// Distance from p to the triangle abc in R³ (Ericson, Real-Time Collision Detection, 5.1.5).
double distance_to_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  }
  const double denominator = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denominator) + ac * (vc * denominator))).norm();
}

// Refining the grid changes neither the surface the user sees nor the work: in the metric
// (u weighted by √h) lengths on M do not grow with N. The images of the two meshes agree to
// the tolerance plus the discretisation's own difference between the grids (O(h²)).
TEST(LargeN, SurfaceDoesNotDependOnTheGrid) {
  tessera::MethodSettings settings;
  settings.tolerance = 0.01;
  const auto coarse_setup = tessera::make_catalogue_problem("bvp:points=100");
  const auto fine_setup = tessera::make_catalogue_problem("bvp:points=400");
  const auto coarse = cover(coarse_setup, "atlas", settings);
  const auto fine = cover(fine_setup, "atlas", settings);
  ASSERT_TRUE(coarse.summary.is_complete()) << coarse.summary.message;
  ASSERT_TRUE(fine.summary.is_complete()) << fine.summary.message;
  const double ratio =
      static_cast<double>(fine.mesh.vertex_count()) / coarse.mesh.vertex_count();
  EXPECT_GT(ratio, 0.8);
  EXPECT_LT(ratio, 1.25);
  // Every 10th vertex of each image against the other image's triangles.
  const auto largest_gap = [](const tessera::CoveringResult& from,
                              const tessera::ImplicitProblem& from_problem,
                              const tessera::CoveringResult& to,
                              const tessera::ImplicitProblem& to_problem) {
    std::vector<Eigen::Vector3d> points(to.mesh.vertex_count());
    for (int v = 0; v < to.mesh.vertex_count(); ++v) {
      points[v] = image(to_problem, to.mesh.point(v));
    }
    double largest = 0.0;
    for (int v = 0; v < from.mesh.vertex_count(); v += 10) {
      const Eigen::Vector3d p = image(from_problem, from.mesh.point(v));
      double nearest = std::numeric_limits<double>::infinity();
      for (const auto& t : to.mesh.triangles()) {
        nearest = std::min(nearest, distance_to_triangle(p, points[t[0]], points[t[1]],
                                                         points[t[2]]));
      }
      largest = std::max(largest, nearest);
    }
    return largest;
  };
  const double gap = std::max(largest_gap(coarse, *coarse_setup.problem, fine, *fine_setup.problem),
                              largest_gap(fine, *fine_setup.problem, coarse, *coarse_setup.problem));
  RecordProperty("image_gap", std::to_string(gap));
  EXPECT_LE(gap, settings.tolerance) << "largest distance between the (lambda, epsilon, |u|) images";
}

// The same problem seen as dense: the report then measures by Gauss–Newton (P) everywhere.
class DenseView final : public tessera::ImplicitProblem {
 public:
  explicit DenseView(const tessera::ImplicitProblem& inner) : inner_(inner) {}
  int ambient_dimension() const override { return inner_.ambient_dimension(); }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override {
    inner_.evaluate(x, F);
  }
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override {
    inner_.jacobian(x, J);
  }
  std::vector<tessera::CoordinateBlock> coordinate_blocks() const override {
    return inner_.coordinate_blocks();
  }

 private:
  const tessera::ImplicitProblem& inner_;
};

// The report measures a sparse problem's centroids and midpoints by the chord from a corner's
// factorisation (solves, not Gauss–Newton's factorisations); both offsets are normal to M up to
// second order, so the distances agree with Gauss–Newton's to a small fraction of themselves.
TEST(LargeN, ReportDistancesByTheCornerChordAgreeWithGaussNewton) {
  const auto setup = tessera::make_catalogue_problem("bvp:points=60");
  tessera::MethodSettings settings;
  settings.step = 0.3;  // 1500 vertices
  const auto result = cover(setup, "front", settings);
  ASSERT_TRUE(result.summary.is_complete()) << result.summary.message;
  const tessera::MeshQuality chord = tessera::measure_quality(result.mesh, *setup.problem);
  const tessera::MeshQuality newton =
      tessera::measure_quality(result.mesh, DenseView(*setup.problem));
  EXPECT_EQ(chord.failed_projections, 0);
  EXPECT_EQ(chord.centroid_distance.count, result.mesh.triangle_count());
  EXPECT_GT(newton.centroid_distance.max, 0.0);
  EXPECT_NEAR(chord.centroid_distance.max, newton.centroid_distance.max,
              0.02 * newton.centroid_distance.max);
  EXPECT_NEAR(chord.midpoint_distance.max, newton.midpoint_distance.max,
              0.02 * newton.midpoint_distance.max);
  EXPECT_NEAR(chord.centroid_distance.mean, newton.centroid_distance.mean,
              0.02 * newton.centroid_distance.mean);
}

}  // namespace
