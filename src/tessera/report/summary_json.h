// SPDX-License-Identifier: MIT
// The JSON run summary and the terminal report of a MeshReport: counts, topology, distances to
// M, angles, area, time, evaluations (docs/summary-json.md).
#pragma once

#include <string>

#include "tessera/report/mesh_report.h"

namespace tessera {

/// The report as a JSON document (documented in docs/summary-json.md), pretty-printed.
std::string to_json(const MeshReport& report);

/// Writes to_json(report) to `path`. \throw InvalidArgument if the file cannot be written.
void write_summary_json(const std::string& path, const MeshReport& report);

/// A short human-readable report (a dozen lines) for the terminal.
std::string to_text(const MeshReport& report);

}  // namespace tessera
