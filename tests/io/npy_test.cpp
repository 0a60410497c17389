// SPDX-License-Identifier: MIT
// NumPy .npy files: points as (N, n) '<f8' and triangles as (T, 3) '<i8', bit for bit, read back
// by a reader written from the format's specification and, when Debian's python3-numpy is
// installed, by numpy.load itself.
#include "tessera/io/npy.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "io/io_test_support.h"
#include "io/npy_test_support.h"
#include "tessera/io/detail/file_buffer.h"
#include "tessera/io/detail/mesh_parsers.h"
#include "tessera/io/mesh_io.h"

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

// ---- reading ---------------------------------------------------------------------------------

TEST(NpyRead, StatesReadBackBitForBit) {
  const TriangleMesh mesh = random_mesh(6, 40, 60, 3);
  const std::string path = test_path("round_trip.npy");
  write_states_npy(path, mesh);
  for (const TriangleMesh& back : {read_states_npy(path), read_mesh(path)}) {
    ASSERT_EQ(back.ambient_dimension(), 6);
    EXPECT_EQ(std::memcmp(back.points().data(), mesh.points().data(), 6 * 40 * sizeof(double)), 0);
    EXPECT_EQ(back.triangles(), mesh.triangles());
  }
}

// An .npy file from its parts, as numpy.save would write it with other choices: `version` 1 or
// 2 (4-byte header length), any header dictionary, the data bytes as given.
std::string npy_bytes(const std::string& dictionary, const std::string& data, int version = 1) {
  const std::size_t preamble = version == 1 ? 10 : 12;
  std::string header = dictionary;
  header.append((64 - (preamble + header.size() + 1) % 64) % 64, ' ');
  header.push_back('\n');
  std::string bytes = "\x93NUMPY";
  bytes.push_back(static_cast<char>(version));
  bytes.push_back(0);
  for (std::size_t k = 0; k < preamble - 8; ++k) {
    bytes.push_back(static_cast<char>((header.size() >> (8 * k)) & 0xff));
  }
  return bytes + header + data;
}

template <class T>
std::string raw_bytes(std::initializer_list<T> values, bool big_endian = false) {
  std::string bytes;
  for (T value : values) {
    char b[sizeof(T)];
    std::memcpy(b, &value, sizeof(T));
    if (big_endian) {
      std::reverse(b, b + sizeof(T));
    }
    bytes.append(b, sizeof(T));
  }
  return bytes;
}

TEST(NpyRead, ReadsWhatNumpyWritesWithOtherTypesAndOrders) {
  // Two points of R^3, (1, 2, 3) and (4, 5, 6).
  const Eigen::MatrixXd expected = (Eigen::MatrixXd(3, 2) << 1, 4, 2, 5, 3, 6).finished();
  const std::string c_order = "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }";
  EXPECT_EQ(io_detail::parse_npy_points(npy_bytes(c_order, raw_bytes<double>({1, 2, 3, 4, 5, 6})),
                                        "p.npy"),
            expected);
  // Big endian, and version 2.0.
  EXPECT_EQ(io_detail::parse_npy_points(
                npy_bytes("{'descr': '>f8', 'fortran_order': False, 'shape': (2, 3), }",
                          raw_bytes<double>({1, 2, 3, 4, 5, 6}, true), 2),
                "p.npy"),
            expected);
  // Single precision in Fortran order (columns of the (2, 3) array one after the other), keys
  // in another order, double quotes.
  EXPECT_EQ(io_detail::parse_npy_points(
                npy_bytes("{\"shape\": (2, 3), \"fortran_order\": True, \"descr\": \"<f4\"}",
                          raw_bytes<float>({1, 4, 2, 5, 3, 6})),
                "p.npy"),
            expected);
  // Triangles as int32, big-endian int16 and uint8.
  const std::vector<Triangle> triangles = {{0, 1, 2}, {2, 1, 3}};
  EXPECT_EQ(io_detail::parse_npy_triangles(
                npy_bytes("{'descr': '<i4', 'fortran_order': False, 'shape': (2, 3), }",
                          raw_bytes<std::int32_t>({0, 1, 2, 2, 1, 3})),
                "t.npy", 4),
            triangles);
  EXPECT_EQ(io_detail::parse_npy_triangles(
                npy_bytes("{'descr': '>i2', 'fortran_order': False, 'shape': (2, 3), }",
                          raw_bytes<std::int16_t>({0, 1, 2, 2, 1, 3}, true)),
                "t.npy", 4),
            triangles);
  EXPECT_EQ(io_detail::parse_npy_triangles(
                npy_bytes("{'descr': '|u1', 'fortran_order': False, 'shape': (2, 3), }",
                          raw_bytes<std::uint8_t>({0, 1, 2, 2, 1, 3})),
                "t.npy", 4),
            triangles);
}

