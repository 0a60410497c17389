// SPDX-License-Identifier: MIT
#include "tessera/problems/expression.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <numbers>
#include <random>

// Counting global allocator: the only way to prove that evaluation does not allocate, since
// std::vector (the workspace) does not go through Eigen's malloc hooks. It counts every
// operator new in this test binary; expression_problem_test.cpp reads it too.
namespace {
std::atomic<long> allocation_counter{0};
}
long tessera_test_allocation_count() { return allocation_counter.load(); }
void* operator new(std::size_t size) {
  ++allocation_counter;
  if (void* memory = std::malloc(size == 0 ? 1 : size)) {
    return memory;
  }
  throw std::bad_alloc();
}
// GCC cannot see that this operator new is the malloc above and warns about free() here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* memory) noexcept { std::free(memory); }
void operator delete(void* memory, std::size_t) noexcept { std::free(memory); }
#pragma GCC diagnostic pop

namespace {

using tessera::Expression;
using tessera::ExpressionSyntaxError;
using tessera::ExpressionWorkspace;
using tessera::InvalidArgument;

const std::vector<std::string> xyz = {"x", "y", "z"};

double evaluate(const std::string& text, const Eigen::VectorXd& x,
                const std::map<std::string, double>& parameters = {}) {
  return Expression(text, xyz, parameters).value(x);
}

TEST(Expression, ReadsNumbersInEveryNotation) {
  const Eigen::VectorXd x = Eigen::VectorXd::Zero(3);
  EXPECT_EQ(evaluate("1e-3", x), 1e-3);
  EXPECT_EQ(evaluate("2.5E+2", x), 250.0);
  EXPECT_EQ(evaluate(".5", x), 0.5);
  EXPECT_EQ(evaluate("3.", x), 3.0);
  EXPECT_EQ(evaluate("12", x), 12.0);
  EXPECT_EQ(evaluate("1E2", x), 100.0);
  EXPECT_EQ(evaluate("pi", x), std::numbers::pi);
}

TEST(Expression, FollowsMathematicalPrecedence) {
  const Eigen::Vector3d x(3.0, 2.0, -1.0);
  const std::vector<std::pair<std::string, double>> cases = {
      {"1 + 2*3", 7.0},    {"2*3^2", 18.0},    {"-2^2", -4.0},    {"-x^2", -9.0},
      {"(-x)^2", 9.0},     {"2^3^2", 512.0},   {"(2^3)^2", 64.0}, {"(1 + 2)*3", 9.0},
      {"8/4/2", 1.0},      {"8 - 4 - 2", 2.0}, {"2^-1", 0.5},     {"x*-y", -6.0},
      {"x - -y", 5.0},     {"+x", 3.0},        {"-x*y", -6.0},    {"x^2*y", 18.0},
      {"1 - x^2/y", -3.5}, {"2*x^y", 18.0},    {"-z^2 + 1", 0.0}, {"x/y*z", -1.5},
  };
  for (const auto& [text, expected] : cases) {
    EXPECT_DOUBLE_EQ(evaluate(text, x), expected) << text;
  }
}

TEST(Expression, UsesParametersAndVariablesInOrder) {
  const Expression f("a*x + b*y - z", xyz, {{"a", 2.0}, {"b", -1.0}});
  EXPECT_EQ(f.variable_count(), 3);
  EXPECT_EQ(f.variable_names(), xyz);
  EXPECT_DOUBLE_EQ(f.value(Eigen::Vector3d(1.0, 10.0, 100.0)), 2.0 - 10.0 - 100.0);
}

TEST(Expression, EveryFunctionHasTheValueOfTheStandardLibrary) {
  const Eigen::Vector3d x(0.3, 0, 0);
  const std::map<std::string, double (*)(double)> reference = {{"exp", [](double t) { return std::exp(t); }},
                                                               {"log", [](double t) { return std::log(t); }},
                                                               {"sqrt", [](double t) { return std::sqrt(t); }},
                                                               {"sin", [](double t) { return std::sin(t); }},
                                                               {"cos", [](double t) { return std::cos(t); }},
                                                               {"tan", [](double t) { return std::tan(t); }},
                                                               {"tanh", [](double t) { return std::tanh(t); }},
                                                               {"sinh", [](double t) { return std::sinh(t); }},
                                                               {"cosh", [](double t) { return std::cosh(t); }},
                                                               {"atan", [](double t) { return std::atan(t); }},
                                                               {"asin", [](double t) { return std::asin(t); }},
                                                               {"acos", [](double t) { return std::acos(t); }},
                                                               {"abs", [](double t) { return std::abs(t); }}};
  ASSERT_EQ(reference.size(), Expression::function_names().size());
  auto same = [](double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); };
  for (const auto& name : Expression::function_names()) {
    EXPECT_EQ(evaluate(name + "(x)", x), reference.at(name)(0.3)) << name;
    // log(-0.3) and sqrt(-0.3) are NaN in both
    EXPECT_TRUE(same(evaluate(name + "(-x)", x), reference.at(name)(-0.3))) << name;
  }
}

