// SPDX-License-Identifier: MIT
#include "tessera/problems/problem_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>

#include "support/test_support.h"
#include "tessera/core/dynamics.h"
#include "tessera/core/error.h"
#include "tessera/problems/catalogue.h"

namespace {

using tessera::InvalidArgument;
using tessera::load_problem_file;
using tessera::parse_problem;
using tessera::ProblemSetup;

const std::string sphere_text = R"(# Sphere cut by the half-space z >= -0.8
name sphere_cut
variables x y z
parameter r = 1
equation x^2 + y^2 + z^2 - r^2
start 0 0 r
step 0.3                      # optional suggested edge length
halfspace normal 0 0 1 point 0 0 -0.8
euler 1
)";

TEST(ProblemFile, SphereReproducesFAndItsJacobian) {
  const ProblemSetup setup = parse_problem(sphere_text, "sphere.tsr");
  const auto& problem = *setup.problem;
  EXPECT_EQ(problem.name(), "sphere_cut");
  EXPECT_EQ(problem.ambient_dimension(), 3);
  EXPECT_EQ(problem.coordinate_names(), (std::vector<std::string>{"x", "y", "z"}));
  std::mt19937 random(3);
  std::uniform_real_distribution<double> coordinate(-2.0, 2.0);
  for (int sample = 0; sample < 50; ++sample) {
    const Eigen::Vector3d x(coordinate(random), coordinate(random), coordinate(random));
    Eigen::VectorXd F(1);
    Eigen::MatrixXd J(1, 3);
    problem.evaluate(x, F);
    problem.jacobian(x, J);
    EXPECT_DOUBLE_EQ(F(0), x.squaredNorm() - 1.0);
    EXPECT_EQ(J, (2.0 * x).transpose()) << "at " << x.transpose();  // exact: 2x has no rounding
  }
}

TEST(ProblemFile, SphereHasItsStartStepDomainAndEuler) {
  const ProblemSetup setup = parse_problem(sphere_text, "sphere.tsr");
  EXPECT_EQ(setup.start, Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(setup.suggested_step, 0.3);
  ASSERT_TRUE(setup.expected_euler_characteristic.has_value());
  EXPECT_EQ(*setup.expected_euler_characteristic, 1);
  EXPECT_FALSE(setup.exact_area.has_value());
  ASSERT_EQ(setup.domain.half_spaces().size(), 1u);
  EXPECT_EQ(setup.domain.half_spaces()[0].label, "z >= -0.8");
  EXPECT_TRUE(setup.domain.contains(Eigen::Vector3d(0, 0, -0.79)));
  EXPECT_FALSE(setup.domain.contains(Eigen::Vector3d(0, 0, -0.81)));
  EXPECT_EQ(setup.description, "sphere_cut from sphere.tsr (r = 1)");
}

TEST(ProblemFile, OverridesReplaceParametersAndReachLaterDefinitions) {
  const std::string text = R"(variables x y z
parameter R = 2
parameter r = R/4
equation (x^2 + y^2 + z^2 + R^2 - r^2)^2 - 4*R^2*(x^2 + y^2)
start R+r 0 0
)";
  const ProblemSetup setup = parse_problem(text, "torus.tsr", {{"R", 4.0}});
  EXPECT_EQ(setup.start, Eigen::Vector3d(5.0, 0, 0));  // R + R/4 with R = 4
  Eigen::VectorXd F(1);
  setup.problem->evaluate(Eigen::Vector3d(3.0, 0, 0), F);  // inner equator R - r = 3
  EXPECT_NEAR(F(0), 0.0, 1e-12);
  EXPECT_EQ(setup.description, "torus from torus.tsr (R = 4, r = 1)");
}

TEST(ProblemFile, OverrideOfAnUnknownParameterIsAnError) {
  try {
    parse_problem(sphere_text, "sphere.tsr", {{"q", 1.0}});
    FAIL() << "no error";
  } catch (const InvalidArgument& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("sphere.tsr"), std::string::npos) << what;
    EXPECT_NE(what.find("override 'q'"), std::string::npos) << what;
    EXPECT_NE(what.find("parameters: r"), std::string::npos) << what;
  }
  EXPECT_THROW(parse_problem(sphere_text, "sphere.tsr", {{"r", INFINITY}}), InvalidArgument);
}

