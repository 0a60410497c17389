// SPDX-License-Identifier: MIT
#include "tessera/core/corrector.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "tessera/core/counted_problem.h"
#include "tessera/core/domain.h"
#include "tessera/core/error.h"
#include "tessera/core/face_projection.h"
#include "tessera/core/factorisation_cache.h"
#include "tessera/core/linearization.h"
#include "tessera/problems/catalogue.h"
#include "tessera/problems/examples.h"

namespace {

// F(x) = (|x|² − 1, x3 − x0·x1 ... ): a 2-manifold in R^4 with a dense or sparse Jacobian.
class TwoEquations final : public tessera::ImplicitProblem {
 public:
  explicit TwoEquations(bool sparse) : sparse_(sparse) {}
  int ambient_dimension() const override { return 4; }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override {
    F(0) = x.squaredNorm() - 1.0;
    F(1) = x(3) - x(0) * x(1);
  }
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override {
    J.row(0) = 2.0 * x.transpose();
    J.row(1) << -x(1), -x(0), 0.0, 1.0;
  }
  bool has_sparse_jacobian() const override { return sparse_; }
  void sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                       Eigen::SparseMatrix<double>& J) const override {
    Eigen::MatrixXd dense(2, 4);
    jacobian(x, dense);
    J = dense.sparseView();
  }

 private:
  bool sparse_;
};

class ZeroOnNan final : public tessera::ImplicitProblem {
 public:
  int ambient_dimension() const override { return 3; }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>&, Eigen::Ref<Eigen::VectorXd> F) const override {
    F(0) = std::nan("");
  }
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>&, Eigen::Ref<Eigen::MatrixXd> J) const override {
    J << 1.0, 0.0, 0.0;
  }
};

class FlatAtOrigin final : public tessera::ImplicitProblem {  // F = |x|², DF(0) = 0
 public:
  int ambient_dimension() const override { return 3; }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> F) const override {
    F(0) = x.squaredNorm();
  }
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::MatrixXd> J) const override {
    J = 2.0 * x.transpose();
  }
};

Eigen::VectorXd point_on_manifold() {
  Eigen::VectorXd x(4);
  x << 0.5, 0.5, 0.0, 0.25;
  x /= x.norm();  // not exactly on M; projected in the tests
  return x;
}

}  // namespace

class LinearizationBothBackends : public ::testing::TestWithParam<bool> {};

TEST_P(LinearizationBothBackends, TangentBasisIsOrthonormalKernel) {
  TwoEquations problem(GetParam());
  tessera::Linearization linearization;
  const Eigen::VectorXd x = point_on_manifold();
  ASSERT_TRUE(linearization.factor(problem, x));
  const Eigen::MatrixXd& T = linearization.tangent_basis();
  Eigen::MatrixXd J(2, 4);
  problem.jacobian(x, J);
  EXPECT_LT((J * T).norm(), 1e-13);
  EXPECT_LT((T.transpose() * T - Eigen::Matrix2d::Identity()).norm(), 1e-13);
}

TEST_P(LinearizationBothBackends, MinimumNormSolveIsOrthogonalToKernel) {
  TwoEquations problem(GetParam());
  tessera::Linearization linearization;
  const Eigen::VectorXd x = point_on_manifold();
  ASSERT_TRUE(linearization.factor(problem, x));
  Eigen::Vector2d rhs(0.3, -0.7);
  Eigen::VectorXd dx(4);
  linearization.solve_minimum_norm(rhs, dx);
  Eigen::MatrixXd J(2, 4);
  problem.jacobian(x, J);
  EXPECT_LT((J * dx - rhs).norm(), 1e-13);
  EXPECT_LT((linearization.tangent_basis().transpose() * dx).norm(), 1e-13);
  // Equals the pseudo-inverse solution Jᵀ(JJᵀ)⁻¹r.
  const Eigen::VectorXd expected = J.transpose() * (J * J.transpose()).ldlt().solve(rhs);
  EXPECT_LT((dx - expected).norm(), 1e-13);
}

TEST_P(LinearizationBothBackends, ReferenceOrientsTheBasis) {
  TwoEquations problem(GetParam());
  tessera::Linearization a;
  tessera::Linearization b;
  const Eigen::VectorXd x = point_on_manifold();
  ASSERT_TRUE(a.factor(problem, x));
  Eigen::MatrixXd flipped = a.tangent_basis();
  flipped.col(1) *= -1.0;
  ASSERT_TRUE(b.factor(problem, x, &flipped));
  EXPECT_GT((b.tangent_basis().transpose() * flipped).determinant(), 0.0);
}

