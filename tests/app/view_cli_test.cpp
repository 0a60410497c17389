// SPDX-License-Identifier: MIT
// `tessera mesh --view` and `--states` as a user meets them: a surface of large n is written in a
// few functionals by default and says so, the states go to NumPy files that numpy reads, a
// problem file's view is used, and a bad view is a usage error that names the item.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "io/npy_test_support.h"
#include "support/test_support.h"
#include "tessera/io/mesh_io.h"
#include "tessera/problems/catalogue.h"
#include "tessera/problems/view.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;
using npy_test::read_npy;
using testing::CommandResult;
using testing::run_cli;

constexpr int kUsageError = 2;

bool contains(const std::string& text, const std::string& fragment) {
  return text.find(fragment) != std::string::npos;
}

std::string quoted(const std::string& text) { return "'" + text + "'"; }

std::vector<std::string> entries(const std::string& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// The points of an .npy states file as an n×V matrix (columns are vertices), and its triangles.
Eigen::MatrixXd states_of(const npy_test::NpyArray& array) {
  return Eigen::Map<const Eigen::MatrixXd>(array.reals.data(), array.columns, array.rows);
}
std::vector<Triangle> triangles_of(const npy_test::NpyArray& array) {
  std::vector<Triangle> triangles;
  for (std::size_t t = 0; t + 2 < array.integers.size(); t += 3) {
    triangles.push_back({static_cast<int>(array.integers[t]),
                         static_cast<int>(array.integers[t + 1]),
                         static_cast<int>(array.integers[t + 2])});
  }
  return triangles;
}

// bvp with 49 grid points: n = 51 > kLargeAmbientDimension, so the default view applies; a
// coarse atlas (a few seconds) gives a few hundred vertices. One run serves the suite.
const std::string kLargeProblem = "bvp:points=49";
static_assert(49 + 2 > kLargeAmbientDimension);

class CliLargeN : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = testing::temporary_directory("view_large_n");
    result_ =
        run_cli("mesh " + kLargeProblem + " --step 3 --tolerance 0.3 -o " +
                quoted(folder_ + "/bvp.vtu") + " --states " + quoted(folder_ + "/bvp_states.npy") +
                " --summary " + quoted(folder_ + "/bvp_states.summary.json"));
  }
  static void TearDownTestSuite() { result_.reset(); }
  // The files are the subject here, not the method: a partial mesh (exit 1) is written the same
  // way, so a change in the atlas that stops this coarse run early does not hide a view bug.
  static void expect_files_written() {
    ASSERT_TRUE(result_->exit_code == 0 || result_->exit_code == 1) << result_->output;
    ASSERT_TRUE(fs::exists(folder_ + "/bvp.vtu")) << result_->output;
  }
  static inline std::string folder_;
  static inline std::optional<CommandResult> result_;
};

TEST_F(CliLargeN, SaysWhichViewItChoseAndWhatItWrote) {
  expect_files_written();
  EXPECT_TRUE(contains(result_->output,
                       "view           lambda, epsilon, max:u (the default for n = 51 > 50; "
                       "--view all writes all 51 coordinates"))
      << result_->output;
  EXPECT_TRUE(contains(result_->output, "wrote          " + folder_ + "/bvp.vtu, " + folder_ +
                                            "/bvp_states.npy, " + folder_ +
                                            "/bvp_states.triangles.npy and " + folder_ +
                                            "/bvp_states.summary.json"))
      << result_->output;
  // Each file was renamed into place: no temporary is left beside them.
  EXPECT_EQ(entries(folder_),
            (std::vector<std::string>{"bvp.vtu", "bvp_states.npy", "bvp_states.summary.json",
                                      "bvp_states.triangles.npy"}));
}

