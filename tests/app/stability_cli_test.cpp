// SPDX-License-Identifier: MIT
// `tessera mesh --stability / --hopf / --diagram` as a user meets them, checked against numbers
// computed here without tessera's stability code: the CSTR's 2×2 Jacobian (trace and
// determinant in closed form), the pleat's 3x² − λ, and on bvp and bratu2d the rule that a fold
// of M over the parameter plane changes the number of unstable eigenvalues by one.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "support/test_support.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/io/mesh_io.h"

namespace tessera {
namespace {

using testing::run_cli;

constexpr int kUsageError = 2;

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

bool contains(const std::string& text, const std::string& fragment) {
  return text.find(fragment) != std::string::npos;
}

const std::vector<double>& scalars(const std::vector<VertexScalars>& data, const std::string& name) {
  for (const auto& d : data) {
    if (d.name == name) {
      return d.values;
    }
  }
  throw std::runtime_error("no vertex data " + name);
}

// The CSTR (β = 0.5) on M: with a = x₁/(1 − x₁), D_uF has this trace and determinant.
double cstr_trace(double x1, double B) { return B * x1 - 2.5 - x1 / (1 - x1); }
double cstr_determinant(double x1, double B) { return 1.5 / (1 - x1) - B * x1; }

TEST(StabilityCli, CstrCountsHopfCurveNeutralSaddlesAndBogdanovTakensPointAreExact) {
  const std::string dir = testing::temporary_directory("stability_cli_cstr");
  const auto result = run_cli("mesh cstr --tolerance 0.01 --diagram " + dir + "/diagram.svg -o " +
                              dir + "/cstr.ply --summary " + dir + "/cstr.json");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(contains(result.output, "every eigenvalue computed: the counts are exact"));
  EXPECT_TRUE(contains(result.output, "1 Bogdanov–Takens point(s)")) << result.output;

  // Every vertex's count from the file's point data against the closed form.
  std::vector<VertexScalars> data;
  const TriangleMesh mesh = read_mesh(dir + "/cstr.ply", data);
  const auto& counts = scalars(data, "unstable_count");
  ASSERT_EQ(static_cast<int>(counts.size()), mesh.vertex_count());
  std::map<int, int> seen;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    const double x1 = mesh.point(v)(0);
    const double B = mesh.point(v)(3);
    const double t = cstr_trace(x1, B);
    const double d = cstr_determinant(x1, B);
    if (std::abs(t) < 1e-6 || std::abs(d) < 1e-6) {
      continue;
    }
    const int expected = d < 0 ? 1 : (t > 0 ? 2 : 0);
    EXPECT_EQ(counts[static_cast<std::size_t>(v)], expected) << "x1 = " << x1 << ", B = " << B;
    ++seen[expected];
  }
  EXPECT_GT(seen[0], 100);
  EXPECT_GT(seen[1], 100);
  EXPECT_GT(seen[2], 5);

