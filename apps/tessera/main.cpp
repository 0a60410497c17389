// SPDX-License-Identifier: MIT
// The tessera command line tool: `tessera mesh`, `tessera problems`, `tessera check`.
// Exit codes: 0 success, 1 a computation failed (message says why), 2 usage error.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "ddt_command.h"
#include "improve_command.h"
#include "output_checks.h"
#include "tessera/core/error.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/io/mesh_io.h"
#include "tessera/io/summary_json.h"
#include "tessera/methods/front/advancing_front.h"
#include "tessera/methods/improvement/improve_mesh.h"
#include "tessera/problems/catalogue.h"

namespace {

constexpr int kComputationFailed = 1;

// CLI11's PositiveNumber lets NaN through; a step of NaN must be a usage error.
const CLI::Validator kFinitePositive(
    [](std::string& text) -> std::string {
      try {
        std::size_t used = 0;
        const double value = std::stod(text, &used);
        if (used == text.size() && std::isfinite(value) && value > 0) {
          return {};
        }
      } catch (const std::exception&) {
      }
      return "'" + text + "' is not a finite number > 0";
    },
    "POSITIVE", "finite positive number");
constexpr int kUsageError = 2;

std::vector<double> parse_numbers(const std::string& text, const std::string& option) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    std::size_t used = 0;
    double value = 0;
    try {
      value = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    while (used < item.size() && std::isspace(static_cast<unsigned char>(item[used]))) {
      ++used;
    }
    if (item.empty() || used != item.size()) {
      throw tessera::InvalidArgument(option + ": '" + item + "' is not a number (expected a "
                                     "comma-separated list such as 0,0,1)");
    }
    values.push_back(value);
  }
  return values;
}

struct MeshCommand {
  std::string problem;
  std::string method = "front";
  double step = 0.0;
  std::string start;
  std::string box;
  std::string output;
  std::string summary;
  bool ascii = false;
  bool quiet = false;
  int max_vertices = 2'000'000;
  double min_gap_degrees = 0.0;
  int max_valence = 0;
  double max_start_distance = 0.0;
  std::string order = "gap";
  std::string obj_coordinates;
  bool improve = false;
};

tessera::MeshReport make_report(const tessera::TriangleMesh& mesh,
                                const tessera::ProblemSetup& setup,
                                const std::string& problem_argument) {
  tessera::MeshReport report;
  report.problem = problem_argument;  // as the user spelled it, e.g. "torus:R=2"
  report.ambient_dimension = setup.problem->ambient_dimension();
  report.validation = tessera::validate(mesh);
  report.quality = tessera::measure_quality(mesh, *setup.problem);
  report.expected_euler_characteristic = setup.expected_euler_characteristic;
  report.exact_area = setup.exact_area;
  return report;
}