TEST(ProblemFile, AcceptsCommentsBlankLinesTabsCrlfAndCompactParameters) {
  const std::string text =
      "\r\n# comment only\r\n\tvariables\tx y z   \r\n\r\nparameter a=2 # trailing\r\n"
      "equation x + y + z - a\r\nstart 2 0 0\r\n";
  const ProblemSetup setup = parse_problem(text);
  Eigen::VectorXd F(1);
  setup.problem->evaluate(Eigen::Vector3d(1, 1, 1), F);
  EXPECT_EQ(F(0), 1.0);
  EXPECT_EQ(setup.problem->name(), "problem");  // no name line, no file
}

TEST(ProblemFile, NameDefaultsToTheFileStem) {
  const auto directory = tessera::testing::temporary_directory("problem_file_stem");
  const auto path = directory + "/my_surface.tsr";
  std::ofstream(path) << "variables x y z\nequation x + y^2 - z\nstart 0 0 0\n";
  const ProblemSetup setup = load_problem_file(path);
  EXPECT_EQ(setup.problem->name(), "my_surface");
  EXPECT_TRUE(setup.domain.is_unbounded());
  EXPECT_EQ(setup.suggested_step, ProblemSetup{}.suggested_step);
}

TEST(ProblemFile, MissingFileIsAnError) {
  try {
    load_problem_file("/nonexistent/where.tsr");
    FAIL() << "no error";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("'/nonexistent/where.tsr' does not exist"),
              std::string::npos)
        << error.what();
  }
}

// ---- the example files ------------------------------------------------------------------

std::vector<std::string> example_files() {
  std::vector<std::string> files;
  for (const auto& entry :
       std::filesystem::directory_iterator(tessera::testing::source_path("examples/problems"))) {
    if (entry.path().extension() == ".tsr") {
      files.push_back(entry.path().string());
    }
  }
  return files;
}

TEST(ProblemFile, EveryExampleParsesAndIsSoundAtItsStart) {
  const auto files = example_files();
  EXPECT_GE(files.size(), 3u);
  for (const auto& file : files) {
    SCOPED_TRACE(file);
    const ProblemSetup setup = load_problem_file(file);
    const auto& problem = *setup.problem;
    const int n = problem.ambient_dimension();
    EXPECT_FALSE(problem.name().empty());
    EXPECT_EQ(setup.start.size(), n);
    EXPECT_TRUE(setup.domain.contains(setup.start));
    EXPECT_GT(setup.suggested_step, 0.0);
    EXPECT_FALSE(setup.description.empty());
    Eigen::VectorXd F(n - 2);
    Eigen::MatrixXd J(n - 2, n);
    problem.evaluate(setup.start, F);
    problem.jacobian(setup.start, J);
    EXPECT_TRUE(F.allFinite());
    EXPECT_TRUE(J.allFinite());
    // Central differences, as an oracle only (error ~1e-10 for these smooth functions).
    const double h = 1e-6;
    for (int i = 0; i < n; ++i) {
      Eigen::VectorXd plus = setup.start;
      Eigen::VectorXd minus = setup.start;
      plus(i) += h;
      minus(i) -= h;
      Eigen::VectorXd F_plus(n - 2);
      Eigen::VectorXd F_minus(n - 2);
      problem.evaluate(plus, F_plus);
      problem.evaluate(minus, F_minus);
      EXPECT_LT((J.col(i) - (F_plus - F_minus) / (2 * h)).norm(), 1e-7) << "column " << i;
    }
  }
}

TEST(ProblemFile, SphereCutExampleKnowsItsArea) {
  const ProblemSetup setup =
      load_problem_file(tessera::testing::source_path("examples/problems/sphere_cut.tsr"));
  ASSERT_TRUE(setup.exact_area.has_value());
  EXPECT_DOUBLE_EQ(*setup.exact_area, 3.6 * std::numbers::pi);  // 4π minus the cap 2π·0.2
  EXPECT_EQ(*setup.expected_euler_characteristic, 1);
}

