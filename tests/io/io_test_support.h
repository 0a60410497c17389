// SPDX-License-Identifier: MIT
// Shared by the io tests: test meshes, temporary files, and checks on files and exceptions.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "support/test_support.h"
#include "tessera/core/error.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera::io_test {

inline std::string test_path(const std::string& file_name) {
  static const std::string directory = testing::temporary_directory("mesh_io");
  return directory + "/" + file_name;
}

inline std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream content;
  content << in.rdbuf();
  return content.str();
}

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Random doubles drawn as random bit patterns (every exponent, subnormals, both zeros), plus
// values whose decimal forms are known to be hard (0.1, 1/3, extremes). Non-finite values are
// skipped: ASCII keeps "nan" but not its payload.
inline TriangleMesh random_mesh(int n, int vertex_count, int triangle_count, unsigned seed = 7) {
  std::mt19937_64 random(seed);
  const double special[] = {0.0,
                            -0.0,
                            0.1,
                            1.0 / 3.0,
                            std::numeric_limits<double>::max(),
                            std::numeric_limits<double>::denorm_min(),
                            std::numeric_limits<double>::min(),
                            -2.2250738585072014e-308};
  Eigen::MatrixXd points(n, vertex_count);
  for (Eigen::Index i = 0; i < points.size(); ++i) {
    double value = 0;
    do {
      value = std::bit_cast<double>(random());
    } while (!std::isfinite(value));
    points.data()[i] = i < static_cast<Eigen::Index>(std::size(special)) ? special[i] : value;
  }
  std::vector<Triangle> triangles;
  std::uniform_int_distribution<int> vertex(0, vertex_count - 1);
  for (int t = 0; t < triangle_count; ++t) {
    triangles.push_back({vertex(random), vertex(random), vertex(random)});
  }
  return TriangleMesh(points, triangles);
}

// Two squares sharing an edge, in R^3: a small mesh whose numbers are easy to read in a file.
inline TriangleMesh two_triangles() {
  Eigen::MatrixXd points(3, 4);
  points << 0, 1, 1, 0,  //
      0, 0, 1, 1,        //
      0, 0, 0, 0.5;
  return TriangleMesh(points, {{0, 1, 2}, {0, 2, 3}});
}

// Bit-for-bit equality of coordinates (so -0.0 differs from 0.0) and equal triangles.
inline void expect_identical(const TriangleMesh& expected, const TriangleMesh& actual) {
  ASSERT_EQ(actual.ambient_dimension(), expected.ambient_dimension());
  ASSERT_EQ(actual.vertex_count(), expected.vertex_count());
  const auto bytes = sizeof(double) * static_cast<std::size_t>(expected.points().size());
  EXPECT_EQ(std::memcmp(actual.points().data(), expected.points().data(), bytes), 0);
  for (Eigen::Index i = 0; i < expected.points().size(); ++i) {
    if (std::bit_cast<std::uint64_t>(actual.points().data()[i]) !=
        std::bit_cast<std::uint64_t>(expected.points().data()[i])) {
      ADD_FAILURE() << "coordinate " << i << ": wrote " << expected.points().data()[i] << ", read "
                    << actual.points().data()[i];
      break;
    }
  }
  EXPECT_EQ(actual.triangles(), expected.triangles());
}

// Runs `action`, expects InvalidArgument, and that its message contains every one of `parts`.
inline void expect_invalid_argument(const std::function<void()>& action,
                                    const std::vector<std::string>& parts) {
  try {
    action();
    ADD_FAILURE() << "no exception; expected one mentioning '" << parts.front() << "'";
  } catch (const InvalidArgument& error) {
    const std::string message = error.what();
    for (const auto& part : parts) {
      EXPECT_NE(message.find(part), std::string::npos)
          << "message lacks '" << part << "': " << message;
    }
  }
}

inline int count_occurrences(const std::string& text, const std::string& pattern) {
  int count = 0;
  for (auto at = text.find(pattern); at != std::string::npos; at = text.find(pattern, at + 1)) {
    ++count;
  }
  return count;
}

// Whole-token parse, correctly rounded (as the writers' std::to_chars output requires).
inline bool parse_number(const std::string& token, double& value) {
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  return error == std::errc() && end == token.data() + token.size() && !token.empty();
}

// Reads `count` numbers from `in` and returns them.
inline std::vector<double> read_numbers(std::istream& in, int count) {
  std::vector<double> values(static_cast<std::size_t>(count));
  for (auto& value : values) {
    std::string token;
    in >> token;
    EXPECT_TRUE(parse_number(token, value)) << "'" << token << "'";
  }
  return values;
}

}  // namespace tessera::io_test
