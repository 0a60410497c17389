// SPDX-License-Identifier: MIT
#include "tessera/report/improvement_report.h"

#include <nlohmann/json.hpp>

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

}  // namespace tessera