INSTANTIATE_TEST_SUITE_P(DenseAndSparse, LinearizationBothBackends, ::testing::Values(false, true));

TEST(GaussNewton, ConvergesQuadraticallyOntoM) {
  TwoEquations problem(false);
  tessera::Linearization workspace;
  Eigen::VectorXd x(4);
  x << 0.6, 0.5, 0.1, 0.2;
  const auto summary = tessera::project_gauss_newton(problem, x, {}, workspace);
  ASSERT_TRUE(summary.is_success()) << summary.brief_report();
  Eigen::Vector2d F;
  problem.evaluate(x, F);
  EXPECT_LT(F.norm(), 1e-12);
  EXPECT_LE(summary.iterations, 6);  // quadratic convergence from distance ~0.1
  EXPECT_LT(summary.contraction, 0.25);  // θ ≈ ω‖dx‖/2, small from distance 0.1
}

TEST(ChordCorrector, ProjectsOrthogonallyToTheFrozenTangentPlane) {
  TwoEquations problem(false);
  tessera::Linearization workspace;
  Eigen::VectorXd center = point_on_manifold();
  ASSERT_TRUE(tessera::project_gauss_newton(problem, center, {}, workspace).is_success());
  tessera::Linearization frozen;
  ASSERT_TRUE(frozen.factor(problem, center));
  const Eigen::MatrixXd U = frozen.tangent_basis();
  const Eigen::VectorXd predicted = center + U * Eigen::Vector2d(0.1, -0.05);
  Eigen::VectorXd x = predicted;
  const auto summary = tessera::project_chord(problem, frozen, x, {});
  ASSERT_TRUE(summary.is_success()) << summary.brief_report();
  Eigen::Vector2d F;
  problem.evaluate(x, F);
  EXPECT_LT(F.norm(), 1e-9);
  EXPECT_LT((U.transpose() * (x - predicted)).norm(), 1e-14);  // eq. (2.5)
  EXPECT_GT(summary.contraction, 0.0);  // chord: linear convergence, θ measured
}

// The bound must not lie below the distance to the point where the chord lands. On the CSTR
// surface, from one end of a long edge (a stress case), the chord's first ratio is 0.08 and its
// second 2.4: a bound trusted after one ratio claimed 0.0199 for a midpoint the chord takes to
// 0.0266 (and Gauss–Newton to 0.0273), so refinement kept an edge 1.4× over the tolerance.
TEST(ChordDistanceBound, IsNeverBelowWhereTheChordLands) {
  const tessera::ProblemSetup cstr = tessera::make_catalogue_problem("cstr");
  const tessera::ImplicitProblem& problem = *cstr.problem;
  Eigen::VectorXd a(4), b(4);
  a << 0.987633, 7.82101, 0.0320418, 11.8784;
  b << 0.998287, 7.89831, 0.216434, 11.8678;
  tessera::Linearization workspace;
  tessera::CorrectorOptions exact;
  exact.tolerance = 1e-13;
  exact.max_iterations = 80;
  exact.max_contraction = 3.0;  // follow the chord past its overshoot to where it lands
  ASSERT_TRUE(tessera::project_gauss_newton(problem, a, exact, workspace).is_success());
  ASSERT_TRUE(tessera::project_gauss_newton(problem, b, exact, workspace).is_success());
  const Eigen::VectorXd midpoint = 0.5 * (a + b);
  for (const Eigen::VectorXd& end : {a, b}) {
    tessera::Linearization frozen;
    ASSERT_TRUE(frozen.factor(problem, end));
    Eigen::VectorXd landed = midpoint;
    ASSERT_TRUE(tessera::project_chord(problem, frozen, landed, exact).is_success());
    const double bound = tessera::chord_distance_bound(problem, frozen, midpoint, 4e-4, {});
    EXPECT_GE(bound, (landed - midpoint).norm() - 4e-4);
  }
}

TEST(Corrector, NanResidualIsReportedNotThrown) {
  ZeroOnNan problem;
  tessera::Linearization workspace;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(3);
  const auto summary = tessera::project_gauss_newton(problem, x, {}, workspace);
  EXPECT_EQ(summary.termination, tessera::CorrectorTermination::NonFiniteResidual);
}

TEST(Corrector, RankDeficientJacobianIsReported) {
  FlatAtOrigin problem;
  tessera::Linearization workspace;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(3);
  const auto summary = tessera::project_gauss_newton(problem, x, {}, workspace);
  EXPECT_EQ(summary.termination, tessera::CorrectorTermination::SingularJacobian);
}

