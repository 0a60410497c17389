// SPDX-License-Identifier: MIT
#include "mesh_command.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

#include "checkpoint_command.h"
#include "cli_support.h"
#include "picture_command.h"
#include "solver_backend.h"
#include "stop_signals.h"
#include "tessera/core/error.h"
#include "tessera/geometry/bezier_surface.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/io/bezier_patches.h"
#include "tessera/io/mesh_io.h"
#include "tessera/io/npy.h"
#include "tessera/io/output_checks.h"
#include "tessera/io/split_mesh_output.h"
#include "tessera/io/view_mesh.h"
#include "tessera/methods/components/component_seeds.h"
#include "tessera/methods/components/cover_components.h"
#include "tessera/methods/stability/state_jacobian.h"
#include "tessera/methods/stop_grace.h"
#include "tessera/picture/run_diagram.h"
#include "tessera/problems/catalogue.h"
#include "tessera/problems/start_and_box.h"
#include "tessera/problems/view.h"
#include "tessera/report/fold_output.h"
#include "tessera/report/improvement_report.h"
#include "tessera/report/level_output.h"
#include "tessera/report/mesh_analyses.h"
#include "tessera/report/mesh_report.h"
#include "tessera/report/problem_record.h"
#include "tessera/report/stability_output.h"
#include "tessera/report/summary_json.h"

