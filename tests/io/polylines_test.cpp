// SPDX-License-Identifier: MIT
// Every polyline format write_polylines writes is read back by read_polylines with the same
// points, marks, closedness, columns, kind and marker: what `tessera mesh --folds/--hopf/--level`
// writes, `tessera render --curves` and `--diagram` read.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include "support/test_support.h"
#include "tessera/core/error.h"
#include "tessera/io/polylines.h"

namespace tessera {
namespace {

std::vector<Polyline> sample_curves(int k) {
  Polyline open;
  open.points = Eigen::MatrixXd::Random(k, 5);
  open.marked = {false, true, false, false, true};
  Polyline closed;
  closed.points = Eigen::MatrixXd::Random(k, 4);
  closed.is_closed = true;
  Polyline single;  // a special point on its own
  single.points = Eigen::MatrixXd::Random(k, 1);
  single.marked = {true};
  Polyline segment;  // after a point on its own, and before a polyline: joined to neither
  segment.points = Eigen::MatrixXd::Random(k, 2);
  return {open, closed, single, segment, open};
}

TEST(Polylines, EveryFormatReadsBackWhatWasWritten) {
  const std::string dir = testing::temporary_directory("polylines_round_trip");
  for (const int k : {2, 3, 6}) {
    PolylineFileOptions options;
    for (int c = 0; c < k; ++c) {
      options.names.push_back("c" + std::to_string(c));
    }
    options.kind = "hopf";
    options.marker_name = "bogdanov_takens";
    const auto curves = sample_curves(k);
    for (const std::string extension : {".json", ".csv", ".vtk", ".vtu", ".ply"}) {
      const std::string path = dir + "/curves" + std::to_string(k) + extension;
      write_polylines(path, curves, options);
      const PolylineFile read = read_polylines(path);
      SCOPED_TRACE(path);
      EXPECT_EQ(read.options.names, options.names);
      EXPECT_EQ(read.options.kind, "hopf");
      EXPECT_EQ(read.options.marker_name, "bogdanov_takens");
      ASSERT_EQ(read.polylines.size(), curves.size());
      for (std::size_t l = 0; l < curves.size(); ++l) {
        if (extension != ".csv") {  // a CSV row has no place for it: curves read back open
          EXPECT_EQ(read.polylines[l].is_closed, curves[l].is_closed) << "polyline " << l;
        }
        ASSERT_EQ(read.polylines[l].points.cols(), curves[l].points.cols()) << "polyline " << l;
        EXPECT_LE((read.polylines[l].points - curves[l].points).cwiseAbs().maxCoeff(), 1e-15);
        for (Eigen::Index i = 0; i < curves[l].points.cols(); ++i) {
          const bool expected = !curves[l].marked.empty() && curves[l].marked[static_cast<std::size_t>(i)];
          const bool found = !read.polylines[l].marked.empty() &&
                             read.polylines[l].marked[static_cast<std::size_t>(i)];
          EXPECT_EQ(found, expected) << "polyline " << l << ", point " << i;
        }
      }
    }
  }
}

// A value that was not computed (NaN: l1 at a Bogdanov-Takens point) is written as null
// (JSON) or nan (CSV) and read back as NaN by every format, so that `render --curves` takes the
// Hopf curves `mesh --hopf` writes (it refused them: "must be an array of numbers").
TEST(Polylines, AValueNotComputedReadsBackAsNaN) {
  const std::string dir = testing::temporary_directory("polylines_nan");
  PolylineFileOptions options;
  options.names = {"Da", "B", "omega", "l1"};
  options.kind = "hopf";
  Polyline line;
  line.points = Eigen::MatrixXd::Random(4, 3);
  line.points(3, 0) = std::numeric_limits<double>::quiet_NaN();
  line.marked = {true, false, false};
  for (const std::string extension : {".json", ".csv", ".vtu", ".ply"}) {
    const std::string path = dir + "/hopf" + extension;
    write_polylines(path, {line}, options);
    const PolylineFile read = read_polylines(path);
    SCOPED_TRACE(path);
    ASSERT_EQ(read.polylines.size(), 1u);
    EXPECT_TRUE(std::isnan(read.polylines[0].points(3, 0)));
    EXPECT_EQ(read.polylines[0].points.rightCols(2), line.points.rightCols(2));
  }
}

// Curve files of tessera before issue 34: legacy VTK POLYDATA with LINES, and VTU with one
// VTK_POLY_LINE per curve (meshio reads neither: tessera now writes unstructured segments).
TEST(Polylines, ReadsTheVtkFilesOfEarlierVersions) {
  const std::string dir = testing::temporary_directory("polylines_earlier");
  const std::string vtk = dir + "/old.vtk";
  {
    std::ofstream file(vtk);
    file << "# vtk DataFile Version 3.0\ntessera polylines; kind: fold\nASCII\n"
            "DATASET POLYDATA\nPOINTS 4 double\n0 0 0\n1 0 0\n2 0 0\n5 5 0\n"
            "LINES 2 6\n3 0 1 2\n1 3\nPOINT_DATA 4\n"
            "SCALARS a double 1\nLOOKUP_TABLE default\n0\n1\n2\n5\n"
            "SCALARS b double 1\nLOOKUP_TABLE default\n0\n0\n0\n5\n"
            "SCALARS cusp int 1\nLOOKUP_TABLE default\n0\n1\n0\n1\n";
  }
  const std::string vtu = dir + "/old.vtu";
  {
    std::ofstream file(vtu);
    file << "<?xml version=\"1.0\"?>\n<!-- kind: fold -->\n"
            "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
            "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"4\" NumberOfCells=\"2\">\n"
            "      <PointData>\n"
            "        <DataArray type=\"Float64\" Name=\"a\" format=\"ascii\">\n0\n1\n2\n5\n"
            "        </DataArray>\n"
            "        <DataArray type=\"Float64\" Name=\"b\" format=\"ascii\">\n0\n0\n0\n5\n"
            "        </DataArray>\n"
            "        <DataArray type=\"Int32\" Name=\"cusp\" format=\"ascii\">\n0\n1\n0\n1\n"
            "        </DataArray>\n      </PointData>\n      <Points>\n"
            "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n"
            "0 0 0\n1 0 0\n2 0 0\n5 5 0\n        </DataArray>\n      </Points>\n      <Cells>\n"
            "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n"
            "0 1 2 \n3 \n        </DataArray>\n"
            "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n3\n4\n"
            "        </DataArray>\n"
            "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n4\n4\n"
            "        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n"
            "</VTKFile>\n";
  }
  for (const std::string& path : {vtk, vtu}) {
    SCOPED_TRACE(path);
    const PolylineFile read = read_polylines(path);
    EXPECT_EQ(read.options.names, (std::vector<std::string>{"a", "b"}));
    EXPECT_EQ(read.options.kind, "fold");
    ASSERT_EQ(read.polylines.size(), 2u);
    ASSERT_EQ(read.polylines[0].points.cols(), 3);
    EXPECT_EQ(read.polylines[0].points(0, 2), 2.0);
    EXPECT_EQ(read.polylines[0].marked, (std::vector<bool>{false, true, false}));
    ASSERT_EQ(read.polylines[1].points.cols(), 1);
    EXPECT_EQ(read.polylines[1].points(1, 0), 5.0);
    EXPECT_EQ(read.polylines[1].marked, (std::vector<bool>{true}));
  }
}

// Issue 34: "[json.exception.out_of_range.406] number overflow parsing '1e999'" reached the user
// of `render --curves`; and a summary given for curves (the docs once named both bvp.json) is
// named for what it is.
TEST(Polylines, JsonErrorsNameTheFileNotNlohmann) {
  const std::string dir = testing::temporary_directory("polylines_json_errors");
  const std::string overflow = dir + "/overflow.json";
  std::ofstream(overflow) << R"({"polylines": [{"points": [[1e999, 2, 3]]}]})";
  const std::string summary = dir + "/bvp.json";
  std::ofstream(summary) << R"({"ambient_dimension": 22, "problem": "bvp:points=20"})";
  for (const auto& [path, expected] : std::vector<std::pair<std::string, std::string>>{
           {overflow, "a number is out of the range of a double"},
           {summary, "found the JSON summary of a `tessera mesh` run"}}) {
    try {
      read_polylines(path);
      ADD_FAILURE() << "accepted " << path;
    } catch (const InvalidArgument& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find("polylines file '" + path + "'"), std::string::npos) << message;
      EXPECT_NE(message.find(expected), std::string::npos) << message;
      EXPECT_EQ(message.find("json.exception"), std::string::npos) << message;
    }
  }
}

// A count in a PLY header that is no number ("tessera: failed: stol") or more than the file can
// hold (std::bad_alloc) is refused naming the file and the line.
TEST(Polylines, PlyCountsAreCheckedBeforeUse) {
  const std::string dir = testing::temporary_directory("polylines_ply_counts");
  for (const std::string count : {"abc", "99999999999999999999", "999999999999", "-1"}) {
    const std::string path = dir + "/bad.ply";
    std::ofstream(path) << "ply\nformat ascii 1.0\ncomment coordinate names: a b c\n"
                           "element vertex " +
                               count +
                               "\nproperty double x\nproperty double y\n"
                               "property double z\nproperty uchar cusp\nelement edge 0\n"
                               "property int vertex1\nproperty int vertex2\nend_header\n";
    try {
      read_polylines(path);
      ADD_FAILURE() << "accepted " << count;
    } catch (const InvalidArgument& error) {
      EXPECT_NE(std::string(error.what()).find("'element vertex " + count + "'"), std::string::npos)
          << error.what();
    }
  }
}

TEST(Polylines, AMeshFileIsNotTakenForCurves) {
  const std::string dir = testing::temporary_directory("polylines_not_curves");
  const std::string path = dir + "/mesh.ply";
  {
    std::ofstream file(path);
    file << "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
            "property double z\nelement face 1\nproperty list uchar int vertex_indices\n"
            "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  }
  try {
    read_polylines(path);
    FAIL() << "accepted a mesh";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("not a polylines file of tessera"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace tessera