TEST(Corrector, DisplacementLimitStopsAJump) {
  TwoEquations problem(false);
  tessera::Linearization workspace;
  Eigen::VectorXd x(4);
  x << 2.0, 2.0, 0.0, 0.0;
  tessera::CorrectorOptions options;
  options.max_displacement = 0.1;
  options.max_contraction = 1.0;
  const auto summary = tessera::project_gauss_newton(problem, x, options, workspace);
  EXPECT_EQ(summary.termination, tessera::CorrectorTermination::TooFar);
}

TEST(CountedProblem, CountsEvaluations) {
  TwoEquations inner(false);
  tessera::CountedProblem problem(inner);
  tessera::Linearization workspace;
  Eigen::VectorXd x(4);
  x << 0.6, 0.5, 0.1, 0.2;
  const auto summary = tessera::project_gauss_newton(problem, x, {}, workspace);
  ASSERT_TRUE(summary.is_success());
  EXPECT_EQ(problem.jacobian_evaluations(), summary.iterations);
  EXPECT_EQ(problem.function_evaluations(), summary.iterations + 1);
  // Gauss–Newton factors once per iteration; the chord never does.
  EXPECT_EQ(problem.factorisations(), summary.iterations);
  const long before = problem.factorisations();
  tessera::Linearization frozen;
  ASSERT_TRUE(frozen.factor(problem, x));
  Eigen::VectorXd y = x;
  y(2) += 0.01;
  ASSERT_TRUE(tessera::project_chord(problem, frozen, y, {}).is_success());
  EXPECT_EQ(problem.factorisations(), before + 1);
}

// TwoEquations with coordinate blocks, to check how they become the metric's weights.
class WithBlocks final : public tessera::ImplicitProblem {
 public:
  explicit WithBlocks(std::vector<tessera::CoordinateBlock> blocks) : blocks_(std::move(blocks)) {}
  int ambient_dimension() const override { return 4; }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override {
    inner_.evaluate(x, F);
  }
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override {
    inner_.jacobian(x, J);
  }
  std::vector<tessera::CoordinateBlock> coordinate_blocks() const override { return blocks_; }

 private:
  TwoEquations inner_{false};
  std::vector<tessera::CoordinateBlock> blocks_;
};

TEST(MetricWeights, EuclideanUnlessABlockIsWeighted) {
  TwoEquations plain(false);
  EXPECT_EQ(tessera::metric_weights(plain).size(), 0);
  EXPECT_EQ(tessera::metric_weights(WithBlocks({{"u", 0, 2, 1.0}})).size(), 0);
  const Eigen::VectorXd weights = tessera::metric_weights(WithBlocks({{"u", 1, 2, 0.25}}));
  ASSERT_EQ(weights.size(), 4);
  EXPECT_EQ(weights, Eigen::Vector4d(1.0, 0.25, 0.25, 1.0));
  // A counted problem passes the blocks on.
  const WithBlocks weighted({{"u", 1, 2, 0.25}});
  EXPECT_EQ(tessera::metric_weights(tessera::CountedProblem(weighted)), weights);
}

TEST(MetricWeights, RejectsBlocksOutsideOverlappingOrUnweighted) {
  EXPECT_THROW(tessera::metric_weights(WithBlocks({{"u", 3, 2, 0.5}})),
               tessera::InvalidArgument);
  EXPECT_THROW(tessera::metric_weights(WithBlocks({{"u", 0, 2, 0.5}, {"v", 1, 2, 0.5}})),
               tessera::InvalidArgument);
  EXPECT_THROW(tessera::metric_weights(WithBlocks({{"u", 0, 2, 0.0}})), tessera::InvalidArgument);
  EXPECT_THROW(tessera::metric_weights(WithBlocks({{"u", 0, 2, std::nan("")}})),
               tessera::InvalidArgument);
}

// Several right-hand sides in one solve give what one solve per column gives, for the dense (QR)
// and the sparse (bordered LU) factorisation, and for bvp's sparse one at n = 202.
TEST(Linearization, ColumnsAreSolvedAsOneByOne) {
  const tessera::ProblemSetup bvp = tessera::make_catalogue_problem("bvp:points=200");
  TwoEquations dense(false);
  TwoEquations sparse(true);
  Eigen::VectorXd on_m(4);
  on_m << 0.6, 0.0, 0.8, 0.0;
  struct Case {
    const tessera::ImplicitProblem* problem;
    Eigen::VectorXd x;
  };
  for (const Case& c : {Case{&dense, on_m}, Case{&sparse, on_m}, Case{bvp.problem.get(), bvp.start}}) {
    tessera::Linearization linearization;
    ASSERT_TRUE(linearization.factor(*c.problem, c.x));
    const int n = c.problem->ambient_dimension();
    const Eigen::MatrixXd rhs = Eigen::MatrixXd::Random(n - 2, 5);
    Eigen::MatrixXd together(n, 5);
    linearization.solve_minimum_norm_columns(rhs, together);
    for (int j = 0; j < 5; ++j) {
      Eigen::VectorXd alone(n);
      linearization.solve_minimum_norm(rhs.col(j), alone);
      EXPECT_LT((together.col(j) - alone).norm(), 1e-12 * (1.0 + alone.norm())) << "n = " << n;
    }
  }
}

