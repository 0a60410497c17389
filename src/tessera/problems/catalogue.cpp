// SPDX-License-Identifier: MIT
// The built-in catalogue: each entry pairs an example problem with a start, a domain and what is
// known about the component of M ∩ S that contains the start.
#include "tessera/problems/catalogue.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <utility>

#include "tessera/core/error.h"
#include "tessera/problems/examples.h"
#include "tessera/problems/problem_file.h"

namespace tessera {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

Eigen::VectorXd vector3(double x, double y, double z) {
  Eigen::VectorXd v(3);
  v << x, y, z;
  return v;
}

Domain box3(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
            const ImplicitProblem& problem) {
  return Domain::box(lower, upper, problem.coordinate_names());
}

// --- Entries ---------------------------------------------------------------------------------

// Surfaces written in the problem-file language (exact derivatives by reverse-mode AD).
ProblemSetup make_flat_torus(const ParameterValues& /*values*/) {
  // The Clifford torus: the product of two unit circles, a flat torus in R^4 (χ = 0,
  // area (2π)², every normal curvature 1 in the directions of the circles).
  return parse_problem(
      "name flat_torus\n"
      "description flat torus x1²+x2² = 1, x3²+x4² = 1 in R^4\n"
      "variables x1 x2 x3 x4\n"
      "equation x1^2 + x2^2 - 1\n"
      "equation x3^2 + x4^2 - 1\n"
      "start 1 0 1 0\n"
      "step 0.3\n"
      "euler 0\n"
      "area 39.47841760435743\n",
      "catalogue:flat_torus");
}

ProblemSetup make_crossing(const ParameterValues& /*values*/) {
  // Two sheets that cross transversally along the circle x² + y² = 1, z = 0, where DF = 0:
  // Henderson's section 8. From the start on the sphere the atlas covers the sphere (χ = 2).
  return parse_problem(
      "name crossing\n"
      "description plane z = 0 through the unit sphere: z(x²+y²+z²−1) = 0\n"
      "variables x y z\n"
      "equation z*(x^2 + y^2 + z^2 - 1)\n"
      "start 0.3 0.2 0.9\n"
      "step 0.2\n"
      "box x -1.5 1.5\n"
      "box y -1.5 1.5\n"
      "box z -1.5 1.5\n"
      "euler 2\n"
      "area 12.566370614359172\n",
      "catalogue:crossing");
}

ProblemSetup make_two_spheres(const ParameterValues& /*values*/) {
  // Two disjoint spheres of radius 1/2 about (±1, 0, 0): the product of their equations, whose
  // gradient on one sphere is the other's (nonzero) value times its own. Two components, each
  // χ = 2; the start lies on the one at x = +1 (tessera mesh --components all finds both).
  return parse_problem(
      "name two_spheres\n"
      "description two spheres of radius 1/2 about (±1, 0, 0): "
      "((x-1)²+y²+z²−1/4)((x+1)²+y²+z²−1/4) = 0\n"
      "variables x y z\n"
      "equation ((x - 1)^2 + y^2 + z^2 - 0.25)*((x + 1)^2 + y^2 + z^2 - 0.25)\n"
      "start 1 0 0.5\n"
      "step 0.15\n"
      "box x -2 2\n"
      "box y -1 1\n"
      "box z -1 1\n"
      "euler 2\n"
      "area 3.141592653589793\n",
      "catalogue:two_spheres");
}

ProblemSetup make_torus_and_sphere(const ParameterValues& /*values*/) {
  // The catalogue's torus (R = 1, r = 0.4, about the x axis) with a sphere of radius 0.3 in its
  // hole, 0.3 from the torus: the product of the two equations. Two components, χ = 0 and 2;
  // the start lies on the torus (Hohmann's guess).
  return parse_problem(
      "name torus_and_sphere\n"
      "description torus R = 1, r = 0.4 about the x axis and a sphere of radius 0.3 in its "
      "hole: ((|x|²+0.84)² − 4(y²+z²))(|x|² − 0.09) = 0\n"
      "variables x y z\n"
      "equation ((x^2 + y^2 + z^2 + 0.84)^2 - 4*(y^2 + z^2))*(x^2 + y^2 + z^2 - 0.09)\n"
      "start -0.4 1 0.1\n"
      "step 0.1\n"
      "box x -1 1\n"
      "box y -1.6 1.6\n"
      "box z -1.6 1.6\n"
      "euler 0\n"
      "area 15.791367041742973\n",
      "catalogue:torus_and_sphere");
}

ProblemSetup make_plane(const ParameterValues& /*values*/) {
  ProblemSetup setup;
  setup.problem = std::make_unique<Plane>();
  setup.start = vector3(0.0, 0.0, 0.0);
  setup.domain = box3(vector3(-1, -1, -kInfinity), vector3(1, 1, kInfinity), *setup.problem);
  setup.suggested_step = 0.2;
  setup.expected_euler_characteristic = 1;  // a square
  setup.exact_area = 4.0;
  return setup;
}

ProblemSetup make_sphere(const ParameterValues& values) {
  const double r = values.at("radius");
  ProblemSetup setup;
  setup.problem = std::make_unique<Sphere>(r);
  setup.start = vector3(0.0, 0.0, r);
  setup.domain = Domain(3);
  setup.suggested_step = 0.3 * r;
  setup.expected_euler_characteristic = 2;
  setup.exact_area = 4.0 * std::numbers::pi * r * r;
  return setup;
}

ProblemSetup make_sphere_cut(const ParameterValues& values) {
  const double r = values.at("radius");
  const double cut = values.at("cut");
  ProblemSetup setup;
  setup.problem = std::make_unique<Sphere>(r);
  TESSERA_CHECK(cut > -r && cut < r,
                "sphere_cut cut = " << cut << " must lie in (-radius, radius) = (" << -r << ", "
                                    << r << ") so that z >= cut is a cap");
  setup.start = vector3(0.0, 0.0, r);
  setup.domain = Domain(3);
  std::ostringstream label;
  label << "z >= " << cut;
  setup.domain.add_half_space(vector3(0, 0, 1), vector3(0, 0, cut), label.str());
  setup.suggested_step = 0.3 * r;
  setup.expected_euler_characteristic = 1;       // a spherical cap is a disk
  setup.exact_area = 2.0 * std::numbers::pi * r * (r - cut);  // Archimedes: the area of a zone is 2πr·height
  return setup;
}

ProblemSetup make_torus(const ParameterValues& values) {
  const double R = values.at("R");
  const double r = values.at("r");
  ProblemSetup setup;
  setup.problem = std::make_unique<Torus>(R, r);
  // Hohmann's initial guess (−0.4, 1.0, 0.1) for R = 1, r = 0.4, scaled with the radii: about
  // r away from the core circle, so within the corrector's reach but not on M.
  setup.start = vector3(-r, R, 0.25 * r);
  setup.domain = Domain(3);
  setup.suggested_step = 0.25 * r;
  setup.expected_euler_characteristic = 0;
  setup.exact_area = 4.0 * std::numbers::pi * std::numbers::pi * R * r;  // Pappus: 2πr · 2πR
  return setup;
}

ProblemSetup make_equipotential(const ParameterValues& values) {
  const double c = values.at("c");
  ProblemSetup setup;
  setup.problem = std::make_unique<Equipotential>(c, values.at("qy"));
  // Hohmann's guess (0, −0.8, 0) for c = 1.7; the surface crosses the negative y axis near
  // y = −1/√c, so the guess is scaled accordingly for other levels.
  setup.start = vector3(0.0, -0.8 * std::sqrt(1.7 / c), 0.0);
  setup.domain = Domain(3);
  setup.suggested_step = 0.15;  // the neck between the charges has radius ≈ 0.42 for c = 1.7
  // F decreases along every ray away from the y axis, so each component is a surface of
  // revolution meeting the axis twice: a sphere, whether the two blobs are joined or not.
  setup.expected_euler_characteristic = 2;
  return setup;
}

ProblemSetup make_whitney_pleat(const ParameterValues& /*values*/) {
  ProblemSetup setup;
  setup.problem = std::make_unique<WhitneyPleat>();
  setup.start = vector3(0.1, 0.1, 0.1);
  setup.domain = box3(vector3(-1.5, -1.5, -1.5), vector3(1.5, 1.5, 1.5), *setup.problem);
  setup.suggested_step = 0.1;
  // M ∩ box is the graph of μ = x³ − λx over {(x, λ) ∈ [−1.5, 1.5]² : |x³ − λx| ≤ 1.5}. For fixed
  // x the allowed λ form the interval [x² − 1.5/|x|, x² + 1.5/|x|] ∩ [−1.5, 1.5], never empty
  // (x² − 1.5/|x| ≤ 1.25): the region is a closed disk.
  setup.expected_euler_characteristic = 1;
  return setup;
}

// True if, for ε > 0, the quintic h(z) = F(X, y, z) has exactly one root z > 0. Then the z > 0
// part of M ∩ {|x| ≤ X} is a single arc (times the y interval): the curve z·g(x, z) = −ε has no
// closed loops in z > 0, because z·g has critical points there only on x = 0, where it is > 0.
bool trough_has_single_upper_arc(double a, double b, double epsilon, double X) {
  if (!(epsilon > 0.0)) {
    return false;
  }
  const auto h = [&](double z) { return z * (a * a * z * z * (b * b - z * z) - X * X) + epsilon; };
  // h'(z) = −5a²z⁴ + 3a²b²z² − X²: a quadratic in w = z². h(0) = ε > 0 and h → −∞, so h has
  // three positive roots exactly when its local minimum is < 0 and its local maximum is > 0.
  const double discriminant = 9.0 * std::pow(a, 4) * std::pow(b, 4) - 20.0 * a * a * X * X;
  if (discriminant <= 0.0) {
    return true;  // h is decreasing on z > 0
  }
  const double w_min = (3.0 * a * a * b * b - std::sqrt(discriminant)) / (10.0 * a * a);
  const double w_max = (3.0 * a * a * b * b + std::sqrt(discriminant)) / (10.0 * a * a);
  const double local_min = h(std::sqrt(w_min));
  const double local_max = h(std::sqrt(w_max));
  return local_min > 0.0 || local_max < 0.0;
}

ProblemSetup make_trough(const ParameterValues& values) {
  const double a = values.at("a");
  const double b = values.at("b");
  const double epsilon = values.at("epsilon");
  constexpr double kHalfWidthX = 0.15;  // Brodzik & Rheinboldt's bounding hyperplanes
  constexpr double kHalfWidthY = 0.14;
  ProblemSetup setup;
  setup.problem = std::make_unique<Trough>(a, b, epsilon);
  // At (0, 0, b) F = ε and ∂F/∂z = −2a²b⁴ < 0: the corrector moves up onto the arch (z > 0).
  setup.start = vector3(0.0, 0.0, b);
  setup.domain = box3(vector3(-kHalfWidthX, -kHalfWidthY, -kInfinity),
                      vector3(kHalfWidthX, kHalfWidthY, kInfinity), *setup.problem);
  setup.suggested_step = 0.03;
  if (trough_has_single_upper_arc(a, b, epsilon, kHalfWidthX)) {
    setup.expected_euler_characteristic = 1;  // the arch: an arc times an interval
  }
  return setup;
}

// M is the graph x₂ = B x₁/(1+β), Da = x₁e^{−x₂}/(1−x₁) over (x₁, B). For β ≥ 0.5 the bound
// x₂ ≤ 8 is implied by x₁ ≤ 1, B ≤ 12, and for fixed x₁ the box leaves the B-interval
// [max(1, L(x₁)), 12] with L(x₁) = ((1+β)/x₁)·ln(x₁/(0.3(1−x₁))) from Da ≤ 0.3. The region is a
// disk iff {x₁ : L(x₁) ≤ 12} is an interval, i.e. q(x₁) = k x₁ − ln(x₁/(0.3(1−x₁))), k = 12/(1+β),
// is ≥ 0 on an interval. q' = k − 1/(x₁(1−x₁)): q is decreasing for k ≤ 4, otherwise it decreases,
// increases, decreases, and it suffices that its local minimum is positive.
bool stirred_tank_region_is_disk(double beta) {
  if (beta < 0.5) {
    return false;  // x₂ ≤ 8 can cut the graph; not analysed
  }
  const double k = 12.0 / (1.0 + beta);
  if (k <= 4.0) {
    return true;
  }
  const double x_min = 0.5 * (1.0 - std::sqrt(1.0 - 4.0 / k));
  return k * x_min - std::log(x_min / (0.3 * (1.0 - x_min))) > 0.0;
}

ProblemSetup make_cstr(const ParameterValues& values) {
  const double beta = values.at("beta");
  ProblemSetup setup;
  setup.problem = std::make_unique<StirredTankReactor>(beta);
  Eigen::VectorXd start(4), lower(4), upper(4);
  start << 0.1, 0.1, 0.1, 5.0;  // Hohmann's initial guess, not on M
  lower << 0.02, 0.0, 0.0, 1.0;
  upper << 1.0, 8.0, 0.3, 12.0;
  setup.start = start;
  setup.domain = Domain::box(lower, upper, setup.problem->coordinate_names());
  setup.suggested_step = 0.1;  // area ≈ 44 for β = 0.5; Da spans only [0, 0.3]
  if (stirred_tank_region_is_disk(beta)) {
    setup.expected_euler_characteristic = 1;
  }
  return setup;
}

ProblemSetup make_bvp(const ParameterValues& values) {
  const double points = values.at("points");
  TESSERA_CHECK(points >= 1 && points <= 1e8 && points == std::floor(points),
                "bvp points = " << points << " must be a whole number in [1, 1e8]");
  const int N = static_cast<int>(points);
  auto problem = std::make_unique<ArrheniusBratu>(N);
  ProblemSetup setup;
  // Start on the middle sheet of the fold, between the ignition and extinction folds of the
  // ε = 0.2 branch (λ ≈ 4.2), well inside the domain; computed to full precision.
  setup.start = problem->point_with_amplitude(5.0, 0.2);
  // λ ∈ [0.5, 10], ε ∈ [0, 0.3] and max u ≤ 20, which keeps exp(u/(1+εu)) ≤ e²⁰ even at ε = 0 and
  // still contains the cusp (ε ≈ 0.2457, max u ≈ 4.9) and the extinction fold for ε ≳ 0.19. On M
  // the profile is positive, symmetric and largest at the middle point, so bounding that one
  // coordinate bounds them all: 5 half-spaces instead of a box's 2N + 4, each an n-vector.
  const int middle = (N - 1) / 2;
  const auto names = problem->coordinate_names();
  setup.domain = Domain(N + 2);
  const auto add_bound = [&](int coordinate, double bound, bool is_lower) {
    Eigen::VectorXd normal = Eigen::VectorXd::Zero(N + 2);
    Eigen::VectorXd point = Eigen::VectorXd::Zero(N + 2);
    normal(coordinate) = is_lower ? 1.0 : -1.0;
    point(coordinate) = bound;
    std::ostringstream label;
    label << names[coordinate] << (is_lower ? " >= " : " <= ") << bound;
    setup.domain.add_half_space(normal, point, label.str());
  };
  add_bound(N, 0.5, true);
  add_bound(N, 10.0, false);
  add_bound(N + 1, 0.0, true);
  add_bound(N + 1, 0.3, false);
  add_bound(middle, 20.0, false);
  // Lengths are measured in the problem's metric (u weighted by √h, the discrete L² norm), so
  // they do not grow with N and neither does the step.
  setup.suggested_step = 0.1;
  // M is a graph over (max u, ε). Scans of λ along max u ∈ [0, 20] for ε = 0, 0.01, …, 0.3 and
  // N = 5, 20, 100 show that {0.5 ≤ λ ≤ 10} is one interval on every such line: M ∩ S is a disk.
  setup.expected_euler_characteristic = 1;
  setup.problem = std::move(problem);
  return setup;
}

ProblemSetup make_bratu2d(const ParameterValues& values) {
  const double grid_size = values.at("N");
  TESSERA_CHECK(grid_size >= 1 && grid_size <= ArrheniusBratu2D::kMaxGridSize &&
                    grid_size == std::floor(grid_size),
                "bratu2d N = " << grid_size << " must be a whole number in [1, "
                               << ArrheniusBratu2D::kMaxGridSize << "] (n = N² + 2 unknowns)");
  const int N = static_cast<int>(grid_size);
  auto problem = std::make_unique<ArrheniusBratu2D>(N);
  ProblemSetup setup;
  // Start on the middle sheet of the fold, between the ignition (u_c ≈ 2.9) and extinction
  // (u_c ≈ 18) folds of the ε = 0.2 branch (λ ≈ 8.4), computed to full precision.
  setup.start = problem->point_with_amplitude(6.0, 0.2);
  // λ ∈ [0.5, 20], ε ∈ [0, 0.3] and u_c ≤ 20: contains the ignition fold for every ε, the
  // extinction fold for ε ≳ 0.19 and the cusp (ε ≈ 0.242, u_c ≈ 6, λ ≈ 10.2); λ stays below 19
  // on M ∩ {u_c ≤ 20, ε ≤ 0.3}, so the face λ = 20 is never reached. Positive solutions are
  // largest at the centre, so bounding u_c bounds every u_ij: 5 half-spaces instead of a box's
  // 2N² + 4.
  const int centre = problem->centre_index();
  const int n = N * N + 2;
  const auto names = problem->coordinate_names();
  setup.domain = Domain(n);
  const auto add_bound = [&](int coordinate, double bound, bool is_lower) {
    Eigen::VectorXd normal = Eigen::VectorXd::Zero(n);
    Eigen::VectorXd point = Eigen::VectorXd::Zero(n);
    normal(coordinate) = is_lower ? 1.0 : -1.0;
    point(coordinate) = bound;
    std::ostringstream label;
    label << names[coordinate] << (is_lower ? " >= " : " <= ") << bound;
    setup.domain.add_half_space(normal, point, label.str());
  };
  add_bound(n - 2, 0.5, true);
  add_bound(n - 2, 20.0, false);
  add_bound(n - 1, 0.0, true);
  add_bound(n - 1, 0.3, false);
  add_bound(centre, 20.0, false);
  // A length in the metric of the coordinate blocks (u weighted by h, so that h‖u‖ is the L²
  // norm on the unit square), the metric in which tessera measures M: unlike the 1-D bvp's
  // Euclidean step it does not grow with N. In that metric M ∩ S has an area of ≈ 130 (N = 15;
  // λ spans [0.5, 19], ‖u‖_L² reaches ≈ 10, ε only 0.3, so that 0.1 puts three edges across
  // the strip near u = 0 where ε hardly matters): by that area a covering has a few thousand to
  // 10⁴ vertices, one to three minutes at the default N = 32 if a vertex costs 2–5
  // factorisations of the bordered n×n Jacobian (≈ 2 ms each there, ≈ 30 ms at N = 100,
  // ≈ 0.5 s at N = 316; bench/history/RESULTS-log.md section 9). An estimate: the coverings do not
  // measure in the weighted metric yet.
  setup.suggested_step = 0.1;
  // M is a graph over (u_c, ε) (point_with_amplitude's bordered Newton system is regular along
  // every line scanned). Scans of λ along u_c ∈ [0, 20] every 0.25 for ε = 0, 0.01, …, 0.3 at
  // N = 5 and 15, and ε = 0, 0.05, …, 0.3 at N = 32 (bench/bratu2d_folds.cpp, mode `disk`), show
  // that {0.5 ≤ λ ≤ 20} is one interval on every such line: M ∩ S is a disk.
  setup.expected_euler_characteristic = 1;
  setup.problem = std::move(problem);
  return setup;
}

// --- Parsing ---------------------------------------------------------------------------------

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) {
    return {};
  }
  const auto last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

