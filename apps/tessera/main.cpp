// SPDX-License-Identifier: MIT
// The tessera command line tool: `tessera mesh`, `tessera problems`, `tessera check`.
// Exit codes: 0 success, 1 a computation failed (message says why), 2 usage error.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>

#include "checkpoint_command.h"
#include "cli_support.h"
#include "compare_command.h"
#include "ddt_command.h"
#include "improve_command.h"
#include "mesh_command.h"
#include "picture_command.h"
#include "solver_backend.h"
#include "tessera/core/error.h"
#include "tessera/core/parallel_for.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/io/mesh_io.h"
#include "tessera/problems/catalogue.h"
#include "tessera/problems/view.h"
#include "tessera/report/mesh_report.h"
#include "tessera/report/problem_record.h"
#include "tessera/report/summary_json.h"

namespace {

using tessera::app::kComputationFailed;
using tessera::app::kUsageError;

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

// The problem of `tessera check`: --problem, else the one the file's comment records (`tessera
// mesh` and `improve` write it), said on stdout (on stderr with --json, whose stdout is JSON).
tessera::ProblemSetup check_problem_setup(const std::string& mesh_path, std::string& problem,
                                          bool json) {
  if (!problem.empty()) {
    return tessera::resolve_problem(problem);
  }
  const auto recorded = tessera::find_recorded_problem(tessera::read_mesh_comments(mesh_path));
  TESSERA_CHECK(recorded.has_value(),
                "check " << mesh_path << ": give the problem with --problem: the file records "
                         << "none (`tessera mesh` and `tessera improve` name it in a comment of "
                            ".ply, .vtk and .vtu files; .obj and .npy files and the files of "
                            "other tools have no place for it)");
  tessera::ProblemSetup setup = tessera::resolve_recorded_problem(*recorded, mesh_path);
  problem = recorded->specification;
  (json ? std::cerr : std::cout) << (json ? "tessera: " : "") << "problem: " << problem
                                 << (recorded->box.empty() ? "" : ", box " + recorded->box)
                                 << " (from the file's comment)\n";
  return setup;
}

int run_check(const std::string& mesh_path, std::string problem, bool json) {
  const tessera::TriangleMesh mesh = tessera::read_mesh(mesh_path);
  const tessera::ProblemSetup setup = check_problem_setup(mesh_path, problem, json);
  const int n = setup.problem->ambient_dimension();
  if (mesh.ambient_dimension() != n) {
    // A view (tessera mesh --view, the default for n > 50) has lost the coordinates that
    // `check` measures M in; say where they are.
    throw tessera::InvalidArgument(
        "the mesh in '" + mesh_path + "' is in R^" + std::to_string(mesh.ambient_dimension()) +
        " but problem '" + problem + "' is in R^" + std::to_string(n) +
        (mesh.ambient_dimension() < n
             ? "; a mesh written in a view (tessera mesh --view, and by default for n > " +
                   std::to_string(tessera::kLargeAmbientDimension) +
                   ") holds the view's functionals, not the states: check the states file of "
                   "--states (FILE.npy) or a mesh written with --view all"
             : ""));
  }
  const tessera::MeshReport report = tessera::make_report(mesh, setup, problem);
  std::cout << (json ? tessera::to_json(report) : tessera::to_text(report));
  // A mesh passes the check if it is valid, has the known topology, and its vertices lie on
  // M (1e-6 leaves room for meshes written by other tools in single precision).
  bool passes = report.validation.is_valid();
  if (!passes) {
    // Every defect kind with its examples (indices and coordinates), not only the first.
    std::cerr << "tessera: check failed: the mesh is not valid:\n" << report.validation.report();
  }
  if (setup.expected_euler_characteristic &&
      report.validation.euler_characteristic != *setup.expected_euler_characteristic) {
    std::cerr << "tessera: check failed: Euler characteristic "
              << report.validation.euler_characteristic << ", but the surface of '" << problem
              << "' has " << *setup.expected_euler_characteristic << "\n";
    passes = false;
  }
  if (report.quality.vertex_distance.max > 1e-6 || report.quality.failed_projections > 0) {
    std::cerr << "tessera: check failed: vertices are not on M (max distance "
              << report.quality.vertex_distance.max << ", " << report.quality.failed_projections
              << " points could not be projected)\n";
    passes = false;
  }
  return passes ? 0 : kComputationFailed;
}

}  // namespace

