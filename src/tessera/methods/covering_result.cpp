// SPDX-License-Identifier: MIT
#include "tessera/methods/covering_result.h"

#include "tessera/core/counted_problem.h"
#include "tessera/core/domain.h"
#include "tessera/core/error.h"

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
  }
  return "unknown";
}

void check_domain_dimension(const Domain& domain, const ImplicitProblem& problem) {
  TESSERA_CHECK(domain.is_unbounded() || domain.ambient_dimension() == problem.ambient_dimension(),
                "domain is in R^" << domain.ambient_dimension() << " but the problem is in R^"
                                  << problem.ambient_dimension());
}

void finish_summary(const TriangleMesh& mesh, CoveringSummary& summary,
                    const CountedProblem& problem, std::chrono::steady_clock::time_point start) {
  summary.vertex_count = mesh.vertex_count();
  summary.triangle_count = mesh.triangle_count();
  summary.function_evaluations = problem.function_evaluations();
  summary.jacobian_evaluations = problem.jacobian_evaluations();
  summary.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace tessera
