// SPDX-License-Identifier: MIT
// Acceptance tests of method `bezier` (Hohmann 1991): every paper example is covered by a valid
// mesh of the right topology on M; the step control reacts to the tolerance; the cubic patches
// interpolate vertices and tangent planes, join continuously and approximate M to higher order
// than the flat triangles; a run that cannot go on returns a valid partial mesh and says where.
#include "tessera/methods/bezier/bezier_continuation.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "support/test_support.h"
#include "tessera/core/corrector.h"
#include "tessera/core/error.h"
#include "tessera/geometry/bezier_surface.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/problems/catalogue.h"
#include "tessera/problems/examples.h"

namespace tessera {
namespace {

// Every vertex ends a Gauss–Newton run stopped at ‖F‖ ≤ 1e-9 (corrector default); 10× leaves
// room for rounding in F itself.
const double kOnManifoldTolerance = 10.0 * CorrectorOptions{}.residual_tolerance;

struct BezierRun {
  ProblemSetup setup;
  CoveringResult result;
};

// Covers a catalogue problem; the initial step is the problem's suggestion unless `fixed_step`.
BezierRun run_bezier(const std::string& specification, BezierOptions options = {},
                     bool fixed_step = false) {
  BezierRun run;
  run.setup = make_catalogue_problem(specification);
  if (!fixed_step) {
    options.step = run.setup.suggested_step;
  }
  run.result = triangulate_by_bezier_continuation(*run.setup.problem, run.setup.start,
                                                  run.setup.domain, options);
  return run;
}

double max_residual(const TriangleMesh& mesh, const ImplicitProblem& problem) {
  Eigen::VectorXd F(problem.equation_count());
  double worst = 0.0;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    problem.evaluate(mesh.point(v), F);
    worst = std::max(worst, F.norm());
  }
  return worst;
}

void expect_invariants(const BezierRun& run, const std::string& name) {
  const TriangleMesh& mesh = run.result.mesh;
  const MeshValidation validation = validate(mesh);
  EXPECT_TRUE(validation.is_valid()) << name << ":\n" << validation.report();
  EXPECT_EQ(validation.non_manifold_edge_count, 0) << name;
  EXPECT_EQ(validation.non_manifold_vertex_count, 0) << name;
  EXPECT_TRUE(validation.is_orientable) << name;
  EXPECT_EQ(validation.component_count, 1) << name;
  EXPECT_LE(max_residual(mesh, *run.setup.problem), kOnManifoldTolerance) << name;
  EXPECT_EQ(static_cast<int>(run.result.patches.size()), mesh.triangle_count()) << name;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    ASSERT_TRUE(run.setup.domain.contains(mesh.point(v), 1e-9)) << name << " vertex " << v;
  }
}

TEST(BezierContinuation, PaperExamplesAreValidWithTheRightEulerCharacteristic) {
  // Hohmann's examples 1–4 with the catalogue's start points (torus R = 1, r = 0.4 from
  // (−0.4, 1, 0.1); the pleat in [−1.5, 1.5]³ from (0.1, 0.1, 0.1)). CSTR: see below.
  for (const std::string name : {"sphere", "equipotential", "whitney_pleat", "torus"}) {
    const BezierRun run = run_bezier(name);
    ASSERT_TRUE(run.result.summary.is_complete()) << name << ": " << run.result.summary.message;
    expect_invariants(run, name);
    ASSERT_TRUE(run.setup.expected_euler_characteristic.has_value());
    EXPECT_EQ(validate(run.result.mesh).euler_characteristic,
              *run.setup.expected_euler_characteristic)
        << name;
    const bool closed = name != "whitney_pleat";
    EXPECT_EQ(validate(run.result.mesh).boundary_edge_count == 0, closed) << name;
    if (!closed) {
      // Box restriction (example 3): the boundary of a completed run lies on M ∩ ∂S — every
      // vertex of a boundary edge is on a face, computed by Gauss–Newton on M ∩ face.
      const TriangleMesh& mesh = run.result.mesh;
      std::map<std::pair<int, int>, int> directed;
      for (const Triangle& t : mesh.triangles()) {
        for (int c = 0; c < 3; ++c) {
          directed[{t[c], t[(c + 1) % 3]}] += 1;
        }
      }
      int boundary_vertices = 0;
      for (const auto& [edge, count] : directed) {
        if (directed.count({edge.second, edge.first}) == 0) {
          for (int v : {edge.first, edge.second}) {
            const double distance =
                run.setup.domain.boundary_distance(mesh.point(v)).signed_distance;
            EXPECT_LE(std::abs(distance), 1e-9) << name << " boundary vertex " << v;
            ++boundary_vertices;
          }
        }
      }
      EXPECT_GT(boundary_vertices, 0);
    }
  }
}