// The chords iterated in lockstep stop where each alone would, so the bounds agree, +∞ included
// (a point too far for the chord).
TEST(ChordDistanceBound, InLockstepEqualsOneAtATime) {
  const tessera::ProblemSetup bvp = tessera::make_catalogue_problem("bvp:points=200");
  const tessera::ImplicitProblem& problem = *bvp.problem;
  tessera::Linearization frozen;
  ASSERT_TRUE(frozen.factor(problem, bvp.start));
  const Eigen::MatrixXd& T = frozen.tangent_basis();
  Eigen::MatrixXd points(problem.ambient_dimension(), 5);
  const double step = bvp.suggested_step;
  points.col(0) = bvp.start;
  points.col(1) = bvp.start + 0.5 * step * T.col(0);
  points.col(2) = bvp.start + step * (T.col(0) + T.col(1));
  points.col(3) = bvp.start - 2.0 * step * T.col(1);
  points.col(4) = bvp.start + 1e3 * T.col(0);  // far off: the chord does not contract
  tessera::CorrectorOptions options;
  const std::vector<double> together =
      tessera::chord_distance_bounds(problem, frozen, points, 1e-6, options);
  ASSERT_EQ(together.size(), 5u);
  for (int j = 0; j < 5; ++j) {
    const double alone = tessera::chord_distance_bound(problem, frozen, points.col(j), 1e-6, options);
    if (std::isinf(alone)) {
      EXPECT_TRUE(std::isinf(together[j])) << j;
    } else {
      EXPECT_NEAR(together[j], alone, 1e-12) << j;
    }
  }
  EXPECT_LT(together[0], 1e-9);  // the start lies on M to solver tolerance
  EXPECT_GT(together[2], 0.0);
  EXPECT_TRUE(std::isinf(together[4]));
}

// Gauss–Newton that keeps its factorisation while it contracts (reuse_factorisation): on a
// sparse problem it reaches M to the same tolerance with fewer factorisations, and it lands
// where full Gauss–Newton does to first order in the distance travelled; a dense problem
// ignores the option.
TEST(GaussNewton, KeepsItsFactorisationWhileItContractsOnSparseProblems) {
  const tessera::ProblemSetup bvp = tessera::make_catalogue_problem("bvp:points=200");
  const int n = bvp.problem->ambient_dimension();
  Eigen::VectorXd offset = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i) {
    offset(i) = 0.05 * std::sin(0.37 * i + 1.0);
  }
  const auto project = [&](const tessera::ImplicitProblem& inner, const Eigen::VectorXd& from,
                           bool reuse, long& factorisations) {
    tessera::CountedProblem problem(inner);
    tessera::CorrectorOptions options;
    options.reuse_factorisation = reuse;
    tessera::Linearization workspace;
    Eigen::VectorXd x = from;
    const auto summary = tessera::project_gauss_newton(problem, x, options, workspace);
    EXPECT_TRUE(summary.is_success()) << summary.brief_report();
    Eigen::VectorXd F(inner.equation_count());
    inner.evaluate(x, F);
    EXPECT_LE(F.norm(), options.residual_tolerance);
    factorisations = problem.factorisations();
    return x;
  };
  const Eigen::VectorXd from = bvp.start + offset;
  long full = 0;
  long kept = 0;
  const Eigen::VectorXd by_newton = project(*bvp.problem, from, false, full);
  const Eigen::VectorXd by_reuse = project(*bvp.problem, from, true, kept);
  EXPECT_GE(full, 3);
  EXPECT_LT(kept, full);
  EXPECT_LT((by_reuse - by_newton).norm(), 0.1 * (by_newton - from).norm());
  // Dense: the option changes nothing.
  TwoEquations dense(false);
  Eigen::VectorXd x(4);
  x << 0.6, 0.5, 0.1, 0.2;
  long dense_full = 0;
  long dense_kept = 0;
  const Eigen::VectorXd a = project(dense, x, false, dense_full);
  const Eigen::VectorXd b = project(dense, x, true, dense_kept);
  EXPECT_EQ(dense_full, dense_kept);
  EXPECT_EQ(a, b);
}

