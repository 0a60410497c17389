// SPDX-License-Identifier: MIT
// Check 1b of validate(): fans that cover M twice, judged from the arcs their corners sweep in
// M's tangent plane at their vertex (docs/validation.md, "Fans, at their vertex").
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <sstream>
#include <vector>

#include "tessera/core/describe.h"
#include "tessera/geometry/detail/mesh_validation_checks.h"

namespace tessera::detail {
namespace {


// Length of the intersection of the arcs [a, a + α] and [b, b + β] of the circle, 0 ≤ α, β ≤ π.
double arc_overlap(double a, double alpha, double b, double beta) {
  constexpr double kTurn = 2.0 * std::numbers::pi;
  const double d = std::fmod(std::fmod(b - a, kTurn) + kTurn, kTurn);  // b − a in [0, 2π)
  const auto common = [](double lo1, double hi1, double lo2, double hi2) {
    return std::max(0.0, std::min(hi1, hi2) - std::max(lo1, lo2));
  };
  return common(0.0, alpha, d, d + beta) + common(0.0, alpha, d - kTurn, d - kTurn + beta);
}

}  // namespace

// 1b. Fans that cover M twice. Around a vertex v on M the projection onto M, to first order,
// is the orthogonal projection onto M's tangent plane there: each triangle at v covers, near v,
// the arc of directions its projected corner sweeps. Where no triangle of the fan stands across
// M at v (|s| ≥ min_tangent_cosine) and all turn the same way (no fold: folds are the check
// above), two arcs that overlap by more than rounding mean that the two triangles cover the
// same part of M near v, however far their projections reach: an open fan that turns more than
// once around its boundary vertex (a front that closed over itself), or a closed fan that
// winds twice. The planar test of check_overlaps finds such pairs only where the overlap is
// wider than its chart's distortion bound, which a pair tilted far from M can undercut (trough,
// bezier, stress seed 2026 case 512: two triangles tilted 68° overlapping by 18° at their
// vertex, 2.5 % of their area).
void check_fan_arcs(const MeshView& view,
                    const std::vector<std::array<double, 3>>& corner_cosine,
                    const std::vector<std::array<std::array<double, 2>, 3>>& corner_arcs,
                    const ValidationOptions& options, DefectRecorder& recorder,
                    MeshValidation& result) {
  // Well above the rounding of the arcs (tangent planes from a neighbour's factorisation are
  // good to 1e-6) and far below any double cover that matters (case 512: 0.31).
  constexpr double kArcOverlapRadians = 1e-3;
  const MeshTopology& topology = view.topology;
  const std::vector<Triangle>& triangles = topology.triangles();
  struct Arc {
    int triangle;
    double start;
    double sweep;
  };
  std::vector<Arc> arcs;
  for (int v = 0; v < view.mesh.vertex_count(); ++v) {
    arcs.clear();
    int turning = 0;  // +1 per counterclockwise arc, −1 per clockwise one
    bool judged = true;
    for (int t : topology.vertex_triangles(v)) {
      const int k = triangles[t][0] == v ? 0 : (triangles[t][1] == v ? 1 : 2);
      const double s = corner_cosine[t][k];
      if (std::isnan(s) || std::abs(s) < options.min_tangent_cosine) {
        judged = false;
        break;
      }
      const auto [start, sweep] = corner_arcs[t][k];
      turning += sweep > 0.0 ? 1 : -1;
      arcs.push_back(sweep > 0.0 ? Arc{t, start, sweep} : Arc{t, start + sweep, -sweep});
    }
    if (!judged || std::abs(turning) != static_cast<int>(arcs.size())) {
      continue;  // a plane across M at v, or a fold (reported above) or a seam of orientation
    }
    for (std::size_t i = 0; i < arcs.size(); ++i) {
      for (std::size_t j = i + 1; j < arcs.size(); ++j) {
        const double overlap =
            arc_overlap(arcs[i].start, arcs[i].sweep, arcs[j].start, arcs[j].sweep);
        if (!(overlap > kArcOverlapRadians)) {
          continue;
        }
        const int s = std::min(view.original[arcs[i].triangle], view.original[arcs[j].triangle]);
        const int t = std::max(view.original[arcs[i].triangle], view.original[arcs[j].triangle]);
        result.overlapping_triangle_pairs.emplace_back(s, t);
        recorder.record(MeshDefectKind::OverlappingTriangles, [&] {
          double total = 0.0;
          for (const Arc& arc : arcs) {
            total += arc.sweep;
          }
          std::ostringstream out;
          out.precision(3);
          const int a = arcs[i].triangle, b = arcs[j].triangle;
          out << triangle_name(view.original[a], triangles[a]) << " and "
              << triangle_name(view.original[b], triangles[b]) << " both cover M next to vertex "
              << v << " at " << describe_point(view.mesh.points().col(v), view.mesh.space())
              << ": their corners there overlap by " << degrees(overlap)
              << "° in M's tangent plane, where the triangles around the vertex turn "
              << degrees(total) << "°";
          return out.str();
        });
      }
    }
  }
}

}  // namespace tessera::detail
