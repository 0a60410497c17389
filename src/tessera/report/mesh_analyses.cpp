// SPDX-License-Identifier: MIT
#include "tessera/report/mesh_analyses.h"

#include "tessera/core/error.h"

namespace tessera {

std::vector<PolylineFile> MeshAnalyses::curves_in_view(const std::vector<std::string>& names) const {
  std::vector<PolylineFile> files;
  auto add = [&](const std::vector<Polyline>& curves, PolylineFileOptions options) {
    options.names = names;
    files.push_back({curves, std::move(options)});
  };
  PolylineFileOptions fold_options;
  fold_options.kind = "fold";
  if (!fold_curves.empty()) {
    add(fold_curves, fold_options);
  }
  if (hopf) {
    add(hopf->curves_in_view, hopf->file.options);
    if (!hopf->neutral_saddle_curves_in_view.empty()) {
      add(hopf->neutral_saddle_curves_in_view, hopf->neutral_saddle_file.options);
    }
    if (!hopf->zero_hopf_points_in_view.empty()) {
      add(hopf->zero_hopf_points_in_view, hopf->zero_hopf_points.options);
    }
  }
  if (level) {
    PolylineFileOptions level_options;
    level_options.kind = "level";
    add(level->curves_in_view, level_options);
  }
  return files;
}

MeshAnalyses analyse_mesh(const ProblemSetup& setup, const TriangleMesh& mesh, const View& view,
                          const AnalysisRequest& request, MeshReport& report) {
  TESSERA_CHECK(!request.hopf || request.stability,
                "Hopf curves need the stability at the vertices (AnalysisRequest::stability)");
  MeshAnalyses analyses;
  if (mesh.triangle_count() == 0) {
    return analyses;
  }
  if (request.fold_plane) {
    // On the finished mesh, in its view; a partial mesh has the folds of what it covers.
    FoldOutput folds = compute_folds(setup, mesh, *request.fold_plane, view, request.fold_file,
                                     request.comments);
    if (folds.report.unrefined_count > 0) {
      analyses.warnings.push_back(
          std::to_string(folds.report.unrefined_count) +
          " fold point(s) did not converge onto the fold curve and are kept at the mesh's linear "
          "estimate (summary: folds.unrefined_points)");
    }
    if (folds.report.singular_triangle_count > 0) {
      analyses.warnings.push_back(
          "det(Dpi T) vanishes on " + std::to_string(folds.report.singular_triangle_count) +
          " triangle(s): there (" + folds.report.plane +
          ") is singular on M's tangent planes over a region, not along a fold curve; those "
          "triangles are left out (summary: folds.singular_triangles)");
    }
    analyses.fold_curves = std::move(folds.curves_in_view);
    report.folds = std::move(folds.report);
    if (!request.fold_file.empty()) {
      analyses.written.push_back(request.fold_file);
    }
  }
  if (request.stability) {
    analyses.stability = request.compute_stability
                             ? request.compute_stability(setup, mesh, *request.stability)
                             : compute_stability_output(setup, mesh, *request.stability);
    const StabilityReport& stability = analyses.stability->report;
    report.stability = stability;
    if (stability.failed_count > 0) {
      analyses.warnings.push_back(
          "the eigenvalues failed at " + std::to_string(stability.failed_count) +
          " vertex(es), whose unstable_count is -1 (summary: stability.failures); first: vertex " +
          std::to_string(stability.failures.front().vertex) + ": " +
          stability.failures.front().message);
    }
  }
  if (request.hopf) {
    analyses.hopf = compute_hopf_output(setup, mesh, analyses.stability->result, view,
                                        request.hopf_file, request.comments);
    const HopfReport& hopf = analyses.hopf->report;
    report.hopf = hopf;
    if (!request.hopf_file.empty()) {
      analyses.written.push_back(request.hopf_file);
      if (!hopf.neutral_saddle_file.empty()) {
        analyses.written.push_back(hopf.neutral_saddle_file);
      }
    }
    if (hopf.unrefined_count > 0) {
      analyses.warnings.push_back(
          "at " + std::to_string(hopf.unrefined_count) +
          " crossing(s) Newton converged neither to a Hopf point nor to a neutral saddle: left "
          "out, the curves are cut there (summary: hopf.unrefined_points)");
    }
  }
  if (request.level) {
    analyses.level = compute_level_curves(setup, mesh, *request.level, view, request.level_file,
                                          request.comments);
    report.level = analyses.level->report;
    if (!request.level_file.empty()) {
      analyses.written.push_back(request.level_file);
    }
    if (analyses.level->report.unrefined_count > 0) {
      analyses.warnings.push_back(
          std::to_string(analyses.level->report.unrefined_count) +
          " level curve point(s) did not converge and are kept at the mesh's linear estimate "
          "(summary: level.unrefined_points)");
    }
  }
  return analyses;
}

}  // namespace tessera