// "key=value,key=value" → values; `owner` names the problem or file in messages. Checks the form,
// duplicates and that each value is a finite number; the caller checks the keys.
std::map<std::string, double> parse_assignments(const std::string& text, const std::string& owner) {
  std::map<std::string, double> values;
  std::istringstream assignments(text);
  std::string assignment;
  while (std::getline(assignments, assignment, ',')) {
    const auto equals = assignment.find('=');
    TESSERA_CHECK(equals != std::string::npos, "problem '" << owner << "': '" << trim(assignment)
                                                           << "' is not of the form key=value");
    const std::string key = trim(assignment.substr(0, equals));
    const std::string number = trim(assignment.substr(equals + 1));
    char* end = nullptr;
    const double value = std::strtod(number.c_str(), &end);
    TESSERA_CHECK(!number.empty() && end == number.c_str() + number.size() && std::isfinite(value),
                  "problem '" << owner << "': parameter '" << key << "' = '" << number
                              << "' is not a finite number");
    TESSERA_CHECK(values.emplace(key, value).second,
                  "problem '" << owner << "': parameter '" << key << "' is given twice");
  }
  return values;
}

std::string known_names() {
  std::ostringstream out;
  for (std::size_t i = 0; i < catalogue().size(); ++i) {
    out << (i ? ", " : "") << catalogue()[i].name;
  }
  return out.str();
}

