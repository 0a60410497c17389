// SPDX-License-Identifier: MIT
// Views: parsing a specification against a problem's names and blocks, the value of every
// functional, the default view of a large problem, and messages that list what is available
// without listing 10⁴ names.
#include "tessera/problems/view.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <numbers>

#include "tessera/problems/examples.h"

namespace tessera {
namespace {

using Kind = ViewFunctionalKind;

// A point of R^(N+2) for ArrheniusBratu(N): u_i = i (i = 1 … N), lambda = 3, epsilon = -0.25.
// The view does not need points of M: its functionals are defined on all of R^n.
Eigen::VectorXd ramp_point(int N) {
  Eigen::VectorXd x(N + 2);
  for (int i = 0; i < N; ++i) {
    x(i) = i + 1.0;
  }
  x(N) = 3.0;
  x(N + 1) = -0.25;
  return x;
}

// The message of the ViewSpecificationError that `specification` raises, and its column.
std::pair<std::string, int> view_error(const std::string& specification,
                                       const ImplicitProblem& problem,
                                       const std::map<std::string, double>& parameters = {}) {
  try {
    parse_view(specification, problem, parameters);
  } catch (const ViewSpecificationError& error) {
    return {error.what(), error.column()};
  }
  ADD_FAILURE() << "no error for view '" << specification << "'";
  return {"", 0};
}

bool contains(const std::string& text, const std::string& fragment) {
  return text.find(fragment) != std::string::npos;
}

TEST(View, ParsesCoordinatesAndBlockFunctionalsInOrder) {
  const ArrheniusBratu bvp(10);
  const View view = parse_view("lambda, epsilon,max:u", bvp);
  EXPECT_EQ(view.ambient_dimension(), 12);
  ASSERT_EQ(view.size(), 3);
  EXPECT_EQ(view.names(), (std::vector<std::string>{"lambda", "epsilon", "max_u"}));
  EXPECT_EQ(view.functionals()[0].kind, Kind::Coordinate);
  EXPECT_EQ(view.functionals()[0].first, 10);
  EXPECT_EQ(view.functionals()[1].first, 11);
  EXPECT_EQ(view.functionals()[2].kind, Kind::BlockMaximum);
  EXPECT_EQ(view.functionals()[2].first, 0);
  EXPECT_EQ(view.functionals()[2].size, 10);
  EXPECT_EQ(view.specification(), "lambda, epsilon, max:u");
  EXPECT_FALSE(view.is_all_coordinates());
}

TEST(View, EveryFunctionalHasItsValue) {
  const int N = 10;
  const ArrheniusBratu bvp(N);
  const double w = std::sqrt(1.0 / (N + 1));  // the block's weight √h
  const View view = parse_view(
      "u3, max:u, min:u, mean:u, absmax:u, norm:u, norm, q = lambda*epsilon + u10, lambda", bvp);
  Eigen::VectorXd x = ramp_point(N);
  x(4) = -20.0;  // u5: the largest |u|, and the minimum
  const Eigen::VectorXd values = view.evaluate(x);
  ASSERT_EQ(values.size(), 9);
  const Eigen::VectorXd u = x.head(N);
  EXPECT_EQ(values(0), 3.0);
  EXPECT_EQ(values(1), 10.0);
  EXPECT_EQ(values(2), -20.0);
  EXPECT_DOUBLE_EQ(values(3), u.sum() / N);
  EXPECT_EQ(values(4), 20.0);
  EXPECT_DOUBLE_EQ(values(5), w * u.norm());
  // The metric's norm: the u block weighted, lambda and epsilon not.
  EXPECT_DOUBLE_EQ(values(6), std::sqrt(w * w * u.squaredNorm() + 3.0 * 3.0 + 0.25 * 0.25));
  EXPECT_EQ(values(7), 3.0 * -0.25 + 10.0);
  EXPECT_EQ(values(8), 3.0);
}

// norm:B is the discrete L² norm: for the grid function sin(πx) on N interior points of [0, 1]
// h Σ sin²(π i h) = 1/2 exactly (h = 1/(N+1)), so norm:u is ‖sin(π·)‖_L² = 1/√2 at every N,
// while the Euclidean norm of the grid values grows like √N.
TEST(View, BlockNormIsTheL2NormOfTheGridFunction) {
  for (const int N : {10, 100, 10000}) {
    const ArrheniusBratu bvp(N);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(N + 2);
    for (int i = 0; i < N; ++i) {
      x(i) = std::sin(std::numbers::pi * (i + 1.0) / (N + 1.0));
    }
    const double norm = parse_view("norm:u, lambda", bvp).evaluate(x)(0);
    EXPECT_NEAR(norm, std::sqrt(0.5), 1e-13) << "N = " << N;
  }
}

TEST(View, BlockNameGivesItsCoordinatesAndAllGivesEveryCoordinate) {
  const ArrheniusBratu bvp(10);
  const View block = parse_view("lambda, u", bvp);
  ASSERT_EQ(block.size(), 11);
  EXPECT_EQ(block.names()[1], "u1");
  EXPECT_EQ(block.names()[10], "u10");
  const View all = parse_view("all", bvp);
  EXPECT_TRUE(all.is_all_coordinates());
  EXPECT_EQ(all.names(), bvp.coordinate_names());
  EXPECT_EQ(all.specification(), "all");
  const Eigen::VectorXd x = ramp_point(10);
  EXPECT_EQ(all.evaluate(x), x);
  EXPECT_TRUE(all_coordinates_view(bvp).is_all_coordinates());
}

TEST(View, SpecificationReadsBackIntoTheSameView) {
  const ArrheniusBratu bvp(10);
  const View view = parse_view("lambda,max:u , r=sqrt( u1^2+epsilon^2 ),norm", bvp);
  const View again = parse_view(view.specification(), bvp);
  EXPECT_EQ(again.names(), view.names());
  EXPECT_EQ(again.specification(), view.specification());
  const Eigen::VectorXd x = ramp_point(10);
  EXPECT_EQ(again.evaluate(x), view.evaluate(x));
}

TEST(View, EvaluatesManyPointsAsColumns) {
  const ArrheniusBratu bvp(10);
  const View view = parse_view("lambda, epsilon, max:u, norm:u", bvp);
  Eigen::MatrixXd points(12, 5);
  for (int j = 0; j < 5; ++j) {
    points.col(j) = ramp_point(10) * (j + 1.0);
  }
  const Eigen::MatrixXd values = view.evaluate_columns(points);
  ASSERT_EQ(values.rows(), 4);
  ASSERT_EQ(values.cols(), 5);
  for (int j = 0; j < 5; ++j) {
    EXPECT_EQ(values.col(j), view.evaluate(points.col(j))) << "point " << j;
  }
  EXPECT_THROW(view.evaluate_columns(Eigen::MatrixXd(3, 2)), InvalidArgument);
}

TEST(View, ExpressionsUseParametersAndOnlyTheCoordinatesTheyName) {
  const ArrheniusBratu bvp(10000);
  const View view = parse_view("s = scale*(u5000 - u1) + 1e-3*lambda", bvp, {{"scale", 2.0}});
  const ViewFunctional& f = view.functionals().front();
  EXPECT_EQ(f.kind, Kind::Expression);
  EXPECT_EQ(f.name, "s");
  EXPECT_EQ(f.variables, (std::vector<int>{4999, 0, 10000}));  // not 10002 variables
  const Eigen::VectorXd x = ramp_point(10000);
  EXPECT_DOUBLE_EQ(view.evaluate(x)(0), 2.0 * (5000 - 1) + 1e-3 * 3.0);
}

TEST(View, DefaultIsEveryCoordinateForSmallNAndASummaryForLargeN) {
  EXPECT_TRUE(default_view(ArrheniusBratu(kLargeAmbientDimension - 2)).is_all_coordinates());
  const View large = default_view(ArrheniusBratu(kLargeAmbientDimension - 1));
  EXPECT_EQ(large.specification(), "lambda, epsilon, max:u");
  EXPECT_EQ(default_view(ArrheniusBratu(100000)).names(),
            (std::vector<std::string>{"lambda", "epsilon", "max_u"}));
}

// A problem with the blocks a test asks for; F is never evaluated.
class BlockProblem final : public ImplicitProblem {
 public:
  BlockProblem(int n, std::vector<CoordinateBlock> blocks) : n_(n), blocks_(std::move(blocks)) {}
  int ambient_dimension() const override { return n_; }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>&,
                Eigen::Ref<Eigen::VectorXd> F) const override {
    F.setZero();
  }
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>&,
                Eigen::Ref<Eigen::MatrixXd> J) const override {
    J.setZero();
  }
  std::vector<CoordinateBlock> coordinate_blocks() const override { return blocks_; }

