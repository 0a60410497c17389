// SPDX-License-Identifier: MIT
#include "tessera/methods/covering_result.h"

namespace tessera {

const char* to_string(CoveringTermination termination) {
  switch (termination) {
    case CoveringTermination::Completed:
      return "completed";
    case CoveringTermination::VertexLimit:
      return "vertex limit reached";
    case CoveringTermination::FrontCollision:
      return "front collision";
    case CoveringTermination::ProjectionFailed:
      return "projection failed";
    case CoveringTermination::StartFailed:
      return "start point failed";
    case CoveringTermination::TriangulationFailed:
      return "triangulation failed";
    case CoveringTermination::Interrupted:
      return "interrupted";
  }
  return "unknown";
}

void CoveringSummary::record_failure(CoveringTermination why, const std::string& what) {
  if (is_complete()) {
    termination = why;
    message = what;
  } else {
    notes.push_back(what);
  }
}

}  // namespace tessera
