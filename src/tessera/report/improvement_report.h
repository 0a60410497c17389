// SPDX-License-Identifier: MIT
// The quality and validity of a mesh before or after `improve` (the CLI's `tessera improve
// --summary` and the bindings' tessera.improve), as JSON.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_validation.h"

namespace tessera {

/// Angles, distances to M, area, validity, χ, boundary of one side of an improvement.
nlohmann::json improvement_quality_json(const MeshQuality& quality,
                                        const MeshValidation& validation);

}  // namespace tessera
