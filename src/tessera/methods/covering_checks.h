// SPDX-License-Identifier: MIT
// The checks of a completed covering's result (run_covering's last steps): each reports what it
// finds as the run's failure, with the place (CoveringSummary::record_failure).
#pragma once

#include "tessera/core/corrector.h"
#include "tessera/core/domain.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/methods/covering_result.h"

namespace tessera::detail {

/// Every boundary edge of the mesh lies on ∂S (both ends on one face or on two adjacent ones);
/// on a closed M there is none. Anything else is a hole in the covering. `step`: the run's, for
/// the tolerance of "on a face". Does nothing unless the run completed.
void check_coverage(const Domain& domain, double step, CoveringResult& result);

/// No triangle with all corners inside S covers a part of M outside S (a hole of M ∩ S smaller
/// than the triangle). Looks at triangles within `snap_distance` of a face (on sparse problems
/// within twice the tolerance, and not at all without one). Does nothing unless the run
/// completed. `stop_requested` (may be empty) is polled before each projection, a
/// factorisation at large n: once true, the triangles not yet looked under are left so and the
/// run is Interrupted, its message saying how many.
void check_holes_covered_over(const ImplicitProblem& problem, const Domain& domain,
                              double snap_distance, double tolerance,
                              const CorrectorOptions& corrector, const StopRequest& stop_requested,
                              CoveringResult& result);

}  // namespace tessera::detail
