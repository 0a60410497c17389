// SPDX-License-Identifier: MIT
// PLY: exact round trips in R^n, foreign files, and errors that name the file and line.
#include "tessera/io/ply.h"

#include <gtest/gtest.h>

#include "io/io_test_support.h"

namespace tessera {
namespace {

using namespace io_test;

// PLY round trips

class PlyRoundTrip : public ::testing::TestWithParam<std::tuple<int, bool>> {};

TEST_P(PlyRoundTrip, IsBitExact) {
  const auto [n, binary] = GetParam();
  const auto mesh = random_mesh(n, 500, 900);
  const std::string path =
      test_path("round_trip_" + std::to_string(n) + (binary ? "b" : "a") + ".ply");
  write_ply(path, mesh, {.binary = binary});
  expect_identical(mesh, read_ply(path));
}

INSTANTIATE_TEST_SUITE_P(DimensionAndEncoding, PlyRoundTrip,
                         ::testing::Combine(::testing::Values(2, 3, 5),
                                            ::testing::Values(true, false)));

// meshio and VTK take the position only from x, y, z (VTK's PLY reader crashed on x0 ...): the
// first three coordinates are always x, y, z, the rest extra properties.
TEST(Ply, HeaderNamesTheFirstThreeCoordinatesXyzForEveryN) {
  const auto path = test_path("names5.ply");
  write_ply(path, random_mesh(5, 4, 2), {.binary = false});
  const std::string text = file_text(path);
  EXPECT_NE(text.find("format ascii 1.0\n"), std::string::npos);
  EXPECT_NE(text.find("comment written by tessera: triangle mesh in R^5\n"), std::string::npos);
  EXPECT_NE(text.find("element vertex 4\nproperty double x\nproperty double y\nproperty "
                      "double z\nproperty double x3\nproperty double x4\nelement face 2\n"
                      "property list uchar int vertex_indices\nend_header\n"),
            std::string::npos)
      << text;
  write_ply(path, random_mesh(3, 4, 2), {.binary = false});
  EXPECT_NE(file_text(path).find("property double x\nproperty double y\nproperty double z\n"),
            std::string::npos);
  write_ply(path, random_mesh(5, 4, 2));
  EXPECT_NE(file_text(path).find("format binary_little_endian 1.0\n"), std::string::npos);
}

TEST(Ply, BinaryLayoutIsLittleEndianDoublesThenUcharIntFaces) {
  const auto path = test_path("layout.ply");
  const auto mesh = two_triangles();
  write_ply(path, mesh);
  const std::string text = file_text(path);
  const auto data = text.substr(text.find("end_header\n") + 11);
  ASSERT_EQ(data.size(), 4 * 3 * 8 + 2 * 13u);  // 4 vertices of 3 doubles, 2 × (uchar + 3 int)
  EXPECT_EQ(data[96], 3);
  EXPECT_EQ(data[97], 0);                   // first index 0, little endian int32
  EXPECT_EQ(data[96 + 13 + 1 + 4 * 2], 3);  // third index of the second triangle is 3
  double y2 = 0;
  std::memcpy(&y2, data.data() + (2 * 3 + 1) * 8, 8);
  if constexpr (std::endian::native == std::endian::little) {
    EXPECT_EQ(y2, 1.0);
  }
}

TEST(Ply, ProblemNamesBeyondTheThirdBecomePropertiesWhenTheyAreIdentifiers) {
  const auto mesh = random_mesh(6, 20, 10);
  const auto path = test_path("named.ply");
  write_ply(path, mesh, {.binary = false, .coordinate_names = {"u", "v", "s", "t", "Da", "B"}});
  std::string text = file_text(path);
  EXPECT_NE(text.find("property double x\nproperty double y\nproperty double z\nproperty double "
                      "t\nproperty double Da\nproperty double B\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("comment coordinate names: u v s t Da B\n"), std::string::npos);
  expect_identical(mesh, read_ply(path));
  expect_identical(mesh, read_ply(path, {"x", "y", "z", "t", "Da", "B"}));

  // Names that are no identifiers, or that clash with x, y, z or a scalar field, are replaced.
  write_ply(path, mesh,
            {.binary = false,
             .coordinate_names = {"a", "b", "c", "x", "d-e", "coordinate_3"},
             .vertex_scalars = {{"r", std::vector<double>(20, 1.0)}}});
  text = file_text(path);
  EXPECT_NE(text.find("property double z\nproperty double coordinate_3\nproperty double "
                      "coordinate_4\nproperty double coordinate_5\nproperty double r\n"),
            std::string::npos)
      << text;
  expect_identical(mesh, read_ply(path));
  expect_invalid_argument(
      [&] {
        write_ply(path, mesh, {.vertex_scalars = {{"y", std::vector<double>(20, 1.0)}}});
      },
      {"'y'", "x, y, z"});
}

// Files written before x, y, z were used for every n: x0 ... x{n-1}, with or without the comment
// that gives n, and with the names x, y, z, coordinate_3 ... that other tools may write.
TEST(Ply, ReadsEveryCoordinateLayoutInOrder) {
  const auto mesh = random_mesh(4, 3, 1);
  auto file = [&](const std::string& comment, const std::vector<std::string>& names) {
    std::string text = "ply\nformat ascii 1.0\n" + comment + "element vertex 3\n";
    for (const auto& name : names) {
      text += "property double " + name + "\n";
    }
    text += "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    for (int v = 0; v < 3; ++v) {
      for (int k = 0; k < 4; ++k) {
        char buffer[32];
        text += std::string(buffer, std::to_chars(buffer, buffer + 32, mesh.point(v)(k)).ptr);
        text += k < 3 ? " " : " 7\n";  // 7: a scalar property after the coordinates
      }
    }
    const auto& triangle = mesh.triangle(0);
    text += "3 " + std::to_string(triangle[0]) + " " + std::to_string(triangle[1]) + " " +
            std::to_string(triangle[2]) + "\n";
    const auto path =
        test_path("layout_" + std::to_string(std::hash<std::string>{}(text)) + ".ply");
    write_text(path, text);
    return path;
  };
  const std::string marker = "comment written by tessera: triangle mesh in R^4\n";
  for (const auto& [comment, names] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {marker, {"x0", "x1", "x2", "x3", "residual"}},
           {"", {"x0", "x1", "x2", "x3", "residual"}},
           {marker, {"x", "y", "z", "x3", "residual"}},
           {"", {"x", "y", "z", "x3", "residual"}},
           {"", {"x", "y", "z", "coordinate_3", "residual"}},
           {marker, {"x", "y", "z", "B", "residual"}},
           {marker, {"a", "b", "c", "d", "residual"}}}) {
    SCOPED_TRACE(comment + names[0] + " " + names[3]);
    expect_identical(mesh, read_ply(file(comment, names)));
  }
  // Without the comment, an unknown fourth name is a scalar field: the mesh is in R^3.
  EXPECT_EQ(read_ply(file("", {"x", "y", "z", "B", "residual"})).ambient_dimension(), 3);
  expect_invalid_argument(
      [&] {
        read_ply(file("comment written by tessera: triangle mesh in R^9\n",
                      {"x", "y", "z", "B", "residual"}));
      },
      {"R^9", "only 5 properties"});
}

TEST(Ply, VertexScalarsAreWrittenAfterCoordinatesAndIgnoredOnRead) {
  const auto mesh = random_mesh(4, 30, 20);
  std::vector<double> residual(30);
  std::vector<double> index(30);
  for (int v = 0; v < 30; ++v) {
    residual[static_cast<std::size_t>(v)] = 1e-12 * v;
    index[static_cast<std::size_t>(v)] = v;
  }
  for (const bool binary : {true, false}) {
    const auto path = test_path(binary ? "scalars_b.ply" : "scalars_a.ply");
    write_ply(path, mesh,
              {.binary = binary,
               .vertex_scalars = {{"residual", residual}, {"index", index}},
               .comments = {"problem: hypersphere", "seed 7"}});
    expect_identical(mesh, read_ply(path));
    const std::string text = file_text(path);
    EXPECT_NE(text.find("property double x3\nproperty double residual\nproperty double index\n"),
              std::string::npos);
    EXPECT_NE(text.find("comment problem: hypersphere\ncomment seed 7\n"), std::string::npos);
    if (!binary) {
      // Vertex 2 is the third data line: its last two numbers are the two scalars.
      std::istringstream data(text.substr(text.find("end_header\n") + 11));
      std::string line;
      for (int i = 0; i < 3; ++i) {
        std::getline(data, line);
      }
      EXPECT_EQ(line.substr(line.size() - 8), " 2e-12 2");
    }
  }
}

TEST(Ply, ReadsForeignAsciiWithFloatsExtraPropertiesQuadsAndCrlf) {
  const auto path = test_path("foreign.ply");
  write_text(path,
             "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nelement vertex 5\r\n"
             "property float x\r\nproperty float y\r\nproperty float z\r\nproperty float nx\r\n"
             "property uchar red\r\nproperty list uchar float weights\r\n"
             "element face 2\r\nproperty uchar flags\r\nproperty list uchar uint vertex_index\r\n"
             "element edge 1\r\nproperty int vertex1\r\nproperty int vertex2\r\nend_header\r\n"
             "0 0 0 1 255 2 0.5 0.5\r\n1 0 0 1 255 0\r\n1 1 0 1 255 0\r\n0 1 0 1 255 0\r\n"
             "0.5 0.5 1.5 1 255 1 7\r\n"
             "0 4 0 1 2 3\r\n9 3 0 1 4\r\n0 1\r\n");
  const auto mesh = read_ply(path);
  EXPECT_EQ(mesh.ambient_dimension(), 3);
  ASSERT_EQ(mesh.vertex_count(), 5);
  EXPECT_EQ(mesh.point(4)(2), 1.5);
  // The quad (0 1 2 3) becomes the fan (0 1 2), (0 2 3), which keeps its orientation.
  EXPECT_EQ(mesh.triangles(), (std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}, {0, 1, 4}}));
}