// The same onto a face of the domain (project_onto_faces, as clipping uses it): on M and exactly
// on the face either way, with fewer factorisations when they are kept.
TEST(FaceProjection, KeepsItsFactorisationWhileItContractsOnSparseProblems) {
  const tessera::ProblemSetup bvp = tessera::make_catalogue_problem("bvp:points=200");
  const int n = bvp.problem->ambient_dimension();
  tessera::Domain domain(n);
  Eigen::VectorXd normal = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd point = Eigen::VectorXd::Zero(n);
  normal(n - 1) = 1.0;  // ε ≥ 0.22
  point(n - 1) = 0.22;
  domain.add_half_space(normal, point, "epsilon >= 0.22");
  Eigen::VectorXd from = bvp.start;
  for (int i = 0; i < n; ++i) {
    from(i) += 0.03 * std::cos(0.21 * i);
  }
  long counts[2] = {0, 0};
  for (const bool reuse : {false, true}) {
    tessera::CountedProblem problem(*bvp.problem);
    tessera::CorrectorOptions options;
    options.reuse_factorisation = reuse;
    Eigen::VectorXd x = from;
    ASSERT_TRUE(tessera::project_onto_faces(problem, domain, {0}, x, 1.0, options))
        << "reuse " << reuse;
    Eigen::VectorXd F(n - 2);
    bvp.problem->evaluate(x, F);
    EXPECT_LE(F.norm(), options.residual_tolerance) << "reuse " << reuse;
    EXPECT_EQ(x(n - 1), 0.22) << "reuse " << reuse;
    counts[reuse ? 1 : 0] = problem.factorisations();
  }
  EXPECT_GE(counts[0], 3);
  EXPECT_LT(counts[1], counts[0]);
}

// Issue 34: bounds on the twin coordinates u3, u4 of bvp:points=6 (whose states are symmetric,
// u3 = u4) coincide on M; a point on M ∩ {u3 = 20} also lies on {u4 = 20}. Projecting onto both,
// or onto both and a third face (the corner where they meet λ = 0.5), is projecting onto one:
// the bordered system with both is singular, and failed. Bounds that are parallel on M but
// apart (u3 = 20, u4 = 19) still have no common point.
TEST(FaceProjection, FacesThatCoincideOnMAreOneConstraint) {
  const tessera::ProblemSetup bvp = tessera::make_catalogue_problem("bvp:points=6");
  const int n = bvp.problem->ambient_dimension();
  tessera::Domain domain(n);
  const auto add_bound = [&](int coordinate, double bound, double sign, const char* label) {
    Eigen::VectorXd normal = Eigen::VectorXd::Zero(n);
    Eigen::VectorXd point = Eigen::VectorXd::Zero(n);
    normal(coordinate) = sign;
    point(coordinate) = bound;
    domain.add_half_space(normal, point, label);
  };
  add_bound(2, 20.0, -1.0, "u3 <= 20");     // face 0
  add_bound(3, 20.0, -1.0, "u4 <= 20");     // face 1
  add_bound(6, 0.5, 1.0, "lambda >= 0.5");  // face 2
  add_bound(3, 19.0, -1.0, "u4 <= 19");     // face 3
  tessera::CorrectorOptions options;
  // Near the corner of u3 = 20 and λ = 0.5 (ε ≈ 0.113); u3 is the middle point, the maximum.
  const auto& problem = dynamic_cast<const tessera::ArrheniusBratu&>(*bvp.problem);
  Eigen::VectorXd on_u3 = problem.point_with_amplitude(20.0, 0.12);
  ASSERT_TRUE(tessera::project_onto_faces(*bvp.problem, domain, {0}, on_u3, 1.0, options));
  ASSERT_EQ(on_u3(2), 20.0);
  EXPECT_NEAR(on_u3(3), 20.0, 1e-12);  // the twin, by symmetry, to rounding
  Eigen::VectorXd F(n - 2);
  for (const std::vector<int>& faces : {std::vector<int>{0, 1}, std::vector<int>{1, 0}}) {
    Eigen::VectorXd x = on_u3;
    ASSERT_TRUE(tessera::project_onto_faces(*bvp.problem, domain, faces, x, 1.0, options));
    EXPECT_EQ(x(2), 20.0);  // exactly on both faces
    EXPECT_EQ(x(3), 20.0);
    bvp.problem->evaluate(x, F);
    EXPECT_LE(F.norm(), options.residual_tolerance);
    EXPECT_LE((x - on_u3).norm(), 1e-9);  // already there
  }
  // The corner of the three faces, from a point on the first two near it.
  Eigen::VectorXd corner = on_u3;
  ASSERT_TRUE(tessera::project_onto_faces(*bvp.problem, domain, {0, 1, 2}, corner, 1.0, options));
  EXPECT_EQ(corner(2), 20.0);
  EXPECT_EQ(corner(3), 20.0);
  EXPECT_EQ(corner(6), 0.5);
  bvp.problem->evaluate(corner, F);
  EXPECT_LE(F.norm(), options.residual_tolerance);
  // Parallel on M but apart: no point on both, as before.
  Eigen::VectorXd apart = on_u3;
  EXPECT_FALSE(tessera::project_onto_faces(*bvp.problem, domain, {0, 3}, apart, 1.0, options));
  // Three faces of which only one holds at the start: refused before any factorisation.
  tessera::CountedProblem counted(*bvp.problem);
  Eigen::VectorXd start = bvp.start;
  EXPECT_FALSE(tessera::project_onto_faces(counted, domain, {0, 2, 3}, start, 1.0, options));
  EXPECT_EQ(counted.factorisations(), 0);
}

