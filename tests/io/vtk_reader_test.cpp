// SPDX-License-Identifier: MIT
// read_vtk and read_vtu: the files tessera writes read back whole, earlier layouts too, and
// malformed files give an error naming the file and line, never a crash or a huge allocation.
#include <gtest/gtest.h>

#include <map>

#include "io/io_test_support.h"
#include "tessera/io/detail/mesh_parsers.h"
#include "tessera/io/mesh_io.h"
#include "tessera/io/vtk.h"

namespace tessera {
namespace {

using namespace io_test;

std::string written(const std::string& file_name, const TriangleMesh& mesh,
                    const VtkOptions& options = {}) {
  const auto path = test_path(file_name);
  if (file_name.ends_with(".vtk")) {
    write_vtk(path, mesh, options);
  } else {
    write_vtu(path, mesh, options);
  }
  return path;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

TEST(VtkReader, ReadsAllCoordinatesFromThePointDataInRn) {
  for (const int n : {2, 3, 4, 6}) {
    const auto mesh = random_mesh(n, 40, 50, 11);
    for (const std::string name : {"rn.vtk", "rn.vtu"}) {
      SCOPED_TRACE(name + " n = " + std::to_string(n));
      expect_identical(
          mesh, name == "rn.vtk" ? read_vtk(written(name, mesh)) : read_vtu(written(name, mesh)));
    }
  }
}

// Before the title always began with "tessera triangle mesh in R^n", `tessera mesh` wrote its
// comments there: the point data x0 ... or the names after "coordinates:" still give n.
TEST(VtkReader, ReadsLegacyFilesOfEarlierVersions) {
  const auto mesh = random_mesh(4, 10, 8);
  auto old_title = [&](const std::string& title, const std::vector<std::string>& names) {
    const auto path = written("old.vtk", mesh, {.coordinate_names = names});
    write_text(path, replaced(file_text(path), "tessera triangle mesh in R^4", title));
    return read_vtk(path);
  };
  expect_identical(mesh, old_title("a run", {}));  // arrays x0 x1 x2 x3
  expect_identical(mesh, old_title("tessera mesh cstr, method atlas; coordinates: x1 x2 Da B",
                                   {"x1", "x2", "Da", "B"}));
  // Nothing says n: the points, in R^3.
  const auto three = old_title("a run", {"x1", "x2", "Da", "B"});
  EXPECT_EQ(three.ambient_dimension(), 3);
  EXPECT_EQ(three.point(7)(2), mesh.point(7)(2));
}

TEST(VtkReader, ReadsForeignPolygonsQuadsAndSkipsOtherData) {
  const auto vtk = test_path("foreign.vtk");
  write_text(vtk,
             "# vtk DataFile Version 3.0\r\nmade by hand\r\nascii\r\nDATASET POLYDATA\r\n"
             "POINTS 5 float\r\n0 0 0 1 0 0 1 1 0 0 1 0 0.5 0.5 1.5\r\n"
             "LINES 1 3\r\n2 0 4\r\n"
             "POLYGONS 2 9\r\n4 0 1 2 3\r\n3 0 1 4\r\n"
             "CELL_DATA 3\r\nSCALARS id int\r\nLOOKUP_TABLE default\r\n0 1 2\r\n"
             "POINT_DATA 5\r\nNORMALS n float\r\n0 0 1 0 0 1 0 0 1 0 0 1 0 0 1\r\n");
  const auto mesh = read_vtk(vtk);
  EXPECT_EQ(mesh.ambient_dimension(), 3);
  EXPECT_EQ(mesh.point(4)(2), 1.5);
  EXPECT_EQ(mesh.triangles(), (std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}, {0, 1, 4}}));