int run_mesh(const MeshCommand& command) {
  tessera::ProblemSetup setup = tessera::resolve_problem(command.problem);
  const int n = setup.problem->ambient_dimension();
  if (!command.start.empty()) {
    const auto values = parse_numbers(command.start, "--start");
    TESSERA_CHECK(static_cast<int>(values.size()) == n,
                  "--start has " << values.size() << " values, problem '" << setup.problem->name()
                                 << "' has n = " << n << " coordinates");
    setup.start = Eigen::Map<const Eigen::VectorXd>(values.data(), n);
  }
  if (!command.box.empty()) {
    const auto values = parse_numbers(command.box, "--box");
    TESSERA_CHECK(static_cast<int>(values.size()) == 2 * n,
                  "--box has " << values.size() << " values, expected " << 2 * n
                               << " (lower,upper for each of the " << n << " coordinates)");
    Eigen::VectorXd lower(n);
    Eigen::VectorXd upper(n);
    for (int i = 0; i < n; ++i) {
      lower(i) = values[2 * i];
      upper(i) = values[2 * i + 1];
    }
    setup.domain.intersect_with(
        tessera::Domain::box(lower, upper, setup.problem->coordinate_names()));
    // The catalogue's topology and area describe its own domain, not the user's box.
    setup.expected_euler_characteristic.reset();
    setup.exact_area.reset();
  }
  // Every option is checked before the computation starts.
  tessera::app::check_mesh_output(command.output);
  tessera::app::check_output_folder(command.summary);
  tessera::MeshFileOptions file_options;
  if (!command.obj_coordinates.empty()) {
    const auto values = parse_numbers(command.obj_coordinates, "--obj-coordinates");
    TESSERA_CHECK(values.size() == 3, "--obj-coordinates needs three coordinate indices, got "
                                          << values.size());
    for (int i = 0; i < 3; ++i) {
      TESSERA_CHECK(values[i] == std::floor(values[i]) && values[i] >= 0 && values[i] < n,
                    "--obj-coordinates: " << values[i] << " is not a coordinate index in [0, "
                                          << n - 1 << "]");
      file_options.obj_coordinates[i] = static_cast<int>(values[i]);
    }
  }
  TESSERA_CHECK(command.method == "front",
                "--method '" << command.method << "' is not available; methods: front");
  tessera::FrontOptions options;
  options.step = command.step > 0 ? command.step : setup.suggested_step;
  options.max_vertices = command.max_vertices;
  if (command.min_gap_degrees > 0) {
    options.min_gap_angle = command.min_gap_degrees * M_PI / 180.0;
  }
  if (command.max_valence > 0) {
    options.max_valence = command.max_valence;
  }
  options.order =
      command.order == "fifo" ? tessera::FrontOrder::Fifo : tessera::FrontOrder::SmallestGapFirst;
  if (command.max_start_distance > 0) {
    options.max_start_distance_steps = command.max_start_distance / options.step;
  }
  const bool show_progress = !command.quiet && isatty(STDERR_FILENO);
  if (show_progress) {
    options.progress = [](const tessera::CoveringProgress& p) {
      std::fprintf(stderr, "\r  %d vertices, %d triangles, front %d   ", p.vertex_count,
                   p.triangle_count, p.front_size);
    };
  }
  tessera::CoveringResult result =
      tessera::triangulate_by_front(*setup.problem, setup.start, setup.domain, options);
  if (show_progress) {
    std::fprintf(stderr, "\r%60s\r", "");
  }
  if (command.improve && result.summary.is_complete()) {
    // Delaunay-type swaps judged in the tangent planes, 3 passes of tangential smoothing, and
    // swaps again (docs/algorithms/improvement.md): validity and boundary are kept.
    tessera::improve_mesh(result.mesh, *setup.problem, tessera::ImprovementOptions{}, 3);
  }
  // Whatever happened, keep the work: write the mesh and the summary before reporting.
  file_options.binary = !command.ascii;
  // PLY keeps the standard names (x, y, z or x0 … x{n−1}) that readers look for; the problem's
  // own names go into a comment, and into the arrays of VTK files.
  const bool is_ply = command.output.size() >= 4 &&
                      command.output.compare(command.output.size() - 4, 4, ".ply") == 0;
  std::string names;
  for (const auto& name : setup.problem->coordinate_names()) {
    names += " " + name;
  }
  if (!is_ply) {
    file_options.coordinate_names = setup.problem->coordinate_names();
  }
  file_options.comments = {"tessera mesh " + command.problem + ", method " + command.method,
                           "coordinates:" + names};
  tessera::write_mesh(command.output, result.mesh, file_options);
  tessera::MeshReport report = make_report(result.mesh, setup, command.problem);
  report.run = result.summary;
  if (!command.summary.empty()) {
    tessera::write_summary_json(command.summary, report);
  }
  if (!command.quiet) {
    std::cout << tessera::to_text(report) << "wrote          " << command.output
              << (command.summary.empty() ? "" : " and " + command.summary) << "\n";
  }
  if (!result.summary.is_complete()) {
    std::cerr << "tessera: the " << command.method << " method stopped early ("
              << tessera::to_string(result.summary.termination)
              << "): " << result.summary.message << "\n"
              << "tessera: the partial mesh was written to " << command.output << "\n";
    return kComputationFailed;
  }
  if (!report.validation.is_valid()) {
    std::cerr << "tessera: the mesh is not valid:\n" << report.validation.report();
    return kComputationFailed;
  }
  return 0;
}

int run_problems() {
  for (const auto& entry : tessera::catalogue()) {
    std::cout << entry.name << std::string(entry.name.size() < 15 ? 15 - entry.name.size() : 1, ' ')
              << entry.summary;
    if (!entry.parameters.empty()) {
      std::cout << " [";
      for (std::size_t i = 0; i < entry.parameters.size(); ++i) {
        std::cout << (i ? ", " : "") << entry.parameters[i].name << "="
                  << entry.parameters[i].default_value;
      }
      std::cout << "]";
    }
    std::cout << "\n";
  }
  std::cout << "\nUse NAME:key=value,... to set parameters, e.g. tessera mesh torus:R=2,r=0.5\n"
               "or pass a problem file (see docs/problem-files.md).\n";
  return 0;
}