const CatalogueEntry* find_entry(const std::string& name) {
  for (const CatalogueEntry& entry : catalogue()) {
    if (entry.name == name) {
      return &entry;
    }
  }
  return nullptr;
}

std::string parameter_list(const CatalogueEntry& entry) {
  if (entry.parameters.empty()) {
    return "it has no parameters";
  }
  std::ostringstream out;
  out << "its parameters are: ";
  for (std::size_t i = 0; i < entry.parameters.size(); ++i) {
    out << (i ? ", " : "") << entry.parameters[i].name;
  }
  return out.str();
}

// "torus R=1 r=0.4: torus (|x|²+R²−r²)² − … about the x axis"
std::string describe(const std::string& name, const std::string& summary,
                     const std::vector<CatalogueParameter>& parameters,
                     const ParameterValues& values) {
  std::ostringstream out;
  out << name;
  for (const CatalogueParameter& parameter : parameters) {
    out << ' ' << parameter.name << '=' << values.at(parameter.name);
  }
  out << ": " << summary;
  return out.str();
}

using Factory = ProblemSetup (*)(const ParameterValues&);

CatalogueEntry make_entry(std::string name, std::string summary,
                          std::vector<CatalogueParameter> parameters, Factory factory) {
  CatalogueEntry entry{name, summary, parameters, {}};
  entry.make = [factory, name = std::move(name), summary = std::move(summary),
                parameters = std::move(parameters)](const ParameterValues& values) {
    ProblemSetup setup = factory(values);
    setup.description = describe(name, summary, parameters, values);
    return setup;
  };
  return entry;
}

}  // namespace

