// SPDX-License-Identifier: MIT
#include "tessera/report/method_comparison.h"

#include <algorithm>
#include <utility>

#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_validation.h"

namespace tessera {

bool CompareReport::passes() const {
  for (const CompareRow& row : rows) {
    if (!row.passes()) {
      return false;
    }
  }
  return true;
}

CompareReport compare_methods(const std::function<ProblemSetup()>& make_setup,
                              const MethodSettings& settings,
                              const std::function<void(const CompareRow&)>& on_row) {
  CompareReport report;
  MethodSettings shared = settings;
  for (const CoveringMethod& method : covering_methods()) {
    const ProblemSetup setup = make_setup();
    report.expected_euler_characteristic = setup.expected_euler_characteristic;
    if (shared.tolerance <= 0) {
      shared.tolerance = default_tolerance(setup);
    }
    report.tolerance = shared.tolerance;
    const CoveringResult result = cover(setup, method, shared);
    const MeshValidation validation = validate(result.mesh, *setup.problem, setup.domain);
    const MeshQuality quality = measure_quality(result.mesh, *setup.problem);
    CompareRow row;
    row.method = method.name;
    row.run = result.summary;
    row.vertex_count = validation.referenced_vertex_count;
    row.triangle_count = validation.triangle_count;
    row.max_distance = std::max(quality.centroid_distance.max, quality.midpoint_distance.max);
    row.min_angle_degrees = quality.min_angle_degrees;
    row.euler_characteristic = validation.euler_characteristic;
    row.valid = validation.is_valid();
    if (on_row) {
      on_row(row);
    }
    report.rows.push_back(std::move(row));
  }
  return report;
}

}  // namespace tessera