  const auto vtu = test_path("foreign.vtu");
  write_text(vtu,
             "<?xml version='1.0'?>\n<VTKFile type='UnstructuredGrid' version='0.1'>\n"
             "<UnstructuredGrid><Piece NumberOfPoints='5' NumberOfCells='2'>\n"
             "<PointData><DataArray type='Float32' Name='t' format='ascii'>1 2 3 4 5"
             "</DataArray></PointData>\n"
             "<Points><DataArray type='Float32' NumberOfComponents='3' format='ascii'>\n"
             "0 0 0 1 0 0 1 1 0 0 1 0 0.5 0.5 1.5</DataArray></Points>\n"
             "<Cells><DataArray type='Int32' Name='connectivity' format='ascii'>0 1 2 3 0 1 4"
             "</DataArray>\n<DataArray type='Int32' Name='offsets' format='ascii'>4 7</DataArray>\n"
             "<DataArray type='UInt8' Name='types' format='ascii'>9 5</DataArray></Cells>\n"
             "</Piece></UnstructuredGrid></VTKFile>\n");
  const auto from_vtu = read_vtu(vtu);
  EXPECT_EQ(from_vtu.points(), mesh.points());
  EXPECT_EQ(from_vtu.triangles(), mesh.triangles());
}

struct Malformed {
  std::string from;  // text of a valid file to replace ...
  std::string to;    // ... by this
  std::vector<std::string> message;
};

// Legacy files of other writers: an unstructured grid with quads, lines and vertices (ParaView),
// and version 5.1 with OFFSETS and CONNECTIVITY (meshio's default).
TEST(VtkReader, ReadsForeignUnstructuredGridsOfVersions42And51) {
  const std::string points = "POINTS 5 float\n0 0 0 1 0 0 1 1 0 0 1 0 0.5 0.5 1.5\n";
  const auto v42 = test_path("foreign_grid.vtk");
  write_text(v42, "# vtk DataFile Version 4.2\nby hand\nASCII\nDATASET UNSTRUCTURED_GRID\n" +
                      points +
                      "CELLS 4 14\n4 0 1 2 3\n2 0 4\n1 4\n3 0 1 4\nCELL_TYPES 4\n9 3 1 5\n"
                      "CELL_DATA 4\nSCALARS id int\nLOOKUP_TABLE default\n0 1 2 3\n");
  const auto mesh = read_vtk(v42);
  EXPECT_EQ(mesh.point(4)(2), 1.5);
  EXPECT_EQ(mesh.triangles(), (std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}, {0, 1, 4}}));

  const auto v51 = test_path("foreign_grid51.vtk");
  write_text(v51,
             "# vtk DataFile Version 5.1\nwritten by meshio v7.0.0\nASCII\n"
             "DATASET UNSTRUCTURED_GRID\n" +
                 points +
                 "CELLS 3 7\nOFFSETS vtktypeint64\n0\n4\n7\n"
                 "CONNECTIVITY vtktypeint64\n0\n1\n2\n3\n0\n1\n4\n"
                 "CELL_TYPES 2\n9\n5\n"
                 "POINT_DATA 5\nFIELD FieldData 1\nt 1 5 double\n1 2 3 4 5\n");
  const auto from_51 = read_vtk(v51);
  EXPECT_EQ(from_51.points(), mesh.points());
  EXPECT_EQ(from_51.triangles(), mesh.triangles());

  const std::vector<Malformed> cases = {
      {"0\n4\n7\nCONN", "1\n4\n7\nCONN", {"CELLS offset 0 is 1"}},
      {"0\n4\n7\nCONN", "0\n4\n6\nCONN", {"offsets end at 6 but the connectivity has 7"}},
      {"0\n1\n4\nCELL_TYPES", "0\n1\n5\nCELL_TYPES", {"vertex index 5", "5 points"}},
      {"OFFSETS vtktypeint64\n0\n4\n7\nCONNECTIVITY",
       "OFFSETS vtktypeint64\n0\n4\n7\nINDICES",
       {"expected CONNECTIVITY"}},
  };
  const std::string good = file_text(v51);
  const auto path = test_path("bad51.vtk");
  for (const auto& bad : cases) {
    SCOPED_TRACE(bad.to);
    write_text(path, replaced(good, bad.from, bad.to));
    try {
      read_vtk(path);
      ADD_FAILURE() << "no error";
    } catch (const InvalidArgument& error) {
      for (const auto& part : bad.message) {
        EXPECT_NE(std::string(error.what()).find(part), std::string::npos) << error.what();
      }
    }
  }
}