const std::vector<CatalogueEntry>& catalogue() {
  static const std::vector<CatalogueEntry> entries = {
      make_entry("plane", "the plane z = 0 over the square [-1, 1]² (flat; the simplest test)", {},
                 make_plane),
      make_entry("sphere", "sphere |x|² − r² = 0", {{"radius", 1.0, "radius r"}}, make_sphere),
      make_entry("sphere_cut",
                 "sphere |x|² − r² = 0 cut by the half-space z ≥ cut (Brodzik & Rheinboldt, "
                 "fig. 5.1)",
                 {{"radius", 1.0, "radius r"}, {"cut", -0.8, "height of the cutting plane"}},
                 make_sphere_cut),
      make_entry("torus", "torus (|x|²+R²−r²)² − 4R²(y²+z²) = 0 about the x axis (Hohmann)",
                 {{"R", 1.0, "major radius"}, {"r", 0.4, "minor radius, 0 < r < R"}}, make_torus),
      make_entry("equipotential",
                 "equipotential 1/|x−p|² + 1/|x−q|² = c of charges at p = 0, q = (0, qy, 0) "
                 "(Bloomenthal, Hohmann)",
                 {{"c", 1.7, "potential level"}, {"qy", 2.0, "y coordinate of the second charge"}},
                 make_equipotential),
      make_entry("whitney_pleat",
                 "Whitney pleat x³ − λx − μ = 0 in the box [-1.5, 1.5]³ (cusp catastrophe)", {},
                 make_whitney_pleat),
      make_entry("trough",
                 "trough z(a²z²(b²−z²) − x²) + ε = 0, |x| ≤ 0.15, |y| ≤ 0.14 (Melville & Mackey); "
                 "the start lies on the arch above z = 0",
                 {{"a", 4.0, "lobe width factor"},
                  {"b", 0.25, "lobe height"},
                  {"epsilon", 5e-5, "opening of the trough"}},
                 make_trough),
      make_entry("cstr",
                 "steady states of a stirred tank reactor in (x1, x2, Da, B) (Hohmann, after "
                 "Uppal, Ray & Poore)",
                 {{"beta", 0.5, "heat transfer coefficient"}}, make_cstr),
      make_entry("flat_torus", "flat (Clifford) torus x1²+x2² = 1, x3²+x4² = 1 in R^4", {},
                 make_flat_torus),
      make_entry("crossing",
                 "plane through a sphere, z(x²+y²+z²−1) = 0: two sheets crossing along a "
                 "circle (Henderson section 8); the start lies on the sphere",
                 {}, make_crossing),
      make_entry("two_spheres",
                 "two disjoint spheres of radius 1/2 about (±1, 0, 0) in [-2, 2]×[-1, 1]²: two "
                 "components (--components all)",
                 {}, make_two_spheres),
      make_entry("torus_and_sphere",
                 "torus R = 1, r = 0.4 about the x axis with a sphere of radius 0.3 in its "
                 "hole: two components, χ 0 and 2 (--components all); the start lies on the "
                 "torus",
                 {}, make_torus_and_sphere),
      make_entry("bvp",
                 "Gelfand–Bratu u'' + λ exp(u/(1+εu)) = 0, u(0) = u(1) = 0 on N points, "
                 "coordinates (u1…uN, lambda, epsilon); sparse J; a fold surface with a cusp",
                 {{"points", 100.0, "number N of interior grid points; n = N + 2"}}, make_bvp),
      make_entry("bratu2d",
                 "Gelfand–Bratu Δu + λ exp(u/(1+εu)) = 0 on the unit square, u = 0 on its "
                 "boundary, N×N grid, coordinates (u_1_1…u_N_N, lambda, epsilon); sparse J; a "
                 "fold surface with a cusp",
                 {{"N", 32.0, "interior grid points per side, 1 … 1000; n = N² + 2"}},
                 make_bratu2d),
  };
  return entries;
}