TEST(Ply, ReadsBinaryBigEndianFloats) {
  const auto path = test_path("big_endian.ply");
  std::string file =
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  auto append_big_endian = [&](auto value) {
    char bytes[sizeof value];
    std::memcpy(bytes, &value, sizeof value);
    if constexpr (std::endian::native == std::endian::little) {
      std::reverse(std::begin(bytes), std::end(bytes));
    }
    file.append(bytes, sizeof value);
  };
  const float coordinates[] = {0.f, 0.f, 0.f, 1.5f, 0.f, 0.f, 0.f, -2.25f, 0.f};
  for (const float c : coordinates) {
    append_big_endian(c);
  }
  file += '\3';
  for (const std::int32_t v : {0, 2, 1}) {
    append_big_endian(v);
  }
  write_text(path, file);
  const auto mesh = read_ply(path);
  ASSERT_EQ(mesh.vertex_count(), 3);
  EXPECT_EQ(mesh.point(1)(0), 1.5);
  EXPECT_EQ(mesh.point(2)(1), -2.25);
  EXPECT_EQ(mesh.triangles(), (std::vector<Triangle>{{0, 2, 1}}));
}

TEST(Ply, MeshWithoutFaceElementHasNoTriangles) {
  const auto path = test_path("points.ply");
  write_text(path,
             "ply\nformat ascii 1.0\nelement vertex 2\nproperty double x\n"
             "property double y\nend_header\n1 2\n3 4\n");
  const auto mesh = read_ply(path);
  EXPECT_EQ(mesh.ambient_dimension(), 2);
  EXPECT_EQ(mesh.vertex_count(), 2);
  EXPECT_EQ(mesh.triangle_count(), 0);
}

