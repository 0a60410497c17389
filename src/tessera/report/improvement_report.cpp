// SPDX-License-Identifier: MIT
#include "tessera/report/improvement_report.h"

#include <nlohmann/json.hpp>
#include <sstream>

namespace tessera {

nlohmann::json improvement_quality_json(const MeshQuality& quality,
                                        const MeshValidation& validation) {
  return {{"min_angle_degrees", quality.min_angle_degrees},
          {"max_angle_degrees", quality.max_angle_degrees},
          {"fraction_angles_below_30", quality.fraction_angles_below_30},
          {"max_centroid_distance", quality.centroid_distance.max},
          {"max_midpoint_distance", quality.midpoint_distance.max},
          {"failed_projections", quality.failed_projections},
          {"area", quality.area},
          {"is_valid", validation.is_valid()},
          {"euler_characteristic", validation.euler_characteristic},
          {"boundary_edge_count", validation.boundary_edge_count}};
}

ImprovementReport improve_covering(TriangleMesh& mesh, const ImplicitProblem& problem) {
  ImprovementReport report;
  const ImprovementOptions options;
  report.criterion = to_string(options.criterion);
  report.smoothing_passes = kCoveringSmoothingPasses;
  report.result = improve_mesh(mesh, problem, options, kCoveringSmoothingPasses);
  return report;
}

nlohmann::json improvement_json(const ImprovementReport& improvement) {
  const ImprovementSummary& swaps = improvement.result.swaps;
  const SmoothingSummary& smoothing = improvement.result.smoothing;
  return {{"criterion", improvement.criterion},
          {"swaps", swaps.swaps},
          {"sweeps", swaps.sweeps},
          {"converged", swaps.converged},
          {"smoothing_passes", smoothing.iterations},
          {"smoothing_moves", smoothing.moves},
          {"min_angle_degrees",
           {{"before", swaps.min_angle_degrees_before}, {"after", swaps.min_angle_degrees_after}}},
          {"fraction_angles_below_30_degrees",
           {{"before", swaps.fraction_angles_below_30_before},
            {"after", swaps.fraction_angles_below_30_after}}}};
}

std::string improvement_text(const ImprovementReport& improvement) {
  const ImprovementSummary& swaps = improvement.result.swaps;
  const SmoothingSummary& smoothing = improvement.result.smoothing;
  std::ostringstream out;
  out.precision(3);
  out << "edge swaps by the " << improvement.criterion << " criterion: " << swaps.swaps << " in "
      << swaps.sweeps << " sweeps ("
      << (swaps.interrupted ? "interrupted"
          : swaps.converged ? "converged"
                            : "sweep cap")
      << ")";
  if (improvement.smoothing_passes > 0) {
    out << "; smoothing: " << smoothing.moves << " moves in " << smoothing.iterations << " passes";
  }
  out << "; min angle " << swaps.min_angle_degrees_before << "° → " << swaps.min_angle_degrees_after
      << "°, angles below 30° " << 100.0 * swaps.fraction_angles_below_30_before << "% → "
      << 100.0 * swaps.fraction_angles_below_30_after << "%";
  return out.str();
}

}  // namespace tessera
