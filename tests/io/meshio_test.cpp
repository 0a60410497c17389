// SPDX-License-Identifier: MIT
// Files other tools can read: meshio (Debian's python3-meshio) opens tessera's PLY files for
// n = 3, 4, 6 and finds every coordinate, bit for bit: x, y, z as its points, the coordinates
// beyond the third as point data. Fails, not skips, when meshio is missing: it is a dependency
// of the test suite (scripts/install-dependencies.sh).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "io/io_test_support.h"
#include "tessera/io/ply.h"

namespace tessera {
namespace {

using namespace io_test;

// The first of $TESSERA_PYTHON, /usr/bin/python3 and python3 that can import meshio (a python3
// of pyenv or a virtualenv may not see Debian's packages), or "" if none can.
std::string python_with_meshio() {
  std::vector<std::string> candidates;
  if (const char* configured = std::getenv("TESSERA_PYTHON")) {
    candidates.emplace_back(configured);
  }
  candidates.insert(candidates.end(), {"/usr/bin/python3", "python3"});
  for (const auto& python : candidates) {
    if (std::system((python + " -c 'import meshio' >/dev/null 2>&1").c_str()) == 0) {
      return python;
    }
  }
  return "";
}

// What meshio reads: one line "<points rows> <points columns> <triangles>", one line with the
// sorted point-data names, then per vertex its points row and the point data `extra` (in that
// order) as Python's shortest round-trip repr, then the triangles.
std::string read_with_meshio(const std::string& python, const std::string& path,
                             const std::vector<std::string>& extra) {
  const std::string script = test_path("read_with_meshio.py");
  write_text(script,
             "import sys, meshio\n"
             "m = meshio.read(sys.argv[1])\n"
             "extra = sys.argv[2:]\n"
             "triangles = m.cells_dict.get('triangle', [])\n"
             "print(m.points.shape[0], m.points.shape[1], len(triangles))\n"
             "print(' '.join(sorted(m.point_data.keys())))\n"
             "for v in range(m.points.shape[0]):\n"
             "    values = list(m.points[v]) + [m.point_data[name][v] for name in extra]\n"
             "    print(' '.join(repr(float(x)) for x in values))\n"
             "for t in triangles:\n"
             "    print(*t)\n");
  std::string command = python + " '" + script + "' '" + path + "'";
  for (const auto& name : extra) {
    command += " " + name;
  }
  command += " 2>&1";
  std::string output;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[4096];
    std::size_t count = 0;
    while ((count = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) {
      output.append(buffer, count);
    }
    const int status = pclose(pipe);
    EXPECT_EQ(status, 0) << command << "\n" << output;
  }
  return output;
}

class MeshioReadsPly : public ::testing::TestWithParam<std::tuple<int, bool>> {};

TEST_P(MeshioReadsPly, AllCoordinatesBitForBit) {
  const auto [n, binary] = GetParam();
  const std::string python = python_with_meshio();
  ASSERT_FALSE(python.empty())
      << "meshio is not installed: run scripts/install-dependencies.sh (python3-meshio)";
  // Moderate values: meshio's ASCII reader parses with NumPy, exact for every double, but the
  // bit patterns of random_mesh include subnormals whose repr we do not want to depend on.
  auto mesh = random_mesh(n, 60, 80, 5);
  Eigen::MatrixXd points = mesh.points();
  for (Eigen::Index i = 0; i < points.size(); ++i) {
    points.data()[i] = std::sin(1.0 + static_cast<double>(i)) * 3.0;
  }
  mesh = TriangleMesh(points, mesh.triangles());
  const std::string path = test_path("meshio_" + std::to_string(n) + (binary ? "b" : "a") + ".ply");
  write_ply(path, mesh,
            {.binary = binary, .vertex_scalars = {{"residual", std::vector<double>(60, 0.5)}}});
  std::vector<std::string> extra;
  for (int k = 3; k < n; ++k) {
    extra.push_back("x" + std::to_string(k));
  }
  std::istringstream in(read_with_meshio(python, path, extra));
  int rows = 0, columns = 0, triangles = 0;
  in >> rows >> columns >> triangles;
  ASSERT_EQ(rows, 60) << in.str();
  EXPECT_EQ(columns, 3);
  EXPECT_EQ(triangles, 80);
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  std::vector<std::string> expected_names = extra;
  expected_names.push_back("residual");
  std::sort(expected_names.begin(), expected_names.end());
  std::string joined;
  for (const auto& name : expected_names) {
    joined += (joined.empty() ? "" : " ") + name;
  }
  EXPECT_EQ(line, joined);
  for (int v = 0; v < 60; ++v) {
    const auto values = read_numbers(in, n);
    for (int k = 0; k < n; ++k) {
      ASSERT_EQ(std::bit_cast<std::uint64_t>(values[static_cast<std::size_t>(k)]),
                std::bit_cast<std::uint64_t>(mesh.point(v)(k)))
          << "vertex " << v << " coordinate " << k;
    }
  }
  for (int t = 0; t < 80; ++t) {
    Triangle triangle{};
    in >> triangle[0] >> triangle[1] >> triangle[2];
    ASSERT_EQ(triangle, mesh.triangle(t)) << "triangle " << t;
  }
}

INSTANTIATE_TEST_SUITE_P(DimensionAndEncoding, MeshioReadsPly,
                         ::testing::Combine(::testing::Values(3, 4, 6),
                                            ::testing::Values(true, false)));

}  // namespace
}  // namespace tessera
