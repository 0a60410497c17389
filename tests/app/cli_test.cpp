// SPDX-License-Identifier: MIT
// The command line as a user meets it: `tessera problems`, `tessera mesh`, `tessera check`.
// Exit codes are part of the interface: 0 success, 1 a computation failed, 2 a usage error; a
// message always names what is wrong, and no input makes the tool crash.
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "support/test_support.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/io/mesh_io.h"
#include "tessera/methods/front/advancing_front.h"
#include "tessera/problems/catalogue.h"

namespace tessera {
namespace {

using testing::CommandResult;
using testing::run_cli;

constexpr int kSuccess = 0;
constexpr int kComputationFailed = 1;
constexpr int kUsageError = 2;

// Vertices end where the corrector stopped, at ‖F‖ ≤ CorrectorOptions::residual_tolerance = 1e-9;
// a factor 10 covers rounding in F.
constexpr double kOnManifoldTolerance = 1e-8;

std::string work_path(const std::string& file_name) {
  static const std::string directory = testing::temporary_directory("cli");
  return directory + "/" + file_name;
}

// Single quotes for the shell; paths of the temporary directory contain none.
std::string quoted(const std::string& text) { return "'" + text + "'"; }

std::string file_content(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream content;
  content << in.rdbuf();
  return content.str();
}

std::string write_problem_file(const std::string& file_name, const std::string& text) {
  const std::string path = work_path(file_name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

bool contains(const std::string& text, const std::string& fragment) {
  return text.find(fragment) != std::string::npos;
}

// The tool ran to an orderly end with `exit_code` (not a signal: run_cli reports those as −1),
// and said something containing every fragment.
void expect_exit(const CommandResult& result, int exit_code,
                 const std::vector<std::string>& fragments) {
  EXPECT_EQ(result.exit_code, exit_code) << result.output;
  for (const std::string& fragment : fragments) {
    EXPECT_TRUE(contains(result.output, fragment))
        << "the message does not name '" << fragment << "':\n"
        << result.output;
  }
}

// --- tessera problems ----------------------------------------------------------------------

TEST(CliProblems, ListsEveryCatalogueEntryInOrder) {
  const CommandResult result = run_cli("problems");
  ASSERT_EQ(result.exit_code, kSuccess) << result.output;
  // One line per entry, "NAME  summary", then a blank line and usage hints.
  std::vector<std::string> listed;
  std::istringstream lines(result.output);
  std::string line;
  while (std::getline(lines, line) && !line.empty()) {
    listed.push_back(line.substr(0, line.find(' ')));
  }
  std::vector<std::string> names;
  for (const CatalogueEntry& entry : catalogue()) {
    names.push_back(entry.name);
  }
  EXPECT_EQ(listed, names) << result.output;
}

// --- tessera mesh, and tessera check of its output ------------------------------------------

class CliMeshSphereCut : public ::testing::Test {
 protected:
  // One run serves every test of the suite.
  static void SetUpTestSuite() {
    result_ = run_cli("mesh sphere_cut --method front -o " + quoted(work_path("cut.ply")) +
                      " --summary " + quoted(work_path("cut.json")));
  }
  static void TearDownTestSuite() { result_.reset(); }
  static inline std::optional<CommandResult> result_;
};

TEST_F(CliMeshSphereCut, WritesAMeshThatReadsBackValid) {
  ASSERT_EQ(result_->exit_code, kSuccess) << result_->output;
  const TriangleMesh mesh = read_mesh(work_path("cut.ply"));
  EXPECT_EQ(mesh.ambient_dimension(), 3);
  const MeshValidation validation = validate(mesh);
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  EXPECT_EQ(validation.euler_characteristic, 1);  // a spherical cap is a disk
}

TEST_F(CliMeshSphereCut, WritesExactlyWhatTheLibraryComputes) {
  ASSERT_EQ(result_->exit_code, kSuccess) << result_->output;
  // The CLI is thin over the library: with the problem's suggested step and default options the
  // binary PLY must hold the library's mesh bit for bit.
  const ProblemSetup setup = make_catalogue_problem("sphere_cut");
  FrontOptions options;
  options.step = setup.suggested_step;
  const CoveringResult expected =
      triangulate_by_front(*setup.problem, setup.start, setup.domain, options);
  const TriangleMesh mesh = read_mesh(work_path("cut.ply"));
  ASSERT_EQ(mesh.vertex_count(), expected.mesh.vertex_count());
  EXPECT_TRUE(mesh.points() == expected.mesh.points());
  EXPECT_TRUE(mesh.triangles() == expected.mesh.triangles());
}

TEST_F(CliMeshSphereCut, SummaryJsonDescribesTheMesh) {
  ASSERT_EQ(result_->exit_code, kSuccess) << result_->output;
  const TriangleMesh mesh = read_mesh(work_path("cut.ply"));
  const MeshValidation validation = validate(mesh);
  const auto summary = nlohmann::json::parse(file_content(work_path("cut.json")));
  EXPECT_EQ(summary.at("counts").at("vertices").get<int>(), mesh.vertex_count());
  EXPECT_EQ(summary.at("counts").at("triangles").get<int>(), mesh.triangle_count());
  EXPECT_EQ(summary.at("counts").at("edges").get<int>(), validation.edge_count);
  EXPECT_EQ(summary.at("topology").at("euler_characteristic").get<int>(), 1);
  EXPECT_TRUE(summary.at("valid").get<bool>());
  EXPECT_TRUE(summary.at("run").at("completed").get<bool>());
  EXPECT_LT(summary.at("distance_to_manifold").at("vertex_residual_F").at("max").get<double>(),
            kOnManifoldTolerance);
}

TEST_F(CliMeshSphereCut, CheckReportsTheSameCounts) {
  ASSERT_EQ(result_->exit_code, kSuccess) << result_->output;
  const CommandResult check =
      run_cli("check " + quoted(work_path("cut.ply")) + " --problem sphere_cut --json");
  ASSERT_EQ(check.exit_code, kSuccess) << check.output;
  const auto report = nlohmann::json::parse(check.output);
  const auto summary = nlohmann::json::parse(file_content(work_path("cut.json")));
  EXPECT_EQ(report.at("counts"), summary.at("counts"));
  EXPECT_EQ(report.at("topology").at("euler_characteristic").get<int>(), 1);
  EXPECT_TRUE(report.at("valid").get<bool>());
  EXPECT_FALSE(report.contains("run"));  // check measures a mesh; it did not compute one
}

TEST(CliMesh, WritesEveryFormatByExtension) {
  const std::string ply = work_path("formats.ply");
  ASSERT_EQ(run_cli("mesh sphere_cut -q -o " + quoted(ply)).exit_code, kSuccess);
  const TriangleMesh reference = read_mesh(ply);
  for (const std::string extension : {".obj", ".vtk", ".vtu"}) {
    SCOPED_TRACE(extension);
    const std::string path = work_path("formats" + extension);
    const CommandResult result = run_cli("mesh sphere_cut -q -o " + quoted(path));
    ASSERT_EQ(result.exit_code, kSuccess) << result.output;
    ASSERT_TRUE(std::filesystem::exists(path));
    EXPECT_GT(std::filesystem::file_size(path), 0u);
    const std::string content = file_content(path);
    if (extension == ".obj") {
      const TriangleMesh mesh = read_mesh(path);
      EXPECT_EQ(mesh.vertex_count(), reference.vertex_count());
      EXPECT_EQ(mesh.triangle_count(), reference.triangle_count());
    } else if (extension == ".vtk") {
      EXPECT_EQ(content.rfind("# vtk DataFile", 0), 0u);
    } else {
      EXPECT_TRUE(contains(content, "<VTKFile"));
    }
  }
}

TEST(CliMesh, IsDeterministic) {
  const std::string first = work_path("first.ply");
  const std::string second = work_path("second.ply");
  ASSERT_EQ(run_cli("mesh whitney_pleat -q -o " + quoted(first)).exit_code, kSuccess);
  ASSERT_EQ(run_cli("mesh whitney_pleat -q -o " + quoted(second)).exit_code, kSuccess);
  const std::string bytes = file_content(first);
  EXPECT_FALSE(bytes.empty());
  EXPECT_TRUE(bytes == file_content(second)) << "binary PLY files differ";
}

// --- Computations that cannot start: exit 1, saying why --------------------------------------

TEST(CliMeshFails, WhenTheStartIsFarFromM) {
  expect_exit(run_cli("mesh sphere --start 100,100,100 -o " + quoted(work_path("far.ply"))),
              kComputationFailed, {"start point (100, 100, 100)", "too far from M"});
}

TEST(CliMeshFails, WhenFIsNotFiniteAtTheStart) {
  // log(x) is NaN for x < 0; the file's own start (1, 0, 0) is fine, the override is not.
  const std::string file = write_problem_file(
      "log.tsr", "variables x y z\nequation log(x) + y^2 + z^2 - 1\nstart 1 0 0\n");
  expect_exit(
      run_cli("mesh " + quoted(file) + " --start -1,0,0 -o " + quoted(work_path("log.ply"))),
      kComputationFailed, {"start point (-1, 0, 0)", "not finite"});
}

TEST(CliMeshFails, WhenTheJacobianIsRankDeficientAtTheStart) {
  // F = |x|² vanishes only at 0, where DF = 2x = 0: not a smooth surface.
  const std::string file =
      write_problem_file("point.tsr", "variables x y z\nequation x^2 + y^2 + z^2\nstart 0 0 0\n");
  expect_exit(run_cli("mesh " + quoted(file) + " -o " + quoted(work_path("point.ply"))),
              kComputationFailed, {"start point (0, 0, 0)", "rank deficient"});
}

TEST(CliMeshFails, WhenTheStartProjectsOutsideTheBox) {
  // The start (0, 0, 1) of the unit sphere projects onto itself, above z <= 0.5.
  expect_exit(run_cli("mesh sphere --box -1,1,-1,1,-0.5,0.5 -o " + quoted(work_path("box.ply"))),
              kComputationFailed, {"outside the domain", "z <= 0.5"});
}

// --- --box on named coordinates ---------------------------------------------------------------

TEST(CliNamedBox, BoundsOnlyTheNamedCoordinates) {
  // The plane z = 0 over [−1, 1]², cut to x ∈ [−0.5, 0.5] and y ≥ 0: y's upper bound is the
  // catalogue's, z is left alone. Area 1 · 1, every vertex within the bounds.
  const std::string mesh_file = work_path("named_box.ply");
  ASSERT_EQ(run_cli("mesh plane -q --box x=-0.5:0.5,y=0: -o " + quoted(mesh_file)).exit_code,
            kSuccess);
  const TriangleMesh mesh = read_mesh(mesh_file);
  EXPECT_NEAR(surface_area(mesh), 1.0, 1e-9);
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    EXPECT_GE(mesh.point(v)(0), -0.5);
    EXPECT_LE(mesh.point(v)(0), 0.5);
    EXPECT_GE(mesh.point(v)(1), 0.0);
  }
}

TEST(CliNamedBox, NamesWhatIsWrong) {
  const std::string out = quoted(work_path("bad_box.ply"));
  expect_exit(run_cli("mesh plane --box w=0:1 -o " + out), kUsageError,
              {"--box names coordinate 'w'", "plane"});
  expect_exit(run_cli("mesh plane --box x=0.5 -o " + out), kUsageError,
              {"--box item 'x=0.5'", "name=lower:upper"});
  expect_exit(run_cli("mesh plane --box x=1:0 -o " + out), kUsageError,
              {"--box is empty", "x"});
  expect_exit(run_cli("mesh plane --box x=a:1 -o " + out), kUsageError, {"'a'"});
  EXPECT_FALSE(std::ifstream(work_path("bad_box.ply")).good());
}

// --- Problem files with mistakes: exit 2, naming the file and line --------------------------

TEST(CliProblemFile, SyntaxErrorNamesFileLineAndColumn) {
  const std::string file =
      write_problem_file("syntax.tsr",
                         "# a missing parenthesis\nvariables x y z\nequation x^2 + (y^2 - 1\n"
                         "start 0 0 1\n");
  expect_exit(run_cli("mesh " + quoted(file) + " -o " + quoted(work_path("syntax.ply"))),
              kUsageError, {file + ":3:", "missing ')'"});
}

TEST(CliProblemFile, StartWhereFIsNotFiniteNamesTheLine) {
  const std::string file = write_problem_file(
      "sqrt.tsr", "variables x y z\nequation sqrt(x) + y^2 + z^2 - 1\nstart -1 0 0\n");
  expect_exit(run_cli("mesh " + quoted(file) + " -o " + quoted(work_path("sqrt.ply"))), kUsageError,
              {file + ":3:", "finite"});
}

// --- Malformed command lines: exit 2, naming the option --------------------------------------

struct UsageCase {
  std::string name;
  std::string arguments;  // `{out}`, `{stl}`: an output path ending in .ply, .stl
  std::vector<std::string> fragments;
};

// gtest prints parameters on failure; the command line says more than the bytes of the struct.
void PrintTo(const UsageCase& usage_case, std::ostream* out) {
  *out << "tessera " << usage_case.arguments;
}

class CliUsageError : public ::testing::TestWithParam<UsageCase> {};

TEST_P(CliUsageError, ExitsWithTwoAndNamesTheMistake) {
  std::string arguments = GetParam().arguments;
  const auto out = arguments.find("{out}");
  if (out != std::string::npos) {
    arguments.replace(out, 5, quoted(work_path(GetParam().name + ".ply")));
  }
  const auto stl = arguments.find("{stl}");
  if (stl != std::string::npos) {
    arguments.replace(stl, 5, quoted(work_path(GetParam().name + ".stl")));
  }
  const CommandResult result = run_cli(arguments);
  expect_exit(result, kUsageError, GetParam().fragments);
  // Issue 34: messages named tessera's source file ("(start_and_box.cpp:113)"), which says
  // nothing to the user (TESSERA_DEBUG=1 brings it back for a bug report).
  EXPECT_FALSE(std::regex_search(result.output, std::regex(R"(\.(cpp|h):[0-9]+)")))
      << result.output;
  // A usage error is found before any work: no mesh file appears.
  EXPECT_FALSE(std::filesystem::exists(work_path(GetParam().name + ".ply")));
}

INSTANTIATE_TEST_SUITE_P(
    Options, CliUsageError,
    ::testing::Values(
        UsageCase{"no_command", "", {"subcommand"}},
        UsageCase{"negative_step", "mesh sphere --step -1 -o {out}", {"--step", "-1"}},
        UsageCase{"zero_step", "mesh sphere --step 0 -o {out}", {"--step", "0"}},
        UsageCase{"step_not_a_number", "mesh sphere --step abc -o {out}", {"--step", "abc"}},
        UsageCase{"step_nan", "mesh sphere --step nan -o {out}", {"--step", "nan"}},
        UsageCase{"max_start_distance_nan",
                  "mesh sphere --max-start-distance nan -o {out}",
                  {"--max-start-distance", "nan"}},
        UsageCase{"start_too_short",
                  "mesh sphere --start 1,2 -o {out}",
                  {"--start has 2 values", "n = 3"}},
        UsageCase{"start_not_a_number",
                  "mesh sphere --start 1,x,3 -o {out}",
                  {"--start", "'x' is not a number"}},
        UsageCase{"start_nan", "mesh sphere --start nan,0,1 -o {out}", {"start point", "finite"}},
        UsageCase{"unknown_option", "mesh sphere --frobnicate -o {out}", {"--frobnicate"}},
        UsageCase{"missing_output", "mesh sphere", {"--output"}},
        UsageCase{
            "unknown_problem", "mesh spheer -o {out}", {"unknown problem 'spheer'", "sphere_cut"}},
        UsageCase{"missing_problem_file",
                  "mesh no/such/file.tsr -o {out}",
                  {"no/such/file.tsr", "neither an existing file"}},
        UsageCase{"unknown_parameter",
                  "mesh sphere:radius=1,colour=2 -o {out}",
                  {"no parameter 'colour'", "radius"}},
        UsageCase{
            "unknown_method", "mesh sphere --method marching -o {out}", {"--method", "marching"}},
        UsageCase{"placement_for_front",
                  "mesh sphere --method front --placement hexagonal -o {out}",
                  {"--placement", "atlas", "front"}},
        UsageCase{"order_for_atlas",
                  "mesh sphere --order fifo -o {out}",
                  {"--order", "only for method 'front'", "atlas"}},
        UsageCase{"box_wrong_count",
                  "mesh sphere --box 1,2,3 -o {out}",
                  {"--box has 3 values", "expected 6"}},
        UsageCase{
            "box_empty", "mesh sphere --box -1,1,1,-1,-1,1 -o {out}", {"empty", "coordinate y"}},
        UsageCase{"unknown_extension", "mesh sphere -o {stl}", {"unknown extension '.stl'"}}),
    [](const ::testing::TestParamInfo<UsageCase>& info) { return info.param.name; });

// Issue 34: the README's `mesh torus --summary torus.json`, then `mesh torus --method bezier
// --patches torus.json`, silently replaced the summary with the patches.
TEST(CliOutputs, PatchesDoNotReplaceTheSummaryOfAnEarlierRun) {
  const std::string summary = work_path("torus_kinds.json");
  const std::string mesh = work_path("torus_kinds.ply");
  ASSERT_EQ(run_cli("mesh torus -t 0.02 -q -o " + quoted(mesh) + " --summary " + quoted(summary))
                .exit_code,
            0);
  const std::string before = file_content(summary);
  const CommandResult patches = run_cli("mesh torus --method bezier --tolerance 0.05 -q -o " +
                                        quoted(mesh) + " --patches " + quoted(summary));
  EXPECT_EQ(patches.exit_code, kUsageError) << patches.output;
  EXPECT_TRUE(contains(patches.output, "holds the JSON summary of a `tessera mesh` run"))
      << patches.output;
  EXPECT_TRUE(contains(patches.output, work_path("torus_kinds.patches.json"))) << patches.output;
  EXPECT_EQ(file_content(summary), before);
  // A summary over the summary of an earlier run, as usual.
  EXPECT_EQ(run_cli("mesh torus -t 0.02 -q -o " + quoted(mesh) + " --summary " + quoted(summary))
                .exit_code,
            0);
}

// Issue 34: a misspelt option or command got CLI11's "The following arguments were not
// expected"; the message now names the nearest ones, as git does.
TEST(CliMisspelling, SuggestsTheNearestOptionOrCommand) {
  const std::string out = quoted(work_path("misspelt.ply"));
  for (const std::string typo : {"--tolerence 1e-3", "--tolerence=1e-3", "--tolernace 1e-3"}) {
    const CommandResult result = run_cli("mesh sphere " + typo + " -o " + out);
    expect_exit(
        result, kUsageError,
        {"unknown option '" + typo.substr(0, typo.find_first_of(" =")) + "' for 'tessera mesh'",
         "did you mean '--tolerance'?"});
    EXPECT_FALSE(contains(result.output, "were not expected")) << result.output;
  }
  expect_exit(run_cli("mesh sphere --stpe 0.1 -o " + out), kUsageError, {"did you mean '--step'?"});
  expect_exit(run_cli("mesh sphere --tol 1e-3 -o " + out), kUsageError,
              {"did you mean '--tolerance'?"});  // an abbreviation
  expect_exit(run_cli("mesg sphere -o " + out), kUsageError,
              {"unknown command 'mesg'", "did you mean 'mesh'?", "commands: mesh"});
  expect_exit(run_cli("comapre sphere"), kUsageError, {"did you mean 'compare'?"});
  // An option of another command says whose it is.
  expect_exit(run_cli("compare sphere --method front"), kUsageError,
              {"unknown option '--method' for 'tessera compare'", "'tessera mesh'"});
  // Nothing near: the option and where to look, no guess.
  const CommandResult far = run_cli("mesh sphere --frobnicate -o " + out);
  expect_exit(far, kUsageError, {"unknown option '--frobnicate'", "tessera mesh --help"});
  EXPECT_FALSE(contains(far.output, "did you mean")) << far.output;
  EXPECT_FALSE(std::filesystem::exists(work_path("misspelt.ply")));
}

TEST(CliCheck, MissingMeshFileIsNamed) {
  const std::string missing = work_path("no_such_mesh.ply");
  const CommandResult result = run_cli("check " + quoted(missing) + " --problem sphere");
  EXPECT_TRUE(result.exit_code == kComputationFailed || result.exit_code == kUsageError)
      << "exit " << result.exit_code << "\n"
      << result.output;
  EXPECT_TRUE(contains(result.output, missing)) << result.output;
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

TEST(CliAtlas, IsTheDefaultMethodAndTakesATolerance) {
  const std::string out = work_path("atlas_default.ply");
  const testing::CommandResult result =
      testing::run_cli("mesh sphere --tolerance 0.01 -o " + quoted(out));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  // A dense problem: the hexagonal placement (--placement auto), and the report says so.
  EXPECT_NE(result.output.find("atlas (hexagonal placement), tolerance 0.01"), std::string::npos)
      << result.output;
  const MeshValidation validation = validate(read_mesh(out));
  EXPECT_TRUE(validation.is_valid());
  EXPECT_EQ(validation.euler_characteristic, 2);
}

// Issue 34: every atlas run printed the same 400 characters on chart radii held below the
// tolerance's, for the one chart next to the start. The note now comes where such charts are a
// tenth of the atlas or more (cstr: 13 %, graded towards the fold; whitney_pleat had a quarter
// until the radius probes of issue 35 measured at the expected radius); the counts are in every
// summary.
TEST(CliAtlas, NotesChartRadiiOnlyWhereTheyChangeTheCost) {
  struct Case {
    std::string problem;
    bool noted;
  };
  for (const Case& c : {Case{"sphere", false}, Case{"cstr", true}}) {
    const std::string summary = work_path(c.problem + "_radii.json");
    const testing::CommandResult result = testing::run_cli(
        "mesh " + c.problem + " -o " + quoted(work_path(c.problem + "_radii.ply")) + " --summary " +
        quoted(summary));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_EQ(contains(result.output, "have a radius below the tolerance's"), c.noted)
        << result.output;
    const nlohmann::json json = nlohmann::json::parse(std::ifstream(summary));
    const nlohmann::json& caps = json["run"]["atlas"]["radius_caps"];
    const int charts = json["run"]["atlas"]["charts"].get<int>();
    ASSERT_TRUE(caps.is_object()) << json["run"].dump(2);
    EXPECT_EQ(caps["total"].get<int>() >= 0.1 * charts, c.noted) << caps.dump();
    EXPECT_EQ(caps["total"].get<int>(),
              caps["curvature"].get<int>() + caps["not_a_graph"].get<int>() +
                  caps["grading"].get<int>() + caps["reach"].get<int>() + caps["band"].get<int>());
    bool in_notes = false;
    for (const auto& note : json["run"]["notes"]) {
      in_notes = in_notes || contains(note.get<std::string>(), "have a radius below");
    }
    EXPECT_EQ(in_notes, c.noted);
  }
}

// Issue 34: the unit of the "by step" numbers came at the end of a long line.
TEST(CliAtlas, ByStepNamesItsUnitFirst) {
  const testing::CommandResult result =
      testing::run_cli("mesh sphere -o " + quoted(work_path("by_step.ply")));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(contains(result.output, "\n  by step (DF / factorisations / solves per vertex): start "))
      << result.output;
  EXPECT_FALSE(contains(result.output, " DF/factorisations per vertex")) << result.output;
}

TEST(CliCompare, PrintsOneRowPerMethodWithValidityAndTopology) {
  const testing::CommandResult result = testing::run_cli("compare sphere");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  // Issue 34: the atlas ran to a tolerance and the others without one. Every method now runs
  // to the same one (the default, the sphere's step 0.3 / 50), named above the table, and
  // every row keeps it.
  EXPECT_NE(result.output.find("every method to tolerance 0.006"), std::string::npos)
      << result.output;
  for (const std::string method : {"atlas", "front", "bezier"}) {
    const auto row = result.output.find("\n" + method + " ");
    ASSERT_NE(row, std::string::npos) << result.output;
    const std::string line =
        result.output.substr(row + 1, result.output.find('\n', row + 1) - row - 1);
    EXPECT_NE(line.find(" 2 yes"), std::string::npos) << line;  // χ = 2, valid
    EXPECT_NE(line.find("completed"), std::string::npos) << line;
    std::istringstream fields(line);
    std::string name;
    int vertices = 0;
    int triangles = 0;
    double seconds = 0.0;
    double max_distance = 0.0;
    fields >> name >> vertices >> triangles >> seconds >> max_distance;
    EXPECT_LE(max_distance, 0.006) << line;
  }
  EXPECT_NE(result.output.find("expected Euler characteristic: 2"), std::string::npos);
}

}  // namespace
}  // namespace tessera

namespace {

// A kill (SIGTERM, e.g. a batch system's time limit) or Ctrl-C during a long run stops the
// method at its next vertex: the valid partial mesh and the summary are written, exit 1.
TEST(CliInterrupt, TermSignalKeepsTheValidPartialMeshAndItsSummary) {
  const std::string folder = tessera::testing::temporary_directory("interrupt");
  const std::string mesh = folder + "/torus.ply";
  const std::string summary = folder + "/torus.json";
  // The torus at 1e-5 takes minutes; the signal comes after a second, once the run has begun.
  const std::string command = "sh -c '" + std::string(TESSERA_CLI) + " mesh torus --tolerance 1e-5 -q -o " +
                              mesh + " --summary " + summary +
                              " & pid=$!; sleep 1.5; kill -TERM $pid; wait $pid; echo exit=$?'";
  const std::string output = tessera::testing::run_shell(command).output;
  EXPECT_NE(output.find("exit=1"), std::string::npos) << output;
  EXPECT_NE(output.find("interrupted"), std::string::npos) << output;
  std::ifstream in(summary);
  ASSERT_TRUE(in.good()) << output;
  const auto json = nlohmann::json::parse(in);
  EXPECT_EQ(json["run"]["termination"], "interrupted");
  EXPECT_TRUE(json["valid"].get<bool>());
  const tessera::TriangleMesh partial = tessera::read_mesh(mesh);
  EXPECT_GT(partial.triangle_count(), 0);
  EXPECT_EQ(partial.vertex_count(), json["counts"]["vertices"].get<int>());
}

}  // namespace