ProblemSetup make_catalogue_problem(const std::string& specification) {
  const auto colon = specification.find(':');
  const std::string name = trim(specification.substr(0, colon));
  const CatalogueEntry* entry = find_entry(name);
  TESSERA_CHECK(entry != nullptr,
                "unknown problem '" << name << "'; known problems: " << known_names());

  ParameterValues values;
  for (const CatalogueParameter& parameter : entry->parameters) {
    values[parameter.name] = parameter.default_value;
  }
  if (colon != std::string::npos) {
    for (const auto& [key, value] : parse_assignments(specification.substr(colon + 1), name)) {
      TESSERA_CHECK(values.count(key) != 0, "problem '" << name << "' has no parameter '" << key
                                                        << "'; " << parameter_list(*entry));
      values[key] = value;
    }
  }
  return entry->make(values);
}

ProblemSetup resolve_problem(const std::string& name_or_file) {
  std::error_code error;
  if (std::filesystem::is_regular_file(name_or_file, error)) {
    return load_problem_file(name_or_file);
  }
  // "path:key=value,…" overrides parameters of a problem file, as for catalogue entries.
  const auto colon = name_or_file.find(':');
  const std::string name = trim(name_or_file.substr(0, colon));
  if (colon != std::string::npos && std::filesystem::is_regular_file(name, error)) {
    return load_problem_file(name, parse_assignments(name_or_file.substr(colon + 1), name));
  }
  // A name that looks like a path was most likely meant as a file: say so rather than only
  // listing the catalogue.
  TESSERA_CHECK(find_entry(name) != nullptr || name.find_first_of("/.\\") == std::string::npos,
                "'" << name_or_file << "' is neither an existing file nor a catalogue problem ("
                    << known_names() << ")");
  return make_catalogue_problem(name_or_file);
}

}  // namespace tessera
