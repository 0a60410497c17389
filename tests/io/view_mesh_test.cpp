// SPDX-License-Identifier: MIT
// A mesh written in a view: every format holds the view's values bit for bit, the first three
// place the vertices, the others are point data under their column names.
#include "tessera/io/view_mesh.h"

#include <gtest/gtest.h>

#include <random>

#include "io/io_test_support.h"
#include "tessera/problems/examples.h"

namespace tessera {
namespace {

using namespace io_test;

// A mesh in R^(N+2) with moderate random coordinates (the view's max and norm are then ordinary
// numbers) and triangles that use every vertex.
TriangleMesh random_state_mesh(int N, int vertex_count) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> value(-3.0, 3.0);
  Eigen::MatrixXd points(N + 2, vertex_count);
  for (Eigen::Index i = 0; i < points.size(); ++i) {
    points.data()[i] = value(random);
  }
  std::vector<Triangle> triangles;
  for (int v = 0; v + 2 < vertex_count; ++v) {
    triangles.push_back({v, v + 1, v + 2});
  }
  return TriangleMesh(points, triangles);
}

TEST(MeshInView, VerticesAreTheViewOfTheVerticesAndTrianglesStay) {
  const ArrheniusBratu bvp(10);
  const TriangleMesh mesh = random_state_mesh(10, 20);
  const View view = parse_view("lambda, epsilon, max:u, norm:u", bvp);
  const TriangleMesh shown = mesh_in_view(mesh, view);
  EXPECT_EQ(shown.ambient_dimension(), 4);
  EXPECT_EQ(shown.points(), view.evaluate_columns(mesh.points()));
  EXPECT_EQ(shown.triangles(), mesh.triangles());
  EXPECT_EQ(coordinate_names_in_view(view),
            (std::vector<std::string>{"lambda", "epsilon", "max_u", "norm_u"}));
}

TEST(MeshInView, TwoFunctionalsLieInThePlaneZEqualsZero) {
  const ArrheniusBratu bvp(10);
  const TriangleMesh mesh = random_state_mesh(10, 20);
  const View view = parse_view("lambda, max:u", bvp);
  const TriangleMesh shown = mesh_in_view(mesh, view);
  ASSERT_EQ(shown.ambient_dimension(), 3);
  EXPECT_EQ(shown.points().topRows(2), view.evaluate_columns(mesh.points()));
  EXPECT_TRUE(shown.points().row(2).isZero(0.0));
  EXPECT_EQ(coordinate_names_in_view(view), (std::vector<std::string>{"lambda", "max_u", "zero"}));
  EXPECT_EQ(coordinate_names_in_view(parse_view("zero = lambda, max:u", bvp)),
            (std::vector<std::string>{"zero", "max_u", "zero_2"}));
}

TEST(MeshInView, RefusesOneFunctionalAndAViewOfAnotherDimension) {
  const ArrheniusBratu bvp(10);
  const TriangleMesh mesh = random_state_mesh(10, 20);
  expect_invalid_argument([&] { mesh_in_view(mesh, parse_view("max:u", bvp)); },
                          {"'max:u' has 1 functional", "at least two"});
  expect_invalid_argument(
      [&] { mesh_in_view(mesh, parse_view("lambda, epsilon", ArrheniusBratu(11))); },
      {"R^13", "R^12"});
}

class WriteMeshInView : public ::testing::TestWithParam<std::string> {};

TEST_P(WriteMeshInView, EveryFormatHoldsTheViewBitForBit) {
  const std::string extension = GetParam();
  const ArrheniusBratu bvp(10);
  const TriangleMesh mesh = random_state_mesh(10, 30);
  const View view = parse_view("lambda, epsilon, max:u, norm:u", bvp);
  const std::string path = test_path("view" + extension);
  write_mesh_in_view(path, mesh, view, {.comments = {"a comment of the caller"}});
  const TriangleMesh back = read_mesh(path);
  const Eigen::MatrixXd values = view.evaluate_columns(mesh.points());
  EXPECT_EQ(back.triangles(), mesh.triangles());
  const std::string text = file_text(path);
  if (extension == ".obj") {
    // OBJ keeps the geometry only: the first three functionals.
    EXPECT_EQ(back.points(), values.topRows(3));
    return;
  }
  EXPECT_EQ(back.points(), values);
  EXPECT_NE(text.find("view: lambda, epsilon, max:u, norm:u"), std::string::npos);
  EXPECT_NE(text.find("a comment of the caller"), std::string::npos);
  if (extension == ".vtk" || extension == ".vtu") {
    for (const std::string name : {"lambda", "epsilon", "max_u", "norm_u"}) {
      EXPECT_NE(text.find(extension == ".vtu" ? "Name=\"" + name + "\"" : "SCALARS " + name),
                std::string::npos)
          << name;
    }
  } else {
    EXPECT_NE(text.find("property double norm_u"), std::string::npos);
    EXPECT_NE(text.find("coordinate names: lambda epsilon max_u norm_u"), std::string::npos);
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, WriteMeshInView,
                         ::testing::Values(".ply", ".vtk", ".vtu", ".obj"),
                         [](const auto& info) { return info.param.substr(1); });

TEST(WriteMeshInView, ExpressionWithTwoDashesStillMakesAValidVtuComment) {
  const ArrheniusBratu bvp(10);
  const TriangleMesh mesh = random_state_mesh(10, 10);
  const View view = parse_view("lambda, epsilon, d = u1--u2", bvp);
  const std::string path = test_path("dashes.vtu");
  write_mesh_in_view(path, mesh, view);
  EXPECT_EQ(read_mesh(path).points(), view.evaluate_columns(mesh.points()));
  EXPECT_NE(file_text(path).find("d = u1- -u2"), std::string::npos);
}

}  // namespace
}  // namespace tessera