TEST(ProblemFile, WhitneyPleatExample) {
  const ProblemSetup setup =
      load_problem_file(tessera::testing::source_path("examples/problems/whitney_pleat.tsr"));
  EXPECT_EQ(setup.problem->coordinate_names(), (std::vector<std::string>{"x", "lambda", "mu"}));
  const Eigen::Vector3d x(0.5, -0.25, 0.75);
  Eigen::VectorXd F(1);
  setup.problem->evaluate(x, F);
  EXPECT_DOUBLE_EQ(F(0), 0.125 + 0.125 - 0.75);
  EXPECT_EQ(setup.domain.half_spaces().size(), 6u);  // the box [-1.5, 1.5]^3
  EXPECT_FALSE(setup.domain.contains(Eigen::Vector3d(0, 1.6, 0)));
}

TEST(ProblemFile, CstrExample) {
  const ProblemSetup setup =
      load_problem_file(tessera::testing::source_path("examples/problems/cstr.tsr"));
  EXPECT_EQ(setup.problem->coordinate_names(), (std::vector<std::string>{"x1", "x2", "Da", "B"}));
  const Eigen::Vector4d x(0.3, 1.2, 0.1, 7.0);
  Eigen::VectorXd F(2);
  setup.problem->evaluate(x, F);
  const double reaction = 0.1 * 0.7 * std::exp(1.2);
  EXPECT_NEAR(F(0), -0.3 + reaction, 1e-15);
  EXPECT_NEAR(F(1), -1.5 * 1.2 + 7.0 * reaction, 1e-14);
  EXPECT_EQ(setup.start, Eigen::Vector4d(0.1, 0.1, 0.1, 5));
  EXPECT_EQ(setup.domain.half_spaces().size(), 8u);
  const ProblemSetup other_beta = load_problem_file(
      tessera::testing::source_path("examples/problems/cstr.tsr"), {{"beta", 1.0}});
  other_beta.problem->evaluate(x, F);
  EXPECT_NEAR(F(1), -2.0 * 1.2 + 7.0 * reaction, 1e-14);
}

TEST(ProblemFile, ViewLineNamesFunctionalsOfTheVariables) {
  const std::string text = R"(variables x1 x2 Da B
parameter beta = 0.5
equation -x1 + Da*(1 - x1)*exp(x2)
equation -(1 + beta)*x2 + B*Da*(1 - x1)*exp(x2)
start 0.1 0.1 0.1 5
view Da, B, heat = (1 + beta)*x2, norm    # a parameter in an expression
)";
  const ProblemSetup setup = parse_problem(text, "cstr.tsr");
  ASSERT_TRUE(setup.view.has_value());
  EXPECT_EQ(setup.view->names(), (std::vector<std::string>{"Da", "B", "heat", "norm"}));
  const Eigen::Vector4d x(0.3, 1.2, 0.1, 7.0);
  const Eigen::VectorXd values = setup.view->evaluate(x);
  EXPECT_EQ(values(0), 0.1);
  EXPECT_EQ(values(1), 7.0);
  EXPECT_EQ(values(2), 1.5 * 1.2);
  EXPECT_DOUBLE_EQ(values(3), x.norm());
  // An override reaches the view's expressions as it reaches the equations.
  const ProblemSetup other_beta = parse_problem(text, "cstr.tsr", {{"beta", 1.0}});
  EXPECT_EQ(other_beta.view->evaluate(x)(2), 2.0 * 1.2);
  // Without a view line the setup has none (the CLI then writes every coordinate).
  EXPECT_FALSE(parse_problem(sphere_text, "sphere.tsr").view.has_value());
}

// ---- dynamics ----------------------------------------------------------------------------