// Central differences are the oracle here only: their error is O(h²)·|f'''| + O(ε/h)·|f|,
// about 1e-10 for h = 1e-5 and the smooth, O(1) functions below, so 1e-7 can only fail for a
// wrong derivative.
void expect_gradient_matches_differences(const Expression& f, const Eigen::VectorXd& x) {
  Eigen::VectorXd gradient(x.size());
  const double value = f.value_and_gradient(x, gradient);
  EXPECT_DOUBLE_EQ(value, f.value(x));
  const double h = 1e-5;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd plus = x;
    Eigen::VectorXd minus = x;
    plus(i) += h;
    minus(i) -= h;
    const double difference = (f.value(plus) - f.value(minus)) / (2 * h);
    EXPECT_NEAR(gradient(i), difference, 1e-7 * (1.0 + std::abs(difference)))
        << f.text() << ", d/d" << f.variable_names()[i] << " at " << x.transpose();
  }
}

TEST(Expression, GradientOfEveryFunctionMatchesCentralDifferences) {
  std::mt19937 random(20240611);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  for (const auto& name : Expression::function_names()) {
    // The argument 0.3x + 0.2yz + c stays in [c - 0.5, c + 0.5]: inside (-1, 1) for asin and
    // acos, positive for log and sqrt, away from the poles of tan; all three variables occur.
    const bool needs_positive = name == "log" || name == "sqrt";
    const Expression f(
        name + "(0.3*x + 0.2*y*z" + (needs_positive ? " + 1.5)" : ")") + " * (1 + z)", xyz);
    for (int sample = 0; sample < 20; ++sample) {
      const Eigen::Vector3d x(coordinate(random), coordinate(random), coordinate(random));
      expect_gradient_matches_differences(f, x);
    }
  }
}

TEST(Expression, GradientOfEveryOperatorMatchesCentralDifferences) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  for (const std::string text :
       {"x + y - z", "x*y*z", "x/(2 + y)", "(2 + x)^(1 + y)", "(1.5 + x)^y", "2^x", "x^3",
        "x^2.5 + 0", "-x^2 + y", "-(x - y*z)", "(x*y - z)^-2 + 0*x", "exp(sin(x*y))/cosh(z)",
        "sqrt(x^2 + y^2 + z^2 + 1)"}) {
    const Expression f(text, xyz);
    for (int sample = 0; sample < 20; ++sample) {
      Eigen::Vector3d x(coordinate(random), coordinate(random), coordinate(random));
      if (text == "x^2.5 + 0") {
        x(0) = std::abs(x(0)) + 0.1;  // a non-integer power of a negative number is NaN
      }
      if (text == "(x*y - z)^-2 + 0*x") {
        x(2) = 2.0;  // keep x*y - z away from the pole
      }
      expect_gradient_matches_differences(f, x);
    }
  }
}