// A factorisation kept for its solves holds no more than memory_bytes() says: the atlas counts
// its open boundary by it, and issue 9 bounds what lies beyond. Ten kept factorisations of one
// pattern, measured as the heap's growth (glibc's counters). DF and the bordered matrix, which
// release_assembly drops, and the pattern, which all share, stayed behind uncounted: 1.4 MB
// each at n = 10⁴, half the memory beyond the atlas's centres.
TEST(Linearization, AKeptFactorisationHoldsWhatItCounts) {
#if !defined(__GLIBC__) || defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "needs glibc's own allocator (mallinfo2)";
#else
  const auto heap_in_use = [] {
    const struct mallinfo2 info = mallinfo2();
    return static_cast<double>(info.uordblks + info.hblkhd);
  };
  const tessera::ProblemSetup bvp = tessera::make_catalogue_problem("bvp:points=4000");
  tessera::Linearization warm;  // the analysis and the shared pattern, made once
  ASSERT_TRUE(warm.factor(*bvp.problem, bvp.start));
  std::vector<tessera::Linearization> kept;
  kept.reserve(10);
  double counted = 0.0;
  const double before = heap_in_use();
  for (int k = 0; k < 10; ++k) {
    Eigen::VectorXd x = bvp.start;
    x(x.size() - 1) += 1e-3 * k;
    tessera::Linearization linearization;
    ASSERT_TRUE(linearization.factor(*bvp.problem, x, &warm.tangent_basis()));
    linearization.release_assembly();
    counted += static_cast<double>(linearization.memory_bytes());
    kept.push_back(std::move(linearization));
  }
  const double held = heap_in_use() - before;
  EXPECT_GT(held, 0.5 * counted);
  EXPECT_LE(held, 1.1 * counted) << "kept " << held << " bytes, counted " << counted;
#endif
}

// One equation (n = 3) has its own factorisation, a single Householder reflection (issue 35):
// at every point the basis must be orthonormal and span ker DF, a solve the minimum-norm
// solution (along ∇F), and a gradient along the first axis (the reflection's degenerate case,
// either sign) and a vanishing one handled. memory_bytes must not read the unused general QR
// (Eigen asserts on it in the sanitizer build; every n = 3 run aborted there once).
TEST(Linearization, OneEquationGivesTheKernelAndMinimumNormSolves) {
  class Plane final : public tessera::ImplicitProblem {
   public:
    explicit Plane(Eigen::Vector3d normal) : normal_(std::move(normal)) {}
    int ambient_dimension() const override { return 3; }
    void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                  Eigen::Ref<Eigen::VectorXd> F) const override {
      F(0) = normal_.dot(x) - 1.0;
    }
    void jacobian(const Eigen::Ref<const Eigen::VectorXd>&,
                  Eigen::Ref<Eigen::MatrixXd> J) const override {
      J.row(0) = normal_.transpose();
    }

   private:
    Eigen::Vector3d normal_;
  };
  const tessera::ProblemSetup torus = tessera::make_catalogue_problem("torus");
  const Plane along_x(Eigen::Vector3d(2.0, 0.0, 0.0));
  const Plane against_x(Eigen::Vector3d(-0.5, 0.0, 0.0));
  const Plane flat(Eigen::Vector3d::Zero());
  const auto check = [](const tessera::ImplicitProblem& problem, const Eigen::Vector3d& x) {
    tessera::Linearization linearization;
    ASSERT_TRUE(linearization.factor(problem, x));
    Eigen::MatrixXd J(1, 3);
    problem.jacobian(x, J);
    const Eigen::MatrixXd& T = linearization.tangent_basis();
    EXPECT_LE((T.transpose() * T - Eigen::Matrix2d::Identity()).norm(), 1e-14);
    EXPECT_LE((J * T).norm(), 1e-14 * J.norm());
    Eigen::VectorXd r(1);
    r(0) = 0.3;
    Eigen::VectorXd dx(3);
    linearization.solve_minimum_norm(r, dx);
    EXPECT_NEAR((J * dx)(0), 0.3, 1e-14);
    EXPECT_LE((T.transpose() * dx).norm(), 1e-14);  // nothing along ker DF
    EXPECT_GT(linearization.memory_bytes(), 0u);
  };
  for (int k = 0; k < 20; ++k) {
    const Eigen::Vector3d x = torus.start + 0.3 * Eigen::Vector3d(std::sin(k), std::cos(3 * k),
                                                                  std::sin(7 * k));
    check(*torus.problem, x);
  }
  check(along_x, Eigen::Vector3d(0.5, 0.2, 0.1));
  check(against_x, Eigen::Vector3d(-2.0, 0.2, 0.1));
  tessera::Linearization singular;
  EXPECT_FALSE(singular.factor(flat, Eigen::Vector3d(0.1, 0.2, 0.3)));
}