TEST(ProblemFile, DynamicsLineDeclaresParametersSignAndMass) {
  const std::string text = R"(variables x1 x2 Da B
parameter beta = 0.5
equation -x1 + Da*(1 - x1)*exp(x2)
equation -(1 + beta)*x2 + B*Da*(1 - x1)*exp(x2)
start 0.1 0.1 0.1 5
dynamics mass 1 2*beta parameters Da B sign -1    # sections in any order
)";
  const ProblemSetup setup = parse_problem(text, "cstr.tsr");
  const auto dynamics = setup.problem->dynamics();
  ASSERT_TRUE(dynamics.has_value());
  EXPECT_EQ(dynamics->parameters, (std::array<int, 2>{2, 3}));
  EXPECT_EQ(dynamics->sign, -1.0);
  EXPECT_EQ(dynamics->mass_diagonal, Eigen::Vector2d(1.0, 1.0));
  EXPECT_EQ(tessera::state_indices(*dynamics, 4), (std::vector<int>{0, 1}));
  // An override reaches the mass as it reaches the equations.
  const auto other_beta = parse_problem(text, "cstr.tsr", {{"beta", 2.0}}).problem->dynamics();
  EXPECT_EQ(other_beta->mass_diagonal, Eigen::Vector2d(1.0, 4.0));
  // Without sign and mass: B·u' = F with B = I.
  const auto plain = parse_problem(
                         "variables x y z\nequation x^3 - y*x - z\nstart 0 0 0\n"
                         "dynamics parameters z x\n")
                         .problem->dynamics();
  ASSERT_TRUE(plain.has_value());
  EXPECT_EQ(plain->parameters, (std::array<int, 2>{2, 0}));
  EXPECT_EQ(plain->sign, 1.0);
  EXPECT_TRUE(plain->has_identity_mass());
  // Without a dynamics line the problem declares none.
  EXPECT_FALSE(parse_problem(sphere_text, "sphere.tsr").problem->dynamics().has_value());
}

TEST(ProblemFile, VariablesMayBeNamedLikeTheDynamicsSections) {
  const std::string text =
      "variables sign mass z\nequation sign^3 - mass*sign - z\nstart 0 0 0\n"
      "dynamics parameters mass z sign -1\n";
  const auto dynamics = parse_problem(text, "t.tsr").problem->dynamics();
  ASSERT_TRUE(dynamics.has_value());
  EXPECT_EQ(dynamics->parameters, (std::array<int, 2>{1, 2}));
  EXPECT_EQ(dynamics->sign, -1.0);
}

TEST(ProblemFile, ExampleDynamicsAreTheCataloguesOwn) {
  for (const std::string name : {"whitney_pleat", "cstr"}) {
    SCOPED_TRACE(name);
    const ProblemSetup file =
        load_problem_file(tessera::testing::source_path("examples/problems/" + name + ".tsr"));
    const ProblemSetup catalogue = tessera::make_catalogue_problem(name);
    const auto ours = file.problem->dynamics();
    const auto theirs = catalogue.problem->dynamics();
    ASSERT_TRUE(ours.has_value());
    ASSERT_TRUE(theirs.has_value());
    EXPECT_EQ(ours->parameters, theirs->parameters);
    EXPECT_EQ(ours->sign, theirs->sign);
    EXPECT_TRUE(ours->has_identity_mass());
    EXPECT_TRUE(theirs->has_identity_mass());
  }
}

// ---- errors: each names the file, the line and what is wrong -------------------------------

// Lines 1–5 are valid; a case appends or replaces lines to break one rule.
const std::string header = "name t\nvariables x y z\nparameter r = 1\n";
const std::string equation = "equation x^2 + y^2 + z^2 - r^2\n";
const std::string start = "start 0 0 1\n";

struct ErrorCase {
  std::string text;
  std::vector<std::string> words;  // each must occur in the message
};

