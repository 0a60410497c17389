// SPDX-License-Identifier: MIT
#include "tessera/report/fold_output.h"

#include <filesystem>

#include "tessera/core/error.h"
#include "tessera/io/file_names.h"
#include "tessera/io/view_mesh.h"
#include "tessera/methods/folds/fold_curves.h"

namespace tessera {

std::string default_fold_file(const std::string& mesh_path) {
  return curve_file_beside(mesh_path, "folds");
}

ParameterPlane parse_folds_option(const std::string& specification,
                                  const ImplicitProblem& problem) {
  try {
    return parse_parameter_plane(specification, problem);
  } catch (const ViewSpecificationError& error) {
    throw InvalidArgument("--folds " + specification + ": " + error.reason());
  } catch (const InvalidArgument& error) {
    throw InvalidArgument("--folds " + specification + ": " + error.what());
  }
}

FoldOutput compute_folds(const ProblemSetup& setup, const TriangleMesh& mesh,
                         const ParameterPlane& plane, const View& view, const std::string& path,
                         const std::vector<std::string>& comments) {
  const FoldCurves folds = find_fold_curves(*setup.problem, mesh, plane);
  FoldOutput output;
  FoldReport& report = output.report;
  report.plane = plane.specification();
  report.plane_names = plane.view().names();
  report.file = path;
  report.columns = coordinate_names_in_view(view);
  report.point_count = folds.point_count();
  report.crossing_count = folds.crossing_count;
  report.unrefined_count = folds.unrefined_count;
  report.singular_triangle_count = folds.singular_triangle_count;
  report.newton_iterations = folds.newton_iterations;
  report.tangent_evaluations = folds.tangent_evaluations;
  report.max_residual = folds.max_residual;
  report.work = folds.work;
  report.seconds = folds.seconds;
  const int k = static_cast<int>(report.columns.size());
  for (const FoldCurve& curve : folds.curves) {
    Polyline line;
    line.points.setZero(k, static_cast<Eigen::Index>(curve.points.size()));
    line.is_closed = curve.is_closed;
    FoldReport::Curve reported;
    reported.is_closed = curve.is_closed;
    for (std::size_t i = 0; i < curve.points.size(); ++i) {
      const FoldPoint& point = curve.points[i];
      const Eigen::VectorXd values = view.evaluate(point.x);  // k = 2: the third stays 0
      line.points.col(static_cast<Eigen::Index>(i)).head(values.size()) = values;
      line.marked.push_back(point.is_cusp);
      const Eigen::VectorXd column = line.points.col(static_cast<Eigen::Index>(i));
      reported.points.emplace_back(column.data(), column.data() + k);
      if (point.is_cusp) {
        const Eigen::Vector2d in_plane = plane.value(point.x);
        report.cusps.push_back(
            {reported.points.back(), {in_plane(0), in_plane(1)}, point.is_refined});
      }
    }
    report.curves.push_back(std::move(reported));
    output.curves_in_view.push_back(std::move(line));
  }
  if (!path.empty()) {
    PolylineFileOptions options;
    options.names = report.columns;
    options.comments = comments;
    options.comments.push_back("fold curves over the plane (" + report.plane + ")");
    options.kind = "fold";
    write_polylines(path, output.curves_in_view, options);
  }
  return output;
}

}  // namespace tessera
