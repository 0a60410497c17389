// SPDX-License-Identifier: MIT
// The JSON run summary: counts, topology, distances to M, angles, area, time, evaluations.
#pragma once

#include <optional>
#include <string>

#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/methods/covering_result.h"

namespace tessera {

/// What one report is made of; `run` is absent for `tessera check` of an existing mesh.
struct MeshReport {
  std::string problem;
  int ambient_dimension = 0;
  std::optional<CoveringSummary> run;
  MeshValidation validation;
  MeshQuality quality;
  std::optional<int> expected_euler_characteristic;
  std::optional<double> exact_area;
};

/// The report as a JSON document (documented in docs/summary-json.md), pretty-printed.
std::string to_json(const MeshReport& report);

/// Writes to_json(report) to `path`. \throw InvalidArgument if the file cannot be written.
void write_summary_json(const std::string& path, const MeshReport& report);

/// A short human-readable report (a dozen lines) for the terminal.
std::string to_text(const MeshReport& report);

}  // namespace tessera
