// SPDX-License-Identifier: MIT
// `tessera check` reads every format `tessera mesh` writes, for surfaces in R^3 and in R^4.
#include <gtest/gtest.h>

#include "io/io_test_support.h"
#include "tessera/io/mesh_io.h"

namespace tessera {
namespace {

using namespace io_test;
using testing::run_cli;

class CheckReadsWhatMeshWrites : public ::testing::TestWithParam<std::string> {};

TEST_P(CheckReadsWhatMeshWrites, TorusAndCstr) {
  const std::string extension = GetParam();
  for (const std::string problem : {"torus", "cstr"}) {
    const std::string path = test_path("cli_" + problem + extension);
    const auto mesh = run_cli("mesh " + problem + " -q -o '" + path + "'");
    ASSERT_EQ(mesh.exit_code, 0) << mesh.output;
    const auto check = run_cli("check '" + path + "' --problem " + problem);
    EXPECT_EQ(check.exit_code, 0) << check.output;
    // The file holds the whole point in R^n (n = 4 for cstr), not only the three shown.
    const int n = problem == "cstr" ? 4 : 3;
    EXPECT_EQ(read_mesh(path).ambient_dimension(), extension == ".obj" ? 3 : n) << path;
    EXPECT_NE(check.output.find("n = " + std::to_string(n)), std::string::npos) << check.output;
  }
}

TEST(CheckCommand, MalformedVtuIsAUsageErrorNamingFileAndLine) {
  const std::string path = test_path("cli_broken.vtu");
  ASSERT_EQ(run_cli("mesh torus -q -o '" + path + "'").exit_code, 0);
  std::string text = file_text(path);
  text.replace(text.find("</Points>"), 9, "</Point>");
  write_text(path, text);
  const auto check = run_cli("check '" + path + "' --problem torus");
  EXPECT_EQ(check.exit_code, 2) << check.output;
  EXPECT_NE(check.output.find("VTU file '" + path + "', line "), std::string::npos) << check.output;
  EXPECT_NE(check.output.find("'</Point>' does not match '<Points>'"), std::string::npos)
      << check.output;
}

INSTANTIATE_TEST_SUITE_P(Formats, CheckReadsWhatMeshWrites,
                         ::testing::Values(".vtu", ".vtk", ".ply"),
                         [](const auto& info) { return info.param.substr(1); });

}  // namespace
}  // namespace tessera