TEST(VtkReader, MalformedLegacyFilesNameTheFileAndLine) {
  Eigen::MatrixXd points(4, 3);
  points << 0, 1, 0, 0, 0, 1, 0, 0, 0, 7, 8, 9;
  const TriangleMesh mesh(points, {{0, 1, 2}});
  const auto good = file_text(written("good.vtk", mesh));
  const std::vector<Malformed> cases = {
      {"# vtk DataFile Version 4.2", "# vtk", {"line 1", "not a legacy VTK file"}},
      {"ASCII", "BINARY", {"line 3", "binary legacy VTK is not supported"}},
      {"ASCII", "TEXT", {"line 3", "expected 'ASCII'"}},
      {"UNSTRUCTURED_GRID", "STRUCTURED_POINTS", {"line 4", "DATASET UNSTRUCTURED_GRID"}},
      {"POINTS 3", "POINTS 300000000", {"line 5", "more than the rest of the file can hold"}},
      {"POINTS 3", "POINTS -3", {"line 5", "the number of points"}},
      {"POINTS 3 double", "POINTS 3 complex", {"line 5", "unknown data type"}},
      {"\n0 0 0\n", "\n0 zero 0\n", {"line 6", "expected a number for POINTS", "'zero'"}},
      {"3 0 1 2", "3 0 1 5", {"line 10", "vertex index 5", "3 points"}},
      {"CELLS 1 4\n3 0 1 2", "CELLS 1 3\n2 0 1", {"line 12", "type 5 and 2 vertices"}},
      {"CELLS 1 4", "CELLS 1 5", {"list size of 5"}},
      {"CELL_TYPES 1\n5", "CELL_TYPES 1\n10", {"line 12", "cell 0 has type 10", "skips"}},
      {"CELL_TYPES 1", "CELL_TYPES 2", {"line 11", "CELL_TYPES 2 does not match the 1 CELLS"}},
      {"CELL_TYPES 1\n5 \n", "", {"CELLS without CELL_TYPES"}},
      {"CELLS 1 4\n3 0 1 2\n", "", {"CELL_TYPES before CELLS"}},
      {"CELLS 1 4", "POLYGONS 1 4", {"line 9", "unsupported section 'POLYGONS'", "CELL_TYPES"}},
      {"POINT_DATA 3", "POINT_DATA 4", {"POINT_DATA 4 does not match the 3 points"}},
      {"SCALARS x0", "TENSORS x0", {"unsupported attribute 'TENSORS'"}},
      {"POINTS", "PIXELS", {"line 5", "unsupported section 'PIXELS'"}},
      {"LOOKUP_TABLE default\n0 1 0 \n",
       "LOOKUP_TABLE default\n1 1 0 \n",
       {"'x0' (coordinate 0) differs from the points at vertex 0"}},
      {"SCALARS x3 double 1\nLOOKUP_TABLE default\n7 8 9 \n",
       "",
       {"R^4 but has only 3 point-data arrays"}},
      {"LOOKUP_TABLE default\n7 8 9", "LOOKUP_TABLE default\n7 8", {"unexpected end of file"}},
  };
  const auto path = test_path("bad.vtk");
  for (const auto& bad : cases) {
    SCOPED_TRACE(bad.to);
    write_text(path, replaced(good, bad.from, bad.to));
    auto parts = bad.message;
    parts.push_back("VTK file '" + path + "'");
    expect_invalid_argument([&] { read_vtk(path); }, parts);
  }
}

TEST(VtkReader, MalformedVtuFilesNameTheFileAndLine) {
  Eigen::MatrixXd points(4, 3);
  points << 0, 1, 0, 0, 0, 1, 0, 0, 0, 7, 8, 9;
  const TriangleMesh mesh(points, {{0, 1, 2}});
  const auto good = file_text(written("good.vtu", mesh));
  const std::vector<Malformed> cases = {
      {"<VTKFile", "<Grid", {"'</VTKFile>' does not match '<Grid>'"}},
      {"UnstructuredGrid\" version", "PolyData\" version", {"reads UnstructuredGrid"}},
      {"NumberOfPoints=\"3\"", "NumberOfPoints=\"three\"", {"NumberOfPoints"}},
      {"NumberOfPoints=\"3\"", "NumberOfPoints=\"300000000\"", {"cannot"}},
      {"format=\"ascii\"", "format=\"binary\"", {"format 'binary'", "ASCII data arrays"}},
      {"format=\"ascii\"", "format=\"appended\"", {"format 'appended'"}},
      {"</Points>", "</Point>", {"'</Point>' does not match '<Points>'"}},
      {"</VTKFile>", "", {"'<VTKFile>' is not closed"}},
      {"Float64\" Name=\"x0\"",
       "Float64\" Name=\"x0\" NumberOfComponents=\"2\"",
       {"line 7", "DataArray 'x0' has 3 values, expected 6"}},
      {"\n0 1 0 \n", "\n0 one 0 \n", {"line 8", "expected a number in DataArray 'x0'", "'one'"}},
      {"\n0 1 0 \n", "\n0 1 0 5 \n", {"line 8", "more than the 3 values"}},
      {"0 1 2 \n", "0 1 7 \n", {"vertex index 7", "3 points"}},
      {"0 1 2 \n", "0 1 2.5 \n", {"expected an integer in DataArray 'connectivity'"}},
      {"format=\"ascii\">\n3 \n", "format=\"ascii\">\n2 \n", {"type 5 and 2 vertices"}},
      {"format=\"ascii\">\n5 \n", "format=\"ascii\">\n10 \n", {"type 10"}},
      {"Name=\"types\"", "Name=\"kinds\"", {"no DataArray named 'types'"}},
      {"<Points>", "<Points><Points>", {"'</Piece>' does not match '<Points>'"}},
      {"R^4", "R^5", {"R^5 but has only 4 point-data arrays"}},
      {"&amp;", "&bogus;", {"unsupported entity '&bogus;'"}},
  };
  const auto path = test_path("bad.vtu");
  for (const auto& bad : cases) {
    SCOPED_TRACE(bad.to);
    auto text = good;
    if (bad.from == "&amp;") {
      text = replaced(text, "Name=\"x0\"", "Name=\"x0&amp;\"");
    }
    write_text(path, replaced(text, bad.from, bad.to));
    auto parts = bad.message;
    parts.push_back("VTU file '" + path + "'");
    expect_invalid_argument([&] { read_vtu(path); }, parts);
  }
}