  const auto summary = read_json(dir + "/cstr.json");
  const auto& stability = summary.at("stability");
  EXPECT_EQ(stability.at("vertices"), mesh.vertex_count());
  EXPECT_EQ(stability.at("failed_vertices"), 0);
  EXPECT_EQ(stability.at("parameters"), nlohmann::json({"Da", "B"}));
  const auto& hopf = summary.at("hopf");
  EXPECT_EQ(hopf.at("unrefined_points"), 0);
  EXPECT_EQ(hopf.at("columns"), nlohmann::json({"x1", "x2", "Da", "B", "omega", "l1"}));
  ASSERT_EQ(hopf.at("curves").size(), 1u);
  ASSERT_EQ(hopf.at("neutral_saddle_curves").size(), 1u);
  int hopf_points = 0;
  for (const auto& point : hopf.at("curves")[0].at("points")) {
    const double x1 = point[0], B = point[3], omega = point[4];
    EXPECT_NEAR(cstr_trace(x1, B), 0.0, 1e-8);
    EXPECT_NEAR(omega * omega, cstr_determinant(x1, B), 1e-8);
    EXPECT_GE(x1, 2.0 / 3.0 - 1e-9);  // Hopf points need a positive determinant
    ++hopf_points;
  }
  EXPECT_GT(hopf_points, 20);
  for (const auto& point : hopf.at("neutral_saddle_curves")[0].at("points")) {
    const double x1 = point[0], B = point[3], kappa = point[4];
    EXPECT_NEAR(cstr_trace(x1, B), 0.0, 1e-8);
    EXPECT_NEAR(-kappa * kappa, cstr_determinant(x1, B), 1e-8);
  }
  // Bogdanov–Takens: trace = determinant = 0 at x₁ = 1/(1 + β) = 2/3, B = (1 + β)³/β = 6.75,
  // x₂ = B x₁/(1 + β) = 3, Da = x₁ e^(−x₂)/(1 − x₁) = 2 e⁻³.
  ASSERT_EQ(hopf.at("special_points").size(), 1u);
  const auto& bt = hopf.at("special_points")[0];
  EXPECT_EQ(bt.at("kind"), "bogdanov_takens");
  EXPECT_NEAR(bt.at("point").at("x1").get<double>(), 2.0 / 3.0, 1e-8);
  EXPECT_NEAR(bt.at("point").at("x2").get<double>(), 3.0, 1e-8);
  EXPECT_NEAR(bt.at("plane").at("B").get<double>(), 6.75, 1e-8);
  EXPECT_NEAR(bt.at("plane").at("Da").get<double>(), 2 * std::exp(-3.0), 1e-8);
  // The Hopf curve ends at the BT point; the diagram and the curve files were written.
  const auto& first = hopf.at("curves")[0].at("points").front();
  const auto& last = hopf.at("curves")[0].at("points").back();
  const double end_x1 = std::abs(first[0].get<double>() - 2.0 / 3.0) < 1e-8 ? first[0].get<double>()
                                                                            : last[0].get<double>();
  EXPECT_NEAR(end_x1, 2.0 / 3.0, 1e-8);
  for (const std::string file : {"diagram.svg", "cstr.hopf.ply", "cstr.neutral_saddles.ply",
                                 "cstr.folds.ply"}) {
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + file)) << file;
  }
}

TEST(StabilityCli, PleatSheetsChangeStabilityExactlyOnTheFold) {
  const std::string dir = testing::temporary_directory("stability_cli_pleat");
  const auto result = run_cli("mesh whitney_pleat --tolerance 0.01 --stability -o " + dir + "/pleat.vtu");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::vector<VertexScalars> data;
  const TriangleMesh mesh = read_mesh(dir + "/pleat.vtu", data);
  const auto& counts = scalars(data, "unstable_count");
  const auto& leading = scalars(data, "leading_real_part");
  int unstable = 0;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    const double x = mesh.point(v)(0);
    const double lambda = mesh.point(v)(1);
    const double mu = -(3 * x * x - lambda);  // x' = −F: the one eigenvalue
    if (std::abs(mu) < 1e-9) {
      continue;
    }
    EXPECT_EQ(counts[static_cast<std::size_t>(v)], mu > 0 ? 1 : 0);
    EXPECT_NEAR(leading[static_cast<std::size_t>(v)], mu, 1e-12);
    unstable += mu > 0;
  }
  EXPECT_GT(unstable, 50);  // the middle sheet is in the mesh
}

