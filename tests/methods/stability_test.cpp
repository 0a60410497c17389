// SPDX-License-Identifier: MIT
// The stability of steady states at points of M, checked against spectra computed here without
// tessera's stability code: closed forms (cstr, pleat, Brusselator) and dense eigenvalues of the
// whole pencil (bvp).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>

#include "support/brusselator.h"
#include "tessera/core/error.h"
#include "tessera/methods/stability/hopf_curves.h"
#include "tessera/methods/stability/hopf_point.h"
#include "tessera/methods/stability/vertex_stability.h"
#include "tessera/problems/examples.h"

namespace tessera {
namespace {

using Complex = std::complex<double>;

// The roots of μ² − t μ + d = 0.
std::pair<Complex, Complex> quadratic_roots(double t, double d) {
  const Complex root = std::sqrt(Complex(t * t / 4 - d, 0.0));
  return {t / 2 + root, t / 2 - root};
}

TEST(Stability, CstrAgreesWithTraceAndDeterminant) {
  const double beta = 0.5;
  const StirredTankReactor cstr(beta);
  int stable = 0;
  int saddles = 0;
  int unstable_foci = 0;
  for (double x1 = 0.05; x1 < 0.96; x1 += 0.05) {
    for (double B = 1.0; B <= 12.0; B += 0.5) {
      const Eigen::VectorXd x = cstr.point_on_manifold(x1, B);
      // D_uF on M: E = Da (1 − x₁) eˣ² = x₁ and Da eˣ² = x₁/(1 − x₁).
      const double a = x1 / (1 - x1);
      const double trace = B * x1 - (2 + beta) - a;
      const double det = (1 + beta) / (1 - x1) - B * x1;
      if (std::abs(det) < 1e-6 || std::abs(trace) < 1e-6) {
        continue;
      }
      const VertexStability s = stability_at(cstr, x);
      ASSERT_FALSE(s.has_failed()) << s.message;
      EXPECT_TRUE(s.is_certain);
      ASSERT_EQ(s.eigenvalues.size(), 2U);
      const auto [r1, r2] = quadratic_roots(trace, det);
      const double expected_leading = std::max(r1.real(), r2.real());
      EXPECT_NEAR(s.leading_real_part, expected_leading, 1e-9 * (1 + std::abs(expected_leading)));
      const int expected = det < 0 ? 1 : (trace > 0 ? 2 : 0);
      EXPECT_EQ(s.unstable_count, expected) << "x1 = " << x1 << ", B = " << B;
      stable += expected == 0;
      saddles += expected == 1;
      unstable_foci += expected == 2 && r1.imag() != 0.0;
    }
  }
  // The grid sees every kind of state, so the comparison above is not vacuous.
  EXPECT_GT(stable, 20);
  EXPECT_GT(saddles, 20);
  EXPECT_GT(unstable_foci, 5);
}

TEST(Stability, PleatOuterSheetsAreStable) {
  const WhitneyPleat pleat;
  for (double x = -1.5; x <= 1.5; x += 0.25) {
    for (double lambda = -1.0; lambda <= 3.0; lambda += 0.5) {
      const Eigen::Vector3d point(x, lambda, x * x * x - lambda * x);
      const double mu = -(3 * x * x - lambda);  // x' = −F
      if (std::abs(mu) < 1e-9) {
        continue;
      }
      const VertexStability s = stability_at(pleat, point);
      ASSERT_FALSE(s.has_failed());
      EXPECT_EQ(s.unstable_count, mu > 0 ? 1 : 0) << "x = " << x << ", lambda = " << lambda;
      EXPECT_NEAR(s.leading_real_part, mu, 1e-12);
    }
  }
}

// Every finite eigenvalue of (s·D_uF, B) from the whole dense pencil: the reference for bvp.
std::vector<double> dense_bvp_spectrum(const ArrheniusBratu& bvp, const Eigen::VectorXd& x) {
  const int N = bvp.point_count();
  Eigen::MatrixXd J(N, N + 2);
  bvp.jacobian(x, J);
  const double h = 1.0 / (N + 1);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(J.leftCols(N) / (h * h));
  std::vector<double> values(solver.eigenvalues().data(), solver.eigenvalues().data() + N);
  return values;
}

TEST(Stability, BvpInertiaCountsEveryEigenvalueAndStepsByOneAcrossFolds) {
  const ArrheniusBratu bvp(100);
  const double epsilon = 0.2;  // an S-shaped branch: ignition and extinction folds
  std::vector<int> counts;
  std::vector<double> lambdas;
  for (double amplitude = 0.5; amplitude <= 20.0; amplitude += 0.25) {
    const Eigen::VectorXd x = bvp.point_with_amplitude(amplitude, epsilon);
    const VertexStability s = stability_at(bvp, x);
    ASSERT_FALSE(s.has_failed()) << s.message;
    EXPECT_TRUE(s.is_certain);
    const std::vector<double> all = dense_bvp_spectrum(bvp, x);
    const int expected = static_cast<int>(std::count_if(all.begin(), all.end(), [](double mu) { return mu > 0; }));
    EXPECT_EQ(s.unstable_count, expected) << "amplitude " << amplitude;
    // The computed eigenvalues are the 6 of the whole spectrum nearest 0.
    std::vector<double> nearest = all;
    std::sort(nearest.begin(), nearest.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
    ASSERT_EQ(s.eigenvalues.size(), 6U);
    for (const Complex& mu : s.eigenvalues) {
      const bool found = std::any_of(nearest.begin(), nearest.begin() + 6, [&](double r) {
        return std::abs(mu.real() - r) <= 1e-8 * (1 + std::abs(r));
      });
      EXPECT_TRUE(found) << mu;
      EXPECT_EQ(mu.imag(), 0.0);
    }
    counts.push_back(s.unstable_count);
    lambdas.push_back(x(100));
  }
  // Along the branch the count changes only at the folds (where λ turns), by one each time.
  int folds = 0;
  int changes = 0;
  for (std::size_t i = 1; i + 1 < counts.size(); ++i) {
    if ((lambdas[i + 1] - lambdas[i]) * (lambdas[i] - lambdas[i - 1]) < 0.0) {
      ++folds;
      EXPECT_EQ(std::abs(counts[i + 1] - counts[i - 1]), 1) << "fold near point " << i;
    }
  }
  for (std::size_t i = 1; i < counts.size(); ++i) {
    changes += std::abs(counts[i] - counts[i - 1]);
  }
  EXPECT_EQ(folds, 2);
  EXPECT_EQ(changes, folds);
  EXPECT_EQ(counts.front(), 0);  // the lower branch is stable
}

TEST(Stability, BrusselatorArnoldiFindsTheHopfPair) {
  // D = 0.2: the other modes stay stable for b < 1 + a² + 2·D·π² (about 7).
  const test::Brusselator brusselator(40, 0.2);
  const double a = 1.5;
  for (const double b : {2.0, 3.0, 3.5, 4.0, 5.0}) {
    const VertexStability s = stability_at(brusselator, brusselator.steady_state(a, b));
    ASSERT_FALSE(s.has_failed()) << s.message;
    EXPECT_FALSE(s.is_certain);  // not symmetric: the count is of the 6 nearest 0
    EXPECT_TRUE(std::isfinite(s.examined_radius));
    // The uniform mode: trace b − 1 − a², determinant a².
    const double expected = (b - 1 - a * a) / 2;
    EXPECT_NEAR(s.leading_real_part, expected, 1e-8);
    EXPECT_EQ(s.unstable_count, expected > 0 ? 2 : 0) << "b = " << b;
  }
}

// The CSTR's Hopf curve from its 2×2 Jacobian (β = 0.5): trace 0 with a positive determinant,
// B = (2 + β)/x₁ + 1/(1 − x₁) for x₁ > 1/(1 + β), ω² = the determinant.
TEST(HopfPoint, CstrPointsSatisfyTraceZeroToSolverTolerance) {
  const double beta = 0.5;
  const StirredTankReactor cstr(beta);
  for (const double x1 : {0.7, 0.8, 0.9}) {
    const double B = (2 + beta) / x1 + 1 / (1 - x1);
    const double omega = std::sqrt((1 + beta) / (1 - x1) - B * x1);
    // Start off the curve and off M: Newton must find both.
    Eigen::VectorXd start = cstr.point_on_manifold(x1 + 0.01, B + 0.2);
    start(0) += 1e-3;
    WorkCounts work;
    const HopfPoint point = refine_hopf_point(cstr, start, 1.1 * omega, 1.0, {}, work);
    ASSERT_TRUE(point.is_refined) << "x1 = " << x1;
    EXPECT_LE(point.residual, 1e-9);
    const double x1_found = point.x(0);
    const double B_found = point.x(3);
    const double a = x1_found / (1 - x1_found);
    EXPECT_NEAR(B_found * x1_found - (2 + beta) - a, 0.0, 1e-8);  // the trace
    EXPECT_NEAR(point.omega * point.omega, (1 + beta) / (1 - x1_found) - B_found * x1_found, 1e-8);
    EXPECT_LE(point.condition_residual, 1e-8);
    ASSERT_EQ(point.curve_tangent.size(), 4);
    EXPECT_GT(work.factorisations, 0);
  }
}

TEST(HopfPoint, CstrBogdanovTakensPointIsWhereTheHopfCurveMeetsTheFold) {
  const double beta = 0.5;
  const StirredTankReactor cstr(beta);
  WorkCounts work;
  const HopfPoint point =
      refine_bogdanov_takens_point(cstr, cstr.point_on_manifold(0.68, 6.9), 1.0, {}, work);
  ASSERT_TRUE(point.is_refined);
  // trace = determinant = 0: x₁ = 1/(1 + β), B = (1 + β)/(x₁(1 − x₁)) = (1 + β)³/β.
  EXPECT_NEAR(point.x(0), 1 / (1 + beta), 1e-8);
  EXPECT_NEAR(point.x(3), std::pow(1 + beta, 3) / beta, 1e-8);
  EXPECT_NEAR(point.x(2), 2 * std::exp(-3.0), 1e-8);  // Da = x₁ e^(−x₂)/(1 − x₁), x₂ = 3
  EXPECT_EQ(point.omega, 0.0);
}

TEST(HopfPoint, BrusselatorSparsePointsLieOnBEqualsOnePlusASquared) {
  const test::Brusselator brusselator(40, 0.2);
  WorkCounts work;
  const HopfPoint point =
      refine_hopf_point(brusselator, brusselator.steady_state(1.5, 3.4), 1.4, 2.0, {}, work);
  ASSERT_TRUE(point.is_refined);
  const int n = brusselator.ambient_dimension();
  const double a = point.x(n - 2);
  const double b = point.x(n - 1);
  EXPECT_NEAR(b, 1 + a * a, 1e-8);
  EXPECT_NEAR(point.omega, a, 1e-8);
}

TEST(Stability, AnEigensolverThatDoesNotConvergeSaysSoPerVertex) {
  // Almost no diffusion: 200 modes with nearly the same eigenvalues, which one restart of
  // Arnoldi cannot separate.
  const test::Brusselator brusselator(200, 1e-9);
  StabilityOptions options;
  options.max_restarts = 1;
  const VertexStability s = stability_at(brusselator, brusselator.steady_state(1.5, 3.0), options);
  EXPECT_TRUE(s.has_failed());
  EXPECT_EQ(s.unstable_count, -1);
  EXPECT_TRUE(std::isnan(s.leading_real_part));
  EXPECT_NE(s.message.find("did not converge"), std::string::npos) << s.message;
}

TEST(Stability, InvalidDynamicsAreRefusedWithTheirFault) {
  struct Case {
    Dynamics dynamics;
    std::string message;
  };
  Dynamics out_of_range;
  out_of_range.parameters = {1, 4};
  Dynamics same;
  same.parameters = {2, 2};
  Dynamics sign;
  sign.parameters = {2, 3};
  sign.sign = 0.5;
  Dynamics mass_size;
  mass_size.parameters = {2, 3};
  mass_size.mass_diagonal = Eigen::VectorXd::Ones(3);
  Dynamics negative_mass;
  negative_mass.parameters = {2, 3};
  negative_mass.mass_diagonal = Eigen::Vector2d(1.0, -1.0);
  for (const Case& c : std::vector<Case>{{out_of_range, "indices 0 … 3), got 1 and 4"},
                                         {same, "the same coordinate (index 2)"},
                                         {sign, "+1 or −1, got 0.5"},
                                         {mass_size, "3 entries, one per state (2)"},
                                         {negative_mass, "entry 1 is -1"}}) {
    try {
      check_dynamics(c.dynamics, 4, "p");
      ADD_FAILURE() << "accepted: " << c.message;
    } catch (const InvalidArgument& error) {
      EXPECT_NE(std::string(error.what()).find(c.message), std::string::npos) << error.what();
    }
  }
}

// The sparse path end to end: a grid of the Brusselator's steady states over (a, b), its
// stability by shift-invert Arnoldi (the 6 eigenvalues nearest 0) and its Hopf curve b = 1 + a².
TEST(HopfCurves, SparseBrusselatorCurveIsBEqualsOnePlusASquared) {
  const test::Brusselator brusselator(40, 0.2);
  const int n = brusselator.ambient_dimension();
  const int rows = 13;
  const int columns = 17;
  Eigen::MatrixXd points(n, rows * columns);
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < columns; ++j) {
      const double a = 1.0 + 1.0 * i / (rows - 1);
      const double b = 1.5 + 5.0 * j / (columns - 1);
      points.col(i * columns + j) = brusselator.steady_state(a, b);
    }
  }
  std::vector<Triangle> triangles;
  for (int i = 0; i + 1 < rows; ++i) {
    for (int j = 0; j + 1 < columns; ++j) {
      const int v = i * columns + j;
      triangles.push_back({v, v + 1, v + columns + 1});
      triangles.push_back({v, v + columns + 1, v + columns});
    }
  }
  const TriangleMesh mesh(points, triangles);
  const StabilityResult stability = compute_stability(brusselator, mesh);
  EXPECT_EQ(stability.failed_count, 0);
  EXPECT_EQ(stability.uncertain_count, mesh.vertex_count());  // Arnoldi: the 6 nearest 0
  const HopfCurves hopf = find_hopf_curves(brusselator, mesh, stability);
  EXPECT_EQ(hopf.unrefined_count, 0);
  ASSERT_EQ(hopf.curves.size(), 1u);
  EXPECT_FALSE(hopf.curves[0].is_neutral_saddle);
  EXPECT_GE(hopf.curves[0].points.size(), 12u);
  for (const HopfPoint& point : hopf.curves[0].points) {
    const double a = point.x(n - 2);
    const double b = point.x(n - 1);
    EXPECT_NEAR(b, 1 + a * a, 1e-8);
    EXPECT_NEAR(point.omega, a, 1e-8);
    EXPECT_TRUE(std::isnan(point.first_lyapunov_coefficient));  // sparse: not computed
  }
}

TEST(Stability, ProblemWithoutDynamicsIsRefusedWithHowToDeclareThem) {
  const Sphere sphere;
  try {
    stability_at(sphere, Eigen::Vector3d(1, 0, 0));
    FAIL() << "no error";
  } catch (const InvalidArgument& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("'sphere' does not say"), std::string::npos) << message;
    EXPECT_NE(message.find("dynamics parameters P1 P2"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace tessera