TEST(BezierContinuation, SphereIsDominatedByTheTangentAngleRestriction) {
  // Paper, example 1: on the sphere the step is limited by α_min = 0.8, i.e. edges of at most
  // about arccos(0.8) = 0.64 rad; Hohmann reports 60 points. The flat sphere F = |y|² − 1 has
  // θ ≈ 0, so the θ control alone would grow the steps to the maximum.
  const BezierRun run = run_bezier("sphere");
  ASSERT_TRUE(run.result.summary.is_complete());
  const MeshQuality shape = measure_shape(run.result.mesh);
  EXPECT_LE(shape.max_edge_length, 1.0);  // a chord of at most ≈ 2 × 0.64 rad, connections included
  EXPECT_GT(run.result.mesh.vertex_count(), 40);
  EXPECT_LT(run.result.mesh.vertex_count(), 90);
}

TEST(BezierContinuation, HalvingTheToleranceGivesMoreSmallerTrianglesWhereThePleatCurves) {
  // The tolerance bounds the distance of new edges' midpoints to M, which grows like κ_n h²/8
  // (κ_n the normal curvature along the edge): at half the tolerance the edges shrink by about
  // √2 and the count about doubles. The pleat μ = x³ − λx is curved near the cusp point (the
  // second fundamental form is 6x dx² − 2 dx dλ over |∇μ|-scaled metric, of order 1 at the
  // origin) and nearly flat far from it, where |∇μ| ≈ 3x² is large: the edges near the cusp
  // must be the shorter ones.
  std::vector<int> counts;
  std::vector<double> near_means, far_means;
  for (double tolerance : {0.01, 0.005}) {
    BezierOptions options;
    options.tolerance = tolerance;
    const BezierRun run = run_bezier("whitney_pleat", options);
    ASSERT_TRUE(run.result.summary.is_complete()) << run.result.summary.message;
    expect_invariants(run, "whitney_pleat");
    const TriangleMesh& mesh = run.result.mesh;
    double near = 0, far = 0;
    int near_count = 0, far_count = 0;
    for (const Triangle& t : mesh.triangles()) {
      for (int c = 0; c < 3; ++c) {
        const Eigen::VectorXd a = mesh.point(t[c]), b = mesh.point(t[(c + 1) % 3]);
        const Eigen::VectorXd m = 0.5 * (a + b);
        if (m.norm() < 0.6) {
          near += (a - b).norm();
          ++near_count;
        } else if (std::abs(m(0)) > 1.0) {
          far += (a - b).norm();
          ++far_count;
        }
      }
    }
    ASSERT_GT(near_count, 0);
    ASSERT_GT(far_count, 0);
    counts.push_back(mesh.triangle_count());
    near_means.push_back(near / near_count);
    far_means.push_back(far / far_count);
    EXPECT_LT(near_means.back(), 0.8 * far_means.back()) << "tolerance " << tolerance;
  }
  EXPECT_GT(counts[1], 1.4 * counts[0]);
  EXPECT_LT(near_means[1], 0.85 * near_means[0]);
}

TEST(BezierContinuation, HalvingTheToleranceDoublesTheTrianglesOnTheTorus) {
  std::vector<int> counts;
  for (double tolerance : {0.01, 0.005}) {
    BezierOptions options;
    options.tolerance = tolerance;
    const BezierRun run = run_bezier("torus", options);
    ASSERT_TRUE(run.result.summary.is_complete()) << run.result.summary.message;
    expect_invariants(run, "torus");
    EXPECT_EQ(validate(run.result.mesh).euler_characteristic, 0);
    counts.push_back(run.result.mesh.triangle_count());
  }
  EXPECT_GT(counts[1], 1.6 * counts[0]);
  EXPECT_LT(counts[1], 2.5 * counts[0]);
}