// Files numpy.save wrote (the seed corpus of the fuzz target, tests/fuzz/corpus/npy/).
TEST(NpyRead, ReadsTheFilesNumpyWrote) {
  const auto corpus = [](const std::string& name) {
    return io_detail::read_file("NumPy", testing::source_path("tests/fuzz/corpus/npy/" + name));
  };
  // numpy.array([[0., 1, 2], [3, 4, 5], [6, 7, 8], [9, 10, 11]])
  const Eigen::MatrixXd points = io_detail::parse_npy_points(corpus("points_f8.npy"), "p");
  ASSERT_EQ(points.rows(), 3);
  ASSERT_EQ(points.cols(), 4);
  for (int v = 0; v < 4; ++v) {
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(points(i, v), 3 * v + i);
    }
  }
  // numpy.asfortranarray(numpy.array([[0.5, 1, 2], [3, 4, 5]], dtype='>f4'))
  EXPECT_EQ(io_detail::parse_npy_points(corpus("points_f4_big_fortran.npy"), "p"),
            (Eigen::MatrixXd(3, 2) << 0.5, 3, 1, 4, 2, 5).finished());
  EXPECT_EQ(io_detail::parse_npy_points(corpus("empty.npy"), "p").cols(), 0);
  EXPECT_EQ(io_detail::parse_npy_triangles(corpus("triangles_i8.npy"), "t", 4),
            (std::vector<Triangle>{{0, 1, 2}, {2, 1, 3}}));
  EXPECT_EQ(io_detail::parse_npy_triangles(corpus("triangles_u1.npy"), "t", 3),
            (std::vector<Triangle>{{0, 1, 2}}));
  EXPECT_EQ(io_detail::parse_npy_triangles(corpus("version2.npy"), "t", 4),
            (std::vector<Triangle>{{1, 2, 3}}));
  expect_invalid_argument([&] { io_detail::parse_npy_points(corpus("one_dimensional.npy"), "p"); },
                          {"the shape has 1 dimensions"});
}

TEST(NpyRead, MalformedFilesAreErrorsNamingTheFileAndTheProblem) {
  const std::string f8 = "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }";
  const std::string six = raw_bytes<double>({1, 2, 3, 4, 5, 6});
  const auto points_error = [](const std::string& bytes, const std::vector<std::string>& parts) {
    expect_invalid_argument([&] { io_detail::parse_npy_points(bytes, "s.npy"); },
                            [&] {
                              std::vector<std::string> all = {"NumPy file 's.npy'"};
                              all.insert(all.end(), parts.begin(), parts.end());
                              return all;
                            }());
  };
  points_error("ply\nformat ascii 1.0\n", {"not an .npy file"});
  points_error(npy_bytes(f8, six.substr(0, 40)), {"needs 48 bytes of data, the file has 40"});
  points_error(npy_bytes(f8, six + "x"), {"needs 48 bytes", "has 49"});
  points_error(npy_bytes("{'descr': '<f8', 'fortran_order': False, 'shape': (6,), }", six),
               {"1 dimensions", "2-d array"});
  points_error(npy_bytes("{'descr': '<i8', 'fortran_order': False, 'shape': (2, 3), }", six),
               {"'<i8'", "floating-point"});
  points_error(npy_bytes("{'descr': '<c16', 'fortran_order': False, 'shape': (1, 3), }", six),
               {"descr '<c16' is not supported"});
  points_error(npy_bytes("{'descr': '<f8', 'shape': (2, 3), }", six), {"lacks 'fortran_order'"});
  points_error(npy_bytes("{'descr': '<f8', 'fortran_order': False, 'shape': (99999999999, "
                         "99999999999), }",
                         six),
               {"needs more bytes of data"});
  points_error(npy_bytes(f8, six, 4), {"format version 4.0"});
  expect_invalid_argument(
      [&] {
        io_detail::parse_npy_triangles(
            npy_bytes("{'descr': '<i8', 'fortran_order': False, 'shape': (1, 3), }",
                      raw_bytes<std::int64_t>({0, 1, 7})),
            "t.npy", 5);
      },
      {"NumPy file 't.npy'", "triangle 0 has vertex index 7", "5 vertices"});
  expect_invalid_argument(
      [&] {
        io_detail::parse_npy_triangles(
            npy_bytes("{'descr': '<i4', 'fortran_order': False, 'shape': (1, 3), }",
                      raw_bytes<std::int32_t>({0, -1, 2})),
            "t.npy", 5);
      },
      {"vertex index -1"});
  expect_invalid_argument([&] { io_detail::parse_npy_triangles(npy_bytes(f8, six), "t.npy", 5); },
                          {"the triangles are of type '<f8'"});
  // States without their triangles.
  const std::string lonely = test_path("lonely.npy");
  write_npy(lonely, Eigen::MatrixXd::Zero(3, 4));
  expect_invalid_argument([&] { read_states_npy(lonely); },
                          {"lonely.triangles.npy", "does not exist"});
}

TEST(NpyRead, EveryTruncationAndByteChangeIsReadOrRefused) {
  const TriangleMesh mesh = random_mesh(3, 4, 2);
  const std::string path = test_path("small.npy");
  write_states_npy(path, mesh);
  const std::string points = file_text(path);
  const std::string triangles = file_text(triangles_npy_path(path));
  for (const std::string* file : {&points, &triangles}) {
    const auto parse = [&](const std::string& bytes) {
      try {
        if (file == &points) {
          io_detail::parse_npy_points(bytes, "s.npy");
        } else {
          io_detail::parse_npy_triangles(bytes, "t.npy", 4);
        }
      } catch (const InvalidArgument&) {
      }
    };
    for (std::size_t length = 0; length < file->size(); ++length) {
      expect_invalid_argument(
          [&] {
            if (file == &points) {
              io_detail::parse_npy_points(file->substr(0, length), "s.npy");
            } else {
              io_detail::parse_npy_triangles(file->substr(0, length), "t.npy", 4);
            }
          },
          {"NumPy file"});
    }
    for (std::size_t k = 0; k < file->size(); ++k) {
      for (const int value :
           {0, 1, 0x7f, 0x80, 0xff, int{'('}, int{')'}, int{','}, int{'\''}, int{'9'}}) {
        std::string changed = *file;
        changed[k] = static_cast<char>(value);
        parse(changed);  // a mesh or InvalidArgument, never a crash (the sanitizer build checks)
      }
    }
  }
}

}  // namespace
}  // namespace tessera