 private:
  int n_;
  std::vector<CoordinateBlock> blocks_;
};

TEST(View, DefaultOfTwoBlocksAndOfOneBlockThatIsAlmostEverything) {
  // x0 … x29 block a, x30 … x57 block b, x58 and x59 alone.
  const BlockProblem two(60, {{"a", 0, 30, 1.0}, {"b", 30, 28, 0.5}});
  EXPECT_EQ(default_view(two).specification(), "x58, x59, max:a, max:b");
  // One coordinate outside the only block: its maximum, then its norm, make three.
  const BlockProblem one(60, {{"v", 1, 59, 0.1}});
  EXPECT_EQ(default_view(one).specification(), "x0, max:v, norm:v");
  // No coordinate outside: max, norm and min.
  const BlockProblem whole(60, {{"v", 0, 60, 0.1}});
  EXPECT_EQ(default_view(whole).specification(), "max:v, norm:v, min:v");
  // Without blocks there is nothing to summarise: every coordinate.
  EXPECT_TRUE(default_view(BlockProblem(60, {})).is_all_coordinates());
}

TEST(View, DescribesCoordinatesWithoutListingEveryName) {
  EXPECT_EQ(describe_coordinates(ArrheniusBratu(1000)), "u1 … u1000 (block u), lambda, epsilon");
  EXPECT_EQ(describe_coordinates(BlockProblem(5, {})), "x0, x1, x2, x3, x4");
  EXPECT_EQ(describe_coordinates(BlockProblem(100, {{"a", 10, 80, 1.0}})),
            "x0, x1, x2, …, x9 (10 coordinates), x10 … x89 (block a), x90, x91, x92, …, x99 "
            "(10 coordinates)");
}

