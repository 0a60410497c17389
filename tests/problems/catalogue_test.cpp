// SPDX-License-Identifier: MIT
// The catalogue: exact Jacobians, reachable starts, known points, topology claims, parsing.
#include "tessera/problems/catalogue.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <random>
#include <string>

#include "support/test_support.h"
#include "tessera/core/error.h"
#include "tessera/problems/examples.h"

namespace tessera {
namespace {

constexpr double kPi = std::numbers::pi;

Eigen::VectorXd residual(const ImplicitProblem& problem, const Eigen::VectorXd& x) {
  Eigen::VectorXd F(problem.equation_count());
  problem.evaluate(x, F);
  return F;
}

Eigen::MatrixXd dense_jacobian(const ImplicitProblem& problem, const Eigen::VectorXd& x) {
  Eigen::MatrixXd J(problem.equation_count(), problem.ambient_dimension());
  problem.jacobian(x, J);
  return J;
}

Eigen::VectorXd point3(double x, double y, double z) {
  Eigen::VectorXd v(3);
  v << x, y, z;
  return v;
}

// The start and three points at distance step/2 from it in fixed pseudo-random directions.
std::vector<Eigen::VectorXd> points_near_start(const ProblemSetup& setup) {
  std::mt19937 generator(42);
  std::normal_distribution<double> normal;
  std::vector<Eigen::VectorXd> points{setup.start};
  for (int k = 0; k < 3; ++k) {
    Eigen::VectorXd direction(setup.start.size());
    for (Eigen::Index i = 0; i < direction.size(); ++i) {
      direction(i) = normal(generator);
    }
    points.push_back(setup.start + 0.5 * setup.suggested_step * direction.normalized());
  }
  return points;
}

// Minimum-norm Gauss–Newton, x ← x − Jᵀ(J Jᵀ)⁻¹ F, written here because the library corrector is
// tested separately. Returns the final |F|.
double gauss_newton(const ImplicitProblem& problem, Eigen::VectorXd& x, int max_iterations = 30) {
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    const Eigen::VectorXd F = residual(problem, x);
    if (F.norm() < 1e-12) {
      break;
    }
    const Eigen::MatrixXd J = dense_jacobian(problem, x);
    x -= J.transpose() * (J * J.transpose()).ldlt().solve(F);
  }
  return residual(problem, x).norm();
}

// The specification of an entry at a size where dense checks are cheap: bratu2d's default grid
// (n ≈ 10⁴) would need a dense Jacobian of 800 MB.
std::string small_instance(const CatalogueEntry& entry) {
  return entry.name == "bratu2d" ? "bratu2d:N=5" : entry.name;
}

TEST(Catalogue, EveryEntryBuildsWithConsistentShapes) {
  ASSERT_GE(catalogue().size(), 9u);
  for (const CatalogueEntry& entry : catalogue()) {
    SCOPED_TRACE(entry.name);
    const ProblemSetup setup = make_catalogue_problem(entry.name);
    ASSERT_NE(setup.problem, nullptr);
    const int n = setup.problem->ambient_dimension();
    EXPECT_EQ(setup.start.size(), n);
    EXPECT_EQ(setup.domain.ambient_dimension(), n);
    EXPECT_EQ(static_cast<int>(setup.problem->coordinate_names().size()), n);
    EXPECT_EQ(setup.problem->name(), entry.name == "sphere_cut" ? "sphere" : entry.name);
    EXPECT_GT(setup.suggested_step, 0.0);
    EXPECT_EQ(setup.description.rfind(entry.name, 0), 0u) << setup.description;
    EXPECT_FALSE(entry.summary.empty());
  }
}

// Central differences with step h have truncation error h²/6·|∂³F| and rounding error
// ≈ 1e-16·|F|/h. With h = 1e-5·max(1, |x_j|), third derivatives below 1e4 and |F| below 1e4 at
// these points, both stay under 1e-6, the tolerance used (relative to the size of J).
TEST(Catalogue, AnalyticJacobianMatchesCentralDifferences) {
  for (const CatalogueEntry& entry : catalogue()) {
    SCOPED_TRACE(entry.name);
    const ProblemSetup setup = make_catalogue_problem(small_instance(entry));
    const ImplicitProblem& problem = *setup.problem;
    for (const Eigen::VectorXd& x : points_near_start(setup)) {
      const Eigen::MatrixXd J = dense_jacobian(problem, x);
      Eigen::MatrixXd difference_quotient(J.rows(), J.cols());
      for (Eigen::Index j = 0; j < x.size(); ++j) {
        const double h = 1e-5 * std::max(1.0, std::abs(x(j)));
        Eigen::VectorXd forward = x, backward = x;
        forward(j) += h;
        backward(j) -= h;
        difference_quotient.col(j) =
            (residual(problem, forward) - residual(problem, backward)) / (2.0 * h);
      }
      const double tolerance = 1e-6 * (1.0 + J.cwiseAbs().maxCoeff());
      EXPECT_LE((J - difference_quotient).cwiseAbs().maxCoeff(), tolerance)
          << "at x = " << x.transpose().head(std::min<Eigen::Index>(x.size(), 6));
    }
  }
}

TEST(Catalogue, DenseAndSparseJacobiansAgree) {
  for (const CatalogueEntry& entry : catalogue()) {
    SCOPED_TRACE(entry.name);
    const ProblemSetup setup = make_catalogue_problem(small_instance(entry));
    for (const Eigen::VectorXd& x : points_near_start(setup)) {
      const Eigen::MatrixXd dense = dense_jacobian(*setup.problem, x);
      Eigen::SparseMatrix<double> sparse;
      setup.problem->sparse_jacobian(x, sparse);
      // Same formulas in both forms: agreement to rounding.
      EXPECT_LE((Eigen::MatrixXd(sparse) - dense).cwiseAbs().maxCoeff(),
                1e-14 * (1.0 + dense.cwiseAbs().maxCoeff()));
    }
  }
}

TEST(Catalogue, BoundaryValueProblemSparseJacobianIsTridiagonalPlusTwoColumnsAndReusesStorage) {
  const ArrheniusBratu problem{50};
  EXPECT_TRUE(problem.has_sparse_jacobian());
  const Eigen::VectorXd x = problem.point_with_amplitude(2.0, 0.1);
  Eigen::SparseMatrix<double> J;
  problem.sparse_jacobian(x, J);
  EXPECT_EQ(J.rows(), 50);
  EXPECT_EQ(J.cols(), 52);
  EXPECT_EQ(J.nonZeros(), 5 * 50 - 2);
  EXPECT_TRUE(J.isCompressed());
  const double* values = J.valuePtr();
  const int* inner = J.innerIndexPtr();
  problem.sparse_jacobian(x + Eigen::VectorXd::Constant(52, 0.01), J);
  EXPECT_EQ(J.valuePtr(), values) << "second call reallocated the values";
  EXPECT_EQ(J.innerIndexPtr(), inner) << "second call reallocated the row indices";
}

TEST(Catalogue, GaussNewtonFromEveryStartConvergesInsideTheDomain) {
  for (const CatalogueEntry& entry : catalogue()) {
    SCOPED_TRACE(entry.name);
    const ProblemSetup setup = make_catalogue_problem(small_instance(entry));
    Eigen::VectorXd x = setup.start;
    EXPECT_LT(gauss_newton(*setup.problem, x), 1e-10);
    EXPECT_TRUE(setup.domain.contains(x, 1e-12))
        << x.transpose().head(std::min<Eigen::Index>(x.size(), 6));
    // The start is a guess near M, within two steps (Hohmann's pleat guess is 0.108 away).
    EXPECT_LT((x - setup.start).norm(), 2.0 * setup.suggested_step);
  }
}

TEST(Catalogue, TroughStartProjectsOntoTheArchAboveTheXAxis) {
  const ProblemSetup setup = make_catalogue_problem("trough");
  Eigen::VectorXd x = setup.start;
  ASSERT_LT(gauss_newton(*setup.problem, x), 1e-10);
  EXPECT_GT(x(2), 0.0);  // the arch, not the loop inside the lower lobe of the figure-eight
  EXPECT_NEAR(x(2), 0.25, 1e-3);  // just above the top of the upper lobe, z = b
}

TEST(Catalogue, KnownPointsLieOnTheManifolds) {
  // Each residual is a few roundings of numbers of size ≤ 16, hence the 1e-13.
  const Sphere sphere{1.5};
  EXPECT_NEAR(residual(sphere, point3(1.5, 0, 0))(0), 0.0, 1e-13);
  EXPECT_NEAR(residual(sphere, point3(0, -0.9, 1.2))(0), 0.0, 1e-13);

  const Torus torus{1.0, 0.4};
  EXPECT_NEAR(residual(torus, point3(0, 1.4, 0))(0), 0.0, 1e-13);  // (0, R + r, 0)
  EXPECT_NEAR(residual(torus, point3(0, 0, 0.6))(0), 0.0, 1e-13);  // (0, 0, R − r)
  EXPECT_NEAR(residual(torus, point3(0.4, 1, 0))(0), 0.0, 1e-13);  // (r, R, 0), top of the tube
  EXPECT_LT(residual(torus, point3(0, 1, 0))(0), 0.0);             // the core circle is inside

  const WhitneyPleat pleat;
  EXPECT_NEAR(residual(pleat, point3(1, 1, 0))(0), 0.0, 1e-13);
  EXPECT_NEAR(residual(pleat, point3(0.7, -0.3, 0.7 * 0.7 * 0.7 + 0.3 * 0.7))(0), 0.0, 1e-13);

  // The trough is a cylinder in y, and for ε = 0 contains the line z = 0 and the figure-eight.
  const Trough trough{4.0, 0.25, 5e-5};
  EXPECT_EQ(residual(trough, point3(0.1, -0.1, 0.2))(0),
            residual(trough, point3(0.1, 0.1, 0.2))(0));
  const Trough unperturbed{4.0, 0.25, 0.0};
  const double z = 0.1;
  EXPECT_NEAR(residual(unperturbed, point3(0.1, 0.05, 0))(0), 0.0, 1e-15);
  EXPECT_NEAR(residual(unperturbed, point3(4 * z * std::sqrt(0.0625 - z * z), 0, z))(0), 0.0,
              1e-15);

  // The equipotential surface is symmetric under y ↦ q_y − y and under rotation about the y axis.
  const Equipotential blobby{1.7, 2.0};
  EXPECT_NEAR(residual(blobby, point3(0.3, -0.2, 0.4))(0),
              residual(blobby, point3(0.3, 2.2, 0.4))(0), 1e-13);
  EXPECT_NEAR(residual(blobby, point3(0.3, -0.2, 0.4))(0),
              residual(blobby, point3(0.5, -0.2, 0))(0), 1e-13);

  const StirredTankReactor reactor{0.5};
  const Eigen::VectorXd steady_state = reactor.point_on_manifold(0.5, 3.0);
  EXPECT_NEAR(steady_state(1), 1.0, 1e-15);             // x2 = B x1 / (1 + β)
  EXPECT_NEAR(steady_state(2), std::exp(-1.0), 1e-15);  // Da = x1 e^{−x2} / (1 − x1)
  EXPECT_LT(residual(reactor, steady_state).norm(), 1e-15);

  const ArrheniusBratu bvp{30};
  Eigen::VectorXd trivial = Eigen::VectorXd::Zero(32);
  trivial(31) = 0.2;  // u = 0, λ = 0 solves the problem for every ε
  EXPECT_EQ(residual(bvp, trivial).norm(), 0.0);
}

// Large N: the setup stays O(N) (a handful of half-spaces, a sparse J) and the start is on M to
// the rounding level of the h²-scaled equations, ~1e-15·max u.
TEST(Catalogue, BoundaryValueProblemScalesToLargeN) {
  const int N = 20000;
  const ProblemSetup setup = make_catalogue_problem("bvp:points=20000");
  EXPECT_EQ(setup.problem->ambient_dimension(), N + 2);
  EXPECT_EQ(setup.domain.half_spaces().size(), 5u);
  EXPECT_GT(setup.domain.boundary_distance(setup.start).signed_distance, 0.0);
  EXPECT_LT(residual(*setup.problem, setup.start).lpNorm<Eigen::Infinity>(), 1e-12);
  Eigen::SparseMatrix<double> J;
  setup.problem->sparse_jacobian(setup.start, J);
  EXPECT_EQ(J.nonZeros(), 5 * N - 2);
}

TEST(Catalogue, BoundaryValuePointWithAmplitudeIsSymmetricAndOnTheManifold) {
  const ArrheniusBratu problem{40};
  const Eigen::VectorXd x = problem.point_with_amplitude(7.0, 0.2);
  EXPECT_LT(residual(problem, x).lpNorm<Eigen::Infinity>(), 1e-12);
  EXPECT_NEAR(x.head(40).maxCoeff(), 7.0, 1e-12);
  EXPECT_NEAR(x(19), 7.0, 1e-12);  // u_20, the middle point ⌊(N+1)/2⌋
  for (int i = 0; i < 40; ++i) {
    EXPECT_NEAR(x(i), x(39 - i), 1e-10);  // positive solutions are symmetric about 1/2
  }
}

// At ε = 0 the problem is Bratu's, with the exact solution u = −2 ln(cosh((t − ½)θ/2)/cosh(θ/4)):
// amplitude α = 2 ln cosh(θ/4), λ = θ² e^{−α}/2. Central differences are second order.
TEST(Catalogue, BoundaryValueProblemConvergesToBratuSolutionWithOrderTwo) {
  const double amplitude = 1.0;
  const double theta = 4.0 * std::acosh(std::exp(amplitude / 2.0));
  const double exact_lambda = theta * theta * std::exp(-amplitude) / 2.0;
  std::vector<double> h, error;
  for (int N : {19, 39, 79, 159}) {  // odd N: a grid point sits at t = ½, where u is largest
    const Eigen::VectorXd x = ArrheniusBratu{N}.point_with_amplitude(amplitude, 0.0);
    h.push_back(1.0 / (N + 1));
    error.push_back(std::abs(x(N) - exact_lambda));
  }
  EXPECT_LT(error.back(), 1e-3);
  EXPECT_NEAR(testing::observed_order(h, error), 2.0, 0.1);
}

// The λ-branch at fixed ε is S-shaped below the cusp and monotone above it.
TEST(Catalogue, BoundaryValueBranchIsSShapedBelowTheCusp) {
  const ArrheniusBratu problem{100};
  const auto lambda = [&](double amplitude, double epsilon) {
    return problem.point_with_amplitude(amplitude, epsilon)(100);
  };
  // ε = 0.2: ignition fold near max u = 2.4 (λ ≈ 4.65), extinction fold near 15.5 (λ ≈ 3.51).
  EXPECT_GT(lambda(2.4, 0.2), lambda(8.0, 0.2));
  EXPECT_GT(lambda(8.0, 0.2), lambda(15.5, 0.2));
  EXPECT_LT(lambda(15.5, 0.2), lambda(30.0, 0.2));
  double previous = 0.0;
  for (double amplitude = 1.0; amplitude <= 20.0; amplitude += 1.0) {
    const double current = lambda(amplitude, 0.3);
    EXPECT_GT(current, previous) << "ε = 0.3 is above the cusp: λ increases with max u";
    previous = current;
  }
}

TEST(Catalogue, ExactAreasAndEulerCharacteristics) {
  EXPECT_DOUBLE_EQ(*make_catalogue_problem("sphere:radius=2").exact_area, 16.0 * kPi);
  EXPECT_DOUBLE_EQ(*make_catalogue_problem("sphere_cut").exact_area, 2.0 * kPi * 1.8);
  EXPECT_DOUBLE_EQ(*make_catalogue_problem("torus").exact_area, 4.0 * kPi * kPi * 0.4);
  EXPECT_DOUBLE_EQ(*make_catalogue_problem("plane").exact_area, 4.0);
  const std::vector<std::pair<std::string, int>> expected = {
      {"plane", 1},         {"sphere", 2}, {"sphere_cut", 1}, {"torus", 0}, {"equipotential", 2},
      {"whitney_pleat", 1}, {"trough", 1}, {"cstr", 1},       {"bvp", 1},   {"bratu2d:N=5", 1}};
  for (const auto& [name, euler] : expected) {
    EXPECT_EQ(make_catalogue_problem(name).expected_euler_characteristic, euler) << name;
  }
  // Without the ε-perturbation the trough is the figure-eight and the line: not a manifold.
  EXPECT_FALSE(make_catalogue_problem("trough:epsilon=0").expected_euler_characteristic);
}

// Whitney pleat: M ∩ box is the graph of μ = x³ − λx over R = {|x|, |λ| ≤ 1.5, |x³ − λx| ≤ 1.5}.
// Every vertical line x = const meets R in one non-empty interval, so R is a disk (χ = 1).
TEST(Catalogue, WhitneyPleatInTheBoxIsAGraphOverADisk) {
  for (int i = 0; i <= 300; ++i) {
    const double x = -1.5 + 3.0 * i / 300;
    int runs = 0;
    bool inside_before = false;
    for (int j = 0; j <= 3000; ++j) {
      const double lambda = -1.5 + 3.0 * j / 3000;
      const bool inside = std::abs(x * x * x - lambda * x) <= 1.5;
      runs += inside && !inside_before;
      inside_before = inside;
    }
    EXPECT_EQ(runs, 1) << "x = " << x;
  }
}

// The trough's arch leaves the box through each face x = ±0.15 exactly once (a single root of
// F(±0.15, y, z) in z > 0), so the component of the start is an arc times [−0.14, 0.14]: χ = 1.
TEST(Catalogue, TroughArchCrossesEachSideFaceOnce) {
  const Trough trough{4.0, 0.25, 5e-5};
  for (double x : {-0.15, 0.15}) {
    int sign_changes = 0;
    double previous = residual(trough, point3(x, 0, 1e-7))(0);
    for (int k = 1; k <= 100000; ++k) {
      const double current = residual(trough, point3(x, 0, k * 1e-5))(0);
      sign_changes += (current > 0) != (previous > 0);
      previous = current;
    }
    EXPECT_EQ(sign_changes, 1) << "x = " << x;
  }
}

// CSTR: M is the graph over (x1, B) given by point_on_manifold; for fixed x1 the box leaves one
// interval of B, and the x1 with a non-empty interval form an interval: a disk (χ = 1), which is
// also what Hohmann's Table I gives (166 − 447 + 282 = 1).
TEST(Catalogue, StirredTankReactorInTheBoxIsAGraphOverADisk) {
  const ProblemSetup setup = make_catalogue_problem("cstr");
  const auto& reactor = dynamic_cast<const StirredTankReactor&>(*setup.problem);
  int nonempty_runs = 0;
  bool nonempty_before = false;
  for (int i = 0; i <= 1000; ++i) {
    const double x1 = 0.02 + 0.98 * i / 1000;
    int runs = 0;
    bool inside_before = false;
    for (int j = 0; j <= 1000; ++j) {
      const double B = 1.0 + 11.0 * j / 1000;
      const bool inside =
          x1 < 1.0 && setup.domain.contains(reactor.point_on_manifold(x1, B), 1e-12);
      runs += inside && !inside_before;
      inside_before = inside;
    }
    EXPECT_LE(runs, 1) << "x1 = " << x1;
    nonempty_runs += runs > 0 && !nonempty_before;
    nonempty_before = runs > 0;
  }
  EXPECT_EQ(nonempty_runs, 1);
}

TEST(Catalogue, ParsesParameters) {
  const ProblemSetup torus = make_catalogue_problem("torus:R=2,r=0.5");
  const auto& shape = dynamic_cast<const Torus&>(*torus.problem);
  EXPECT_EQ(shape.major_radius(), 2.0);
  EXPECT_EQ(shape.minor_radius(), 0.5);
  EXPECT_NE(torus.description.find("R=2 r=0.5"), std::string::npos) << torus.description;
  // Spaces around names, keys and values are allowed; omitted parameters keep their defaults.
  const ProblemSetup spaced = make_catalogue_problem(" torus : r = 0.25 ");
  EXPECT_EQ(dynamic_cast<const Torus&>(*spaced.problem).major_radius(), 1.0);
  EXPECT_EQ(dynamic_cast<const Torus&>(*spaced.problem).minor_radius(), 0.25);
  EXPECT_EQ(make_catalogue_problem("bvp:points=10").problem->ambient_dimension(), 12);
  EXPECT_EQ(make_catalogue_problem("sphere_cut:cut=0.5").domain.half_spaces().size(), 1u);
}

void expect_invalid(const std::string& specification, const std::vector<std::string>& fragments) {
  try {
    make_catalogue_problem(specification);
    ADD_FAILURE() << "no exception for '" << specification << "'";
  } catch (const InvalidArgument& e) {
    for (const std::string& fragment : fragments) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos)
          << "'" << specification << "': " << e.what();
    }
  }
}