int main(int argc, char** argv) {
  tessera::app::become_petsc_program_if_asked(argc, argv);
  CLI::App app{"tessera: trustworthy triangulations of implicitly defined surfaces F(x) = 0"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "tessera 0.1.0");

  tessera::app::MeshCommand mesh;
  tessera::app::add_mesh_command(app, mesh);

  app.add_subcommand("problems", "list the built-in catalogue");

  tessera::app::CompareCommand compare;
  tessera::app::add_compare_command(app, compare);
  tessera::app::DdtCommand ddt;
  tessera::app::add_ddt_command(app, ddt);
  tessera::app::ImproveCommand improve;
  tessera::app::RenderCommand render;
  tessera::app::add_improve_command(app, improve);
  tessera::app::add_render_command(app, render);
  tessera::app::ResumeCommand resume;
  tessera::app::add_resume_command(app, resume);
  tessera::app::ExtendCommand extend;
  tessera::app::add_extend_command(app, extend);

  std::string check_mesh;
  std::string check_problem;
  bool check_json = false;
  auto* check_app = app.add_subcommand("check", "validate a mesh and measure it against M");
  check_app
      ->add_option("mesh", check_mesh,
                   "mesh file (.ply, .obj, .vtk or .vtu) or the states of `mesh --states` (.npy)")
      ->required();
  check_app->add_option("--problem,-p", check_problem,
                        "catalogue name or problem file (default: the problem the file's comment "
                        "records, as `tessera mesh` and `improve` write it)");
  check_app->add_flag("--json", check_json, "print the report as JSON");

  // Every command takes --threads (docs/threads.md): the data-parallel steps' threads.
  int threads = 0;
  for (CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
    command
        ->add_option("--threads", threads,
                     "threads for the data-parallel steps: the tolerance check, the validation, "
                     "the report's distances (default: TESSERA_THREADS, OMP_NUM_THREADS or every "
                     "core; the mesh is the same whatever the count)")
        ->check(CLI::PositiveNumber);
  }
  // PETSc's own options (-ksp_type gmres, -log_view, …) are PETSc's to parse (--backend petsc).
  mesh.petsc_options = tessera::app::take_petsc_options(argc, argv);
  // The command line as given, for the checkpoints of `tessera mesh --checkpoint`.
  mesh.arguments.assign(argv + 1, argv + argc);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // A misspelt option or command: name it and the nearest ones, as git does.
    if (const auto explained = tessera::app::explain_parse_error(app, e)) {
      std::cerr << "tessera: error: " << *explained << "\n";
      return kUsageError;
    }
    const int code = app.exit(e);
    return code == 0 ? 0 : kUsageError;
  }
  if (!mesh.petsc_options.empty() && !app.got_subcommand("mesh")) {
    std::cerr << "tessera: error: " << mesh.petsc_options.front()
              << " is an option of PETSc, which only `tessera mesh --backend petsc` uses\n";
    return kUsageError;
  }
  try {
    tessera::set_thread_count(threads);
    if (app.got_subcommand("mesh")) {
      return tessera::app::run_mesh(mesh);
    }
    if (app.got_subcommand("resume")) {
      return tessera::app::run_resume(resume);
    }
    if (app.got_subcommand("extend")) {
      return tessera::app::run_extend(extend);
    }
    if (app.got_subcommand("problems")) {
      return run_problems();
    }
    if (app.got_subcommand("compare")) {
      return tessera::app::run_compare(compare);
    }
    if (app.got_subcommand("ddt")) {
      return tessera::app::run_ddt(ddt);
    }
    if (app.got_subcommand("render")) {
      return tessera::app::run_render(render);
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
