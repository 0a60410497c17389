// SPDX-License-Identifier: MIT
// VTK legacy and VTU: files checked by reading their text back with the counts the formats need.
#include "tessera/io/vtk.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "io/io_test_support.h"
#include "tessera/io/mesh_io.h"

namespace tessera {
namespace {

using namespace io_test;

TEST(Vtk, LegacyFileHasPointsPolygonsAndOneArrayPerCoordinateAndScalar) {
  const int n = 5;
  const auto mesh = random_mesh(n, 23, 17);
  std::vector<double> residual(23, 0.25);
  const auto path = test_path("mesh.vtk");
  write_vtk(path, mesh, {.vertex_scalars = {{"residual", residual}}, .comments = {"torus"}});

  std::istringstream in(file_text(path));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "# vtk DataFile Version 4.2");
  std::getline(in, line);
  EXPECT_EQ(line, "tessera triangle mesh in R^5; torus");  // read_vtk takes n from here
  std::getline(in, line);
  EXPECT_EQ(line, "ASCII");
  std::getline(in, line);
  EXPECT_EQ(line, "DATASET UNSTRUCTURED_GRID");  // meshio reads no POLYDATA
  std::string keyword, type;
  int count = 0;
  in >> keyword >> count >> type;
  EXPECT_EQ(keyword, "POINTS");
  EXPECT_EQ(count, 23);
  EXPECT_EQ(type, "double");
  const auto xyz = read_numbers(in, 3 * 23);
  EXPECT_EQ(xyz[3 * 7 + 2], mesh.point(7)(2));
  int size = 0;
  in >> keyword >> count >> size;
  EXPECT_EQ(keyword, "CELLS");
  EXPECT_EQ(count, 17);
  EXPECT_EQ(size, 4 * 17);
  for (int t = 0; t < 17; ++t) {
    int corners = 0;
    Triangle triangle{};
    in >> corners >> triangle[0] >> triangle[1] >> triangle[2];
    EXPECT_EQ(corners, 3);
    EXPECT_EQ(triangle, mesh.triangle(t));
  }
  in >> keyword >> count;
  EXPECT_EQ(keyword, "CELL_TYPES");
  EXPECT_EQ(count, 17);
  for (int t = 0; t < 17; ++t) {
    int type = 0;
    in >> type;
    EXPECT_EQ(type, 5) << "cell " << t << ": VTK_TRIANGLE";
  }
  in >> keyword >> count;
  EXPECT_EQ(keyword, "POINT_DATA");
  EXPECT_EQ(count, 23);
  const std::vector<std::string> names = {"x0", "x1", "x2", "x3", "x4", "residual"};
  for (std::size_t a = 0; a < names.size(); ++a) {
    std::string name, lookup, table_name;
    int components = 0;
    in >> keyword >> name >> type >> components >> lookup >> table_name;
    EXPECT_EQ(keyword, "SCALARS");
    EXPECT_EQ(name, names[a]);
    EXPECT_EQ(type, "double");
    EXPECT_EQ(components, 1);
    EXPECT_EQ(lookup + " " + table_name, "LOOKUP_TABLE default");
    const auto values = read_numbers(in, 23);
    EXPECT_EQ(values[11], a < n ? mesh.point(11)(static_cast<Eigen::Index>(a)) : 0.25) << name;
  }
  in >> keyword;
  EXPECT_TRUE(in.eof()) << "unexpected trailing text '" << keyword << "'";
}

TEST(Vtk, PlanarMeshGetsZeroThirdCoordinate) {
  const auto path = test_path("planar.vtk");
  write_vtk(path, random_mesh(2, 3, 1));
  const std::string text = file_text(path);
  std::istringstream in(text.substr(text.find("double\n") + 7));
  const auto xyz = read_numbers(in, 9);
  EXPECT_EQ(xyz[2], 0.0);
  EXPECT_EQ(xyz[8], 0.0);
  EXPECT_EQ(count_occurrences(text, "SCALARS"), 2);
}

TEST(Vtu, XmlFileHasMatchingTagsAndCounts) {
  const auto mesh = random_mesh(4, 31, 20);
  const auto path = test_path("mesh.vtu");
  write_vtu(path, mesh,
            {.vertex_scalars = {{"residual", std::vector<double>(31, 1e-9)}},
             .comments = {"a <comment> & more"}});
  const std::string text = file_text(path);
  EXPECT_EQ(text.rfind("<?xml version=\"1.0\"?>\n", 0), 0u);
  EXPECT_NE(text.find("<Piece NumberOfPoints=\"31\" NumberOfCells=\"20\">"), std::string::npos);
  for (const std::string tag :
       {"VTKFile", "UnstructuredGrid", "Piece", "PointData", "Points", "Cells", "DataArray"}) {
    EXPECT_EQ(count_occurrences(text, "<" + tag + " ") + count_occurrences(text, "<" + tag + ">"),
              count_occurrences(text, "</" + tag + ">"))
        << tag;
  }
  // 4 coordinates + 1 scalar field + Points + connectivity, offsets, types.
  EXPECT_EQ(count_occurrences(text, "<DataArray "), 4 + 1 + 1 + 3);

  // Each array holds the number of values its role requires.
  auto array_values = [&](const std::string& name) {
    const auto open = text.find("Name=\"" + name + "\"");
    EXPECT_NE(open, std::string::npos) << name;
    const auto begin = text.find('>', open) + 1;
    const auto end = text.find("</DataArray>", begin);
    std::istringstream in(text.substr(begin, end - begin));
    std::vector<double> values;
    for (std::string token; in >> token;) {
      double value = 0;
      EXPECT_TRUE(parse_number(token, value)) << token;
      values.push_back(value);
    }
    return values;
  };
  EXPECT_EQ(array_values("x3").size(), 31u);
  EXPECT_EQ(array_values("x3")[5], mesh.point(5)(3));
  EXPECT_EQ(array_values("residual").size(), 31u);
  EXPECT_EQ(array_values("Points").size(), 3 * 31u);
  const auto connectivity = array_values("connectivity");
  ASSERT_EQ(connectivity.size(), 3 * 20u);
  EXPECT_EQ(connectivity[3 * 19 + 2], mesh.triangle(19)[2]);
  const auto offsets = array_values("offsets");
  ASSERT_EQ(offsets.size(), 20u);
  EXPECT_EQ(offsets.back(), 60.0);
  const auto types = array_values("types");
  ASSERT_EQ(types.size(), 20u);
  EXPECT_EQ(types.front(), 5.0);  // VTK_TRIANGLE
  // "--" may not occur in an XML comment: it is written "- -" (a recorded command line stays
  // legible) and the file stays well formed.
  write_vtu(path, mesh, {.comments = {"tessera improve x.ply --criterion angle"}});
  std::ifstream in(path);
  const std::string with_dashes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(with_dashes.find("<!-- tessera improve x.ply - -criterion angle -->"), std::string::npos);
  EXPECT_EQ(read_mesh(path).triangle_count(), mesh.triangle_count());
}

}  // namespace
}  // namespace tessera
