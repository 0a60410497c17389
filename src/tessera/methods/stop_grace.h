// SPDX-License-Identifier: MIT
// A stop request with a grace period: what the checks after a stop poll, so that they finish
// while they are cheap (small n) and are cut short when they are not (a factorisation is a
// second at n = 10⁵), and the files are written within a batch system's grace period.
#pragma once

#include "tessera/methods/covering_result.h"

namespace tessera {

/// The checks of a stopped run (the final geometric validation, the check for holes covered
/// over) get this long after the stop before they are cut short. The latency from a SIGTERM
/// to the files is the method's poll (one vertex), this, and the writing: well within the 30 s
/// that Slurm grants by default (docs/stopping.md has the measured figures).
inline constexpr double kCheckSecondsAfterStop = 2.0;

/// A StopRequest that returns true once `grace_seconds` have passed since `request` first
/// returned true; until then it polls `request`, and after that it no longer does. Copies
/// share one clock, so one grace can span several checks. An empty `request` gives a request
/// that never stops.
/// \pre grace_seconds >= 0.
StopRequest after_grace(StopRequest request, double grace_seconds = kCheckSecondsAfterStop);

/// The grace for checks whose items (a projection, a factorisation) take about `item_seconds`
/// each: an item begun later than this would end past `grace_seconds`, so none is begun then.
/// At n = 10⁵ a factorisation takes 1–5 s, as long as the grace itself or longer, and the checks
/// then stop at once; at small n this is the grace.
inline double grace_before_items(double grace_seconds, double item_seconds) {
  return grace_seconds > item_seconds ? grace_seconds - item_seconds : 0.0;
}

}  // namespace tessera