TEST_F(CliLargeN, MeshFileHoldsTheViewOfTheStatesBitForBit) {
  expect_files_written();
  const auto states = read_npy(folder_ + "/bvp_states.npy");
  const auto triangles = read_npy(folder_ + "/bvp_states.triangles.npy");
  ASSERT_EQ(states.columns, 51);
  ASSERT_EQ(triangles.columns, 3);
  const Eigen::MatrixXd X = states_of(states);  // 51×V
  const TriangleMesh shown = read_mesh(folder_ + "/bvp.vtu");
  ASSERT_EQ(shown.ambient_dimension(), 3);
  ASSERT_EQ(shown.vertex_count(), states.rows);
  EXPECT_EQ(shown.triangles(), triangles_of(triangles));
  for (int j = 0; j < shown.vertex_count(); ++j) {
    EXPECT_EQ(shown.point(j)(0), X(49, j));                      // lambda
    EXPECT_EQ(shown.point(j)(1), X(50, j));                      // epsilon
    EXPECT_EQ(shown.point(j)(2), X.col(j).head(49).maxCoeff());  // max:u
  }
  // The states are points of M: F vanishes to the corrector's tolerance at every vertex.
  const ProblemSetup setup = make_catalogue_problem(kLargeProblem);
  Eigen::VectorXd F(49);
  for (int j = 0; j < X.cols(); ++j) {
    setup.problem->evaluate(X.col(j), F);
    EXPECT_LT(F.norm(), 1e-8) << "vertex " << j;
  }
}

TEST_F(CliLargeN, SummaryRecordsTheViewAndTheStateColumns) {
  expect_files_written();
  const nlohmann::json json =
      nlohmann::json::parse(std::ifstream(folder_ + "/bvp_states.summary.json"));
  EXPECT_EQ(json["view"]["specification"], "lambda, epsilon, max:u");
  EXPECT_EQ(json["view"]["origin"], "default for large n");
  EXPECT_EQ(json["view"]["columns"], nlohmann::json({"lambda", "epsilon", "max_u"}));
  const auto& states = json["states"];
  EXPECT_EQ(states["file"], folder_ + "/bvp_states.npy");
  EXPECT_EQ(states["triangles_file"], folder_ + "/bvp_states.triangles.npy");
  EXPECT_EQ(states["shape"][1], 51);
  EXPECT_EQ(states["shape"][0], json["counts"]["vertices"]);
  EXPECT_EQ(states["triangles_shape"][0], json["counts"]["triangles"]);
  // u is one entry with its range, not 49.
  ASSERT_EQ(states["columns"].size(), 3u);
  EXPECT_EQ(states["columns"][0]["name"], "u");
  EXPECT_EQ(states["columns"][0]["first"], 0);
  EXPECT_EQ(states["columns"][0]["size"], 49);
  EXPECT_EQ(states["columns"][0]["block"], true);
  EXPECT_EQ(states["columns"][1]["name"], "lambda");
  EXPECT_EQ(states["columns"][1]["first"], 49);
  EXPECT_EQ(states["columns"][2]["name"], "epsilon");
}

TEST_F(CliLargeN, NumpyLoadsTheStatesAndTriangles) {
  expect_files_written();
  const std::string python = npy_test::python_with_numpy();
  if (python.empty()) {
    GTEST_SKIP() << "numpy is not installed (python3-numpy; scripts/install-dependencies.sh)";
  }
  // As docs/mesh-files.md tells users to read them.
  const auto [output, status] = npy_test::run_python(
      python,
      "import sys, json, numpy\n"
      "X = numpy.load(sys.argv[1]); T = numpy.load(sys.argv[2])\n"
      "s = json.load(open(sys.argv[3]))\n"
      "c = {e['name']: slice(e['first'], e['first'] + e['size']) for e in s['states']['columns']}\n"
      "u, lam = X[:, c['u']], X[:, c['lambda']]\n"
      "print(X.shape[1], X.dtype, T.shape[1], T.dtype, u.shape[1], lam.shape[1],\n"
      "      X.shape[0] == s['counts']['vertices'], int(T.max()) < X.shape[0])\n",
      {folder_ + "/bvp_states.npy", folder_ + "/bvp_states.triangles.npy",
       folder_ + "/bvp_states.summary.json"});
  EXPECT_EQ(status, 0) << output;
  EXPECT_EQ(output, "51 float64 3 int64 49 1 True True\n");
}