TEST(BezierContinuation, ToleranceFarBelowTheInitialStepShrinksTheInitialTriangle) {
  // Regression: with ε = 0.002 and the sphere's initial step 0.3 (flat-edge distance ≈ 0.011),
  // the initial triangle's edges were too long for any later edge to meet ε, and the run
  // stopped at the first edge. Every edge is at least half as long as the edge it grows from.
  BezierOptions options;
  options.tolerance = 0.002;
  const BezierRun run = run_bezier("sphere", options);
  ASSERT_TRUE(run.result.summary.is_complete()) << run.result.summary.message;
  expect_invariants(run, "sphere");
  const MeshQuality quality = measure_quality(run.result.mesh, *run.setup.problem);
  EXPECT_LE(quality.midpoint_distance.max, 2.0 * options.tolerance);
}

TEST(BezierContinuation, PatchesInterpolateVerticesAndTangentPlanes) {
  const BezierRun run = run_bezier("torus");
  ASSERT_TRUE(run.result.summary.is_complete());
  const TriangleMesh& mesh = run.result.mesh;
  Eigen::MatrixXd J(1, 3);
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle& tri = mesh.triangle(t);
    const CubicBezierPatch& patch = run.result.patches[t];
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d corner = Eigen::Vector3d::Unit(i);
      EXPECT_EQ((patch.evaluate(corner) - mesh.point(tri[i])).norm(), 0.0);
      run.setup.problem->jacobian(mesh.point(tri[i]), J);
      const Eigen::VectorXd normal = J.row(0).transpose().normalized();
      for (int j = 0; j < 3; ++j) {
        if (j == i) {
          continue;
        }
        // D_{e_j − e_i} p(e_i) lies in the tangent plane ker DF(y_i): eq. 3.4. The tangent
        // basis is that of the last Gauss–Newton iterate, at most the corrector tolerance
        // (1e-10) from y_i, so the plane is exact to about 1e-10 × curvature.
        const Eigen::VectorXd d = patch.derivative(corner, Eigen::Vector3d::Unit(j) - corner);
        EXPECT_LT(std::abs(d.dot(normal)), 1e-9 * d.norm()) << "triangle " << t;
      }
    }
  }
}

TEST(BezierContinuation, CubicSurfaceIsContinuousAndRefinesToAValidMesh) {
  for (const std::string name : {"sphere", "whitney_pleat"}) {
    const BezierRun run = run_bezier(name);
    ASSERT_TRUE(run.result.summary.is_complete());
    // The edge curve of eq. 3.5 depends only on the edge's end data: both patches agree.
    EXPECT_LT(max_edge_mismatch(run.result.mesh, run.result.patches), 1e-14) << name;
    const TriangleMesh refined = refine_bezier_surface(run.result.mesh, run.result.patches, 4);
    const MeshValidation validation = validate(refined);
    EXPECT_TRUE(validation.is_valid()) << validation.report();
    EXPECT_EQ(validation.euler_characteristic, validate(run.result.mesh).euler_characteristic);
    EXPECT_EQ(refined.triangle_count(), 16 * run.result.mesh.triangle_count());
  }
}

// Largest distance to the unit sphere of the cubic surface (sampled on a 6×6 subdivision) and
// of the flat triangles (their centroids and edge midpoints), for a run with fixed step h.
struct SphereErrors {
  double h, cubic, flat;
};
SphereErrors sphere_errors(double h, double edge_length_factor) {
  BezierOptions options;
  options.step = h;
  options.max_step = h;  // fixed steps (the sphere's θ ≈ 0 would otherwise grow them)
  options.edge_length_factor = edge_length_factor;
  const BezierRun run = run_bezier("sphere", options, /*fixed_step=*/true);
  EXPECT_TRUE(run.result.summary.is_complete()) << run.result.summary.message;
  const TriangleMesh refined = refine_bezier_surface(run.result.mesh, run.result.patches, 6);
  SphereErrors errors{h, 0.0, 0.0};
  for (int v = 0; v < refined.vertex_count(); ++v) {
    errors.cubic = std::max(errors.cubic, std::abs(refined.point(v).norm() - 1.0));
  }
  const TriangleMesh flat = refine_bezier_surface(
      run.result.mesh,
      [&] {
        // Flat patches: the linear interpolant written as a cubic (b_α = Σ α_i y_i / 3).
        std::vector<CubicBezierPatch> linear;
        for (const Triangle& t : run.result.mesh.triangles()) {
          Eigen::MatrixXd b(3, 10);
          for (int c = 0; c < 10; ++c) {
            const auto& alpha = CubicBezierPatch::multi_indices()[c];
            b.col(c) =
                (alpha[0] * run.result.mesh.point(t[0]) + alpha[1] * run.result.mesh.point(t[1]) +
                 alpha[2] * run.result.mesh.point(t[2])) /
                3.0;
          }
          linear.emplace_back(b);
        }
        return linear;
      }(),
      6);
  for (int v = 0; v < flat.vertex_count(); ++v) {
    errors.flat = std::max(errors.flat, std::abs(flat.point(v).norm() - 1.0));
  }
  return errors;
}

