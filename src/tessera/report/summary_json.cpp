// SPDX-License-Identifier: MIT
#include "tessera/report/summary_json.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tessera/core/error.h"
#include "tessera/io/text_file.h"
#include "tessera/problems/view.h"
#include "tessera/report/component_report.h"
#include "tessera/report/improvement_report.h"

namespace tessera {
namespace {

nlohmann::json statistic(const Statistic& s) {
  return {{"max", s.max}, {"mean", s.mean}, {"count", s.count}, {"population", s.population}};
}

// Whether this process held every vertex's whole state (no backend said it split them).
bool is_whole_states(const MeshReport& report) {
  return !report.backend || report.backend->states == "whole";
}

// The index lists of the geometric defects are complete in MeshValidation; the summary keeps
// the first ones (a broken mesh may have 10⁵) and the complete counts beside them.
constexpr std::size_t max_listed_in_json = 100;

template <class T>
std::vector<T> first_entries(const std::vector<T>& list) {
  return {list.begin(), list.begin() + std::min(list.size(), max_listed_in_json)};
}

nlohmann::json geometry(const MeshValidation& v) {
  nlohmann::json pairs = nlohmann::json::array();
  for (const auto& [s, t] : first_entries(v.overlapping_triangle_pairs)) {
    pairs.push_back({s, t});
  }
  return {
      {"checked", v.is_geometry_checked},
      {"cut_short", v.checks_cut_short},
      {"flipped_triangles",
       {{"count", v.flipped_triangle_count}, {"triangles", first_entries(v.flipped_triangles)}}},
      {"overlapping_triangles", {{"count", v.overlapping_pair_count}, {"pairs", pairs}}},
      {"vertices_outside_domain",
       {{"count", v.vertex_outside_domain_count},
        {"vertices", first_entries(v.vertices_outside_domain)}}},
      {"unoriented_triangles", v.unoriented_triangle_count},
      {"crossing_pairs", v.crossing_pair_count}};
}

nlohmann::json level_json(const LevelReport& level) {
  nlohmann::json curves = nlohmann::json::array();
  for (const auto& curve : level.curves) {
    curves.push_back({{"closed", curve.is_closed}, {"points", curve.points}});
  }
  return {{"level", level.level},
          {"functional", level.functional},
          {"name", level.functional_name},
          {"value", level.value},
          {"file", level.file},
          {"columns", level.columns},
          {"curve_count", level.curves.size()},
          {"point_count", level.point_count},
          {"edge_crossings", level.crossing_count},
          {"unrefined_points", level.unrefined_count},
          {"undefined_vertices", level.undefined_vertex_count},
          {"max_residual", level.max_residual},
          {"max_level_residual", level.max_level_residual},
          {"newton_iterations", level.newton_iterations},
          {"max_point_iterations", level.max_point_iterations},
          {"work",
           {{"function_evaluations", level.work.function_evaluations},
            {"jacobian_evaluations", level.work.jacobian_evaluations},
            {"factorisations", level.work.factorisations}}},
          {"seconds", level.seconds},
          {"curves", std::move(curves)}};
}

nlohmann::json work_json(const WorkCounts& work) {
  return {{"function_evaluations", work.function_evaluations},
          {"jacobian_evaluations", work.jacobian_evaluations},
          {"factorisations", work.factorisations}};
}

nlohmann::json stability_json(const StabilityReport& stability) {
  nlohmann::json failures = nlohmann::json::array();
  for (const auto& failure : stability.failures) {
    failures.push_back({{"vertex", failure.vertex}, {"message", failure.message}});
  }
  return {{"parameters", stability.parameters},
          {"method", stability.method},
          {"eigenvalues_per_vertex",
           stability.eigenvalue_count == 0 ? nlohmann::json("all")
                                           : nlohmann::json(stability.eigenvalue_count)},
          {"vertices", stability.vertex_count},
          {"stable_vertices", stability.stable_count},
          {"vertices_by_index", stability.index_counts},
          {"failed_vertices", stability.failed_count},
          {"uncertain_vertices", stability.uncertain_count},
          {"certainty", stability.certainty},
          {"failures", std::move(failures)},
          {"factorisations", stability.factorisations},
          {"solves", stability.solves},
          {"jacobian_evaluations", stability.jacobian_evaluations},
          {"seconds", stability.seconds}};
}

nlohmann::json hopf_json(const HopfReport& hopf) {
  auto named = [&](const std::vector<double>& point) {
    nlohmann::json values = nlohmann::json::object();
    for (std::size_t i = 0; i < point.size() && i < hopf.columns.size(); ++i) {
      values[hopf.columns[i]] = point[i];
    }
    return values;
  };
  nlohmann::json special = nlohmann::json::array();
  for (const auto& p : hopf.special_points) {
    special.push_back(
        {{"kind", p.kind},
         {"point", named(p.point)},
         {"plane", {{hopf.plane_names.at(0), p.plane[0]}, {hopf.plane_names.at(1), p.plane[1]}}}});
  }
  nlohmann::json curves = nlohmann::json::array();
  for (const auto& curve : hopf.curves) {
    curves.push_back({{"closed", curve.is_closed}, {"points", curve.points}});
  }
  nlohmann::json neutral_saddles = nlohmann::json::array();
  for (const auto& curve : hopf.neutral_saddle_curves) {
    neutral_saddles.push_back({{"closed", curve.is_closed}, {"points", curve.points}});
  }
  return {{"file", hopf.file},
          {"columns", hopf.columns},
          {"plane", hopf.plane_names},
          {"curve_count", hopf.curves.size()},
          {"point_count", hopf.point_count},
          {"edge_crossings", hopf.crossing_count},
          {"unrefined_points", hopf.unrefined_count},
          {"hopf_points", hopf.hopf_point_count},
          {"neutral_saddle_points", hopf.neutral_saddle_point_count},
          {"mixed_crossings", hopf.mixed_crossing_count},
          {"supercritical_points", hopf.supercritical_count},
          {"subcritical_points", hopf.subcritical_count},
          {"neutral_saddle_file", hopf.neutral_saddle_file},
          {"special_points", std::move(special)},
          {"max_residual", hopf.max_residual},
          {"max_condition_residual", hopf.max_condition_residual},
          {"newton_iterations", hopf.newton_iterations},
          {"work", work_json(hopf.work)},
          {"seconds", hopf.seconds},
          {"curves", std::move(curves)},
          {"neutral_saddle_curves", std::move(neutral_saddles)}};
}

nlohmann::json folds_json(const FoldReport& folds) {
  auto named = [&](const std::vector<double>& point) {
    nlohmann::json values = nlohmann::json::object();
    for (std::size_t i = 0; i < point.size() && i < folds.columns.size(); ++i) {
      values[folds.columns[i]] = point[i];
    }
    return values;
  };
  nlohmann::json cusps = nlohmann::json::array();
  for (const auto& cusp : folds.cusps) {
    cusps.push_back(
        {{"point", named(cusp.point)},
         {"plane",
          {{folds.plane_names.at(0), cusp.plane[0]}, {folds.plane_names.at(1), cusp.plane[1]}}},
         {"refined", cusp.is_refined}});
  }
  nlohmann::json curves = nlohmann::json::array();
  for (const auto& curve : folds.curves) {
    curves.push_back({{"closed", curve.is_closed}, {"points", curve.points}});
  }
  return {{"plane", folds.plane},
          {"file", folds.file},
          {"columns", folds.columns},
          {"curve_count", folds.curves.size()},
          {"point_count", folds.point_count},
          {"edge_crossings", folds.crossing_count},
          {"unrefined_points", folds.unrefined_count},
          {"singular_triangles", folds.singular_triangle_count},
          {"cusps", std::move(cusps)},
          {"max_residual", folds.max_residual},
          {"newton_iterations", folds.newton_iterations},
          {"tangent_evaluations", folds.tangent_evaluations},
          {"work",
           {{"function_evaluations", folds.work.function_evaluations},
            {"jacobian_evaluations", folds.work.jacobian_evaluations},
            {"factorisations", folds.work.factorisations}}},
          {"seconds", folds.seconds},
          {"curves", std::move(curves)}};
}

// A block is one entry with its range, a coordinate outside blocks one entry of size 1: the
// column ranges of the states array without n names.
nlohmann::json state_columns(const StatesReport& states) {
  nlohmann::json columns = nlohmann::json::array();
  const int n = static_cast<int>(states.coordinate_names.size());
  for (int i = 0; i < n;) {
    const auto block =
        std::find_if(states.blocks.begin(), states.blocks.end(),
                     [&](const CoordinateBlock& b) { return b.first == i && b.size >= 1; });
    if (block != states.blocks.end()) {
      columns.push_back({{"name", block->name},
                         {"first", block->first},
                         {"size", block->size},
                         {"block", true},
                         {"weight", block->weight}});
      i += block->size;
    } else {
      columns.push_back({{"name", states.coordinate_names[static_cast<std::size_t>(i)]},
                         {"first", i},
                         {"size", 1},
                         {"block", false}});
      ++i;
    }
  }
  return columns;
}

}  // namespace

std::string to_json(const MeshReport& report) {
  const MeshValidation& v = report.validation;
  const MeshQuality& q = report.quality;
  nlohmann::json j;
  j["problem"] = report.problem;
  j["ambient_dimension"] = report.ambient_dimension;
  if (report.run) {
    const CoveringSummary& r = *report.run;
    j["run"] = {{"method", r.method},
                {"termination", to_string(r.termination)},
                {"completed", r.is_complete()},
                {"message", r.message},
                {"step", r.step},
                {"wall_seconds", r.wall_seconds},
                {"threads", r.threads},
                {"function_evaluations", r.function_evaluations},
                {"jacobian_evaluations", r.jacobian_evaluations},
                {"factorisations", r.factorisations},
                {"solves", r.solves},
                {"factorisation_seconds", r.factorisation_seconds},
                {"merges", r.merges},
                {"front_connections", r.front_connections},
                {"step_reductions", r.step_reductions},
                {"clipped_half_spaces", r.clipped_half_spaces},
                {"tolerance", r.tolerance},
                {"max_sampled_distance", r.max_sampled_distance},
                {"refined_edges", r.refined_edges},
                {"removed_triangles", r.removed_triangles},
                {"repaired_holes", r.repaired_holes}};
    if (r.charts > 0) {
      j["run"]["atlas"] = {{"charts", r.charts},
                           {"placement", r.placement},
                           {"min_chart_radius", r.min_chart_radius},
                           {"max_chart_radius", r.max_chart_radius},
                           {"singular_crossings", r.singular_crossings},
                           {"sheet_rejections", r.sheet_rejections},
                           {"filled_holes", r.filled_holes},
                           {"borrowed_factorisations", r.borrowed_factorisations},
                           {"boundary_peak_bytes", r.boundary_peak_bytes},
                           {"radius_caps",
                            {{"total", r.radius_caps.total()},
                             {"curvature", r.radius_caps.curvature},
                             {"not_a_graph", r.radius_caps.not_a_graph},
                             {"grading", r.radius_caps.grading},
                             {"reach", r.radius_caps.reach},
                             {"band", r.radius_caps.band},
                             {"reduced_later", r.radius_caps.reduced_later}}}};
    }
    nlohmann::json phases = nlohmann::json::array();
    for (const PhaseWork& p : r.work_by_phase) {
      phases.push_back({{"phase", p.phase},
                        {"function_evaluations", p.counts.function_evaluations},
                        {"jacobian_evaluations", p.counts.jacobian_evaluations},
                        {"factorisations", p.counts.factorisations},
                        {"solves", p.counts.solves},
                        {"wall_seconds", p.wall_seconds}});
    }
    j["run"]["work_by_phase"] = phases;
    if (r.resumed_from) {
      // A run continued from a checkpoint: the counts above include the work before it.
      // The atlas counts its charts, the front its vertices.
      nlohmann::json& resumed = j["run"]["resumed_from"];
      if (r.resumed_from->vertices > 0) {
        resumed["vertices"] = r.resumed_from->vertices;
      } else {
        resumed["charts"] = r.resumed_from->charts;
      }
      resumed["build_seconds"] = r.resumed_from->build_seconds;
      resumed["function_evaluations"] = r.resumed_from->counts.function_evaluations;
      resumed["jacobian_evaluations"] = r.resumed_from->counts.jacobian_evaluations;
      resumed["factorisations"] = r.resumed_from->counts.factorisations;
    }
    if (r.vertex_count > 0) {
      const double V = r.vertex_count;
      j["run"]["per_vertex"] = {{"function_evaluations", r.function_evaluations / V},
                                {"jacobian_evaluations", r.jacobian_evaluations / V},
                                {"factorisations", r.factorisations / V},
                                {"solves", r.solves / V},
                                {"wall_seconds", r.wall_seconds / V}};
      if (r.factorisations > 0 && r.factorisation_seconds > 0) {
        // Time per vertex in units of the run's mean factorisation: the cost of a vertex in
        // factorisations' worth, comparable across n and machines.
        j["run"]["per_vertex"]["factorisations_worth"] =
            r.wall_seconds / V / (r.factorisation_seconds / r.factorisations);
      }
    }
    if (r.resident_peak_bytes > 0) {
      // The sampled resident memory; against the vertices' own states (8n bytes each) where
      // the states are whole in this process.
      j["run"]["memory"] = {
          {"resident_peak_bytes", r.resident_peak_bytes},
          {"resident_beyond_boundary_peak_bytes", r.resident_beyond_boundary_peak_bytes}};
      if (r.vertex_count > 0 && is_whole_states(report)) {
        j["run"]["memory"]["beyond_boundary_per_state"] =
            r.resident_beyond_boundary_peak_bytes /
            (8.0 * report.ambient_dimension * r.vertex_count);
      }
    }
    j["run"]["notes"] = r.notes;
    add_components_json(r, report.ambient_dimension, j["run"]);
  }
  if (report.improvement) {
    j["improvement"] = improvement_json(*report.improvement);
  }
  if (report.stop) {
    j["stop"] = {{"signal", report.stop->signal},
                 {"signals", report.stop->signal_count},
                 {"stage", report.stop->stage},
                 {"left_out", report.stop->left_out}};
  }
  if (report.backend) {
    j["backend"] = {{"name", report.backend->name},
                    {"ranks", report.backend->ranks},
                    {"states", report.backend->states}};
  }
  if (report.view) {
    j["view"] = {{"specification", report.view->specification}, {"origin", report.view->origin}};
    if (!report.view->columns.empty()) {
      j["view"]["columns"] = report.view->columns;
    }
  }
  if (report.states) {
    const StatesReport& states = *report.states;
    j["states"] = {
        {"file", states.states_file},
        {"triangles_file", states.triangles_file},
        {"shape", {states.vertex_count, static_cast<int>(states.coordinate_names.size())}},
        {"triangles_shape", {states.triangle_count, 3}},
        {"columns", state_columns(states)}};
  }
  if (report.folds) {
    j["folds"] = folds_json(*report.folds);
  }
  if (report.level) {
    j["level"] = level_json(*report.level);
  }
  if (report.stability) {
    j["stability"] = stability_json(*report.stability);
  }
  if (report.hopf) {
    j["hopf"] = hopf_json(*report.hopf);
  }
  j["counts"] = {
      {"vertices", v.referenced_vertex_count},   {"edges", v.edge_count},
      {"triangles", v.triangle_count},           {"boundary_edges", v.boundary_edge_count},
      {"boundary_loops", v.boundary_loop_count}, {"components", v.component_count}};
  j["topology"] = {{"euler_characteristic", v.euler_characteristic},
                   {"orientable", v.is_orientable},
                   {"closed", v.is_closed()},
                   {"genus", v.genus}};
  if (report.expected_euler_characteristic) {
    j["topology"]["expected_euler_characteristic"] = *report.expected_euler_characteristic;
  }
  j["valid"] = v.is_valid();
  nlohmann::json defects = nlohmann::json::array();
  for (const MeshDefect& d : v.defects) {
    defects.push_back(
        {{"kind", std::string(to_string(d.kind))}, {"count", d.count}, {"examples", d.examples}});
  }
  j["defects"] = defects;
  j["geometry"] = geometry(v);
  j["distance_to_manifold"] = {{"vertex_residual_F", statistic(q.vertex_residual)},
                               {"vertices", statistic(q.vertex_distance)},
                               {"centroids", statistic(q.centroid_distance)},
                               {"edge_midpoints", statistic(q.midpoint_distance)},
                               {"failed_projections", q.failed_projections}};
  j["shape"] = {{"min_angle_degrees", q.min_angle_degrees},
                {"max_angle_degrees", q.max_angle_degrees},
                {"fraction_angles_below_30_degrees", q.fraction_angles_below_30},
                {"min_edge_length", q.min_edge_length},
                {"max_edge_length", q.max_edge_length},
                {"area", q.area}};
  if (report.exact_area) {
    j["shape"]["exact_area"] = *report.exact_area;
    j["shape"]["area_relative_error"] = std::abs(q.area - *report.exact_area) / *report.exact_area;
  }
  return j.dump(2) + "\n";
}

void write_summary_json(const std::string& path, const MeshReport& report) {
  write_text_file(path, to_json(report), "JSON summary");
}

std::string to_text(const MeshReport& report) {
  const MeshValidation& v = report.validation;
  const MeshQuality& q = report.quality;
  std::ostringstream out;
  out.precision(3);
  out << "problem        " << report.problem << " (n = " << report.ambient_dimension << ")\n";
  if (report.run) {
    const CoveringSummary& r = *report.run;
    out << "method         " << r.method;
    if (r.charts > 0) {
      out << (r.placement.empty() ? "" : " (" + r.placement + " placement)") << ", tolerance "
          << r.tolerance << ", " << r.charts << " charts of radius "
          << r.min_chart_radius << " … " << r.max_chart_radius;
    } else {
      out << ", step " << r.step;
      if (r.tolerance > 0) {
        out << ", tolerance " << r.tolerance;
      }
    }
    out << ", " << to_string(r.termination) << (r.message.empty() ? "" : ": " + r.message) << "\n";
    if (report.run->resumed_from) {
      const auto& resumed = *report.run->resumed_from;
      out << "resumed        from a checkpoint of "
          << (resumed.vertices > 0 ? resumed.vertices : resumed.charts)
          << (resumed.vertices > 0 ? " vertices (" : " charts (") << resumed.build_seconds
          << " s of build)\n";
    }
    if (report.stop) {
      out << "stopped        by " << report.stop->signal << " during " << report.stop->stage;
      for (std::size_t i = 0; i < report.stop->left_out.size(); ++i) {
        out << (i ? "; " : "; left out: ") << report.stop->left_out[i];
      }
      out << "\n";
    }
    out << components_text(r, report.ambient_dimension);
    if (r.max_sampled_distance >= 0) {
      out << "tolerance      every triangle checked: largest sampled distance to M "
          << r.max_sampled_distance << " (bound " << r.tolerance << "), " << r.refined_edges
          << " edge(s) bisected\n";
    }
    if (r.removed_triangles > 0) {
      out << "repair         " << r.removed_triangles << " triangle(s) removed by the final check, "
          << r.repaired_holes << " place(s) triangulated again\n";
    }
    if (report.improvement) {
      out << "improve        " << improvement_text(*report.improvement) << "\n";
    }
    for (const std::string& note : r.notes) {
      out << "note           " << note << "\n";
    }
    out << "work           " << r.wall_seconds << " s on " << r.threads
        << (r.threads == 1 ? " thread, " : " threads, ") << r.function_evaluations
        << " evaluations of F, " << r.jacobian_evaluations << " of DF, " << r.factorisations
        << " factorisations, " << r.solves << " solves";
    if (r.vertex_count > 0) {
      const double V = r.vertex_count;
      out << " (" << r.function_evaluations / V << ", " << r.jacobian_evaluations / V << ", "
          << r.factorisations / V << " and " << r.solves / V << " per vertex)";
    }
    out << "\n";
    // In factorisations' worth where factorisations are the cost (large n); at small n one
    // takes a microsecond and the ratio says nothing.
    if (r.vertex_count > 0 && r.factorisations > 0 && r.factorisation_seconds > 0 &&
        report.ambient_dimension > kLargeAmbientDimension) {
      const double one = r.factorisation_seconds / r.factorisations;
      out << "  per vertex   " << 1000.0 * r.wall_seconds / r.vertex_count
          << " ms = " << r.wall_seconds / r.vertex_count / one
          << " factorisations' time (one: " << 1000.0 * one << " ms, DF and analysis included)\n";
    }
    if (r.resident_peak_bytes > 0 && r.vertex_count > 0 && is_whole_states(report) &&
        report.ambient_dimension > kLargeAmbientDimension) {
      const double states = 8.0 * report.ambient_dimension * r.vertex_count;
      out << "  memory       " << r.resident_peak_bytes / 1e6 << " MB resident at most (sampled), "
          << r.resident_beyond_boundary_peak_bytes / states
          << " × the vertices' states (8n bytes each) beyond the open boundary\n";
    }
    if (r.vertex_count > 0 && !r.work_by_phase.empty()) {
      // Where the work went, per vertex of the result: DF evaluations/factorisations per step.
      const double V = r.vertex_count;
      // The unit first, so that the numbers after it read as what they are.
      out << "  by step (DF / factorisations / solves per vertex): ";
      for (std::size_t i = 0; i < r.work_by_phase.size(); ++i) {
        const PhaseWork& p = r.work_by_phase[i];
        out << (i ? ", " : "") << p.phase << " " << p.counts.jacobian_evaluations / V << "/"
            << p.counts.factorisations / V << "/" << p.counts.solves / V;
      }
      out << "\n";
    }
  }
  if (report.backend && report.backend->name != "serial") {
    out << "backend        " << report.backend->name << " on " << report.backend->ranks
        << (report.backend->ranks == 1 ? " rank" : " ranks") << ", states "
        << report.backend->states << "\n";
  }
  if (report.view && !(report.view->specification == "all" && report.view->origin == "default")) {
    out << "view           " << report.view->specification << " (";
    if (report.view->origin == "default for large n") {
      // Say why the file does not hold the coordinates, and how to get them.
      out << "the default for n = " << report.ambient_dimension << " > " << kLargeAmbientDimension
          << "; --view all writes all " << report.ambient_dimension
          << " coordinates, --states FILE.npy the states";
    } else {
      out << "from " << report.view->origin;
    }
    out << ")\n";
  }
  if (report.states) {
    const StatesReport& states = *report.states;
    out << "states         " << states.states_file << " (" << states.vertex_count << " × "
        << states.coordinate_names.size() << ", <f8) and " << states.triangles_file << " ("
        << states.triangle_count << " × 3, <i8)\n";
  }
  if (report.folds) {
    const FoldReport& folds = *report.folds;
    out << "folds          " << folds.curves.size() << " curve(s) over (" << folds.plane << "), "
        << folds.point_count << " points on the fold to solver tolerance";
    if (folds.unrefined_count > 0) {
      out << " (" << folds.unrefined_count << " NOT refined: at the mesh's estimate)";
    }
    if (folds.singular_triangle_count > 0) {
      out << " (det(Dπ·T) = 0 on all of " << folds.singular_triangle_count
          << " triangles: no fold curve there)";
    }
    out << ", " << folds.cusps.size() << " cusp(s)";
    for (const auto& cusp : folds.cusps) {
      out << "; cusp at " << folds.plane_names.at(0) << " = " << cusp.plane[0] << ", "
          << folds.plane_names.at(1) << " = " << cusp.plane[1]
          << (cusp.is_refined ? "" : " (bracketed, not refined)");
    }
    out << (folds.file.empty() ? "" : " → " + folds.file) << "\n";
  }
  if (report.level) {
    const LevelReport& level = *report.level;
    out << "level          " << level.curves.size() << " curve(s) where " << level.level << ", "
        << level.point_count << " points on it to solver tolerance";
    if (level.unrefined_count > 0) {
      out << " (" << level.unrefined_count << " NOT refined: at the mesh's estimate)";
    }
    if (level.undefined_vertex_count > 0) {
      out << " (" << level.functional << " not finite at " << level.undefined_vertex_count
          << " vertices: curves may end there)";
    }
    out << (level.file.empty() ? "" : " → " + level.file) << "\n";
  }
  if (report.stability) {
    const StabilityReport& stability = *report.stability;
    out << "stability      " << stability.stable_count << " of " << stability.vertex_count
        << " vertices stable";
    for (std::size_t i = 1; i < stability.index_counts.size(); ++i) {
      if (stability.index_counts[i] > 0) {
        out << ", " << stability.index_counts[i] << " with " << i << " unstable eigenvalue"
            << (i == 1 ? "" : "s");
      }
    }
    if (stability.failed_count > 0) {
      out << ", " << stability.failed_count << " FAILED (summary: stability.failures)";
    }
    out << "; " << stability.certainty << "\n";
  }
  if (report.hopf) {
    const HopfReport& hopf = *report.hopf;
    out << "hopf           " << hopf.curves.size() << " curve(s), " << hopf.hopf_point_count
        << " points on them to solver tolerance";
    if (hopf.supercritical_count + hopf.subcritical_count > 0) {
      out << " (" << hopf.supercritical_count << " supercritical, " << hopf.subcritical_count
          << " subcritical)";
    }
    if (!hopf.neutral_saddle_curves.empty()) {
      out << "; " << hopf.neutral_saddle_curves.size() << " neutral saddle curve(s), "
          << hopf.neutral_saddle_point_count << " points";
    }
    if (hopf.unrefined_count > 0) {
      out << " (" << hopf.unrefined_count
          << " crossing(s) where Newton converged to neither: left out, the curves cut there)";
    }
    int bogdanov_takens = 0;
    int zero_hopf = 0;
    int bautin = 0;
    for (const auto& p : hopf.special_points) {
      bogdanov_takens += p.kind == "bogdanov_takens";
      zero_hopf += p.kind == "zero_hopf";
      bautin += p.kind == "bautin";
    }
    out << ", " << bogdanov_takens << " Bogdanov–Takens point(s)";
    if (zero_hopf > 0) {
      out << ", " << zero_hopf << " fold–Hopf point(s)";
    }
    if (bautin > 0) {
      out << ", " << bautin << " Bautin point(s)";
    }
    for (const auto& p : hopf.special_points) {
      out << "; " << (p.kind == "zero_hopf" ? "fold–Hopf" : p.kind == "bautin" ? "Bautin" : "BT")
          << " at "
          << hopf.plane_names.at(0) << " = " << p.plane[0] << ", " << hopf.plane_names.at(1)
          << " = " << p.plane[1];
    }
    out << (hopf.file.empty() ? "" : " → " + hopf.file)
        << (hopf.neutral_saddle_curves.empty() || hopf.neutral_saddle_file.empty()
                ? ""
                : ", " + hopf.neutral_saddle_file)
        << "\n";
  }
  out << "mesh           " << v.referenced_vertex_count << " vertices, " << v.edge_count
      << " edges, " << v.triangle_count << " triangles, " << v.boundary_loop_count
      << " boundary loop(s)\n";
  out << "topology       Euler characteristic " << v.euler_characteristic;
  if (report.expected_euler_characteristic) {
    out << " (expected " << *report.expected_euler_characteristic << ")";
  }
  out << ", " << (v.is_orientable ? "orientable" : "non-orientable") << ", "
      << (!v.is_valid()      ? "INVALID"
          : v.is_cut_short() ? "valid as far as checked"
                             : "valid")
      << "\n";
  if (v.is_geometry_checked) {
    out << "geometry       " << v.flipped_triangle_count << " flipped triangle(s), "
        << v.overlapping_pair_count << " overlapping pair(s), " << v.vertex_outside_domain_count
        << " vertex(es) outside the domain";
    if (v.unoriented_triangle_count > 0) {
      out << "; " << v.unoriented_triangle_count << " triangle(s) not oriented (DF singular)";
    }
    if (v.crossing_pair_count > 0) {
      out << "; " << v.crossing_pair_count
          << " pair(s) of triangles where components cross (sheets of M crossing)";
    }
    out << "\n";
    for (const std::string& cut : v.checks_cut_short) {
      out << "  cut short   " << cut << " (a stop request)\n";
    }
  }
  for (const MeshDefect& d : v.defects) {
    out << "  defect       " << to_string(d.kind) << ": " << d.count
        << (d.examples.empty() ? "" : " (" + d.examples.front() + ")") << "\n";
  }
  const bool is_measured = q.vertex_residual.count > 0 || q.centroid_distance.count > 0 ||
                           q.vertex_residual.population == 0;
  if (!is_measured) {
    // A stopped run's report: nothing measured, not "0".
    out << "on M           not measured" << (report.stop ? " (the run was stopped)" : "") << "\n";
  } else {
    out << "on M           max |F| " << q.vertex_residual.max << " at vertices; distance to M: "
        << "vertices " << q.vertex_distance.max << ", centroids " << q.centroid_distance.max
        << ", edge midpoints " << q.midpoint_distance.max;
    if (q.centroid_distance.count < q.centroid_distance.population) {
      // The largest of K uniform samples exceeds the q-quantile with probability 1 − q^K.
      const int samples = std::max(1, q.centroid_distance.count);
      const double bounded = 100.0 * std::pow(0.05, 1.0 / samples);
      std::ostringstream share;
      share.precision(3);
      share << bounded;
      out << " (largest of " << q.centroid_distance.count
          << " uniform samples of each: with 95% confidence it bounds " << share.str()
          << "% of the points)";
    }
    out << "\n";
  }
  if (q.failed_projections > 0) {
    out << "  warning      " << q.failed_projections << " points could not be projected onto M\n";
  }
  out << "shape          angles " << q.min_angle_degrees << "° … " << q.max_angle_degrees << "°, "
      << 100 * q.fraction_angles_below_30 << "% below 30°; edges " << q.min_edge_length << " … "
      << q.max_edge_length << "\n";
  out.precision(8);
  out << "area           " << q.area;
  if (report.exact_area) {
    out.precision(3);
    out << " (exact " << *report.exact_area << ", relative error "
        << std::abs(q.area - *report.exact_area) / *report.exact_area << ")";
  }
  out << "\n";
  return out.str();
}

}  // namespace tessera