TEST(ProblemFile, EveryErrorNamesTheLineAndTheProblem) {
  const std::vector<ErrorCase> cases = {
      {header + "equation x^2 + w\n" + start,
       {"t.tsr:4:16: equation 1: unknown name 'w' (variables: x, y, z; parameters: r)",
        "\n    equation x^2 + w\n                   ^"}},
      {header + "equation expp(x) + y + z\n" + start, {"t.tsr:4:10:", "unknown function 'expp'"}},
      {header + "equation (x^2 + y^2\n" + start, {"t.tsr:4:", "missing ')'"}},
      {header + equation + "start 0 0\n",
       {"t.tsr:5:", "start has 2 values, expected 3", "one per variable: x, y, z"}},
      {"variables x y x\n" + equation + start, {"t.tsr:1:15:", "duplicate variable 'x'"}},
      {"variables x y pi\nequation x+y\n" + start, {"t.tsr:1:15:", "'pi' is reserved"}},
      {"variables x y\nequation x+y\nstart 0 0\n", {"t.tsr:1:", "at least 3"}},
      {header + "equatoin x\n" + start, {"t.tsr:4:1:", "unknown keyword 'equatoin'", "keywords:"}},
      {header + equation + start + "box x 2 1\n", {"t.tsr:6:", "empty domain", "of x"}},
      {header + equation + start + "box w 0 1\n", {"t.tsr:6:5:", "unknown variable 'w'"}},
      {header + equation + start + "box x -1 1\nbox x -2 2\n",
       {"t.tsr:7:", "'x' is already bounded on line 6"}},
      {header + equation + start + "box x -1\n", {"t.tsr:6:", "box VARIABLE LOWER UPPER"}},
      {header + equation, {"t.tsr:", "missing 'start' line"}},
      {header + start, {"t.tsr:", "missing equations", "3 variables need n-2 = 1 equation"}},
      {header + equation + "equation x - y\n" + start,
       {"t.tsr:5:", "too many equations", "3 variables need n-2 = 1 equation, found 2",
        "lines 4, 5"}},
      {"variables a b c d\nequation a + b\nstart 0 0 0 0\n",
       {"t.tsr:1:", "too few equations", "4 variables need n-2 = 2 equations, found 1"}},
      {header + equation + "start 0 0 1e999\n", {"t.tsr:5:11:", "out of the range"}},
      {header + equation + start + "step 1/0\n", {"t.tsr:6:", "step = inf is not a finite"}},
      {header + equation + start + "step -0.1\n", {"t.tsr:6:", "step = -0.1 must be > 0"}},
      {"variables x y z\nparameter r = log(0)\n" + equation + start,
       {"t.tsr:2:", "parameter 'r' = -inf is not a finite number"}},
      {header + equation + start + start,
       {"t.tsr:6:1:", "duplicate 'start' line", "first given on line 5"}},
      {header + "parameter r = 2\n" + equation + start,
       {"t.tsr:4:", "duplicate parameter 'r'", "first defined on line 3"}},
      {"variables x y z\nparameter a = b\nparameter b = 1\n" + equation + start,
       {"t.tsr:2:15:", "unknown name 'b'"}},
      {header + "parameter x = 2\n" + equation + start, {"t.tsr:4:", "same name as a variable"}},
      {header + "parameter s 2\n" + equation + start, {"t.tsr:4:", "parameter NAME = VALUE"}},
      {header + equation + start + "halfspace normal 0 1 point 0 0 -0.8\n",
       {"t.tsr:6:", "halfspace normal has 2 values, expected 3"}},
      {header + equation + start + "halfspace normal 0 0 0 point 0 0 -0.8\n",
       {"t.tsr:6:", "normal is zero"}},
      {header + equation + start + "halfspace 0 0 1 0 0 -0.8\n",
       {"t.tsr:6:", "halfspace normal N1"}},
      {header + equation + "start 0 0 -1\nhalfspace normal 0 0 1 point 0 0 -0.8\n",
       {"t.tsr:5:", "outside the domain", "z >= -0.8"}},
      {"variables x y z\nequation log(x) + y + z\nstart -1 0 0\n",
       {"t.tsr:3:", "equation 1 is", "must be finite"}},
      {header + equation + start + "euler 1.5\n", {"t.tsr:6:7:", "integer Euler characteristic"}},
      {header + equation + start + "area 0\n", {"t.tsr:6:", "area = 0 must be > 0"}},
      {"name two words\nvariables x y z\nparameter r = 1\n" + equation + start,
       {"t.tsr:1:6:", "one word"}},
      {equation + start, {"t.tsr:", "missing 'variables' line"}},
      {header + "equation\n" + start, {"t.tsr:4:", "expected an expression"}},
      {header + equation + start + "view x, w\n",
       {"t.tsr:6:9: view: 'w' is no coordinate", "coordinates: x, y, z", "NAME = EXPRESSION",
        "\n    view x, w\n            ^"}},
      {header + equation + start + "view x, y, s = x + q\n",
       {"t.tsr:6:20: view: 's = x + q': unknown name 'q'", "parameters: r"}},
      {header + equation + start + "view x, y, s = x +\n",
       {"t.tsr:6:", "view: 's = x +': expected"}},
      {header + equation + start + "view x, max:u\n",
       {"t.tsr:6:13:", "no block 'u'", "has no coordinate blocks"}},
      {header + equation + start + "view x, x\n", {"t.tsr:6:9:", "'x' is given twice"}},
      {header + equation + start + "view x = 2*y, z\n",
       {"t.tsr:6:6:", "'x = 2*y'", "give the expression another name"}},
      {header + equation + start + "view z\n", {"t.tsr:6:", "1 functional given, need at least 2"}},
      {header + equation + start + "view\n", {"t.tsr:6:", "expected functionals after 'view'"}},
      {header + equation + start + "view x, y\nview x, z\n", {"t.tsr:7:1:", "duplicate 'view'"}},
      // dynamics
      {header + equation + start + "dynamics parameters x w\n",
       {"t.tsr:6:23: dynamics: unknown variable 'w' (variables: x, y, z)"}},
      {header + equation + start + "dynamics parameters x x\n",
       {"t.tsr:6:23:", "the same variable 'x' twice"}},
      {header + equation + start + "dynamics parameters x r\n",
       {"t.tsr:6:23:", "'r' is a constant ('parameter' on line 3), not a variable of M",
        "two of the variables (x, y, z)"}},
      {header + equation + start + "dynamics parameters x\n",
       {"t.tsr:6:10:", "parameters: expected two variables, found 1 word"}},
      {header + equation + start + "dynamics parameters x y z\n",
       {"t.tsr:6:10:", "expected two variables, found 3 words"}},
      {header + equation + start + "dynamics parameters x y mass 1 1\n",
       {"t.tsr:6:25:", "mass has 2 values, expected 1", "one per equation"}},
      {header + equation + start + "dynamics parameters x y mass -r\n",
       {"t.tsr:6:30:", "mass entry 1 = -1 must be >= 0", "algebraic equation"}},
      {header + equation + start + "dynamics parameters x y mass 1/0\n",
       {"t.tsr:6:", "mass entry 1 = inf is not a finite number"}},
      {header + equation + start + "dynamics parameters x y mass q\n",
       {"t.tsr:6:30:", "unknown name 'q'"}},
      {header + equation + start + "dynamics parameters x y sign 2\n",
       {"t.tsr:6:30:", "sign = 2 must be 1", "or -1"}},
      {header + equation + start + "dynamics parameters x y sign\n",
       {"t.tsr:6:25:", "sign: expected one value, 1 or -1, found 0 words"}},
      {header + equation + start + "dynamics parameters x y sign 1 sign -1\n",
       {"t.tsr:6:32:", "'sign' is given twice"}},
      {header + equation + start + "dynamics x y\n",
       {"t.tsr:6:10:", "found 'x' where 'parameters', 'sign' or 'mass' was expected",
        "dynamics parameters P1 P2"}},
      {header + equation + start + "dynamics sign -1\n",
       {"t.tsr:6:", "missing 'parameters P1 P2'"}},
      {header + equation + start + "dynamics\n",
       {"t.tsr:6:", "expected 'dynamics parameters P1 P2 [sign -1] [mass B1 … Bm]'"}},
      {header + equation + start + "dynamics parameters x y\ndynamics parameters y z\n",
       {"t.tsr:7:1:", "duplicate 'dynamics' line", "first given on line 6"}},
  };
  for (const auto& test : cases) {
    try {
      parse_problem(test.text, "t.tsr");
      ADD_FAILURE() << "no error for:\n" << test.text;
    } catch (const InvalidArgument& error) {
      const std::string what = error.what();
      for (const auto& word : test.words) {
        EXPECT_NE(what.find(word), std::string::npos) << "message\n"
                                                      << what << "\nlacks '" << word << "'; file:\n"
                                                      << test.text;
      }
    }
  }
}

}  // namespace