TEST(BezierContinuation, CubicSurfaceConvergesFasterThanTheFlatTriangles) {
  // Measured (docs/algorithms/bezier.md): with l_ij = ‖y_j − y_i‖ the cubic surface's largest
  // distance to the sphere falls like h^3.8 (the edge curves match circles to fourth order), the
  // flat triangles' like h^1.8. The paper's l_ij = 1.2‖y_j − y_i‖ overshoots every edge curve by
  // 0.025 L² and is, at h = 0.05, no closer to M than the flat triangles.
  std::vector<double> h, cubic, flat, cubic_paper;
  for (double step : {0.2, 0.1, 0.05}) {
    const SphereErrors errors = sphere_errors(step, 1.0);
    h.push_back(step);
    cubic.push_back(errors.cubic);
    flat.push_back(errors.flat);
    cubic_paper.push_back(sphere_errors(step, 1.2).cubic);

    EXPECT_LT(errors.cubic, 0.05 * errors.flat) << "h = " << step;
  }
  EXPECT_NEAR(testing::observed_order(h, flat), 2.0, 0.3);
  EXPECT_GT(testing::observed_order(h, cubic), 3.5);
  EXPECT_LT(testing::observed_order(h, cubic_paper), 2.5);
  EXPECT_GT(cubic_paper.back(), 100.0 * cubic.back());
}

// The double cone x² + y² − z² = 0: M is singular at the apex, where DF = 0.
class DoubleCone final : public ImplicitProblem {
 public:
  int ambient_dimension() const override { return 3; }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override {
    F(0) = x(0) * x(0) + x(1) * x(1) - x(2) * x(2);
  }
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override {
    J << 2 * x(0), 2 * x(1), -2 * x(2);
  }
};

TEST(BezierContinuation, StopsAtTheApexOfAConeWithAValidPartialMeshAndSaysWhere) {
  DoubleCone cone;
  Eigen::VectorXd start(3);
  start << 1.0, 0.0, 1.0;
  // The domain z ≥ −2 keeps the lower nappe bounded once the method crosses the apex.
  Domain domain(3);
  Eigen::VectorXd normal(3), point(3);
  normal << 0, 0, 1;
  point << 0, 0, -2;
  domain.add_half_space(normal, point, "z >= -2");
  normal << 0, 0, -1;
  point << 0, 0, 2;
  domain.add_half_space(normal, point, "z <= 2");
  BezierOptions options;
  options.step = 0.2;
  const CoveringResult result = triangulate_by_bezier_continuation(cone, start, domain, options);
  ASSERT_FALSE(result.summary.is_complete());
  EXPECT_NE(result.summary.message.find("("), std::string::npos) << result.summary.message;
  EXPECT_TRUE(validate(result.mesh).is_valid()) << validate(result.mesh).report();
  EXPECT_GT(result.mesh.triangle_count(), 10);
  EXPECT_EQ(static_cast<int>(result.patches.size()), result.mesh.triangle_count());
}

TEST(BezierContinuation, VertexLimitReturnsAValidPartialMesh) {
  BezierOptions options;
  options.max_vertices = 40;
  const BezierRun run = run_bezier("torus", options);
  EXPECT_EQ(run.result.summary.termination, CoveringTermination::VertexLimit);
  EXPECT_TRUE(validate(run.result.mesh).is_valid()) << validate(run.result.mesh).report();
  EXPECT_LE(run.result.mesh.vertex_count(), 40);
}