TEST(Catalogue, RejectsBadSpecificationsWithActionableMessages) {
  expect_invalid("doughnut", {"unknown problem 'doughnut'", "torus", "sphere_cut", "bvp"});
  expect_invalid("torus:q=1", {"no parameter 'q'", "R, r"});
  expect_invalid("plane:size=2", {"no parameter 'size'", "no parameters"});
  expect_invalid("torus:R=abc", {"'R'", "'abc'", "not a finite number"});
  expect_invalid("torus:R=1.5x", {"'1.5x'"});
  expect_invalid("torus:R=", {"'R'", "not a finite number"});
  expect_invalid("torus:R=inf", {"not a finite number"});
  expect_invalid("torus:R=2,R=3", {"'R' is given twice"});
  expect_invalid("torus:R", {"'R' is not of the form key=value"});
  expect_invalid("torus:R=0.3", {"R = 0.3", "r = 0.4", "0 < r < R"});
  expect_invalid("sphere:radius=-1", {"radius = -1"});
  expect_invalid("sphere_cut:cut=1.2", {"cut = 1.2"});
  expect_invalid("bvp:points=2.5", {"points = 2.5", "whole number"});
}

TEST(Catalogue, ResolveProblemUsesTheCatalogueOrAnExistingFile) {
  EXPECT_EQ(resolve_problem("sphere:radius=3").problem->name(), "sphere");
  try {
    resolve_problem("no/such/problem.tsr");
    ADD_FAILURE() << "no exception";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("neither an existing file"), std::string::npos)
        << e.what();
  }
  // An existing file goes to the problem-file reader, whatever its name; this one is not a
  // valid problem file, so the reader (not the catalogue) rejects it.
  const std::string path = testing::temporary_directory("catalogue_resolve") + "/sphere";
  std::ofstream(path) << "this is not a problem file\n";
  try {
    resolve_problem(path);
    ADD_FAILURE() << "no exception";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(std::string(e.what()).find("known problems"), std::string::npos) << e.what();
  }
  // "file:key=value" overrides the file's parameters, like "name:key=value" for the catalogue.
  const std::string ball = testing::temporary_directory("catalogue_resolve") + "/ball.tsr";
  std::ofstream(ball) << "name ball\nvariables x y z\nparameter r = 1\n"
                         "equation x^2 + y^2 + z^2 - r^2\nstart 0 0 r\n";
  EXPECT_EQ(resolve_problem(ball).start(2), 1.0);
  EXPECT_EQ(resolve_problem(ball + ":r=2").start(2), 2.0);
}

}  // namespace
}  // namespace tessera
