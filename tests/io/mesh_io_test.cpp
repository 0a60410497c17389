// SPDX-License-Identifier: MIT
// Mesh files by extension: dispatch to the format writers and readers.
#include "tessera/io/mesh_io.h"

#include <gtest/gtest.h>

#include "io/io_test_support.h"

namespace tessera {
namespace {

using namespace io_test;

TEST(MeshFile, DispatchesOnTheExtension) {
  const auto mesh = random_mesh(3, 50, 60);
  for (const std::string name : {"d.ply", "d.PLY", "d.obj"}) {
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

TEST(MeshFile, UnknownExtensionListsTheSupportedOnes) {
  const auto mesh = two_triangles();
  expect_invalid_argument([&] { write_mesh(test_path("m.stl"), mesh); },
                          {"m.stl", "'.stl'", ".ply, .obj, .vtk, .vtu"});
  expect_invalid_argument([&] { write_mesh(test_path("no_extension"), mesh); },
                          {"no_extension", "unknown extension"});
  write_vtk(test_path("m.vtk"), mesh);
  expect_invalid_argument([&] { read_mesh(test_path("m.vtk")); },
                          {"m.vtk", "'.vtk'", "supported: .ply, .obj"});
}

}  // namespace
}  // namespace tessera
