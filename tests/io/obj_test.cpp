// SPDX-License-Identifier: MIT
// OBJ: exact round trips, projections of R^n, foreign files, and errors that name the line.
#include "tessera/io/obj.h"

#include <gtest/gtest.h>

#include "io/io_test_support.h"

namespace tessera {
namespace {

using namespace io_test;

TEST(Obj, RoundTripInR3IsBitExact) {
  const auto mesh = random_mesh(3, 300, 500);
  const auto path = test_path("round_trip.obj");
  write_obj(path, mesh);
  expect_identical(mesh, read_obj(path));
}

TEST(Obj, WritesChosenCoordinatesOfRnAndPadsPlanarMeshes) {
  const auto mesh = random_mesh(5, 40, 30);
  const auto path = test_path("projection.obj");
  write_obj(path, mesh, {4, 0, 2});
  const auto projected = read_obj(path);
  ASSERT_EQ(projected.vertex_count(), 40);
  for (int v = 0; v < 40; ++v) {
    EXPECT_EQ(projected.point(v)(0), mesh.point(v)(4));
    EXPECT_EQ(projected.point(v)(1), mesh.point(v)(0));
    EXPECT_EQ(projected.point(v)(2), mesh.point(v)(2));
  }
  EXPECT_EQ(projected.triangles(), mesh.triangles());

  const auto planar = random_mesh(2, 10, 5);
  write_obj(path, planar);
  const auto lifted = read_obj(path);
  EXPECT_EQ(lifted.point(3)(1), planar.point(3)(1));
  EXPECT_EQ(lifted.points().row(2).cwiseAbs().maxCoeff(), 0.0);

  expect_invalid_argument([&] { write_obj(path, mesh, {0, 1, 5}); }, {"coordinate index 5", "R^5"});
  expect_invalid_argument([&] { write_obj(path, mesh, {0, -1, 2}); }, {"coordinate index -1"});
}

TEST(Obj, ReadsSlashFormsNegativeIndicesPolygonsAndIgnoresTheRest) {
  const auto path = test_path("foreign.obj");
  write_text(path,
             "# a quad and a triangle\nmtllib x.mtl\no thing\n"
             "v 0 0 0\nv 1 0 0 1.0\nv 1 1 0 0.5 0.5 0.5\nv 0 1 0\n"
             "vt 0 0\nvn 0 0 1\ng group\ns off\nusemtl red\n"
             "f 1/1/1 2/1/1 3/1/1 4/1/1  # quad\n"
             "v 0.5 0.5 1\n"
             "f -5//1 -4//1 -1//1\nl 1 2\n");
  const auto mesh = read_obj(path);
  ASSERT_EQ(mesh.vertex_count(), 5);
  EXPECT_EQ(mesh.point(4)(2), 1.0);
  EXPECT_EQ(mesh.triangles(), (std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}, {0, 1, 4}}));
}

TEST(ObjErrors, NameTheFileAndTheLine) {
  const auto path = test_path("bad.obj");
  expect_invalid_argument([&] { read_obj(test_path("missing.obj")); }, {"missing.obj"});
  const std::pair<std::string, std::vector<std::string>> cases[] = {
      {"v 0 0 0\nv 1 0\n", {"line 2", "3 coordinates"}},
      {"v 0 0 0\nv 1 0 x\n", {"line 2", "expected a number, found 'x'"}},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", {"line 4", "at least 3 vertices"}},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", {"line 4", "found '0'"}},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", {"line 4", "'-4' is out of range"}},
      {"v 0 0 0\nv 1 0 0\nf 1 2 4\nv 0 1 0\n", {"line 3", "index 4 is out of range", "3 vertices"}},
  };
  for (const auto& [text, parts] : cases) {
    write_text(path, text);
    auto expected = parts;
    expected.push_back(path);
    expect_invalid_argument([&] { read_obj(path); }, expected);
  }
}

}  // namespace
}  // namespace tessera
