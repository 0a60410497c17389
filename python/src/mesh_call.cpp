// SPDX-License-Identifier: MIT
#include "mesh_call.h"

#include <cstdio>
#include <optional>

#include "interrupt_handler.h"
#include "progress.h"
#include "tessera/core/error.h"
#include "tessera/core/parallel_for.h"
#include "tessera/geometry/bezier_surface.h"
#include "tessera/io/output_checks.h"
#include "tessera/methods/components/cover_components.h"
#include "tessera/methods/improvement/improve_mesh.h"
#include "tessera/methods/stability/state_jacobian.h"
#include "tessera/picture/picture.h"
#include "tessera/picture/run_diagram.h"
#include "tessera/problems/start_and_box.h"
#include "tessera/report/fold_output.h"
#include "tessera/report/improvement_report.h"
#include "tessera/report/level_output.h"
#include "tessera/report/mesh_analyses.h"
#include "tessera/report/mesh_report.h"
#include "tessera/report/stability_output.h"
#include "tessera/report/summary_json.h"

namespace py = pybind11;

namespace tessera::python {

std::string join_numbers(const std::vector<double>& values) {
  std::string text;
  char buffer[32];
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::snprintf(buffer, sizeof buffer, "%.17g", values[i]);
    text += (i ? "," : "") + std::string(buffer);
  }
  return text;
}

View choose_view(const std::string& specification, const ProblemHandle& problem) {
  if (!specification.empty()) {
    try {
      return parse_view(specification, *problem.problem);
    } catch (const ViewSpecificationError& error) {
      throw InvalidArgument("view " + specification + ": " + error.reason());
    }
  }
  return problem.view ? *problem.view : default_view(*problem.problem);
}


std::string box_text(const MeshRequest& request) {
  if (!request.named_box.empty()) {
    return request.named_box;
  }
  return request.box.empty() ? "" : join_numbers(request.box);
}

