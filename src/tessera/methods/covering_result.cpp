// SPDX-License-Identifier: MIT
#include "tessera/methods/covering_result.h"

#include <algorithm>

#include "tessera/core/process_memory.h"

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

void CoveringSummary::note_resident_memory(double boundary_bytes) {
  const auto resident = static_cast<double>(resident_bytes());
  resident_peak_bytes = std::max(resident_peak_bytes, resident);
  resident_beyond_boundary_peak_bytes =
      std::max(resident_beyond_boundary_peak_bytes, resident - boundary_bytes);
}

}  // namespace tessera