// A fold of M over the parameter plane changes the index by one; only there does the parity of
// the index change, so it agrees with the orientation of the triangles projected on the plane
// (the first two columns of the mesh file's view): one sign for even indices, the other for odd.
void expect_index_parity_follows_the_folds(const std::string& problem, const std::string& name) {
  const std::string dir = testing::temporary_directory("stability_cli_" + name);
  const auto result = run_cli("mesh " + problem + " --stability -o " + dir + "/m.ply");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(contains(result.output, "counts from the inertia of s·D_uF (Sylvester's law): exact"))
      << result.output;
  std::vector<VertexScalars> data;
  const TriangleMesh mesh = read_mesh(dir + "/m.ply", data);  // view: lambda, epsilon, max_u
  const auto& counts = scalars(data, "unstable_count");
  const auto& certain = scalars(data, "stability_certain");
  // Triangles within one ring of an index change are left out: a flat triangle beside the fold
  // can be folded over in the projection without the fold separating its corners.
  const MeshTopology topology(mesh);
  std::vector<char> near_change(static_cast<std::size_t>(mesh.vertex_count()), 0);
  for (int e = 0; e < topology.edge_count(); ++e) {
    const auto& edge = topology.edge(e);
    if (counts[static_cast<std::size_t>(edge[0])] != counts[static_cast<std::size_t>(edge[1])]) {
      near_change[static_cast<std::size_t>(edge[0])] = near_change[static_cast<std::size_t>(edge[1])] = 1;
    }
  }
  int agree = 0;
  int disagree = 0;
  int odd = 0;
  for (const Triangle& t : mesh.triangles()) {
    const int c = static_cast<int>(counts[static_cast<std::size_t>(t[0])]);
    if (near_change[static_cast<std::size_t>(t[0])] || near_change[static_cast<std::size_t>(t[1])] ||
        near_change[static_cast<std::size_t>(t[2])]) {
      continue;
    }
    EXPECT_EQ(certain[static_cast<std::size_t>(t[0])], 1.0);
    const Eigen::Vector2d a = mesh.point(t[0]).head<2>();
    const Eigen::Vector2d ab = mesh.point(t[1]).head<2>() - a;
    const Eigen::Vector2d ac = mesh.point(t[2]).head<2>() - a;
    const double orientation = ab(0) * ac(1) - ab(1) * ac(0);
    if (std::abs(orientation) <= 1e-3 * ab.norm() * ac.norm()) {
      continue;  // seen edge-on from the plane: its sign is not the tangent plane's
    }
    ((orientation > 0) == (c % 2 == 0) ? agree : disagree) += 1;
    odd += c % 2;
  }
  EXPECT_GT(odd, 100);  // both sides of the fold are there
  // All one way, or all the other (the mesh's orientation is arbitrary).
  EXPECT_EQ(std::min(agree, disagree), 0) << agree << " agree, " << disagree << " disagree";
  // Across every edge the index changes by at most 2 (one fold, or two eigenvalues of a
  // symmetric pair at once on the square).
  for (int e = 0; e < topology.edge_count(); ++e) {
    const auto& edge = topology.edge(e);
    EXPECT_LE(std::abs(counts[static_cast<std::size_t>(edge[0])] - counts[static_cast<std::size_t>(edge[1])]), 2);
  }
}

TEST(StabilityCli, BvpIndexChangesByOneAcrossEachFold) {
  expect_index_parity_follows_the_folds("bvp:points=60", "bvp");
}

TEST(StabilityCli, Bratu2dIndexChangesByOneAcrossEachFold) {
  expect_index_parity_follows_the_folds("bratu2d:N=12", "bratu2d");
}

