// SPDX-License-Identifier: MIT
// Mesh files by extension: dispatch to the format writers and readers.
#include "tessera/io/mesh_io.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "io/io_test_support.h"
#include "tessera/core/implicit_problem.h"

namespace tessera {
namespace {

using namespace io_test;

TEST(MeshFile, DispatchesOnTheExtension) {
  const auto mesh = random_mesh(3, 50, 60);
  for (const std::string name : {"d.ply", "d.PLY", "d.obj", "d.vtk", "d.VTU"}) {
    write_mesh(test_path(name), mesh);
    expect_identical(mesh, read_mesh(test_path(name)));
  }
  write_mesh(test_path("d_ascii.ply"), mesh, {.binary = false});
  EXPECT_NE(file_text(test_path("d_ascii.ply")).find("format ascii"), std::string::npos);
  write_mesh(test_path("d.vtk"), mesh, {.vertex_scalars = {{"r", std::vector<double>(50, 1)}}});
  EXPECT_EQ(count_occurrences(file_text(test_path("d.vtk")), "SCALARS"), 4);
  write_mesh(test_path("d.vtu"), mesh);
  EXPECT_NE(file_text(test_path("d.vtu")).find("UnstructuredGrid"), std::string::npos);
}

// What `tessera check FILE` reads the recorded problem from (issue 34).
TEST(MeshFile, CommentsReadBackFromEveryFormatThatHasThem) {
  const auto mesh = random_mesh(3, 20, 20);
  const std::vector<std::string> comments = {"tessera improve m.ply --problem sphere",
                                             "problem: torus:R=2,r=0.5"};
  for (const std::string name : {"c.ply", "c_ascii.ply", "c.vtk", "c.vtu", "c.obj"}) {
    SCOPED_TRACE(name);
    write_mesh(test_path(name), mesh, {.binary = name != "c_ascii.ply", .comments = comments});
    const auto read = read_mesh_comments(test_path(name));
    std::vector<std::string> expected = comments;
    if (name == "c.vtu") {
      expected[0] = "tessera improve m.ply - -problem sphere";  // XML comments hold no "--"
    }
    const std::string marker = "written by tessera: triangle mesh in R^3";
    if (name == "c.obj") {
      expected.clear();  // OBJ has no place for comments
    } else if (name == "c.vtk") {
      expected.insert(expected.begin(), "tessera triangle mesh in R^3");
    } else {
      expected.insert(expected.begin(), marker);
    }
    EXPECT_EQ(read, expected);
  }
  // A legacy title is cut at 255 characters: its last, cut part is not returned.
  write_mesh(test_path("long.vtk"), mesh,
             {.comments = {"problem: sphere", "problem file fnv1a64: " + std::string(300, 'a')}});
  EXPECT_EQ(read_mesh_comments(test_path("long.vtk")),
            (std::vector<std::string>{"tessera triangle mesh in R^3", "problem: sphere"}));
  EXPECT_TRUE(read_mesh_comments(test_path("no_such_file.ply")).empty());
}

TEST(MeshFile, UnknownExtensionListsTheSupportedOnes) {
  const auto mesh = two_triangles();
  expect_invalid_argument([&] { write_mesh(test_path("m.stl"), mesh); },
                          {"m.stl", "'.stl'", ".ply, .obj, .vtk, .vtu"});
  expect_invalid_argument([&] { write_mesh(test_path("no_extension"), mesh); },
                          {"no_extension", "unknown extension"});
  write_vtk(test_path("m.vtk"), mesh);
  std::filesystem::copy_file(test_path("m.vtk"), test_path("m.vtkx"),
                             std::filesystem::copy_options::overwrite_existing);
  expect_invalid_argument([&] { read_mesh(test_path("m.vtkx")); },
                          {"m.vtkx", "'.vtkx'", "supported: .ply, .obj, .vtk, .vtu"});
}

// The names a mesh was written with come back from every format that keeps them (PLY, VTK,
// VTU), with a scalar field beside them; otherwise the defaults.
TEST(MeshFile, CoordinateNamesReadBack) {
  for (const int n : {3, 4}) {
    const auto mesh = random_mesh(n, 20, 30);
    std::vector<std::string> names = {"lambda", "epsilon", "max_u", "B"};
    names.resize(static_cast<std::size_t>(n));
    for (const std::string file_name : {"names.ply", "names_ascii.ply", "names.vtk", "names.VTU"}) {
      const std::string path = test_path(std::to_string(n) + file_name);
      write_mesh(path, mesh,
                 {.binary = file_name != "names_ascii.ply",
                  .coordinate_names = names,
                  .vertex_scalars = {{"residual", std::vector<double>(20, 0.5)}},
                  .comments = {"coordinates: a b"}});
      EXPECT_EQ(read_coordinate_names(path, n), names) << file_name;
      write_mesh(path, mesh);
      EXPECT_EQ(read_coordinate_names(path, n), default_coordinate_names(n)) << file_name;
    }
  }
  // `tessera mesh` without a view names the problem's coordinates in a comment only.
  const auto mesh = random_mesh(3, 20, 30);
  write_mesh(test_path("comment.ply"), mesh, {.comments = {"coordinates: u v w"}});
  EXPECT_EQ(read_coordinate_names(test_path("comment.ply"), 3),
            (std::vector<std::string>{"u", "v", "w"}));
  write_mesh(test_path("comment.vtk"), mesh, {.comments = {"coordinates: u v w"}});
  EXPECT_EQ(read_coordinate_names(test_path("comment.vtk"), 3),
            (std::vector<std::string>{"x", "y", "z"}));  // the arrays of write_vtk come first
  // Counts that do not match, repeated names, other formats, missing files: the defaults.
  write_mesh(test_path("short.ply"), mesh, {.comments = {"coordinates: u v"}});
  EXPECT_EQ(read_coordinate_names(test_path("short.ply"), 3), default_coordinate_names(3));
  write_text(test_path("repeated.ply"),
             "ply\nformat ascii 1.0\ncomment coordinate names: a a b\nelement vertex 0\n"
             "property double x\nproperty double y\nproperty double z\nend_header\n");
  EXPECT_EQ(read_coordinate_names(test_path("repeated.ply"), 3), default_coordinate_names(3));
  write_mesh(test_path("m.obj"), mesh);
  EXPECT_EQ(read_coordinate_names(test_path("m.obj"), 3), default_coordinate_names(3));
  EXPECT_EQ(read_coordinate_names(test_path("missing.ply"), 4), default_coordinate_names(4));
}

// Every format tessera writes reads back: PLY (both encodings), VTK and VTU with all n
// coordinates bit for bit, OBJ (three coordinates, so n = 3) too.
class EveryFormatRoundTrip : public ::testing::TestWithParam<std::tuple<int, std::string>> {};

TEST_P(EveryFormatRoundTrip, IsBitExactWithTheSameTriangles) {
  const auto [n, file_name] = GetParam();
  const auto mesh = random_mesh(n, 120, 200, static_cast<unsigned>(n));
  const auto path = test_path(std::to_string(n) + "_" + file_name);
  const bool ascii = file_name.find("ascii") != std::string::npos;
  std::vector<double> residual(120);
  for (std::size_t v = 0; v < residual.size(); ++v) {
    residual[v] = 1e-3 * static_cast<double>(v);
  }
  // Problem names and a scalar field, as `tessera mesh` writes them: neither may disturb n.
  std::vector<std::string> names = {"x1", "x2", "Da", "B", "gamma", "delta"};
  names.resize(static_cast<std::size_t>(n));
  write_mesh(path, mesh,
             {.binary = !ascii,
              .coordinate_names = names,
              .vertex_scalars = {{"residual", residual}},
              .comments = {"tessera mesh test", "coordinates: " + names.front()}});
  expect_identical(mesh, read_mesh(path));
  // Without names, scalars or comments: the defaults.
  write_mesh(path, mesh, {.binary = !ascii});
  expect_identical(mesh, read_mesh(path));
}

INSTANTIATE_TEST_SUITE_P(DimensionAndFormat, EveryFormatRoundTrip,
                         ::testing::Combine(::testing::Values(3, 4, 6),
                                            ::testing::Values("binary.ply", "ascii.ply", "mesh.vtk",
                                                              "mesh.vtu")),
                         [](const auto& info) {
                           std::string name = "n" + std::to_string(std::get<0>(info.param)) + "_" +
                                              std::get<1>(info.param);
                           std::replace(name.begin(), name.end(), '.', '_');
                           return name;
                         });

TEST(MeshFile, ObjKeepsThreeCoordinatesBitForBit) {
  const auto mesh = random_mesh(3, 120, 200);
  write_mesh(test_path("exact.obj"), mesh);
  expect_identical(mesh, read_mesh(test_path("exact.obj")));
  const auto mesh6 = random_mesh(6, 30, 20);
  write_mesh(test_path("exact6.obj"), mesh6, {.obj_coordinates = {5, 0, 3}});
  const auto read = read_mesh(test_path("exact6.obj"));
  ASSERT_EQ(read.vertex_count(), 30);
  EXPECT_EQ(read.triangles(), mesh6.triangles());
  for (int v = 0; v < 30; ++v) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(read.point(v)(0)),
              std::bit_cast<std::uint64_t>(mesh6.point(v)(5)));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(read.point(v)(2)),
              std::bit_cast<std::uint64_t>(mesh6.point(v)(3)));
  }
}

}  // namespace
}  // namespace tessera