std::shared_ptr<MeshHandle> mesh_problem(const std::shared_ptr<ProblemHandle>& problem,
                                         MeshRequest request, const py::object& progress,
                                         bool handle_interrupt) {
  const ThreadCountScope threads(request.threads);
  ProblemSetup setup = problem->setup();
  apply_start_and_box(setup, request.start.empty() ? "" : join_numbers(request.start),
                      box_text(request));
  const CoveringMethod& method = request.method.empty() ? covering_methods().front()
                                                        : find_covering_method(request.method);
  // As `tessera mesh --start … --start …` and `--components all`.
  std::vector<Eigen::VectorXd> starts;
  if (!request.more_starts.empty()) {
    std::vector<std::string> texts{join_numbers(request.start)};
    for (const std::vector<double>& start : request.more_starts) {
      texts.push_back(join_numbers(start));
    }
    starts = parse_starts(texts, *setup.problem);
  }
  TESSERA_CHECK(request.components == "start" || request.components == "all",
                "components = '" << request.components << "' must be 'start' or 'all'");
  const bool covers_several = request.components == "all" || starts.size() > 1;
  TESSERA_CHECK(request.component_seeds == 0 || request.components == "all",
                "component_seeds = " << request.component_seeds
                                     << " needs components='all' (the search it seeds)");
  // As `tessera mesh`: a method's own options given to another method would be ignored.
  refuse_options_of_other_methods(request.settings, method.name, /*keyword_names=*/true);
  const bool wants_patches = request.refine > 0 || request.wants_patches;
  TESSERA_CHECK(!wants_patches || method.name == "bezier",
                "refine and patches need the cubic surface of method 'bezier', not '"
                    << method.name << "'");
  TESSERA_CHECK(!(wants_patches && request.improve),
                "improve changes the triangles, so it cannot be combined with refine (the "
                "patches belong to the unimproved triangles)");
  const View view = choose_view(request.view, *problem);
  std::optional<ParameterPlane> fold_plane;
  if (!request.folds.empty()) {
    fold_plane = parse_folds_option(request.folds, *setup.problem);
  }
  // As `tessera mesh`: the diagram draws the Hopf curves, which need the eigenvalues.
  const bool wants_hopf = request.hopf || !request.diagram.empty();
  const bool wants_stability = request.stability || wants_hopf;
  if (wants_stability) {
    const char* option = request.stability ? "stability" : request.hopf ? "hopf" : "diagram";
    const Dynamics dynamics = required_dynamics(*setup.problem, option);
    TESSERA_CHECK(request.eigenvalues >= 1,
                  "eigenvalues = " << request.eigenvalues << " must be at least 1");
    if (!request.diagram.empty() && !fold_plane) {
      // The diagram's fold curves: over the dynamics' parameters.
      const auto names = setup.problem->coordinate_names();
      fold_plane =
          parse_folds_option(names.at(static_cast<std::size_t>(dynamics.parameters[0])) + "," +
                                 names.at(static_cast<std::size_t>(dynamics.parameters[1])),
                             *setup.problem);
    }
  }
  if (!request.diagram.empty()) {
    check_output_folder(request.diagram);
    TESSERA_CHECK(is_picture_file(request.diagram),
                  "diagram " << request.diagram << ": a picture is .png or .svg");
  }
  std::optional<LevelSet> level_set;
  if (!request.level.empty()) {
    level_set = parse_level_option(request.level, *setup.problem);
  }

  if (request.checkpoint.is_used()) {
    // As `tessera mesh --checkpoint` (apps/tessera/checkpoint_command.cpp).
    TESSERA_CHECK(!covers_several, "checkpoint: checkpoints are for runs of one start's "
                                   "component (not components='all' or several starts)");
  }
  MethodSettings settings = request.settings;
  apply_python_checkpointing(request.checkpoint, method.name, settings);
  // A progress callable that raises stops the run; its exception is raised afterwards.
  ProgressReporter reporter(progress);
  settings.progress = reporter.callback();
  const InterruptHandler interrupt(handle_interrupt);
  // The methods call progress and stop_requested from the run's thread, so the reporter's error
  // is only ever touched by that thread (with the GIL in progress, without it here).
  settings.stop_requested = [&interrupt, &reporter] {
    return interrupt.is_requested() || reporter.has_error();
  };

  auto handle = std::make_shared<MeshHandle>();
  handle->problem = problem;
  handle->comment = "tessera mesh " + problem->argument + ", method " + method.name;
  {
    py::gil_scoped_release release;
    CoveringResult result;
    if (covers_several) {
      ComponentSearchOptions search;
      search.every_component = request.components == "all";
      if (request.component_seeds > 0) {
        search.seed_count = request.component_seeds;
      }
      result = cover_components(setup, method, settings, starts, search);
    } else {
      result = cover(setup, method, settings);
    }
    std::optional<ImprovementReport> improvement;
    if (request.improve && result.summary.is_complete()) {
      // As `tessera mesh --improve`: swaps, 3 passes of tangential smoothing, swaps again.
      improvement = improve_covering(result.mesh, *setup.problem);
      result.validation.reset();
    }
    if (request.refine > 0 && result.mesh.triangle_count() > 0) {
      result.mesh = refine_bezier_surface(result.mesh, result.patches, request.refine);
      result.validation.reset();
    }
    // The report measures the mesh against M (a projection per sample; with a Python F, often
    // longer than the covering) and the analyses follow: two more stages for the progress.
    const auto report_stage = [&](std::string_view stage) {
      if (settings.progress) {
        CoveringProgress record;
        record.vertex_count = result.mesh.vertex_count();
        record.triangle_count = result.mesh.triangle_count();
        record.stage = stage;
        settings.progress(record);
      }
    };
    report_stage("report");
    ReportOptions report_options;
    report_options.samples = request.report_samples;
    report_options.run_seconds = result.summary.wall_seconds;
    MeshReport report =
        make_report(result.mesh, setup, problem->argument,
                    result.validation ? &*result.validation : nullptr, report_options);
    if (result.summary.components.size() > 1) {
      // The problem's known topology and area are the first start's component's.
      report.expected_euler_characteristic.reset();
      report.exact_area.reset();
    }
    report.run = result.summary;
    report.improvement = improvement;
    report.backend = BackendReport{"serial", 1};  // the bindings solve in this process
    report.view = ViewReport{view.specification(),
                             view.is_all_coordinates() ? std::vector<std::string>() : view.names(),
                             request.view.empty() ? (problem->view ? "problem file" : "default")
                                                  : "--view"};
    // As `tessera mesh --folds/--stability/--hopf/--level`, on the finished mesh, in the view;
    // the curves are in the summary, no file is written.
    AnalysisRequest analysis;
    analysis.fold_plane = fold_plane;
    if (wants_stability) {
      analysis.stability = StabilityOptions{};
      analysis.stability->eigenvalue_count = request.eigenvalues;
    }
    analysis.hopf = wants_hopf;
    analysis.level = level_set;
    if (fold_plane || wants_stability || level_set) {
      report_stage("analyses");
    }
    MeshAnalyses analyses = analyse_mesh(setup, result.mesh, view, analysis, report);
    if (analyses.hopf && !request.diagram.empty()) {
      handle->note = write_run_diagram(request.diagram, problem->argument, report,
                                       analyses.fold_curves, *analyses.hopf, view);
    }
    if (analyses.stability) {
      // Written by Mesh.write as point data, as `tessera mesh --stability` writes them.
      handle->vertex_scalars = std::move(analyses.stability->vertex_data);
      handle->stability = std::move(analyses.stability->result.vertices);
    }
    handle->summary_json = to_json(report);
    handle->termination = to_string(result.summary.termination);
    if (!result.summary.is_complete()) {
      handle->failure = "the " + method.name + " method stopped early (" + handle->termination +
                        "): " + result.summary.message;
    } else if (!report.validation.is_valid()) {
      handle->failure = "the mesh is not valid:\n" + report.validation.report();
    }
    handle->mesh = std::move(result.mesh);
    handle->patches = std::move(result.patches);
  }
  reporter.finish();
  handle->interrupted = interrupt.is_requested();
  handle->interrupt_count = interrupt.count();
  reporter.raise_error();
  return handle;
}

}  // namespace tessera::python