// The truncated normal form of the fold–Hopf bifurcation (Kuznetsov, Elements of Applied
// Bifurcation Theory, §8.5): z' = μ₁ + z² + u² + v², (u + iv)' = (μ₂ + z + i)(u + iv). Its steady
// states u = v = 0, μ₁ = −z² fold along z = 0; there the eigenvalues are 2z and μ₂ + z ± i, so
// the Hopf curve μ₂ = −z (ω = 1) crosses the fold at the origin: a fold–Hopf point.
TEST(StabilityCli, FoldHopfPointOfTheNormalFormIsFoundOnTheHopfCurve) {
  const std::string dir = testing::temporary_directory("stability_cli_zero_hopf");
  {
    std::ofstream file(dir + "/zh.tsr");
    file << "name fold_hopf\nvariables z u v mu1 mu2\n"
            "equation mu1 + z^2 + u^2 + v^2\n"
            "equation (mu2 + z)*u - v\n"
            "equation u + (mu2 + z)*v\n"
            "start 0.1 0 0 -0.01 0.05\n"
            "box z -0.5 0.5\nbox u -1 1\nbox v -1 1\nbox mu1 -1 1\nbox mu2 -0.4 0.4\n"
            "dynamics parameters mu1 mu2\n";
  }
  const auto result = run_cli("mesh " + dir + "/zh.tsr --tolerance 0.002 --hopf -o " + dir +
                              "/zh.ply --summary " + dir + "/zh.json");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(contains(result.output, "1 fold–Hopf point(s)")) << result.output;
  const auto hopf = read_json(dir + "/zh.json").at("hopf");
  ASSERT_EQ(hopf.at("special_points").size(), 1u);
  const auto& zh = hopf.at("special_points")[0];
  EXPECT_EQ(zh.at("kind"), "zero_hopf");
  for (const std::string name : {"z", "u", "v", "mu1", "mu2"}) {
    EXPECT_NEAR(zh.at("point").at(name).get<double>(), 0.0, 1e-8) << name;
  }
  EXPECT_NEAR(zh.at("point").at("omega").get<double>(), 1.0, 1e-8);
  for (const auto& curve : hopf.at("curves")) {
    for (const auto& point : curve.at("points")) {  // z u v mu1 mu2 omega
      EXPECT_NEAR(point[4].get<double>(), -point[0].get<double>(), 1e-8);
      EXPECT_NEAR(point[5].get<double>(), 1.0, 1e-8);
    }
  }
}

// The Bautin normal form in real coordinates, r² = u² + v²:
//     u' = μ₁u − v + μ₂u r² − u r⁴,  v' = u + μ₁v + μ₂v r² − v r⁴.
// Its steady states u = v = 0 form the plane over (μ₁, μ₂); the Hopf curve is μ₁ = 0 (ω = 1). In
// w = u + iv, w' = (μ₁ + i)w + μ₂ w|w|²; with the unit eigenvector q = (1, −i)/√2, x = z q + z̄ q̄
// gives z = w/√2 and z' = (μ₁ + i)z + 2μ₂ z|z|², so l₁ = 2μ₂: supercritical below μ₂ = 0,
// subcritical above, and the Bautin point at the origin.
TEST(StabilityCli, BautinPointOfTheNormalFormAndTheSignsOfTheLyapunovCoefficient) {
  const std::string dir = testing::temporary_directory("stability_cli_bautin");
  {
    std::ofstream file(dir + "/gh.tsr");
    file << "name bautin\nvariables u v mu1 mu2\n"
            "equation mu1*u - v + mu2*u*(u^2 + v^2) - u*(u^2 + v^2)^2\n"
            "equation u + mu1*v + mu2*v*(u^2 + v^2) - v*(u^2 + v^2)^2\n"
            "start 0 0 0.05 0.05\n"
            "box u -1 1\nbox v -1 1\nbox mu1 -0.5 0.5\nbox mu2 -0.5 0.5\n"
            "dynamics parameters mu1 mu2\n";
  }
  const auto result = run_cli("mesh " + dir + "/gh.tsr --tolerance 0.002 --hopf -o " + dir +
                              "/gh.ply --summary " + dir + "/gh.json");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(contains(result.output, "1 Bautin point(s)")) << result.output;
  const auto hopf = read_json(dir + "/gh.json").at("hopf");
  EXPECT_GE(hopf.at("supercritical_points").get<int>(), 4);
  EXPECT_GE(hopf.at("subcritical_points").get<int>(), 4);
  int checked = 0;
  for (const auto& curve : hopf.at("curves")) {
    for (const auto& point : curve.at("points")) {  // u v mu1 mu2 omega l1
      EXPECT_NEAR(point[2].get<double>(), 0.0, 1e-9);
      EXPECT_NEAR(point[4].get<double>(), 1.0, 1e-9);
      EXPECT_NEAR(point[5].get<double>(), 2 * point[3].get<double>(), 1e-6);
      ++checked;
    }
  }
  EXPECT_GE(checked, 10);
  ASSERT_EQ(hopf.at("special_points").size(), 1u);
  const auto& bautin = hopf.at("special_points")[0];
  EXPECT_EQ(bautin.at("kind"), "bautin");
  EXPECT_NEAR(bautin.at("plane").at("mu1").get<double>(), 0.0, 1e-9);
  EXPECT_NEAR(bautin.at("plane").at("mu2").get<double>(), 0.0, 1e-6);
}