TEST(Ply, LargeMeshRoundTripsInBothEncodings) {
  // Big enough that the output buffer (1 MiB) is flushed many times.
  const auto mesh = random_mesh(3, 200'000, 400'000);
  for (const bool binary : {true, false}) {
    const auto path = test_path(binary ? "large_b.ply" : "large_a.ply");
    write_ply(path, mesh, {.binary = binary});
    expect_identical(mesh, read_ply(path));
  }
}

// ---------------------------------------------------------------------------------------------
// PLY errors: every message names the file; ASCII ones also name the line.

const std::string kHeader3 =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
    "property double z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

TEST(PlyErrors, MissingFile) {
  const auto path = test_path("does_not_exist.ply");
  expect_invalid_argument([&] { read_ply(path); }, {"PLY file", path, "cannot open"});
  expect_invalid_argument([&] { write_ply(test_path("no_such_dir/mesh.ply"), two_triangles()); },
                          {"no_such_dir/mesh.ply", "cannot open for writing"});
}

TEST(PlyErrors, BadHeader) {
  const auto path = test_path("bad_header.ply");
  const std::pair<std::string, std::vector<std::string>> cases[] = {
      {"PLY\nformat ascii 1.0\n", {"line 1", "not a PLY file"}},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty double x\n", {"no 'end_header'"}},
      {"ply\nformat ascii 2.0 x\nend_header\n", {"line 2", "format"}},
      {"ply\nformat utf8 1.0\nend_header\n", {"line 2", "unknown format 'utf8'"}},
      {"ply\nformat ascii 1.0\nelement vertex -3\nend_header\n", {"line 3", "count >= 0"}},
      {"ply\nformat ascii 1.0\nproperty double x\nend_header\n", {"line 3", "before any"}},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty real x\nend_header\n",
       {"line 4", "property <type> <name>"}},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty double x\nbogus\nend_header\n",
       {"line 5", "unknown header keyword 'bogus'"}},
      {"ply\nelement vertex 1\nproperty double x\nend_header\n0\n", {"no 'format' line"}},
      {"ply\nformat ascii 1.0\nelement face 0\nend_header\n", {"no 'vertex' element"}},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty double x\nelement face 1\n"
       "property int flags\nend_header\n0\n1\n",
       {"no list property 'vertex_indices'", "flags"}},
  };
  for (const auto& [text, parts] : cases) {
    write_text(path, text);
    auto expected = parts;
    expected.push_back(path);
    expect_invalid_argument([&] { read_ply(path); }, expected);
  }
}

