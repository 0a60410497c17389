// SPDX-License-Identifier: MIT
// NumPy .npy files: points as (N, n) '<f8' and triangles as (T, 3) '<i8', bit for bit, read back
// by a reader written from the format's specification and, when Debian's python3-numpy is
// installed, by numpy.load itself.
#include "tessera/io/npy.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "io/io_test_support.h"
#include "io/npy_test_support.h"

namespace tessera {
namespace {

using namespace io_test;
using npy_test::python_with_numpy;
using npy_test::read_npy;
using npy_test::run_python;

TEST(Npy, PointsAreRowsOfADoubleArrayBitForBit) {
  // Random bit patterns: every exponent, subnormals, both zeros.
  const TriangleMesh mesh = random_mesh(7, 50, 0);
  const std::string path = test_path("points.npy");
  write_npy(path, mesh.points());
  const auto array = read_npy(path);
  EXPECT_EQ(array.descr, "<f8");
  EXPECT_FALSE(array.fortran_order);
  ASSERT_EQ(array.rows, 50);
  ASSERT_EQ(array.columns, 7);
  ASSERT_EQ(array.reals.size(), 350u);
  for (int j = 0; j < 50; ++j) {
    for (int i = 0; i < 7; ++i) {
      // Compare bits: -0.0 and 0.0 differ, as they must in a copy.
      EXPECT_EQ(std::bit_cast<std::uint64_t>(array.reals[7 * j + i]),
                std::bit_cast<std::uint64_t>(mesh.points()(i, j)))
          << "vertex " << j << ", coordinate " << i;
    }
  }
}

TEST(Npy, PointsOfABlockOfALargerMatrix) {
  // A Ref to a block has an outer stride: each column is written by itself.
  const Eigen::MatrixXd matrix = Eigen::MatrixXd::Random(6, 9);
  const std::string path = test_path("block.npy");
  write_npy(path, matrix.block(1, 2, 4, 5));
  const auto array = read_npy(path);
  ASSERT_EQ(array.rows, 5);
  ASSERT_EQ(array.columns, 4);
  for (int j = 0; j < 5; ++j) {
    for (int i = 0; i < 4; ++i) {
      EXPECT_EQ(array.reals[4 * j + i], matrix(1 + i, 2 + j));
    }
  }
}

TEST(Npy, TrianglesAreRowsOfAnInt64Array) {
  const TriangleMesh mesh = random_mesh(3, 40, 70);
  const std::string path = test_path("triangles.npy");
  write_npy(path, mesh.triangles());
  const auto array = read_npy(path);
  EXPECT_EQ(array.descr, "<i8");
  ASSERT_EQ(array.rows, 70);
  ASSERT_EQ(array.columns, 3);
  for (int t = 0; t < 70; ++t) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(array.integers[3 * t + k], mesh.triangle(t)[k]);
    }
  }
}

TEST(Npy, HeaderIsPaddedSoThatDataStartsAtAMultipleOf64) {
  // Shapes whose numbers have 1 … 6 digits give headers of different lengths.
  for (const int rows : {0, 1, 9, 10, 999, 123456}) {
    for (const int columns : {1, 3, 12, 1002}) {
      if (static_cast<long>(rows) * columns > 300'000) {
        continue;
      }
      const std::string path = test_path("shape.npy");
      write_npy(path, Eigen::MatrixXd::Zero(columns, rows));
      const auto array = read_npy(path);
      EXPECT_EQ(array.rows, rows);
      EXPECT_EQ(array.columns, columns);
      EXPECT_EQ(array.data_offset % 64, 0u);
    }
  }
}

TEST(Npy, StatesGoBesideTheirTriangles) {
  EXPECT_EQ(triangles_npy_path("out/bvp_states.npy"), "out/bvp_states.triangles.npy");
  EXPECT_EQ(triangles_npy_path("states"), "states.triangles.npy");
  EXPECT_EQ(triangles_npy_path(".npy"), ".npy.triangles.npy");
  const TriangleMesh mesh = random_mesh(5, 30, 40);
  const std::string path = test_path("mesh_states.npy");
  write_states_npy(path, mesh);
  EXPECT_EQ(read_npy(path).rows, 30);
  EXPECT_EQ(read_npy(path).columns, 5);
  EXPECT_EQ(read_npy(test_path("mesh_states.triangles.npy")).rows, 40);
}

TEST(Npy, BadTriangleIndexWritesNothing) {
  TriangleMesh mesh = random_mesh(3, 10, 5);
  mesh.add_triangle(0, 1, 10);
  const std::string path = test_path("bad_states.npy");
  expect_invalid_argument([&] { write_states_npy(path, mesh); }, {"triangle 5", "10"});
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(triangles_npy_path(path)));
}

TEST(Npy, UnwritableFileIsAnErrorNamingIt) {
  const std::string path = test_path("no/such/folder/states.npy");
  expect_invalid_argument([&] { write_npy(path, Eigen::MatrixXd::Zero(3, 2)); },
                          {"NumPy file '" + path + "'"});
}

TEST(Npy, NumpyLoadsWhatIsWritten) {
  const std::string python = python_with_numpy();
  if (python.empty()) {
    GTEST_SKIP() << "numpy is not installed (python3-numpy; scripts/install-dependencies.sh)";
  }
  const TriangleMesh mesh = random_mesh(4, 25, 30, 11);
  const std::string points = test_path("numpy_points.npy");
  const std::string triangles = test_path("numpy_triangles.npy");
  write_npy(points, mesh.points());
  write_npy(triangles, mesh.triangles());
  // numpy compares against the same numbers given in hexadecimal (exact): every bit is checked.
  std::string expected_points;
  for (int j = 0; j < mesh.vertex_count(); ++j) {
    for (int i = 0; i < 4; ++i) {
      char hex[64];
      std::snprintf(hex, sizeof hex, "%a ", mesh.points()(i, j));
      expected_points += hex;
    }
  }
  std::string expected_triangles;
  for (const Triangle& t : mesh.triangles()) {
    expected_triangles +=
        std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + " ";
  }
  write_text(test_path("expected_points.txt"), expected_points);
  write_text(test_path("expected_triangles.txt"), expected_triangles);
  const std::string script =
      "import sys, numpy\n"
      "X = numpy.load(sys.argv[1]); T = numpy.load(sys.argv[2])\n"
      "P = numpy.array([float.fromhex(v) for v in open(sys.argv[3]).read().split()])\n"
      "E = numpy.array([int(v) for v in open(sys.argv[4]).read().split()])\n"
      "print(X.shape, X.dtype, T.shape, T.dtype)\n"
      "assert X.flags.c_contiguous and X.tobytes() == P.reshape(X.shape).tobytes()\n"
      "assert (T == E.reshape(T.shape)).all()\n"
      "M = numpy.load(sys.argv[1], mmap_mode='r'); assert (M == X).all()\n"
      "print('same')\n";
  const auto [output, status] = run_python(
      python, script,
      {points, triangles, test_path("expected_points.txt"), test_path("expected_triangles.txt")});
  EXPECT_EQ(status, 0) << output;
  EXPECT_NE(output.find("(25, 4) float64 (30, 3) int64\nsame"), std::string::npos) << output;
}

}  // namespace
}  // namespace tessera
