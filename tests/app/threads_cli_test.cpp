// SPDX-License-Identifier: MIT
// `tessera mesh --threads N`: the mesh file and the summary are the same bytes whatever N
// (docs/threads.md), but for the times, the sampled memory and the thread count itself.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>
#include <string>

#include "support/test_support.h"

namespace tessera {
namespace {

using testing::run_cli;

std::string work_path(const std::string& file_name) {
  static const std::string directory = testing::temporary_directory("threads_cli");
  return directory + "/" + file_name;
}

std::string file_content(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream content;
  content << in.rdbuf();
  return content.str();
}

// The summary without what differs between two runs of one command: wall times (and ratios of
// them), the sampled memory and the threads.
nlohmann::json without_how_it_ran(const nlohmann::json& value) {
  if (value.is_object()) {
    nlohmann::json kept = nlohmann::json::object();
    for (const auto& [key, item] : value.items()) {
      if (key.find("seconds") == std::string::npos && key.find("worth") == std::string::npos &&
          key != "memory" && key != "threads") {
        kept[key] = without_how_it_ran(item);
      }
    }
    return kept;
  }
  if (value.is_array()) {
    nlohmann::json kept = nlohmann::json::array();
    for (const auto& item : value) {
      kept.push_back(without_how_it_ran(item));
    }
    return kept;
  }
  return value;
}

struct Case {
  std::string name;
  std::string arguments;  // the problem and its options
};

// Named in the test's output, not as bytes.
void PrintTo(const Case& c, std::ostream* out) { *out << c.name; }

class SameOutputWhateverTheThreads : public ::testing::TestWithParam<Case> {};

TEST_P(SameOutputWhateverTheThreads, MeshAndSummary) {
  const Case& c = GetParam();
  std::string mesh_of_one;
  nlohmann::json summary_of_one;
  for (int threads : {1, 2, 3}) {
    const std::string stem = work_path(c.name + "_" + std::to_string(threads));
    const auto run = run_cli("mesh " + c.arguments + " --threads " + std::to_string(threads) +
                             " -q -o " + stem + ".ply --summary " + stem + ".json");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const std::string mesh = file_content(stem + ".ply");
    const auto summary = nlohmann::json::parse(file_content(stem + ".json"));
    ASSERT_TRUE(summary["valid"].get<bool>()) << c.name;
    if (threads == 1) {
      mesh_of_one = mesh;
      summary_of_one = without_how_it_ran(summary);
      EXPECT_EQ(summary["run"]["threads"], 1);
      continue;
    }
    EXPECT_EQ(mesh, mesh_of_one) << c.name << ": the mesh on " << threads << " threads";
    EXPECT_EQ(without_how_it_ran(summary), summary_of_one)
        << c.name << ": the summary on " << threads << " threads";
  }
}

// Catalogue surfaces and a problem file, every method; a box (clipping, boundary gaps in the
// tolerance check) and a sparse problem (bvp: one thread whatever is asked).
INSTANTIATE_TEST_SUITE_P(
    Threads, SameOutputWhateverTheThreads,
    ::testing::Values(
        Case{"atlas_torus", "torus --tolerance 0.003"},
        Case{"front_sphere", "sphere --method front --tolerance 0.005"},
        Case{"bezier_sphere", "sphere --method bezier --tolerance 0.005"},
        Case{"atlas_equipotential_box", "equipotential --tolerance 0.004 --box -2,2,-2,2,0,2"},
        Case{"front_cstr", "cstr --method front --tolerance 0.01"},
        Case{"atlas_problem_file", "'" + testing::source_path("examples/problems/sphere_cut.tsr") +
                                       "' --tolerance 0.005"},
        Case{"atlas_bvp", "bvp:points=16 --tolerance 0.05"}),
    [](const ::testing::TestParamInfo<Case>& info) { return info.param.name; });

TEST(ThreadsOption, SummaryAndWorkLineSayHowManyThreads) {
  const std::string stem = work_path("count");
  const auto run = run_cli("mesh sphere --tolerance 0.01 --threads 2 -o " + stem +
                           ".ply --summary " + stem + ".json");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find(" s on 2 threads, "), std::string::npos) << run.output;
  const auto summary = nlohmann::json::parse(file_content(stem + ".json"));
  EXPECT_EQ(summary["run"]["threads"], 2);
  // A sparse problem runs on one thread (docs/threads.md) and says so.
  const auto sparse = run_cli("mesh bvp:points=16 --tolerance 0.05 --threads 2 -o " + stem +
                              "_bvp.ply --summary " + stem + "_bvp.json");
  ASSERT_EQ(sparse.exit_code, 0) << sparse.output;
  EXPECT_EQ(nlohmann::json::parse(file_content(stem + "_bvp.json"))["run"]["threads"], 1);
  EXPECT_EQ(run_cli("mesh sphere --threads 0 -o " + stem + ".ply").exit_code, 2);
}

}  // namespace
}  // namespace tessera
