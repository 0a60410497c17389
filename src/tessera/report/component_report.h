// SPDX-License-Identifier: MIT
// The components of a run that covers several (`tessera mesh --components all`, several
// `--start`s; methods/components/cover_components.h) in the summary: the JSON of run.components,
// run.starts and run.component_search, and the report's lines (docs/summary-json.md).
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "tessera/methods/covering_result.h"

namespace tessera {

/// Adds "components", "starts" and "component_search" to the summary's "run" object `run`
/// when the run had them (nothing for a run of one start's component). Points are listed for
/// n ≤ kLargeAmbientDimension. Components are numbered from 1, as in the report.
void add_components_json(const CoveringSummary& summary, int ambient_dimension,
                         nlohmann::json& run);

/// The report's lines about them, each ending in a newline; empty for a run of one start's
/// component:
///   components     2 (512 seeds over x, y, z, spacing 0.5; 2 started one, 431 on one covered …)
///     1            start 1 at (1, 0, 0.5): 598 vertices, 1192 triangles, χ 2, closed
///   starts         start 1 → component 1; start 2 → component 1 (already covered)
std::string components_text(const CoveringSummary& summary, int ambient_dimension);

}  // namespace tessera