TEST(Expression, GradientIsExactNotApproximate) {
  const Expression f("x^2*y + 3*z", xyz);
  Eigen::Vector3d gradient;
  EXPECT_EQ(f.value_and_gradient(Eigen::Vector3d(3.0, 2.0, 1.0), gradient), 21.0);
  EXPECT_EQ(gradient, Eigen::Vector3d(12.0, 9.0, 3.0));
}

TEST(Expression, DerivativeOfAbsIsTheSign) {
  const Expression f("abs(x) + 0*y*z", xyz);
  Eigen::Vector3d gradient;
  f.value_and_gradient(Eigen::Vector3d(-2.0, 0, 0), gradient);
  EXPECT_EQ(gradient(0), -1.0);
  f.value_and_gradient(Eigen::Vector3d(2.0, 0, 0), gradient);
  EXPECT_EQ(gradient(0), 1.0);
  f.value_and_gradient(Eigen::Vector3d(0.0, 0, 0), gradient);
  EXPECT_EQ(gradient(0), 0.0);
}

TEST(Expression, PowerOfANegativeBaseToAFixedExponentHasAFiniteGradient) {
  // x^3 at x = -2: 3x² = 12. A general a^b derivative would add b-term 0·log(−2) = NaN.
  const Expression f("x^3 + y + z", xyz);
  Eigen::Vector3d gradient;
  EXPECT_EQ(f.value_and_gradient(Eigen::Vector3d(-2.0, 0, 0), gradient), -8.0);
  EXPECT_EQ(gradient, Eigen::Vector3d(12.0, 1.0, 1.0));
}

TEST(Expression, FoldsConstantSubexpressions) {
  const std::map<std::string, double> r = {{"r", 2.0}};
  EXPECT_EQ(Expression("r^2 + 2*pi*sin(r) - exp(-r)", xyz, r).tape_length(), 1);
  EXPECT_EQ(Expression("x^2", xyz, r).tape_length(), 2);  // variable, power
  EXPECT_EQ(Expression("x^2 - r^2", xyz, r).tape_length(), 4);
  EXPECT_DOUBLE_EQ(evaluate("x^2 - r^2", Eigen::Vector3d(3, 0, 0), r), 5.0);
}

TEST(Expression, KnowsWhichVariablesItDependsOn) {
  const Expression f("x*y + 0", xyz);
  EXPECT_TRUE(f.depends_on(0));
  EXPECT_TRUE(f.depends_on(1));
  EXPECT_FALSE(f.depends_on(2));
}

TEST(Expression, OutsideTheDomainGivesNaNNotAnException) {
  const Expression f("log(x) + y + z", xyz);
  EXPECT_TRUE(std::isnan(f.value(Eigen::Vector3d(-1.0, 0, 0))));
}

TEST(Expression, EvaluationWithAWorkspaceDoesNotAllocate) {
  const Expression f("exp(-x^2 - y^2)*cos(3*z) + sqrt(1 + x^2)*atan(y/(1 + z^2))", xyz);
  ExpressionWorkspace workspace;
  const Eigen::Vector3d x(0.1, 0.2, 0.3);
  Eigen::Vector3d gradient;
  f.value_and_gradient(x, gradient, workspace);  // sizes the workspace
  const long before = tessera_test_allocation_count();
  double sum = 0;
  for (int i = 0; i < 100; ++i) {
    sum += f.value(x, workspace);
    sum += f.value_and_gradient(x, gradient, workspace);
  }
  EXPECT_EQ(tessera_test_allocation_count() - before, 0);
  EXPECT_TRUE(std::isfinite(sum));
}

TEST(Expression, ChecksTheSizeOfX) {
  const Expression f("x + y + z", xyz);
  EXPECT_THROW(f.value(Eigen::Vector2d(1, 2)), InvalidArgument);
  Eigen::VectorXd gradient(2);
  EXPECT_THROW(f.value_and_gradient(Eigen::Vector3d(1, 2, 3), gradient), InvalidArgument);
}