// Issue 30: a linearisation that borrows another point's factorisation. On bratu2d (sparse, a
// 2-D grid) at a point y a step from the factored x0:
//  - tangent_basis_near with an angle tolerance gives ker DF(y) (‖DF(y)·T‖ at rounding, judged
//    against the exact basis from a factorisation at y);
//  - the borrowed solves solve the bordered system [DF(x0); Tᵀ] dx = [r; 0];
//  - the chord from it ends on M at y's own pointOnDisk point (Tᵀ(x − predicted) = 0), where
//    a factorisation at y puts it, with no factorisation made;
//  - the factors are shared, not copied, and factoring the borrower again leaves the lender's
//    solves as they were.
TEST(Linearization, BorrowedFactorisationSolvesTheBorderedSystemOfItsOwnTangent) {
  const tessera::ProblemSetup bratu = tessera::make_catalogue_problem("bratu2d:N=8");
  const tessera::CountedProblem problem(*bratu.problem);
  const int n = problem.ambient_dimension();
  tessera::Linearization at_x0;
  ASSERT_TRUE(at_x0.factor(problem, bratu.start));
  // y: a step along M from x0.
  Eigen::VectorXd y = bratu.start + 0.5 * bratu.suggested_step * at_x0.tangent_basis().col(0);
  ASSERT_TRUE(tessera::project_chord(problem, at_x0, y, {}).is_success());
  tessera::Linearization at_y;
  ASSERT_TRUE(at_y.factor(problem, y, &at_x0.tangent_basis()));
  Eigen::MatrixXd T;
  ASSERT_TRUE(tessera::tangent_basis_near(problem, at_x0, y, T, 0.0, 8, 1e-10));
  // The same plane as the factorisation's at y: the projection onto it moves T by rounding.
  const Eigen::MatrixXd& exact = at_y.tangent_basis();
  EXPECT_LT((T - exact * (exact.transpose() * T)).norm(), 1e-9);
  EXPECT_GT((exact.transpose() * T).determinant(), 0.0);  // oriented like x0's basis

  const long factorisations = problem.counts().factorisations;
  tessera::Linearization borrowed;
  ASSERT_TRUE(borrowed.borrow(problem, at_x0, y, T));
  EXPECT_TRUE(borrowed.is_borrowed());
  EXPECT_EQ(borrowed.factorisation_identity(), at_x0.factorisation_identity());
  EXPECT_EQ(borrowed.factored_point(), bratu.start);
  EXPECT_EQ(borrowed.point(), y);
  // [DF(x0); Tᵀ] dx = [r; 0].
  Eigen::MatrixXd J0(n - 2, n);
  problem.jacobian(bratu.start, J0);
  const Eigen::VectorXd r = Eigen::VectorXd::LinSpaced(n - 2, -1.0, 1.0);
  Eigen::VectorXd dx(n);
  borrowed.solve_minimum_norm(r, dx);
  EXPECT_LT((J0 * dx - r).norm(), 1e-10 * r.norm() * J0.norm());
  EXPECT_LT((T.transpose() * dx).norm(), 1e-12 * dx.norm());
  Eigen::MatrixXd columns(n, 2);
  borrowed.solve_minimum_norm_columns(Eigen::MatrixXd(r.replicate(1, 2)), columns);
  EXPECT_LT((columns.col(0) - dx).norm(), 1e-12 * dx.norm());

  // pointOnDisk of y's chart, from its borrowed solves and from its own factorisation.
  const Eigen::VectorXd predicted = y + 0.3 * bratu.suggested_step * T.col(1);
  Eigen::VectorXd by_borrowed = predicted;
  Eigen::VectorXd by_own = predicted;
  const auto chord = tessera::project_chord(problem, borrowed, by_borrowed, {});
  ASSERT_TRUE(chord.is_success()) << chord.brief_report();
  ASSERT_TRUE(tessera::project_chord(problem, at_y, by_own, {}).is_success());
  EXPECT_LT((T.transpose() * (by_borrowed - predicted)).norm(), 1e-12);
  EXPECT_LT((by_borrowed - by_own).norm(), 1e-8);
  EXPECT_EQ(problem.counts().factorisations, factorisations);  // none was made

  // Shared, not copied: a copy borrows the same factors; factoring the borrower anew makes
  // its own and leaves the lender's solves unchanged.
  const tessera::Linearization copy = borrowed;
  EXPECT_EQ(copy.factorisation_identity(), at_x0.factorisation_identity());
  Eigen::VectorXd before(n);
  at_x0.solve_minimum_norm(r, before);
  ASSERT_TRUE(borrowed.factor(problem, by_own, &T));
  EXPECT_FALSE(borrowed.is_borrowed());
  EXPECT_NE(borrowed.factorisation_identity(), at_x0.factorisation_identity());
  Eigen::VectorXd after(n);
  at_x0.solve_minimum_norm(r, after);
  EXPECT_EQ(before, after);
  // Too oblique a tangent is refused.
  Eigen::MatrixXd oblique = T;
  oblique.col(1) = J0.row(0).transpose().normalized();
  tessera::Linearization refused;
  EXPECT_FALSE(refused.borrow(problem, at_x0, y, oblique));
  EXPECT_FALSE(refused.is_factored());
}