int run_check(const std::string& mesh_path, const std::string& problem, bool json) {
  const tessera::ProblemSetup setup = tessera::resolve_problem(problem);
  const tessera::TriangleMesh mesh = tessera::read_mesh(mesh_path);
  const tessera::MeshReport report = make_report(mesh, setup, problem);
  std::cout << (json ? tessera::to_json(report) : tessera::to_text(report));
  // A mesh passes the check if it is valid, has the known topology, and its vertices lie on
  // M (1e-6 leaves room for meshes written by other tools in single precision).
  bool passes = report.validation.is_valid();
  if (!passes) {
    std::cerr << "tessera: check failed: the mesh is not valid\n";
  }
  if (setup.expected_euler_characteristic &&
      report.validation.euler_characteristic != *setup.expected_euler_characteristic) {
    std::cerr << "tessera: check failed: Euler characteristic " << report.validation.euler_characteristic
              << ", but the surface of '" << problem << "' has "
              << *setup.expected_euler_characteristic << "\n";
    passes = false;
  }
  if (report.quality.vertex_distance.max > 1e-6 || report.quality.failed_projections > 0) {
    std::cerr << "tessera: check failed: vertices are not on M (max distance "
              << report.quality.vertex_distance.max << ", "
              << report.quality.failed_projections << " points could not be projected)\n";
    passes = false;
  }
  return passes ? 0 : kComputationFailed;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"tessera: trustworthy triangulations of implicitly defined surfaces F(x) = 0"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "tessera 0.1.0");

  MeshCommand mesh;
  auto* mesh_app = app.add_subcommand("mesh", "cover a problem's surface with a triangle mesh");
  mesh_app->add_option("problem", mesh.problem, "catalogue name (see `tessera problems`) or problem file")
      ->required();
  mesh_app->add_option("--method", mesh.method, "covering method")
      ->check(CLI::IsMember({"front"}));
  mesh_app->add_option("--step,-s", mesh.step, "edge length h (default: the problem's suggestion)")
      ->check(kFinitePositive);
  mesh_app->add_option("--start", mesh.start, "start point, comma separated, e.g. 0,0,1");
  mesh_app->add_option("--box", mesh.box,
                       "clip to a box: lower,upper for each coordinate, e.g. -1,1,-1,1,-0.8,1");
  mesh_app->add_option("-o,--output", mesh.output, "mesh file: .ply, .obj, .vtk or .vtu")
      ->required();
  mesh_app->add_option("--summary", mesh.summary, "write a JSON summary to this file");
  mesh_app->add_flag("--ascii", mesh.ascii, "write ASCII instead of binary PLY");
  mesh_app->add_flag("--improve", mesh.improve,
                     "improve the mesh: edge swaps and tangential smoothing on M (as `tessera "
                     "improve --smooth 3`)");
  mesh_app->add_option("--obj-coordinates", mesh.obj_coordinates,
                       "the three coordinates written to an .obj file, e.g. 0,2,3 (default 0,1,2)");
  mesh_app->add_flag("--quiet,-q", mesh.quiet, "print nothing but errors");
  mesh_app->add_option("--max-vertices", mesh.max_vertices, "stop after this many vertices")
      ->check(CLI::Range(7, 100'000'000));
  mesh_app->add_option("--min-gap-angle", mesh.min_gap_degrees,
                       "front: α_min in degrees (default 45.8)")
      ->check(CLI::Range(1.0, 89.0));
  mesh_app->add_option("--max-valence", mesh.max_valence,
                       "front: most triangles per vertex (paper: 6; default 7)")
      ->check(CLI::Range(6, 12));
  mesh_app->add_option("--order", mesh.order,
                       "front: 'gap' (smallest gap first, default) or 'fifo' (the paper's queue)")
      ->check(CLI::IsMember({"gap", "fifo"}));
  mesh_app->add_option("--max-start-distance", mesh.max_start_distance,
                       "how far the start may be from M (default: 10 steps)")
      ->check(kFinitePositive);

  app.add_subcommand("problems", "list the built-in catalogue");

  tessera::app::DdtCommand ddt;
  tessera::app::add_ddt_command(app, ddt);
  tessera::app::ImproveCommand improve;
  tessera::app::add_improve_command(app, improve);

  std::string check_mesh;
  std::string check_problem;
  bool check_json = false;
  auto* check_app = app.add_subcommand("check", "validate a mesh and measure it against M");
  check_app->add_option("mesh", check_mesh, "mesh file (.ply or .obj)")->required();
  check_app->add_option("--problem,-p", check_problem, "catalogue name or problem file")
      ->required();
  check_app->add_flag("--json", check_json, "print the report as JSON");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kUsageError;
  }
  try {
    if (app.got_subcommand("mesh")) {
      return run_mesh(mesh);
    }
    if (app.got_subcommand("problems")) {
      return run_problems();
    }
    if (app.got_subcommand("ddt")) {
      return tessera::app::run_ddt(ddt);
    }
    if (app.got_subcommand("improve")) {
      return tessera::app::run_improve(improve);
    }
    return run_check(check_mesh, check_problem, check_json);
  } catch (const tessera::InvalidArgument& e) {
    std::cerr << "tessera: error: " << e.what() << "\n";
    return kUsageError;
  } catch (const tessera::ComputationFailed& e) {
    std::cerr << "tessera: failed: " << e.what() << "\n";
    return kComputationFailed;
  } catch (const std::exception& e) {
    std::cerr << "tessera: failed: " << e.what() << "\n";
    return kComputationFailed;
  }
}
