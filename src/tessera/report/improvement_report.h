// SPDX-License-Identifier: MIT
// The quality and validity of a mesh before or after `improve` (the CLI's `tessera improve
// --summary` and the bindings' tessera.improve), as JSON; and `tessera mesh --improve`, the
// improvement of a covering's mesh that its report describes.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/report/mesh_report.h"

namespace tessera {

/// Angles, distances to M, area, validity, χ, boundary of one side of an improvement.
nlohmann::json improvement_quality_json(const MeshQuality& quality,
                                        const MeshValidation& validation);

/// The passes of tangential smoothing of `tessera mesh --improve` (as `improve --smooth 3`).
constexpr int kCoveringSmoothingPasses = 3;

/// `tessera mesh --improve` and the bindings' mesh(improve=True), one definition for both:
/// swaps by the max-min angle criterion, kCoveringSmoothingPasses passes of tangential smoothing
/// and swaps again (docs/algorithms/improvement.md); validity and boundary are kept. The result
/// goes into MeshReport::improvement.
ImprovementReport improve_covering(TriangleMesh& mesh, const ImplicitProblem& problem);

/// The summary's "improvement" object: criterion, swaps, sweeps, smoothing, and the smallest
/// angle and the share of angles below 30° before and after.
nlohmann::json improvement_json(const ImprovementReport& improvement);

/// The report's line after "improve": "edge swaps by the angle criterion: 812 in 6 sweeps
/// (converged); smoothing: 4012 moves in 3 passes; min angle 18.9° → 27.3°, angles below 30°
/// 0.41% → 0.012%".
std::string improvement_text(const ImprovementReport& improvement);

}  // namespace tessera