// Points visited in turn borrow from the nearest kept factorisation: one near a lender borrows
// its factors (no factorisation), one far from every lender does not, and the lenders kept are
// bounded in number.
TEST(FactorisationLenders, NearPointsBorrowTheNearestKeptFactorisation) {
  const tessera::ProblemSetup bratu = tessera::make_catalogue_problem("bratu2d:N=8");
  const tessera::CountedProblem problem(*bratu.problem);
  const double h = 0.25 * bratu.suggested_step;
  tessera::FactorisationLenders lenders(2, std::size_t{1} << 30);
  tessera::Linearization first;
  ASSERT_TRUE(first.factor(problem, bratu.start));
  ASSERT_TRUE(tessera::worth_sharing(first));  // the 2-D grid's LU fills in
  const Eigen::MatrixXd T0 = first.tangent_basis();
  tessera::Linearization at_start;
  lenders.keep(problem, std::move(first), at_start);
  EXPECT_TRUE(at_start.is_borrowed());  // the lender's own solves, at its own point
  EXPECT_FALSE(at_start.solves_from_elsewhere());
  EXPECT_EQ(at_start.point(), bratu.start);
  // Points along M at one and at twenty local edge lengths from the start.
  const auto along = [&](double distance) {
    Eigen::VectorXd y = bratu.start + distance * T0.col(0);
    EXPECT_TRUE(tessera::project_chord(problem, at_start, y, {}).is_success());
    return y;
  };
  const Eigen::VectorXd near = along(h);
  const long factorisations = problem.counts().factorisations;
  tessera::Linearization borrowed;
  ASSERT_TRUE(lenders.borrow(problem, near, h, borrowed));
  EXPECT_EQ(problem.counts().factorisations, factorisations);
  EXPECT_TRUE(borrowed.solves_from_elsewhere());
  EXPECT_EQ(borrowed.factored_point(), bratu.start);
  EXPECT_EQ(borrowed.factorisation_identity(), at_start.factorisation_identity());
  EXPECT_FALSE(lenders.borrow(problem, along(20 * h), h, borrowed));
  // Three more lenders: the first is dropped (at most two kept), and a point next to it no
  // longer borrows, while one next to the newest does.
  for (int k = 1; k <= 3; ++k) {
    tessera::Linearization own;
    ASSERT_TRUE(own.factor(problem, along(10 * k * h)));
    tessera::Linearization unused;
    lenders.keep(problem, std::move(own), unused);
  }
  EXPECT_FALSE(lenders.borrow(problem, near, h, borrowed));
  tessera::Linearization next_to_newest;
  EXPECT_TRUE(lenders.borrow(problem, along(30 * h + 0.5 * h), h, next_to_newest));
}
