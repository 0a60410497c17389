// SPDX-License-Identifier: MIT
#include "tessera/report/level_output.h"

#include <filesystem>

#include "tessera/core/error.h"
#include "tessera/io/file_names.h"
#include "tessera/io/view_mesh.h"

namespace tessera {

std::string default_level_file(const std::string& mesh_path) {
  return curve_file_beside(mesh_path, "level");
}

LevelSet parse_level_option(const std::string& specification, const ImplicitProblem& problem) {
  try {
    return parse_level_set(specification, problem);
  } catch (const ViewSpecificationError& error) {
    throw InvalidArgument("--level " + specification + ": " + error.reason());
  } catch (const InvalidArgument& error) {
    throw InvalidArgument("--level " + specification + ": " + error.what());
  }
}

LevelOutput compute_level_curves(const ProblemSetup& setup, const TriangleMesh& mesh,
                                 const LevelSet& level, const View& view, const std::string& path,
                                 const std::vector<std::string>& comments) {
  const LevelCurves curves = find_level_curves(*setup.problem, mesh, level);
  LevelOutput output;
  LevelReport& report = output.report;
  report.level = level.specification();
  report.functional = level.functional.specification();
  report.functional_name = level.functional.names().front();
  report.value = level.value;
  report.file = path;
  report.columns = coordinate_names_in_view(view);
  report.point_count = curves.point_count();
  report.crossing_count = curves.crossing_count;
  report.unrefined_count = curves.unrefined_count;
  report.undefined_vertex_count = curves.undefined_vertex_count;
  report.newton_iterations = curves.newton_iterations;
  report.max_point_iterations = curves.max_point_iterations;
  report.max_residual = curves.max_residual;
  report.max_level_residual = curves.max_level_residual;
  report.work = curves.work;
  report.seconds = curves.seconds;
  const int k = static_cast<int>(report.columns.size());
  for (const LevelCurve& curve : curves.curves) {
    Polyline line;
    line.points.setZero(k, static_cast<Eigen::Index>(curve.points.size()));
    line.is_closed = curve.is_closed;
    LevelReport::Curve reported;
    reported.is_closed = curve.is_closed;
    for (std::size_t i = 0; i < curve.points.size(); ++i) {
      const LevelPoint& point = curve.points[i];
      const Eigen::VectorXd values = view.evaluate(point.x);
      line.points.col(static_cast<Eigen::Index>(i)).head(values.size()) = values;
      line.marked.push_back(!point.is_refined);
      const Eigen::VectorXd column = line.points.col(static_cast<Eigen::Index>(i));
      reported.points.emplace_back(column.data(), column.data() + k);
    }
    report.curves.push_back(std::move(reported));
    output.curves_in_view.push_back(std::move(line));
  }
  if (!path.empty()) {
    PolylineFileOptions options;
    options.names = report.columns;
    options.marker_name = "unrefined";
    options.comments = comments;
    options.comments.push_back("level curves " + report.level);
    write_polylines(path, output.curves_in_view, options);
  }
  return output;
}

}  // namespace tessera
