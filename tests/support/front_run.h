// SPDX-License-Identifier: MIT
// Covering a catalogue problem with the front method, shared by the tests that need a mesh of M.
#pragma once

#include <string>

#include "tessera/methods/front/advancing_front.h"
#include "tessera/problems/catalogue.h"

namespace tessera::testing {

struct FrontRun {
  ProblemSetup setup;
  CoveringResult result;
};

/// Covers the catalogue problem `specification` with step h (the problem's suggestion if h = 0).
inline FrontRun run_front(const std::string& specification, double h = 0.0) {
  FrontRun run;
  run.setup = make_catalogue_problem(specification);
  FrontOptions options;
  options.step = h > 0.0 ? h : run.setup.suggested_step;
  run.result = triangulate_by_front(*run.setup.problem, run.setup.start, run.setup.domain, options);
  return run;
}

}  // namespace tessera::testing