TEST(Expression, RejectsInvalidNames) {
  EXPECT_THROW(Expression("x", {"x", "x"}), InvalidArgument);
  EXPECT_THROW(Expression("x", {"sin"}), InvalidArgument);
  EXPECT_THROW(Expression("x", {"pi"}), InvalidArgument);
  EXPECT_THROW(Expression("x", {"1x"}), InvalidArgument);
  EXPECT_THROW(Expression("x", {"x"}, {{"x", 1.0}}), InvalidArgument);
  EXPECT_THROW(Expression("x", {"x"}, {{"a", std::nan("")}}), InvalidArgument);
  std::string why;
  EXPECT_FALSE(Expression::is_valid_name("x-1", &why));
  EXPECT_NE(why.find("not a valid name"), std::string::npos) << why;
  EXPECT_TRUE(Expression::is_valid_name("lambda_2"));
}

struct SyntaxErrorCase {
  std::string text;
  int column;
  std::vector<std::string> words;  // each must occur in the reason
};

TEST(Expression, SyntaxErrorsNameTheColumnAndWhatWasExpected) {
  const std::vector<SyntaxErrorCase> cases = {
      {"x + expp(y)", 5, {"unknown function 'expp'", "functions: exp, log"}},
      {"x + w", 5, {"unknown name 'w' (variables: x, y, z; parameters: a, b)"}},
      {"sin(x", 6, {"missing ')' to close 'sin(', found the end of the expression"}},
      {"(x + y", 7, {"missing ')' to close '('"}},
      {"sin(x y)", 7, {"missing ')' to close 'sin(', found 'y'"}},
      {"x)", 2, {"unmatched ')'"}},
      {"", 1, {"empty expression"}},
      {"   ", 4, {"empty expression"}},
      {"x +", 4, {"expected a number, a name or '('", "end of the expression"}},
      {"2x", 2, {"found 'x'", "implicit multiplication"}},
      {"2 (x)", 3, {"implicit multiplication"}},
      {"x**2", 2, {"'**'", "x^y"}},
      {"1e", 1, {"malformed number '1e'"}},
      {"1e999", 1, {"'1e999'", "out of the range"}},
      {"sin x", 1, {"'sin' needs its argument in parentheses"}},
      {"x(y)", 1, {"'x' is a variable, not a function"}},
      {"a(y)", 1, {"'a' is a parameter, not a function"}},
      {"ln(x)", 1, {"unknown function 'ln'", "log is the natural logarithm"}},
      {"x $ y", 3, {"found '$'"}},
      {"x * e", 5, {"unknown name 'e'", "exp(1)"}},
      {"x^", 3, {"expected a number"}},
      {". + x", 1, {"found '.'"}},
  };
  for (const auto& test : cases) {
    try {
      Expression(test.text, xyz, {{"a", 1.0}, {"b", 2.0}});
      ADD_FAILURE() << "no error for '" << test.text << "'";
    } catch (const ExpressionSyntaxError& error) {
      EXPECT_EQ(error.column(), test.column) << test.text << ": " << error.what();
      for (const auto& word : test.words) {
        EXPECT_NE(error.reason().find(word), std::string::npos)
            << "'" << test.text << "': reason '" << error.reason() << "' lacks '" << word << "'";
      }
      const std::string what = error.what();
      EXPECT_NE(what.find("column " + std::to_string(test.column)), std::string::npos) << what;
    }
  }
}

TEST(Expression, DeepNestingIsAnErrorNotAStackOverflow) {
  const std::string deep = std::string(100000, '(') + "x" + std::string(100000, ')');
  EXPECT_THROW(Expression(deep, xyz), ExpressionSyntaxError);
  const std::string fine = std::string(50, '(') + "x" + std::string(50, ')');
  EXPECT_EQ(Expression(fine, xyz).value(Eigen::Vector3d(2, 0, 0)), 2.0);
}

TEST(Expression, UnknownNameListsOnlyWhatExists) {
  try {
    Expression("w", {"x", "y", "z"});
    FAIL() << "no error";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("(variables: x, y, z)"), std::string::npos)
        << error.what();
  }
  try {
    Expression("w", {});
    FAIL() << "no error";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("no variables or parameters"), std::string::npos)
        << error.what();
  }
}

}  // namespace