namespace tessera::app {

namespace {

struct ChosenView {
  View view;
  std::string origin;  ///< ViewReport::origin
};

// The view the mesh file is written in: --view, else --obj-coordinates, else the problem file's,
// else default_view (every coordinate unless n is large). Checked before any computation.
ChosenView choose_view(const MeshCommand& command, const ProblemSetup& setup) {
  const ImplicitProblem& problem = *setup.problem;
  const int n = problem.ambient_dimension();
  TESSERA_CHECK(command.view.empty() || command.obj_coordinates.empty(),
                "--view and --obj-coordinates both choose what is written; give --view only "
                "(--obj-coordinates I,J,K is --view with the names of coordinates I, J, K)");
  ChosenView chosen;
  std::string option;  // for messages: the option or file line the view came from
  if (!command.view.empty()) {
    option = "--view " + command.view;
    try {
      chosen = {parse_view(command.view, problem), "--view"};
    } catch (const ViewSpecificationError& error) {
      throw InvalidArgument(option + ": " + error.reason());
    }
  } else if (!command.obj_coordinates.empty()) {
    option = "--obj-coordinates " + command.obj_coordinates;
    const auto values = parse_numbers(command.obj_coordinates, "--obj-coordinates");
    TESSERA_CHECK(values.size() == 3,
                  "--obj-coordinates needs three coordinate indices, got " << values.size());
    const auto names = problem.coordinate_names();
    std::string specification;
    for (int i = 0; i < 3; ++i) {
      TESSERA_CHECK(values[i] == std::floor(values[i]) && values[i] >= 0 && values[i] < n,
                    "--obj-coordinates: " << values[i] << " is not a coordinate index in [0, "
                                          << n - 1 << "]");
      specification += (i ? "," : "") + names[static_cast<std::size_t>(values[i])];
    }
    try {
      chosen = {parse_view(specification, problem), "--obj-coordinates"};
    } catch (const ViewSpecificationError& error) {
      throw InvalidArgument(option + ": " + error.reason());
    }
  } else if (setup.view) {
    option = "the problem file's view";
    chosen = {*setup.view, "problem file"};
  } else {
    chosen.view = default_view(problem);
    chosen.origin = chosen.view.is_all_coordinates() ? "default" : "default for large n";
  }
  TESSERA_CHECK(chosen.view.size() >= 2,
                option << ": a view needs at least two functionals to place the vertices (three "
                          "for a surface in space), got "
                       << chosen.view.size());
  return chosen;
}

// Two outputs of one run at the same path would silently replace one another (a summary
// `torus.json` and `--patches torus.json`): refused, naming both options.
void check_distinct_outputs(const std::vector<std::pair<std::string, std::string>>& outputs) {
  std::vector<std::pair<std::filesystem::path, std::string>> seen;
  for (const auto& [option, path] : outputs) {
    if (path.empty()) {
      continue;
    }
    const std::filesystem::path normal = std::filesystem::absolute(path).lexically_normal();
    for (const auto& [other, other_option] : seen) {
      TESSERA_CHECK(other != normal, option << " " << path << " is the file of " << other_option
                                            << " too: one would replace the other; give "
                                               "them different names");
    }
    seen.emplace_back(normal, option);
  }
}

// A curve file of --folds-output, --hopf-output or --level-output: its folder and format.
void check_polyline_output(const std::string& option, const std::string& path) {
  check_output_folder(path);
  TESSERA_CHECK(is_polyline_file(path),
                option << " " << path << ": unknown extension (use .vtk, .vtu, .ply, .json or .csv)");
}

void check_states_output(const std::string& path) {
  check_output_folder(path);
  TESSERA_CHECK(std::filesystem::path(path).extension() == ".npy",
                "--states " << path << ": the states file must end in .npy (a NumPy array; the "
                            << "triangles go beside it to "
                            << std::filesystem::path(triangles_npy_path(path)).filename().string()
                            << ")");
}

int mesh_on(SolverBackend& backend, const MeshCommand& command);

}  // namespace

int run_mesh(const MeshCommand& command) {
  SolverBackend backend(command.backend, command.petsc_options);
  if (backend.ranks() == 1) {
    return mesh_on(backend, command);
  }
  try {
    return mesh_on(backend, command);
  } catch (const std::exception& error) {
    // The other ranks may wait in a collective call for this one: end them all.
    const bool is_usage = dynamic_cast<const InvalidArgument*>(&error) != nullptr;
    std::cerr << "tessera: " << (is_usage ? "error" : "failed") << " (rank " << backend.rank()
              << " of " << backend.ranks() << "): " << error.what() << "\n";
    backend.abort(is_usage ? kUsageError : kComputationFailed);
  }
}

namespace {

int mesh_on(SolverBackend& backend, const MeshCommand& command) {
  ProblemSetup setup = resolve_problem(command.problem);
  const int n = setup.problem->ambient_dimension();
  apply_start_and_box(setup, command.starts.empty() ? "" : command.starts.front(), command.box);
  const std::vector<Eigen::VectorXd> starts = parse_starts(command.starts, *setup.problem);
  // Several components: more than one start, or the search of the region.
  const bool searches = command.components == "all";
  const bool covers_several = searches || starts.size() > 1;
  TESSERA_CHECK(command.component_seeds == 0 || searches,
                "--component-seeds " << command.component_seeds
                                     << " needs --components all (the search it seeds)");
  TESSERA_CHECK(!covers_several || command.backend == "serial",
                (searches ? "--components all" : "--start given more than once")
                    << " is not yet available with --backend " << command.backend
                    << ": run it with the serial backend, or one start per run");
  if (searches) {
    TESSERA_CHECK(!seeded_box(setup.domain).is_empty(),
                  "--components all searches a bounded region, but the domain of '"
                      << command.problem << "' ("
                      << (setup.domain.is_unbounded() ? "all of R^" + std::to_string(n)
                                                      : setup.domain.describe())
                      << ") bounds no coordinate on both sides: give --box, "
                      << box_syntax(*setup.problem));
  }
  const CoveringMethod& method =
      command.method.empty() ? covering_methods().front() : find_covering_method(command.method);
  // The atlas and the front run on split states (each rank its rows of every vertex); bezier,
  // and the improvement and fold curves (not yet converted), on whole ones on every rank.
  const bool splits = method.name == "atlas" || method.name == "front";
  // --diagram draws the fold and Hopf curves; --hopf needs the eigenvalues of --stability.
  const bool wants_hopf = command.hopf || !command.diagram.empty();
  const bool wants_stability = command.stability || wants_hopf;
  backend.adopt(setup, /*split_states=*/splits && !command.improve && command.folds.empty() &&
                           !wants_hopf && command.level.empty());
  // Every rank computes; the root prints and writes.
  const bool is_root = backend.is_root();
  const bool quiet = command.quiet || !is_root;
  // A method's own options given to another method would be ignored silently: refuse them.
  refuse_options_of_other_methods(command.settings, method.name, /*keyword_names=*/false);
  check_checkpoint_options(command, method.name, covers_several);
  // Every option is checked before the computation starts.
  check_mesh_output(command.output);
  check_output_folder(command.summary);
  check_output_folder(command.patches);
  const bool wants_patches = command.refine > 0 || !command.patches.empty();
  TESSERA_CHECK(!wants_patches || method.name == "bezier",
                "--refine and --patches need the cubic surface of --method bezier, not '"
                    << method.name << "'");
  TESSERA_CHECK(!(wants_patches && command.improve),
                "--improve changes the triangles, so it cannot be combined with --refine or "
                "--patches (the patches belong to the unimproved triangles)");
  if (!command.states.empty()) {
    check_states_output(command.states);
  }
  const ChosenView chosen = choose_view(command, setup);
  const View& view = chosen.view;
  // A distributed problem makes a split mesh, whose whole points are not gathered at large n.
  check_split_mesh_output(*setup.problem->space(), view);
  TESSERA_CHECK(!command.folds.empty() || !command.diagram.empty() || command.folds_output.empty(),
                "--folds-output " << command.folds_output
                                  << " needs --folds (the parameter plane, e.g. --folds lambda,mu)");
  if (!command.picture.empty()) {
    check_output_folder(command.picture);
    TESSERA_CHECK(is_picture_file(command.picture),
                  "--picture " << command.picture << ": a picture is .png or .svg");
  }
  std::optional<ParameterPlane> fold_plane;
  std::string fold_file;
  if (!command.folds.empty()) {
    fold_plane = parse_folds_option(command.folds, *setup.problem);
    fold_file = command.folds_output.empty() ? default_fold_file(command.output)
                                             : command.folds_output;
    check_polyline_output("--folds-output", fold_file);
  }
  std::string hopf_file;
  if (wants_stability) {
    const std::string option = command.stability ? "--stability" : command.hopf ? "--hopf" : "--diagram";
    // The Hopf points' Newton solves complex (or doubled real) bordered systems, which the
    // PETSc backend does not have yet; the eigenvalues of --stability it has (SLEPc).
    TESSERA_CHECK(command.backend != "petsc" || !wants_hopf,
                  (command.hopf ? "--hopf" : "--diagram")
                      << " is not yet available with --backend petsc (its Hopf points need complex "
                         "distributed systems): run it with the serial backend; --stability alone "
                         "runs on the PETSc backend");
    backend.check_stability_available(option);
    const Dynamics dynamics = required_dynamics(*setup.problem, option);
    if (!command.diagram.empty() && !fold_plane) {
      // The diagram's fold curves: over the dynamics' parameters, written beside the mesh too.
      const auto names = setup.problem->coordinate_names();
      fold_plane = parse_folds_option(names.at(static_cast<std::size_t>(dynamics.parameters[0])) +
                                          "," +
                                          names.at(static_cast<std::size_t>(dynamics.parameters[1])),
                                      *setup.problem);
      fold_file = command.folds_output.empty() ? default_fold_file(command.output)
                                               : command.folds_output;
      check_polyline_output("--folds-output", fold_file);
    }
  }
  TESSERA_CHECK(wants_hopf || command.hopf_output.empty(),
                "--hopf-output " << command.hopf_output << " needs --hopf");
  if (wants_hopf) {
    hopf_file = command.hopf_output.empty() ? default_hopf_file(command.output) : command.hopf_output;
    check_polyline_output("--hopf-output", hopf_file);
  }
  if (!command.diagram.empty()) {
    check_output_folder(command.diagram);
    TESSERA_CHECK(is_picture_file(command.diagram),
                  "--diagram " << command.diagram << ": a picture is .png or .svg");
  }
  TESSERA_CHECK(!command.level.empty() || command.level_output.empty(),
                "--level-output " << command.level_output
                                  << " needs --level (e.g. --level x1=0.5)");
  std::optional<LevelSet> level_set;
  std::string level_file;
  if (!command.level.empty()) {
    level_set = parse_level_option(command.level, *setup.problem);
    level_file = command.level_output.empty() ? default_level_file(command.output) : command.level_output;
    check_polyline_output("--level-output", level_file);
  }
  check_distinct_outputs({{"-o", command.output},
                          {"--summary", command.summary},
                          {"--checkpoint", command.checkpoint},
                          {"--patches", command.patches},
                          {"--states", command.states},
                          {"--states (its triangles)",
                           command.states.empty() ? "" : triangles_npy_path(command.states)},
                          {"--folds-output", fold_file},
                          {"--hopf-output", hopf_file},
                          {"--hopf-output (its neutral saddles)",
                           hopf_file.empty() ? "" : neutral_saddle_file_beside(hopf_file)},
                          {"--level-output", level_file},
                          {"--picture", command.picture},
                          {"--diagram", command.diagram}});
  // A file of another kind (an earlier run's summary where the patches go) is not replaced.
  check_replaces_same_kind("-o", command.output, TesseraFileKind::Mesh);
  check_replaces_same_kind("--summary", command.summary, TesseraFileKind::MeshSummary);
  check_replaces_same_kind("--patches", command.patches, TesseraFileKind::BezierPatches);
  check_replaces_same_kind("--folds-output", fold_file, TesseraFileKind::Curves);
  check_replaces_same_kind("--hopf-output", hopf_file, TesseraFileKind::Curves);
  check_replaces_same_kind("--hopf-output (its neutral saddles)",
                           hopf_file.empty() ? "" : neutral_saddle_file_beside(hopf_file),
                           TesseraFileKind::Curves);
  check_replaces_same_kind("--level-output", level_file, TesseraFileKind::Curves);
  MeshFileOptions file_options;
  MethodSettings settings = command.settings;
  // On a terminal a status line; with --progress (a batch job's log) a line per report. Every
  // report also tells the stop signals the stage now running.
  const bool show_progress = !quiet && isatty(STDERR_FILENO) && !command.progress;
  const bool progress_lines = !quiet && command.progress;
  settings.progress = [show_progress, progress_lines](const CoveringProgress& p) {
    StopSignals::enter(stage_of_progress(p.stage));
    const std::string stage(p.stage);
    if (progress_lines && p.stage == "build") {
      std::fprintf(stderr, "tessera: build: %d vertices, %d triangles, front %d\n", p.vertex_count,
                   p.triangle_count, p.front_size);
    } else if (progress_lines) {
      std::fprintf(stderr, "tessera: %s: %d vertices, %d triangles\n", stage.c_str(),
                   p.vertex_count, p.triangle_count);
    } else if (show_progress && p.stage == "build") {
      std::fprintf(stderr, "\r  %d vertices, %d triangles, front %d   ", p.vertex_count,
                   p.triangle_count, p.front_size);
    } else if (show_progress) {
      std::fprintf(stderr, "\r  %s: %d vertices, %d triangles          ", stage.c_str(),
                   p.vertex_count, p.triangle_count);
    }
  };
  // Ctrl-C or a kill (SIGTERM, e.g. a batch system's time limit) stops the run at its next
  // vertex, projection or check; the checks after it get a grace of kCheckSecondsAfterStop,
  // and the valid partial mesh and the summary are written at once, the report's measurements
  // left out (docs/stopping.md). A second signal is counted, a third ends the process.
  const StopSignals signals(/*notify=*/!quiet);
  // Collective on the PETSc backend: every rank stops at the same vertex.
  settings.stop_requested = [&backend] { return backend.any_rank(StopSignals::is_requested()); };
  // The method's checkpoints, and the state of `tessera resume` (checkpoint_command.h).
  if (method.name == "front") {
    settings.front_checkpoint = make_front_checkpointing(command, progress_lines);
  } else {
    settings.atlas_checkpoint = make_atlas_checkpointing(command, progress_lines);
  }
  CoveringResult result;
  if (covers_several) {
    ComponentSearchOptions search;
    search.every_component = searches;
    if (command.component_seeds > 0) {
      search.seed_count = command.component_seeds;
    }
    result = cover_components(setup, method, settings, starts, search);
  } else {
    result = backend.cover(setup, method, settings);
  }
  if (show_progress) {
    std::fprintf(stderr, "\r%60s\r", "");
  }
  StopSignals::enter(RunStage::Report);
  if (progress_lines) {
    std::fprintf(stderr, "tessera: report: %d vertices, %d triangles\n", result.mesh.vertex_count(),
                 result.mesh.triangle_count());
  }
  // After a stop the files come first: what only measures or adds to the mesh is left out,
  // each named in the summary's stop.left_out (decided together on the PETSc backend).
  const bool stopped = backend.any_rank(StopSignals::is_requested());
  std::vector<std::string> left_out;
  const auto leave_out_analyses = [&] {
    if (fold_plane) {
      left_out.push_back("fold curves: not computed, " + fold_file + " not written");
    }
    if (level_set) {
      left_out.push_back("level curves: not computed, " + level_file + " not written");
    }
    if (wants_stability) {
      left_out.push_back("stability: not computed");
    }
    if (wants_hopf) {
      left_out.push_back("Hopf curves: not computed, " + hopf_file + " not written");
    }
    if (!command.picture.empty()) {
      left_out.push_back("picture: " + command.picture + " not drawn");
    }
    if (!command.diagram.empty()) {
      left_out.push_back("diagram: " + command.diagram + " not drawn");
    }
  };
  const auto stop_report = [&](const MeshReport& made) -> std::optional<StopReport> {
    if (!StopSignals::is_requested()) {
      return std::nullopt;
    }
    StopReport stop{std::string(StopSignals::first_signal()), StopSignals::count(),
                    std::string(to_string(StopSignals::stage_at_stop())), left_out};
    for (const std::string& cut : made.validation.checks_cut_short) {
      stop.left_out.push_back("geometric validation cut short: " + cut);
    }
    return stop;
  };
  std::optional<ImprovementReport> improvement;
  if (command.improve && stopped) {
    left_out.push_back("--improve: the mesh was not improved");
  } else if (command.improve && result.summary.is_complete()) {
    // Delaunay-type swaps judged in the tangent planes, 3 passes of tangential smoothing, and
    // swaps again (docs/algorithms/improvement.md): validity and boundary are kept. The report
    // says what they did; the covering's final check saw other triangles, so it is not reused.
    improvement = improve_covering(result.mesh, *setup.problem);
    result.validation.reset();
  }
  if (!command.patches.empty() && is_root) {
    write_bezier_patches(command.patches,
                         {result.mesh, result.patches, setup.problem->coordinate_names()});
  }
  if (command.refine > 0 && result.mesh.triangle_count() > 0) {
    // The cubic surface sampled on a K×K subdivision of each triangle; the report below then
    // measures the cubic surface (its centroids and edge midpoints) instead of the flat mesh.
    result.mesh = refine_bezier_surface(result.mesh, result.patches, command.refine);
  }
  // Whatever happened, keep the work: write the mesh and the summary before reporting.
  file_options.binary = !command.ascii;
  file_options.comments = {"tessera mesh " + command.problem + ", method " + method.name};
  // What `tessera check FILE` takes for the problem when it is not given.
  for (auto& comment : problem_record_comments(command.problem, command.box)) {
    file_options.comments.push_back(std::move(comment));
  }
  // An empty mesh (the start failed) is not written: it would replace a good file with nothing.
  const bool has_mesh = result.mesh.triangle_count() > 0;
  // A split mesh (every rank its rows of the points) is written by every rank together: the
  // view's reductions and the gathers are collective, rank 0 alone touches files.
  const bool is_split = result.mesh.space().is_distributed();
  std::vector<std::string> written;
  if (has_mesh && view.is_all_coordinates()) {
    // PLY keeps the standard names (x, y, z, x3, …) that readers look for; the problem's own
    // names go into a comment, and into the arrays of VTK files.
    const bool is_ply = std::filesystem::path(command.output).extension() == ".ply";
    std::string names;
    for (const auto& name : setup.problem->coordinate_names()) {
      names += " " + name;
    }
    if (!is_ply) {
      file_options.coordinate_names = setup.problem->coordinate_names();
    }
    file_options.comments.push_back("coordinates:" + names);
  } else if (has_mesh) {
    file_options.comments.push_back("a view of the states in R^" + std::to_string(n) + ": " +
                                    describe_coordinates(*setup.problem));
  }
  if (has_mesh && is_split) {
    written = write_mesh_output(result.mesh, {command.output, view, file_options, ""});
  } else if (has_mesh && is_root && view.is_all_coordinates()) {
    write_mesh(command.output, result.mesh, file_options);
    written.push_back(command.output);
  } else if (has_mesh && is_root) {
    write_mesh_in_view(command.output, result.mesh, view, file_options);
    written.push_back(command.output);
  }
  const BackendReport backend_report{backend.name(), backend.ranks(),
                                     backend.splits_states() ? "split" : "whole"};
  const ViewReport view_report{
      view.specification(),
      view.is_all_coordinates() ? std::vector<std::string>() : view.names(), chosen.origin};
  // The run's summary before the distances are measured (minutes at large n): a run killed
  // during the measurement still leaves it. Replaced below by the complete one; after a stop it
  // is the final one (the validation of a mesh not yet validated cut short by the same grace).
  ReportOptions report_options;
  report_options.samples = command.report_samples;
  report_options.measure_distances = false;
  const double factorisation_seconds =
      result.summary.factorisations > 0
          ? result.summary.factorisation_seconds / static_cast<double>(result.summary.factorisations)
          : 0.0;
  report_options.validation.stop_requested =
      after_grace([] { return StopSignals::is_requested(); },
                  grace_before_items(kCheckSecondsAfterStop, factorisation_seconds));
  // The problem's known topology and area are those of the first start's component.
  const bool has_several_components = result.summary.components.size() > 1;
  const auto only_known_of_one_component = [&](MeshReport& made) {
    if (has_several_components) {
      made.expected_euler_characteristic.reset();
      made.exact_area.reset();
    }
  };
  MeshReport before =
      make_report(result.mesh, setup, command.problem,
                  result.validation ? &*result.validation : nullptr, report_options);
  only_known_of_one_component(before);
  before.run = result.summary;
  before.improvement = improvement;
  before.view = view_report;
  before.backend = backend_report;
  if (stopped) {
    left_out.push_back(
        "distances to M: not measured (each a projection onto M, a factorisation at large n)");
    leave_out_analyses();
    before.stop = stop_report(before);
  }
  if (!command.summary.empty() && is_root) {
    write_summary_json(command.summary, before);
  }
  MeshReport report = before;
  if (!stopped) {
    report_options.measure_distances = true;
    report_options.run_seconds = result.summary.wall_seconds;
    // A stop during the measurement ends it with what it has (the counts say how much).
    report_options.stop_requested = [] { return StopSignals::is_requested(); };
    // Every rank measures the same samples (collective projections) and stops at the same one.
    report_options.decide_together = [&backend](bool stop) { return backend.any_rank(stop); };
    report = make_report(result.mesh, setup, command.problem, &before.validation, report_options);
    only_known_of_one_component(report);
    report.run = result.summary;
    report.improvement = improvement;
    report.view = view_report;
    report.backend = backend_report;
  }
  const bool stopped_in_report = !stopped && backend.any_rank(StopSignals::is_requested());
  if (stopped_in_report) {
    left_out.push_back("distances to M: measured until the stop (their counts say how many)");
    leave_out_analyses();
  }
  const bool is_stopped = stopped || stopped_in_report;
  // Folds, stability, Hopf and level curves on the finished mesh, in its view; the root writes
  // their files. Once begun they run to their end (a stop is not polled there).
  MeshAnalyses analyses;
  if (!is_stopped) {
    AnalysisRequest request;
    request.fold_plane = fold_plane;
    if (wants_stability) {
      request.stability = StabilityOptions{};
      request.stability->eigenvalue_count = command.eigenvalues;
    }
    request.hopf = wants_hopf;
    request.level = level_set;
    if (is_root) {
      request.fold_file = fold_file;
      request.hopf_file = hopf_file;
      request.level_file = level_file;
    }
    request.comments = file_options.comments;
    // The stability on the backend's own (the PETSc backend's: SLEPc on the ranks).
    request.compute_stability = [&backend](const ProblemSetup& s, const TriangleMesh& m,
                                           const StabilityOptions& o) {
      return backend.stability_output(s, m, o);
    };
    analyses = analyse_mesh(setup, result.mesh, view, request, report);
  }
  written.insert(written.end(), analyses.written.begin(), analyses.written.end());
  for (const std::string& warning : is_root ? analyses.warnings : std::vector<std::string>()) {
    std::cerr << "tessera: " << warning << "\n";
  }
  if (analyses.stability) {
    // The mesh file again, now with the stability as point data (a split mesh by every rank).
    MeshFileOptions with_data = file_options;
    with_data.vertex_scalars = analyses.stability->vertex_data;
    if (is_split) {
      write_mesh_output(result.mesh, {command.output, view, with_data, ""});
    } else if (is_root) {
      if (view.is_all_coordinates()) {
        write_mesh(command.output, result.mesh, with_data);
      } else {
        write_mesh_in_view(command.output, result.mesh, view, with_data);
      }
    }
  }
  // Curves for the picture, each with its kind (columns: the view's).
  std::vector<PolylineFile> picture_curves = analyses.curves_in_view(coordinate_names_in_view(view));
  if (has_mesh && !command.states.empty() && (is_root || is_split)) {
    if (is_split) {
      write_mesh_output(result.mesh, {"", view, {}, command.states});  // streamed to rank 0
    } else {
      write_states_npy(command.states, result.mesh);
    }
    report.states = StatesReport{command.states,
                                 triangles_npy_path(command.states),
                                 result.mesh.vertex_count(),
                                 result.mesh.triangle_count(),
                                 setup.problem->coordinate_names(),
                                 setup.problem->coordinate_blocks()};
    written.push_back(report.states->states_file);
    written.push_back(report.states->triangles_file);
  }
  if (has_mesh && !command.picture.empty() && !is_stopped && (is_root || is_split)) {
    PictureOptions picture;
    picture.choose_view = true;  // kept for continuation views (write_mesh_picture)
    picture.title = command.problem + " (" + method.name + ")";
    // Fold curves of a surface in R³ are pictured with the parameter plane horizontal and the
    // third coordinate (the state) as the height, as bifurcation diagrams are drawn.
    View picture_view = view;
    if (fold_plane && n == 3 && view.is_all_coordinates()) {
      std::vector<std::string> order = fold_plane->view().names();
      for (const auto& name : setup.problem->coordinate_names()) {
        if (std::find(order.begin(), order.end(), name) == order.end()) {
          order.push_back(name);
        }
      }
      if (order.size() == 3) {
        picture_view = parse_view(order[0] + "," + order[1] + "," + order[2], *setup.problem);
        for (PolylineFile& file : picture_curves) {  // the same reordering of the curves' columns
          for (Polyline& curve : file.polylines) {
            Eigen::MatrixXd points(3, curve.points.cols());
            for (int row = 0; row < 3; ++row) {
              const auto& names = setup.problem->coordinate_names();
              const auto at = std::find(names.begin(), names.end(), order[static_cast<std::size_t>(row)]);
              points.row(row) = curve.points.row(static_cast<Eigen::Index>(at - names.begin()));
            }
            curve.points = std::move(points);
          }
          file.options.names = {order[0], order[1], order[2]};
        }
      }
    }
    // Collective on a split mesh; drawn from the view alone (colour "height").
    const TriangleMesh shown = mesh_in_view(result.mesh, picture_view);
    if (is_root) {
      write_mesh_picture(command.picture, result.mesh, shown,
                         coordinate_names_in_view(picture_view), picture_curves,
                         analyses.stability ? analyses.stability->vertex_data
                                            : std::vector<VertexScalars>(),
                         analyses.stability ? "stability" : "height", picture, &setup);
    }
    written.push_back(command.picture);
  }
  if (has_mesh && analyses.hopf && !command.diagram.empty() && is_root) {
    // The two-parameter bifurcation diagram: fold and Hopf curves over the dynamics' parameters.
    const std::string note =
        write_run_diagram(command.diagram, command.problem, report, analyses.fold_curves,
                          *analyses.hopf, view);
    if (!note.empty()) {
      std::cerr << "tessera: " << note << "\n";
    }
    written.push_back(command.diagram);
  }
  report.stop = stop_report(report);
  if (!command.summary.empty() && is_root) {
    write_summary_json(command.summary, report);
    written.push_back(command.summary);
  }
  if (!quiet && !written.empty()) {
    std::cout << to_text(report) << "wrote          ";
    for (std::size_t i = 0; i < written.size(); ++i) {
      std::cout << (i == 0 ? "" : i + 1 == written.size() ? " and " : ", ") << written[i];
    }
    std::cout << "\n";
  }
  if (!result.summary.is_complete()) {
    if (!is_root) {
      return kComputationFailed;
    }
    std::cerr << "tessera: the " << method.name << " method stopped early ("
              << to_string(result.summary.termination) << "): " << result.summary.message << "\n";
    if (has_mesh) {
      std::cerr << "tessera: the partial mesh was written to " << command.output << "\n";
    } else {
      std::cerr << "tessera: no mesh was made; " << command.output << " was not written\n";
    }
    return kComputationFailed;
  }
  if (!report.validation.is_valid()) {
    if (is_root) {
      std::cerr << "tessera: the mesh is not valid:\n" << report.validation.report();
    }
    return kComputationFailed;
  }
  return 0;
}

}  // namespace

}  // namespace tessera::app