TEST(View, LargeNIsParsedInLinearTime) {
  // "all" at n = 10⁵ makes 10⁵ columns; a quadratic check of their names would take minutes.
  const ArrheniusBratu bvp(100000);
  const auto start = std::chrono::steady_clock::now();
  const View view = parse_view("all", bvp);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(view.size(), 100002);
  EXPECT_LT(seconds, 10.0);
}

TEST(View, ErrorsNameTheItemAndListWhatIsAvailable) {
  const ArrheniusBratu bvp(1000);
  {
    const auto [message, column] = view_error("lambda, maxu", bvp);
    EXPECT_EQ(column, 9);
    EXPECT_TRUE(contains(message, "'maxu' is no coordinate, block or functional")) << message;
    // The coordinates in a line, not a thousand names.
    EXPECT_TRUE(contains(message, "u1 … u1000 (block u), lambda, epsilon")) << message;
    EXPECT_FALSE(contains(message, "u17")) << message;
    EXPECT_TRUE(contains(message, "max:B")) << message;
  }
  {
    const auto [message, column] = view_error("lambda,max:v", bvp);
    EXPECT_EQ(column, 12);
    EXPECT_TRUE(contains(message, "'max:v': no block 'v' (blocks: u)")) << message;
  }
  {
    const auto [message, column] = view_error("maximum:u", bvp);
    EXPECT_EQ(column, 1);
    EXPECT_TRUE(contains(message,
                         "unknown block functional 'maximum' (max, min, mean, absmax, "
                         "norm)"))
        << message;
  }
  EXPECT_TRUE(contains(view_error("", bvp).first, "the view is empty"));
  EXPECT_TRUE(contains(view_error("  ", bvp).first, "the view is empty"));
  EXPECT_EQ(view_error("lambda,,epsilon", bvp).second, 8);
  EXPECT_TRUE(contains(view_error("lambda,", bvp).first, "empty item"));
  EXPECT_TRUE(
      contains(view_error("lambda, epsilon, lambda", bvp).first, "'lambda' is given twice"));
  EXPECT_TRUE(contains(view_error("u, u7", bvp).first, "'u7' gives the column 'u7', as 'u' does"));
  {
    const auto [message, column] = view_error("lambda, r = sqrt(u1^2 + w)", bvp);
    EXPECT_EQ(column, 25);  // at the w
    EXPECT_TRUE(contains(message, "unknown name 'w'")) << message;
    EXPECT_TRUE(contains(message, "u1 … u1000 (block u)")) << message;
  }
  {
    const auto [message, column] = view_error("r = sqrt(u1^2 + )", bvp);
    EXPECT_EQ(column, 17);  // at the ')'
    EXPECT_TRUE(contains(message, "'r = sqrt(u1^2 + )'")) << message;
  }
  EXPECT_TRUE(contains(view_error("lambda = 2*epsilon", bvp).first, "give the expression another"));
  EXPECT_TRUE(contains(view_error("2r = epsilon", bvp).first, "not a valid name"));
  EXPECT_TRUE(contains(view_error("r = ", bvp).first, "expected an expression"));
  EXPECT_TRUE(contains(view_error("max:u, max_u = 1", bvp).first, "'max_u = 1' gives the column"));
  // A problem without blocks says so.
  const BlockProblem plain(3, {});
  EXPECT_TRUE(contains(view_error("x, max:u", plain).first,
                       "no block 'u' (problem 'problem' has no coordinate blocks; its "
                       "coordinates: x, y, z)"));
}

}  // namespace
}  // namespace tessera