TEST(PlyErrors, TruncatedBinary) {
  const auto path = test_path("truncated.ply");
  write_ply(path, random_mesh(3, 100, 150));
  const std::string whole = file_text(path);
  // Cut inside the face data: the size check passes, the record reader finds the end.
  write_text(path, whole.substr(0, whole.size() - 5));
  expect_invalid_argument([&] { read_ply(path); },
                          {path, "unexpected end of file in face 149 of 150", "truncated"});
  // Cut inside the vertex data: the header promises more than the file holds.
  write_text(path, whole.substr(0, whole.find("end_header\n") + 11 + 800));
  expect_invalid_argument([&] { read_ply(path); }, {path, "100 'vertex' records", "truncated"});
}

TEST(PlyErrors, TruncatedAndMalformedAsciiNameTheLine) {
  const auto path = test_path("bad_ascii.ply");
  write_text(path, kHeader3 + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n");
  expect_invalid_argument([&] { read_ply(path); },
                          {path, "line 13", "unexpected end of file in face 0 of 1"});
  write_text(path, kHeader3 + "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n");
  expect_invalid_argument([&] { read_ply(path); },
                          {path, "line 11", "expected a number", "vertex 1 of 3", "'zero'"});
  write_text(path, kHeader3 + "0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n");
  expect_invalid_argument([&] { read_ply(path); }, {path, "line 13", "expected an integer"});
}

TEST(PlyErrors, IndexOutOfRange) {
  const auto path = test_path("out_of_range.ply");
  write_text(path, kHeader3 + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
  expect_invalid_argument([&] { read_ply(path); },
                          {path, "line 13", "face 0 has vertex index 3; the file has 3 vertices"});
  write_text(path, kHeader3 + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n");
  expect_invalid_argument([&] { read_ply(path); }, {path, "vertex index -1"});
  write_text(path, kHeader3 + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n");
  expect_invalid_argument([&] { read_ply(path); },
                          {path, "line 13", "face 0 has 2 vertices; a face needs at least 3"});

  auto mesh = random_mesh(3, 10, 5);
  write_ply(path, mesh);
  std::string binary = file_text(path);
  const std::int32_t bad = 10;  // last index of the last face
  std::memcpy(binary.data() + binary.size() - 4, &bad, 4);
  if constexpr (std::endian::native == std::endian::little) {
    write_text(path, binary);
    expect_invalid_argument([&] { read_ply(path); },
                            {path, "face 4 has vertex index 10; the file has 10 vertices"});
  }
}

TEST(PlyErrors, WriteRejectsInconsistentOptionsAndMeshes) {
  const auto mesh = two_triangles();
  const auto path = test_path("rejected.ply");
  expect_invalid_argument(
      [&] {
        write_ply(path, mesh, {.coordinate_names = {"a", "b"}});
      },
      {"PlyOptions::coordinate_names has 2 names", "R^3"});
  expect_invalid_argument(
      [&] {
        write_ply(path, mesh, {.coordinate_names = {"a", "b c", "d"}});
      },
      {"'b c'", "without whitespace"});
  expect_invalid_argument(
      [&] {
        write_ply(path, mesh, {.vertex_scalars = {{"residual", {1.0, 2.0}}}});
      },
      {"'residual' has 2 values; the mesh has 4 vertices"});
  expect_invalid_argument(
      [&] {
        write_ply(path, mesh, {.vertex_scalars = {{"y", {1, 2, 3, 4}}}});
      },
      {"'y' is already used"});
  expect_invalid_argument([&] { write_ply(path, mesh, {.comments = {"two\nlines"}}); },
                          {"single line"});
  TriangleMesh broken = mesh;
  broken.add_triangle(0, 1, 4);
  expect_invalid_argument([&] { write_ply(path, broken); },
                          {path, "triangle 2 has vertex index 4; the mesh has 4 vertices"});
}

}  // namespace
}  // namespace tessera
