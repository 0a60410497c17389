// SPDX-License-Identifier: MIT
// Every polyline format write_polylines writes is read back by read_polylines with the same
// points, marks, closedness, columns, kind and marker: what `tessera mesh --folds/--hopf/--level`
// writes, `tessera render --curves` and `--diagram` read.
#include <gtest/gtest.h>

#include <fstream>
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
  return {open, closed, single};
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
