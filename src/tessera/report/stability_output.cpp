// SPDX-License-Identifier: MIT
#include "tessera/report/stability_output.h"

#include <algorithm>
#include <filesystem>

#include "tessera/io/file_names.h"
#include "tessera/io/view_mesh.h"
#include "tessera/methods/stability/state_jacobian.h"

namespace tessera {

namespace {

// What the counts are sure of, in words.
std::string certainty_of(const StabilityResult& result, const StabilityOptions& options) {
  if (result.method == "dense") {
    return "every eigenvalue computed: the counts are exact";
  }
  const std::string k = std::to_string(options.eigenvalue_count);
  if (result.uncertain_count == 0) {
    return "counts from the inertia of s·D_uF (Sylvester's law): exact; the " + k +
           " eigenvalues nearest 0 computed per vertex";
  }
  std::string text = "the counts are of the " + k +
                     " eigenvalues nearest 0 per vertex (shift-invert Arnoldi); eigenvalues "
                     "farther from 0 were not examined";
  if (result.uncertain_count < static_cast<int>(result.vertices.size()) - result.failed_count) {
    text += " at " + std::to_string(result.uncertain_count) +
            " vertices (exact from the inertia of s·D_uF at the others)";
  }
  return text;
}

}  // namespace

StabilityOutput compute_stability_output(const ProblemSetup& setup, const TriangleMesh& mesh,
                                         const StabilityOptions& options) {
  const ImplicitProblem& problem = *setup.problem;
  required_dynamics(problem, "--stability");  // the message that says how to declare them
  return make_stability_output(problem, compute_stability(problem, mesh, options), options);
}

StabilityOutput make_stability_output(const ImplicitProblem& problem, StabilityResult result,
                                      const StabilityOptions& options) {
  StabilityOutput output;
  const Dynamics dynamics = required_dynamics(problem, "--stability");
  output.result = std::move(result);
  const StabilityResult& computed = output.result;
  const int vertex_count = static_cast<int>(computed.vertices.size());
  StabilityReport& report = output.report;
  const auto names = problem.coordinate_names();
  report.parameters = {names.at(static_cast<std::size_t>(dynamics.parameters[0])),
                       names.at(static_cast<std::size_t>(dynamics.parameters[1]))};
  report.method = computed.method;
  report.eigenvalue_count = computed.eigenvalue_count;
  report.vertex_count = vertex_count;
  report.stable_count = computed.stable_count;
  report.index_counts = computed.index_counts;
  report.failed_count = computed.failed_count;
  report.uncertain_count = computed.uncertain_count;
  report.certainty = certainty_of(computed, options);
  report.factorisations = computed.factorisations;
  report.solves = computed.solves;
  report.jacobian_evaluations = computed.jacobian_evaluations;
  report.seconds = computed.seconds;
  VertexScalars counts{"unstable_count", {}};
  VertexScalars leading{"leading_real_part", {}};
  VertexScalars certain{"stability_certain", {}};
  for (int v = 0; v < vertex_count; ++v) {
    const VertexStability& s = computed.vertices[static_cast<std::size_t>(v)];
    counts.values.push_back(s.unstable_count);
    leading.values.push_back(s.leading_real_part);
    certain.values.push_back(s.is_certain ? 1.0 : 0.0);
    if (s.has_failed() && report.failures.size() < 10) {
      report.failures.push_back({v, s.message});
    }
  }
  output.vertex_data = {std::move(counts), std::move(leading), std::move(certain)};
  return output;
}

std::string default_hopf_file(const std::string& mesh_path) {
  return curve_file_beside(mesh_path, "hopf");
}

std::string neutral_saddle_file_beside(const std::string& hopf_path) {
  std::filesystem::path path(hopf_path);
  std::string stem = path.stem().string();
  const std::string suffix = ".hopf";
  if (stem.size() > suffix.size() && stem.compare(stem.size() - suffix.size(), suffix.size(), suffix) == 0) {
    stem.resize(stem.size() - suffix.size());
  }
  return (path.parent_path() / (stem + ".neutral_saddles" + path.extension().string())).string();
}

HopfOutput compute_hopf_output(const ProblemSetup& setup, const TriangleMesh& mesh,
                               const StabilityResult& stability, const View& view,
                               const std::string& path, const std::vector<std::string>& comments) {
  const ImplicitProblem& problem = *setup.problem;
  const Dynamics dynamics = required_dynamics(problem, "--hopf");
  const HopfCurves hopf = find_hopf_curves(problem, mesh, stability);
  HopfOutput output;
  HopfReport& report = output.report;
  const auto names = problem.coordinate_names();
  const std::array<int, 2> parameters = dynamics.parameters;
  report.plane_names = {names.at(static_cast<std::size_t>(parameters[0])),
                        names.at(static_cast<std::size_t>(parameters[1]))};
  const std::vector<std::string> view_columns = coordinate_names_in_view(view);
  report.columns = view_columns;
  std::vector<int> extra;  // parameters not in the view
  for (int i = 0; i < 2; ++i) {
    const std::string& name = report.plane_names[static_cast<std::size_t>(i)];
    if (std::find(view_columns.begin(), view_columns.end(), name) == view_columns.end()) {
      report.columns.push_back(name);
      extra.push_back(parameters[static_cast<std::size_t>(i)]);
    }
  }
  report.columns.push_back("omega");
  report.columns.push_back("l1");  // the first Lyapunov coefficient (NaN: not computed)
  report.file = path;
  report.point_count = hopf.point_count();
  report.crossing_count = hopf.crossing_count;
  report.unrefined_count = hopf.unrefined_count;
  report.hopf_point_count = hopf.hopf_point_count;
  report.neutral_saddle_point_count = hopf.neutral_saddle_point_count;
  report.mixed_crossing_count = hopf.mixed_crossing_count;
  for (const HopfCurve& curve : hopf.curves) {
    for (const HopfPoint& point : curve.points) {
      if (point.is_bautin) {
        continue;
      }
      report.supercritical_count += point.first_lyapunov_coefficient < 0.0;
      report.subcritical_count += point.first_lyapunov_coefficient > 0.0;
    }
  }
  report.newton_iterations = hopf.newton_iterations;
  report.max_residual = hopf.max_residual;
  report.max_condition_residual = hopf.max_condition_residual;
  report.work = hopf.work;
  report.seconds = hopf.seconds;
  const int k_view = static_cast<int>(view_columns.size());
  const int k = static_cast<int>(report.columns.size());
  for (const HopfCurve& curve : hopf.curves) {
    Polyline in_view;
    Polyline written;
    in_view.points.setZero(k_view, static_cast<Eigen::Index>(curve.points.size()));
    written.points.setZero(k, static_cast<Eigen::Index>(curve.points.size()));
    in_view.is_closed = written.is_closed = curve.is_closed;
    HopfReport::Curve reported;
    reported.is_closed = curve.is_closed;
    for (std::size_t i = 0; i < curve.points.size(); ++i) {
      const HopfPoint& point = curve.points[i];
      const Eigen::VectorXd values = view.evaluate(point.x);
      const auto column = static_cast<Eigen::Index>(i);
      in_view.points.col(column).head(values.size()) = values;
      written.points.col(column).head(k_view) = in_view.points.col(column);
      for (std::size_t e = 0; e < extra.size(); ++e) {
        written.points(k_view + static_cast<Eigen::Index>(e), column) = point.x(extra[e]);
      }
      written.points(k - 2, column) = curve.is_neutral_saddle ? point.kappa : point.omega;
      written.points(k - 1, column) = point.first_lyapunov_coefficient;
      in_view.marked.push_back(point.is_bogdanov_takens);
      written.marked.push_back(point.is_bogdanov_takens);
      const Eigen::VectorXd full = written.points.col(column);
      reported.points.emplace_back(full.data(), full.data() + k);
      if (point.is_zero_hopf) {
        Polyline single_in_view;
        single_in_view.points = in_view.points.col(column);
        single_in_view.marked = {true};
        output.zero_hopf_points_in_view.push_back(std::move(single_in_view));
        Polyline single;
        single.points = written.points.col(column);
        single.marked = {true};
        output.zero_hopf_points.polylines.push_back(std::move(single));
      }
      if (point.is_bogdanov_takens || point.is_zero_hopf || point.is_bautin) {
        HopfReport::SpecialPoint special;
        special.kind = point.is_zero_hopf ? "zero_hopf"
                       : point.is_bautin  ? "bautin"
                                          : "bogdanov_takens";
        special.point = reported.points.back();
        special.plane[0] = point.x(parameters[0]);
        special.plane[1] = point.x(parameters[1]);
        // The same point ends two curves (a BT point the Hopf and the neutral saddle curve).
        const bool is_known = std::any_of(
            report.special_points.begin(), report.special_points.end(), [&](const auto& other) {
              return other.kind == special.kind && other.plane[0] == special.plane[0] &&
                     other.plane[1] == special.plane[1];
            });
        if (!is_known) {
          report.special_points.push_back(std::move(special));
        }
      }
    }
    if (curve.is_neutral_saddle) {
      report.neutral_saddle_curves.push_back(std::move(reported));
      output.neutral_saddle_curves_in_view.push_back(std::move(in_view));
      output.neutral_saddle_file.polylines.push_back(std::move(written));
    } else {
      report.curves.push_back(std::move(reported));
      output.curves_in_view.push_back(std::move(in_view));
      output.file.polylines.push_back(std::move(written));
    }
  }
  output.zero_hopf_points.options.names = report.columns;
  output.zero_hopf_points.options.kind = "hopf";
  output.zero_hopf_points.options.marker_name = "zero_hopf";
  PolylineFileOptions& saddle_options = output.neutral_saddle_file.options;
  saddle_options.names = report.columns;
  saddle_options.names[saddle_options.names.size() - 2] = "kappa";
  saddle_options.comments = comments;
  saddle_options.comments.push_back("neutral saddles of the dynamics over (" +
                                    report.plane_names[0] + ", " + report.plane_names[1] +
                                    "): real eigenvalue pairs ±kappa");
  saddle_options.kind = "neutral_saddle";
  saddle_options.marker_name = "bogdanov_takens";
  if (!output.neutral_saddle_file.polylines.empty() && !path.empty()) {
    report.neutral_saddle_file = neutral_saddle_file_beside(path);
    write_polylines(report.neutral_saddle_file, output.neutral_saddle_file.polylines,
                    saddle_options);
  }
  PolylineFileOptions& options = output.file.options;
  options.names = report.columns;
  options.comments = comments;
  options.comments.push_back("Hopf curves of the dynamics over (" + report.plane_names[0] + ", " +
                             report.plane_names[1] + "); omega: the frequency");
  options.kind = "hopf";
  options.marker_name = "bogdanov_takens";
  if (!path.empty()) {
    write_polylines(path, output.file.polylines, options);
  }
  return output;
}

}  // namespace tessera