TEST(StabilityCli, LevelCurveOfTheSphereIsAClosedGreatCircle) {
  const std::string dir = testing::temporary_directory("stability_cli_level");
  const auto result = run_cli("mesh sphere --tolerance 0.005 --level x=0.6 -o " + dir +
                              "/s.ply --summary " + dir + "/s.json");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(std::filesystem::exists(dir + "/s.level.ply"));
  const auto level = read_json(dir + "/s.json").at("level");
  EXPECT_EQ(level.at("unrefined_points"), 0);
  ASSERT_EQ(level.at("curves").size(), 1u);
  EXPECT_TRUE(level.at("curves")[0].at("closed").get<bool>());
  for (const auto& point : level.at("curves")[0].at("points")) {  // the circle x = 0.6, r = 0.8
    EXPECT_NEAR(point[0].get<double>(), 0.6, 1e-9);
    EXPECT_NEAR(std::hypot(point[1].get<double>(), point[2].get<double>()), 0.8, 1e-9);
  }
}

TEST(StabilityCli, BadStabilityOptionsAreRefusedBeforeTheComputation) {
  const std::string dir = testing::temporary_directory("stability_cli_errors");
  struct Case {
    std::string arguments;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"mesh sphere --stability -o " + dir + "/s.ply", "'sphere' does not say what its equations"},
      {"mesh torus --hopf -o " + dir + "/s.ply", "--hopf: problem 'torus' does not say"},
      {"mesh cstr --hopf --hopf-output " + dir + "/h.txt -o " + dir + "/s.ply",
       "--hopf-output " + dir + "/h.txt: unknown extension"},
      {"mesh cstr --hopf-output " + dir + "/h.json -o " + dir + "/s.ply", "needs --hopf"},
      {"mesh cstr --diagram " + dir + "/d.jpg -o " + dir + "/s.ply", "a picture is .png or .svg"},
      {"mesh cstr --stability --eigenvalues 0 -o " + dir + "/s.ply", "--eigenvalues"},
      {"mesh cstr --level x1 -o " + dir + "/s.ply", "--level x1"},
      {"mesh cstr --level-output " + dir + "/l.csv -o " + dir + "/s.ply", "needs --level"},
      {"mesh cstr --summary " + dir + "/s.json --patches " + dir + "/s.json --method bezier -o " +
           dir + "/s.ply",
       "--patches " + dir + "/s.json is the file of --summary too"},
      {"mesh cstr --hopf --hopf-output " + dir + "/s.ply -o " + dir + "/s.ply",
       "--hopf-output " + dir + "/s.ply is the file of -o too"},
  };
  for (const Case& c : cases) {
    const auto result = run_cli(c.arguments);
    EXPECT_EQ(result.exit_code, kUsageError) << c.arguments << "\n" << result.output;
    EXPECT_TRUE(contains(result.output, c.message)) << c.arguments << "\n" << result.output;
    EXPECT_FALSE(std::filesystem::exists(dir + "/s.ply")) << c.arguments;
  }
}

}  // namespace
}  // namespace tessera