// The Python of docs/mesh-files.md, run as printed on the files of this run: it reads the states
// and the summary, and writes a .vtu for ParaView with meshio.
TEST_F(CliLargeN, TheDocumentedPythonRuns) {
  expect_files_written();
  const std::string python = npy_test::python_with_numpy();
  if (python.empty() || npy_test::run_python(python, "import meshio", {}).second != 0) {
    GTEST_SKIP() << "numpy or meshio is not installed (scripts/install-dependencies.sh)";
  }
  std::ifstream in(testing::source_path("docs/mesh-files.md"));
  const std::string docs((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string script = "import os\nos.chdir(" + std::string("'") + folder_ + "')\n";
  for (auto begin = docs.find("```python\n"); begin != std::string::npos;
       begin = docs.find("```python\n", begin)) {
    begin += 10;
    const auto end = docs.find("```", begin);
    script += docs.substr(begin, end - begin);
  }
  script +=
      "assert X.shape[1] == 51 and T.shape[1] == 3\n"
      "assert u.shape == (X.shape[0], 49) and lam.shape == (X.shape[0],)\n"
      "assert (lam == X[:, 49]).all()\n"
      "print('ok', points.shape)\n";
  const std::string path = folder_ + "/documented.py";
  std::ofstream(path) << script;
  const auto [output, status] =
      npy_test::run_python(python, "import runpy, sys; runpy.run_path(sys.argv[1])", {path});
  EXPECT_EQ(status, 0) << output << "\n" << script;
  EXPECT_TRUE(contains(output, "ok (")) << output;
  EXPECT_TRUE(fs::exists(folder_ + "/bvp_middle.vtu"));
  fs::remove(path);
  fs::remove(folder_ + "/bvp_middle.vtu");
}

TEST_F(CliLargeN, CheckOfAViewSaysWhereTheStatesAre) {
  expect_files_written();
  const CommandResult check =
      run_cli("check " + quoted(folder_ + "/bvp.vtu") + " --problem " + kLargeProblem);
  EXPECT_EQ(check.exit_code, kUsageError) << check.output;
  EXPECT_TRUE(contains(check.output, "is in R^3 but problem '" + kLargeProblem + "' is in R^51"))
      << check.output;
  EXPECT_TRUE(contains(check.output, "holds the view's functionals")) << check.output;
}

TEST_F(CliLargeN, CheckReadsTheStatesWithTheirTriangles) {
  expect_files_written();
  // The check a view cannot have: the states against M (valid, the known topology, on M).
  const CommandResult check =
      run_cli("check " + quoted(folder_ + "/bvp_states.npy") + " --problem " + kLargeProblem);
  EXPECT_NE(check.exit_code, kUsageError) << check.output;  // read, and measured against M
  if (result_->exit_code == 0) {
    EXPECT_EQ(check.exit_code, 0) << check.output;  // a completed run passes its check
  }
  EXPECT_TRUE(contains(check.output, "problem        " + kLargeProblem + " (n = 51)"))
      << check.output;
  const nlohmann::json json =
      nlohmann::json::parse(std::ifstream(folder_ + "/bvp_states.summary.json"));
  EXPECT_TRUE(contains(
      check.output,
      "mesh           " + std::to_string(json["counts"]["vertices"].get<int>()) + " vertices"))
      << check.output;
}

// --- small n: views are asked for ---------------------------------------------------------

TEST(CliView, ExplicitViewWithAnExpressionMatchesTheLibrary) {
  const std::string folder = testing::temporary_directory("view_cstr");
  const CommandResult result =
      run_cli("mesh cstr --view 'Da, B, x1, r = sqrt(x1^2 + x2^2)' -o " +
              quoted(folder + "/cstr.ply") + " --states " + quoted(folder + "/cstr.npy"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(contains(result.output,
                       "view           Da, B, x1, r = sqrt(x1^2 + x2^2) (from "
                       "--view)"))
      << result.output;
  const TriangleMesh shown = read_mesh(folder + "/cstr.ply");
  const Eigen::MatrixXd X = states_of(read_npy(folder + "/cstr.npy"));
  const ProblemSetup setup = make_catalogue_problem("cstr");
  const View view = parse_view("Da, B, x1, r = sqrt(x1^2 + x2^2)", *setup.problem);
  ASSERT_EQ(shown.ambient_dimension(), 4);  // the fourth functional is a vertex property
  EXPECT_EQ(shown.points(), view.evaluate_columns(X));
}

TEST(CliView, AllIsTheDefaultForSmallNByteForByte) {
  const std::string folder = testing::temporary_directory("view_all");
  ASSERT_EQ(run_cli("mesh cstr -q --view all -o " + quoted(folder + "/all.ply")).exit_code, 0);
  ASSERT_EQ(run_cli("mesh cstr -q -o " + quoted(folder + "/default.ply")).exit_code, 0);
  std::ifstream all(folder + "/all.ply", std::ios::binary);
  std::ifstream plain(folder + "/default.ply", std::ios::binary);
  EXPECT_TRUE(std::equal(std::istreambuf_iterator<char>(all), std::istreambuf_iterator<char>(),
                         std::istreambuf_iterator<char>(plain), std::istreambuf_iterator<char>()));
}

// --report-samples sets how many points of each kind the report projects onto M, and says so.
TEST(CliView, ReportSamplesBoundTheDistanceMeasurement) {
  const std::string folder = testing::temporary_directory("report_samples");
  const auto result = run_cli("mesh " + kLargeProblem + " --step 3 --tolerance 0.3 -o " +
                              quoted(folder + "/bvp.ply") + " --report-samples 7 --summary " +
                              quoted(folder + "/bvp.json"));
  ASSERT_TRUE(result.exit_code == 0 || result.exit_code == 1) << result.output;
  EXPECT_TRUE(contains(result.output, "(largest of 7 uniform samples of each: with 95% confidence it bounds 65.2% of the points)"))
      << result.output;
  std::ifstream in(folder + "/bvp.json");
  const auto summary = nlohmann::json::parse(in);
  const auto& centroids = summary["distance_to_manifold"]["centroids"];
  EXPECT_EQ(centroids["count"], 7);
  EXPECT_GT(centroids["population"].get<int>(), 7);
  const auto refused = run_cli("mesh " + kLargeProblem + " --report-samples -1 -o " +
                               quoted(folder + "/x.ply"));
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_TRUE(contains(refused.output, "--report-samples")) << refused.output;
}

TEST(CliView, ObjCoordinatesIsTheViewOfThoseCoordinates) {
  const std::string folder = testing::temporary_directory("view_obj");
  ASSERT_EQ(
      run_cli("mesh cstr -q --obj-coordinates 0,2,3 -o " + quoted(folder + "/old.obj")).exit_code,
      0);
  ASSERT_EQ(run_cli("mesh cstr -q --view x1,Da,B -o " + quoted(folder + "/new.obj")).exit_code, 0);
  std::ifstream old_file(folder + "/old.obj", std::ios::binary);
  std::ifstream new_file(folder + "/new.obj", std::ios::binary);
  EXPECT_TRUE(std::equal(std::istreambuf_iterator<char>(old_file), std::istreambuf_iterator<char>(),
                         std::istreambuf_iterator<char>(new_file),
                         std::istreambuf_iterator<char>()));
}

TEST(CliView, ProblemFileViewIsTheDefaultAndViewOverridesIt) {
  const std::string folder = testing::temporary_directory("view_file");
  const std::string problem = folder + "/cap.tsr";
  std::ofstream(problem) << "variables x y z\n"
                            "equation x^2 + y^2 + z^2 - 1\n"
                            "start 0 0 1\n"
                            "step 0.3\n"
                            "halfspace normal 0 0 1 point 0 0 0.5\n"
                            "view x, y, rho = sqrt(x^2 + y^2)\n";
  CommandResult result = run_cli("mesh " + quoted(problem) + " -o " + quoted(folder + "/a.vtk"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(contains(result.output,
                       "view           x, y, rho = sqrt(x^2 + y^2) (from problem "
                       "file)"))
      << result.output;
  const TriangleMesh shown = read_mesh(folder + "/a.vtk");
  ASSERT_EQ(shown.ambient_dimension(), 3);
  for (int j = 0; j < shown.vertex_count(); ++j) {
    const Eigen::Vector3d p = shown.point(j);
    EXPECT_DOUBLE_EQ(p(2), std::sqrt(p(0) * p(0) + p(1) * p(1)));
  }
  result = run_cli("mesh " + quoted(problem) + " --view z,x -o " + quoted(folder + "/b.vtk"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(contains(result.output, "view           z, x (from --view)")) << result.output;
  EXPECT_GE(read_mesh(folder + "/b.vtk").points().row(0).minCoeff(), 0.5 - 1e-9);  // z ≥ 0.5
}

// --- usage errors: exit 2 before any work, naming the item -----------------------------------

struct ViewUsageCase {
  std::string name;
  std::string arguments;  // {out}: the mesh path
  std::vector<std::string> fragments;
};

void PrintTo(const ViewUsageCase& usage_case, std::ostream* out) {
  *out << "tessera " << usage_case.arguments;
}

class CliViewUsageError : public ::testing::TestWithParam<ViewUsageCase> {};

TEST_P(CliViewUsageError, ExitsWithTwoNamingTheItemAndWritesNothing) {
  const std::string folder = testing::temporary_directory("view_usage_" + GetParam().name);
  std::string arguments = GetParam().arguments;
  for (auto out = arguments.find("{out}"); out != std::string::npos;
       out = arguments.find("{out}")) {
    arguments.replace(out, 5, quoted(folder + "/m.ply"));
  }
  const CommandResult result = run_cli(arguments);
  EXPECT_EQ(result.exit_code, kUsageError) << result.output;
  for (const std::string& fragment : GetParam().fragments) {
    EXPECT_TRUE(contains(result.output, fragment))
        << "the message does not name '" << fragment << "':\n"
        << result.output;
  }
  EXPECT_TRUE(entries(folder).empty()) << result.output;
}

INSTANTIATE_TEST_SUITE_P(
    Options, CliViewUsageError,
    ::testing::Values(
        ViewUsageCase{"unknown_name",
                      "mesh bvp:points=1000 --view lambda,lamda -o {out}",
                      {"--view lambda,lamda: 'lamda' is no coordinate",
                       "u1 … u1000 (block u), lambda, epsilon", "max:B"}},
        ViewUsageCase{"unknown_block",
                      "mesh bvp --view lambda,max:v -o {out}",
                      {"'max:v': no block 'v' (blocks: u)"}},
        ViewUsageCase{"unknown_functional",
                      "mesh bvp --view lambda,median:u -o {out}",
                      {"unknown block functional 'median'", "absmax"}},
        ViewUsageCase{
            "no_blocks", "mesh sphere --view x,max:u -o {out}", {"has no coordinate blocks"}},
        ViewUsageCase{"one_functional",
                      "mesh bvp --view max:u -o {out}",
                      {"--view max:u: a view needs at least two functionals"}},
        ViewUsageCase{"twice", "mesh sphere --view x,y,x -o {out}", {"'x' is given twice"}},
        ViewUsageCase{"bad_expression",
                      "mesh sphere --view 'x,y,r=sqrt(x^2+' -o {out}",
                      {"'r = sqrt(x^2+'", "found the end of the expression"}},
        ViewUsageCase{"view_and_obj_coordinates",
                      "mesh sphere --view x,y,z --obj-coordinates 0,1,2 -o {out}",
                      {"--view and --obj-coordinates"}},
        ViewUsageCase{"states_extension",
                      "mesh sphere --states {out} -o {out}",
                      {"--states", "must end in .npy"}},
        ViewUsageCase{"states_folder",
                      "mesh sphere --states /no/such/folder/s.npy -o {out}",
                      {"/no/such/folder", "does not exist"}}),
    [](const ::testing::TestParamInfo<ViewUsageCase>& info) { return info.param.name; });

}  // namespace
}  // namespace tessera