TEST(BezierContinuation, StirredTankReactorInR4GivesAValidMesh) {
  // Example 5 in R⁴ from (0.1, 0.1, 0.1, 5). In the catalogue's box the θ control shrinks the
  // steps where exp(x2) is large (docs/algorithms/bezier.md); a vertex limit keeps this fast.
  BezierOptions options;
  options.max_vertices = 1500;
  const BezierRun run = run_bezier("cstr", options);
  expect_invariants(run, "cstr");
  EXPECT_GT(run.result.mesh.triangle_count(), 100);
}

TEST(BezierContinuation, StirredTankReactorCompletesWithAMaximumStep) {
  // Regression pin (measured, not a theorem): with the default maximum step 0.8 the run stops in
  // the steep corner x1 → 1, Da = 0.3 of the catalogue's box (docs/algorithms/bezier.md); with
  // max_step = 0.5 it completes with ≈ 290 points.
  BezierOptions options;
  options.max_step = 0.5;
  const BezierRun run = run_bezier("cstr", options);
  ASSERT_TRUE(run.result.summary.is_complete()) << run.result.summary.message;
  expect_invariants(run, "cstr");
  EXPECT_EQ(validate(run.result.mesh).euler_characteristic, 1);
}

TEST(BezierContinuation, DischargeBvpCompletesAtItsSuggestedStep) {
  // M ∩ S has bands narrower than the steps the θ control grows to (ε ∈ [0, 0.3] on the lower
  // sheet, where u hardly depends on ε): without holding the step to half the band's width
  // there the front folded over itself ("front collision", 174 vertices).
  const BezierRun run = run_bezier("bvp:points=100");
  ASSERT_TRUE(run.result.summary.is_complete()) << run.result.summary.message;
  expect_invariants(run, "bvp");
  EXPECT_EQ(validate(run.result.mesh).euler_characteristic, 1);
  EXPECT_GT(run.result.mesh.vertex_count(), 200);
}

TEST(BezierContinuation, Bratu2dConnectsAlongTheBoundaryOnlyWithinTwoSteps) {
  // At the ignition fold of bratu2d (N = 10, λ ≈ 6.9, near the face ε = 0) one vertex used to
  // connect to front neighbours ever farther along the face (new edges 2.1, 3.0, 3.6, 4.3, 5.1
  // with steps ≤ 0.8) until an edge too long to realise stopped the run.
  const BezierRun run = run_bezier("bratu2d:N=10");
  ASSERT_TRUE(run.result.summary.is_complete()) << run.result.summary.message;
  expect_invariants(run, "bratu2d");
  EXPECT_EQ(validate(run.result.mesh).euler_characteristic, 1);
  // Edge lengths in the metric the method works in (the u block weighted by h): the fan's
  // reached 5.1; edges grown from the steps stay near twice the largest step 0.8 (1.67 now).
  const TriangleMesh& mesh = run.result.mesh;
  const Eigen::VectorXd weights = metric_weights(*run.setup.problem);
  double longest = 0.0;
  for (const Triangle& t : mesh.triangles()) {
    for (int e = 0; e < 3; ++e) {
      const Eigen::VectorXd edge = mesh.point(t[e]) - mesh.point(t[(e + 1) % 3]);
      longest = std::max(longest, weights.cwiseProduct(edge).norm());
    }
  }
  EXPECT_LT(longest, 2.0);
}

TEST(BezierContinuation, RefusesBadOptionsNamingThem) {
  const ProblemSetup setup = make_catalogue_problem("sphere");
  BezierOptions options;
  options.min_tangent_cosine = 1.5;
  try {
    triangulate_by_bezier_continuation(*setup.problem, setup.start, setup.domain, options);
    FAIL() << "no exception";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("min_tangent_cosine = 1.5"), std::string::npos)
        << error.what();
  }
}

TEST(BezierContinuation, IsReproducible) {
  const BezierRun first = run_bezier("equipotential");
  const BezierRun second = run_bezier("equipotential");
  ASSERT_EQ(first.result.mesh.vertex_count(), second.result.mesh.vertex_count());
  EXPECT_EQ((first.result.mesh.points() - second.result.mesh.points()).norm(), 0.0);
  EXPECT_EQ(first.result.mesh.triangles(), second.result.mesh.triangles());
}

}  // namespace
}  // namespace tessera
