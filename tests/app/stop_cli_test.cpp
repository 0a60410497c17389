// SPDX-License-Identifier: MIT
// A batch system's stop (SIGTERM, then SIGKILL after a grace period) in every stage of a real
// `tessera mesh` run: the valid partial mesh and the summary are written, and the summary says
// that the run was stopped and in which stage (docs/stopping.md). Each run is told apart by
// its own progress lines (--progress), not by a pause planted for the test; how fast the files
// come is measured in bench/stop_latency.sh, not asserted here.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/test_support.h"

namespace tessera {
namespace {

struct StoppedRun {
  bool exited = false;   ///< ended by exit(), not by a signal
  int exit_code = -1;    ///< when `exited`
  int end_signal = 0;    ///< the signal that ended it, when not `exited`
  std::string progress;  ///< its stderr
  std::string mesh;      ///< the mesh file's path
  std::string summary;   ///< the summary file's path
};

// Runs `tessera mesh ARGUMENTS --progress -o … --summary …`, waits until its stderr has a line
// that matches `stage_line` (e.g. "tessera: clip: " at the start of the clipping), then sends
// the `signals` one after another, 20 ms apart, and waits for the process to end.
StoppedRun stop_when(const std::vector<std::string>& arguments, const std::string& stage_line,
                     const std::vector<int>& signals, const std::string& name) {
  const std::string folder = testing::temporary_directory("stop_" + name);
  StoppedRun run;
  run.mesh = folder + "/mesh.ply";
  run.summary = folder + "/summary.json";
  const std::string progress_file = folder + "/progress.txt";
  std::vector<std::string> words = {TESSERA_CLI, "mesh"};
  words.insert(words.end(), arguments.begin(), arguments.end());
  for (const char* word : {"--progress", "-o"}) {
    words.emplace_back(word);
  }
  words.push_back(run.mesh);
  words.emplace_back("--summary");
  words.push_back(run.summary);
  const pid_t child = testing::spawn(words, progress_file);
  const std::regex line(stage_line);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  int status = 0;
  bool ended = false;
  while (!std::regex_search(testing::read_file_bytes(progress_file), line)) {
    if (waitpid(child, &status, WNOHANG) == child) {
      ended = true;
      break;
    }
    if (std::chrono::steady_clock::now() > deadline) {
      kill(child, SIGKILL);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (!ended) {
    for (const int signal : signals) {
      kill(child, signal);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    waitpid(child, &status, 0);
  }
  run.progress = testing::read_file_bytes(progress_file);
  EXPECT_FALSE(ended) << "the run ended before a line matched '" << stage_line << "':\n"
                      << run.progress;
  run.exited = WIFEXITED(status);
  run.exit_code = run.exited ? WEXITSTATUS(status) : -1;
  run.end_signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  return run;
}

// The files of a stopped run: a mesh valid by `tessera check` (the whole geometric check, not
// cut short), and a summary that names the stop, its stage and agrees with the mesh.
nlohmann::json expect_files_of_stopped_run(const StoppedRun& run, const std::string& stage) {
  EXPECT_TRUE(std::filesystem::exists(run.mesh)) << run.progress;
  EXPECT_TRUE(std::filesystem::exists(run.summary)) << run.progress;
  if (!std::filesystem::exists(run.summary) || !std::filesystem::exists(run.mesh)) {
    return {};
  }
  // Replaced by a rename: no temporary is left beside them.
  for (const auto& entry :
       std::filesystem::directory_iterator(std::filesystem::path(run.mesh).parent_path())) {
    const std::string file = entry.path().filename().string();
    EXPECT_TRUE(file == "mesh.ply" || file == "summary.json" || file == "progress.txt") << file;
  }
  const nlohmann::json summary = nlohmann::json::parse(testing::read_file_bytes(run.summary));
  EXPECT_TRUE(summary.contains("stop")) << summary.dump(1);
  if (!summary.contains("stop")) {
    return summary;
  }
  EXPECT_EQ(summary["stop"]["signal"], "SIGTERM");
  EXPECT_EQ(summary["stop"]["stage"], stage) << run.progress;
  EXPECT_TRUE(summary["valid"].get<bool>()) << summary["defects"].dump(1);
  // Its JSON only: a partial mesh may fail the problem's expected topology (a clipping cut
  // short leaves pieces), which `check` reports on stderr; valid it must be.
  const testing::CommandResult check = testing::run_shell(
      "{ " + std::string(TESSERA_CLI) + " check --json " + run.mesh + " 2>/dev/null; }");
  const auto at = check.output.find('{');
  EXPECT_NE(at, std::string::npos) << check.output;
  if (at != std::string::npos) {
    const nlohmann::json checked = nlohmann::json::parse(check.output.substr(at));
    EXPECT_TRUE(checked["valid"].get<bool>()) << check.output;
    EXPECT_TRUE(checked["geometry"]["checked"].get<bool>());
    EXPECT_TRUE(checked["geometry"]["cut_short"].empty());
    EXPECT_EQ(checked["counts"]["vertices"], summary["counts"]["vertices"]);
    EXPECT_EQ(checked["counts"]["triangles"], summary["counts"]["triangles"]);
  }
  return summary;
}

// bvp:points=1000 (n = 1002) with the atlas: about 4 s of build, then clipping, tolerance
// check and validation of about 1 s each on this 2-core machine, and a report of 1 s. All
// coordinates are written, so that `tessera check` can check the mesh on M.
const std::vector<std::string> kRun = {"bvp:points=1000", "--view", "all"};

TEST(CliStop, InTheBuildKeepsThePartialMeshAndSaysSo) {
  const StoppedRun run = stop_when(kRun, "tessera: build: ", {SIGTERM}, "build");
  EXPECT_TRUE(run.exited);
  EXPECT_EQ(run.exit_code, 1) << run.progress;  // the covering was interrupted
  const nlohmann::json summary = expect_files_of_stopped_run(run, "build");
  EXPECT_EQ(summary["run"]["termination"], "interrupted");
  EXPECT_NE(summary["stop"]["left_out"].dump().find("distances to M: not measured"),
            std::string::npos)
      << summary["stop"].dump();
}

TEST(CliStop, InTheClippingKeepsTheMeshInsideTheDomain) {
  const StoppedRun run = stop_when(kRun, "tessera: clip: ", {SIGTERM}, "clip");
  EXPECT_EQ(run.exit_code, 1) << run.progress;
  const nlohmann::json summary = expect_files_of_stopped_run(run, "clip");
  EXPECT_EQ(summary["run"]["termination"], "interrupted");
  EXPECT_NE(summary["run"]["message"].get<std::string>().find("clipping"), std::string::npos)
      << summary["run"]["message"];
  EXPECT_EQ(summary["geometry"]["vertices_outside_domain"]["count"], 0);
}

TEST(CliStop, InTheToleranceCheckSaysTheToleranceIsNotEnforced) {
  const StoppedRun run = stop_when(kRun, "tessera: refine: ", {SIGTERM}, "refine");
  EXPECT_EQ(run.exit_code, 1) << run.progress;
  const nlohmann::json summary = expect_files_of_stopped_run(run, "refine");
  EXPECT_EQ(summary["run"]["termination"], "interrupted");
  EXPECT_EQ(summary["run"]["max_sampled_distance"], -1.0);  // no bound for the whole mesh
}

// The validation goes on for its grace (2 s) after the stop: here it finishes, and the mesh is
// the whole covering, complete; only the report's measurement is left out (exit 0). Had it been
// cut short, the run would be interrupted and geometry.cut_short would say what was not judged.
TEST(CliStop, InTheValidationFinishesOrSaysWhatWasNotJudged) {
  const StoppedRun run = stop_when(kRun, "tessera: validate: ", {SIGTERM}, "validate");
  const nlohmann::json summary = expect_files_of_stopped_run(run, "validate");
  const bool cut_short = !summary["geometry"]["cut_short"].empty();
  EXPECT_EQ(summary["run"]["termination"], cut_short ? "interrupted" : "completed");
  EXPECT_EQ(run.exit_code, cut_short ? 1 : 0) << run.progress;
}

TEST(CliStop, InTheReportEndsTheMeasurementWithWhatItHas) {
  const StoppedRun run = stop_when(kRun, "tessera: report: ", {SIGTERM}, "report");
  EXPECT_EQ(run.exit_code, 0) << run.progress;  // the covering is complete and valid
  const nlohmann::json summary = expect_files_of_stopped_run(run, "report");
  EXPECT_EQ(summary["run"]["termination"], "completed");
  const auto& centroids = summary["distance_to_manifold"]["centroids"];
  EXPECT_LE(centroids["count"].get<int>(), centroids["population"].get<int>());
}

// The front on the same problem, stopped after about 4000 vertices: writing its files takes
// most of a second (the final check of the partial mesh), long after a batch system's second
// signal 20 ms later. That one no longer kills the run before its files are written ...
const std::vector<std::string> kFrontRun = {"bvp:points=1000", "--method", "front", "--view",
                                            "all"};
const std::string kFrontBuilt = "tessera: build: [4-9][0-9]{3} vertices";

TEST(CliStop, ASecondSignalIsCountedAndTheFilesAreStillWritten) {
  const StoppedRun run = stop_when(kFrontRun, kFrontBuilt, {SIGTERM, SIGTERM}, "second");
  EXPECT_TRUE(run.exited) << "ended by signal " << run.end_signal << "\n" << run.progress;
  EXPECT_EQ(run.exit_code, 1) << run.progress;
  const nlohmann::json summary = expect_files_of_stopped_run(run, "build");
  EXPECT_EQ(summary["stop"]["signals"], 2);
  EXPECT_NE(run.progress.find("a third signal ends the process"), std::string::npos)
      << run.progress;
}

// ... and a third one ends the process at once, as the default action of the signal would.
TEST(CliStop, AThirdSignalEndsTheProcessAtOnce) {
  const StoppedRun run = stop_when(kFrontRun, kFrontBuilt, {SIGTERM, SIGINT, SIGTERM}, "third");
  EXPECT_FALSE(run.exited) << "exit " << run.exit_code << "\n" << run.progress;
  EXPECT_EQ(run.end_signal, SIGTERM);
}

}  // namespace
}  // namespace tessera