// Every prefix of a valid file and every single-byte change of it is either read or refused
// with InvalidArgument: a small exhaustive stand-in for the fuzzing to come (PLY included, whose
// reader now takes n from a comment).
TEST(VtkReader, EveryTruncationAndByteChangeIsReadOrRefusedCleanly) {
  Eigen::MatrixXd points(4, 4);
  points << 0, 1, 0, 0.5, 0, 0, 1, 0.5, 0, 0, 0, 1, 7, 8, 9, 1e-300;
  const TriangleMesh mesh(points, {{0, 1, 2}, {0, 1, 3}});
  // Besides what write_mesh writes: a legacy file of version 5.1 (meshio's) and one of POLYDATA
  // (tessera's before issue 34).
  const std::string points_text = "POINTS 4 double\n0 0 0 1 0 0 0 1 0 0.5 0.5 1\n";
  const std::map<std::string, std::string> others = {
      {"fuzz51.vtk", "# vtk DataFile Version 5.1\nmeshio\nASCII\nDATASET UNSTRUCTURED_GRID\n" +
                         points_text +
                         "CELLS 3 6\nOFFSETS vtktypeint64\n0\n3\n6\nCONNECTIVITY "
                         "vtktypeint64\n0\n1\n2\n0\n1\n3\nCELL_TYPES 2\n5\n5\n"
                         "POINT_DATA 4\nFIELD FieldData 1\nr 1 4 double\n1 2 3 4\n"},
      {"fuzz_polydata.vtk",
       "# vtk DataFile Version 4.2\ntessera triangle mesh in R^3\nASCII\n"
       "DATASET POLYDATA\n" +
           points_text +
           "POLYGONS 2 8\n3 0 1 2\n3 0 1 3\nPOINT_DATA 4\n"
           "SCALARS x double 1\nLOOKUP_TABLE default\n0 1 0 0.5\n"
           "SCALARS y double 1\nLOOKUP_TABLE default\n0 0 1 0.5\n"
           "SCALARS z double 1\nLOOKUP_TABLE default\n0 0 0 1\n"}};
  for (const std::string name :
       {"fuzz.vtk", "fuzz.vtu", "fuzz_ascii.ply", "fuzz.ply", "fuzz51.vtk", "fuzz_polydata.vtk"}) {
    const auto written_path = test_path(name);
    if (others.count(name) != 0) {
      write_text(written_path, others.at(name));
    } else {
      write_mesh(written_path, mesh,
                 {.binary = name == "fuzz.ply", .vertex_scalars = {{"r", {1, 2, 3, 4}}}});
    }
    const auto good = file_text(written_path);
    ASSERT_NO_THROW(read_mesh(written_path)) << name;
    const auto path = test_path("mutated_" + name);
    int refused = 0;
    int read_count = 0;
    auto attempt = [&](const std::string& text) {
      try {
        const auto result = name.ends_with(".vtk")   ? io_detail::parse_vtk(text, path)
                            : name.ends_with(".vtu") ? io_detail::parse_vtu(text, path)
                                                     : io_detail::parse_ply(text, path);
        for (const auto& triangle : result.triangles()) {
          for (const int v : triangle) {
            ASSERT_TRUE(v >= 0 && v < result.vertex_count());
          }
        }
        ++read_count;
      } catch (const InvalidArgument& error) {
        EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
        ++refused;
      }
    };
    for (std::size_t length = 0; length < good.size(); ++length) {
      attempt(good.substr(0, length));
    }
    for (std::size_t at = 0; at < good.size(); ++at) {
      for (const char c : {'\0', '9', '<', '-', '"', ' ', '\n'}) {
        std::string text = good;
        text[at] = c;
        attempt(text);
      }
    }
    EXPECT_GT(refused, static_cast<int>(good.size()) / 2) << name;
    EXPECT_GT(read_count, 0) << name;
  }
}

}  // namespace
}  // namespace tessera
