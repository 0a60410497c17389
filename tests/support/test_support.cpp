// SPDX-License-Identifier: MIT
#include "support/test_support.h"

#include <fcntl.h>
#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>

#include "tessera/geometry/triangle_mesh.h"

namespace tessera::testing {

int spawn(std::vector<std::string> words, const std::string& stderr_path,
          const std::string& stdout_path) {
  const pid_t child = fork();
  if (child == 0) {
    const int null = open("/dev/null", O_RDWR);
    const int err = open(stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int out = stdout_path.empty()         ? null
                    : stdout_path == stderr_path ? err
                                                 : open(stdout_path.c_str(),
                                                        O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(null, STDIN_FILENO);
    dup2(out, STDOUT_FILENO);
    dup2(err, STDERR_FILENO);
    std::vector<char*> argv;
    for (std::string& word : words) {
      argv.push_back(word.data());
    }
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  return child;
}

std::string read_file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

void expect_identical_meshes(const TriangleMesh& a, const TriangleMesh& b, const std::string& what) {
  ASSERT_EQ(a.vertex_count(), b.vertex_count()) << what;
  ASSERT_EQ(a.triangle_count(), b.triangle_count()) << what;
  ASSERT_EQ(a.points().rows(), b.points().rows()) << what;
  int differing = 0;
  for (Eigen::Index k = 0; k < a.points().size(); ++k) {
    differing += std::bit_cast<std::uint64_t>(a.points().data()[k]) !=
                 std::bit_cast<std::uint64_t>(b.points().data()[k]);
  }
  EXPECT_EQ(differing, 0) << what << ": coordinates that differ in their bits";
  EXPECT_TRUE(a.triangles() == b.triangles()) << what << ": the triangles differ";
}

CommandResult run_cli(const std::string& arguments) {
  return run_shell(std::string(TESSERA_CLI) + " " + arguments);
}

CommandResult run_shell(const std::string& command_line) {
  const std::string command = command_line + " 2>&1 </dev/null";
  CommandResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) {
    throw std::runtime_error("cannot run " + command);
  }
  std::array<char, 4096> buffer{};
  std::size_t count = 0;
  while ((count = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) {
    result.output.append(buffer.data(), count);
  }
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  // In a sanitizer build (scripts/run-sanitizer-tests.sh) a report from the child fails the
  // calling test whatever exit code that test expects: a test of a failing run expects exit 1,
  // which is also what a sanitizer may exit with.
  if (result.output.find("Sanitizer:") != std::string::npos ||
      result.output.find("runtime error:") != std::string::npos) {
    ADD_FAILURE() << "sanitizer report from: " << command << "\n" << result.output;
  }
  return result;
}

std::string temporary_directory(const std::string& name) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("tessera_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(path);
  std::filesystem::create_directories(path);
  return path.string();
}

double observed_order(const std::vector<double>& h, const std::vector<double>& error) {
  if (h.size() != error.size() || h.size() < 2) {
    throw std::invalid_argument("observed_order needs at least two (h, error) pairs");
  }
  double mean_x = 0;
  double mean_y = 0;
  const double count = static_cast<double>(h.size());
  for (std::size_t i = 0; i < h.size(); ++i) {
    mean_x += std::log(h[i]) / count;
    mean_y += std::log(error[i]) / count;
  }
  double sxy = 0;
  double sxx = 0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double dx = std::log(h[i]) - mean_x;
    sxy += dx * (std::log(error[i]) - mean_y);
    sxx += dx * dx;
  }
  return sxy / sxx;
}

std::string source_path(const std::string& relative) {
  return std::string(TESSERA_SOURCE_DIR) + "/" + relative;
}

}  // namespace tessera::testing
