// SPDX-License-Identifier: MIT
#include "tessera/methods/atlas/chart_polygon.h"

#include <algorithm>
#include <cmath>

namespace tessera {

ChartPolygon::ChartPolygon(double half_width) {
  const double w = half_width;
  vertices_ = {{-w, -w, kNoNeighbour}, {w, -w, kNoNeighbour}, {w, w, kNoNeighbour},
               {-w, w, kNoNeighbour}};
}

bool ChartPolygon::cut(double normal_s, double normal_t, double offset, int label) {
  const std::size_t m = vertices_.size();
  if (m == 0) {
    return false;
  }
  // Signed excess over the line; a vertex within rounding of it counts as inside, so that a
  // neighbour's line through an existing vertex does not create a zero-length edge.
  const double scale = std::abs(offset) + 1e-300;
  // Scratch reused across calls: cutting runs ~15 times per chart, allocation would dominate.
  thread_local std::vector<double> excess;
  thread_local std::vector<Vertex> kept;
  excess.resize(m);
  bool any_outside = false;
  for (std::size_t i = 0; i < m; ++i) {
    excess[i] = normal_s * vertices_[i].s + normal_t * vertices_[i].t - offset;
    if (excess[i] <= 1e-13 * scale) {
      excess[i] = std::min(excess[i], 0.0);
    } else {
      any_outside = true;
    }
  }
  if (!any_outside) {
    return false;
  }
  // Sutherland–Hodgman against one line, carrying the edge labels along.
  kept.clear();
  for (std::size_t i = 0; i < m; ++i) {
    const Vertex& a = vertices_[i];
    const Vertex& b = vertices_[(i + 1) % m];
    const double ea = excess[i];
    const double eb = excess[(i + 1) % m];
    if (ea <= 0) {
      if (eb <= 0) {
        kept.push_back(a);
      } else if (ea == 0) {
        // a lies on the line: the polygon turns onto the line right there.
        kept.push_back({a.s, a.t, label});
      } else {
        // Leaving: the part of edge a→b up to the line keeps a's label; from the crossing on,
        // the polygon follows the new line.
        kept.push_back(a);
        const double w = ea / (ea - eb);
        kept.push_back({a.s + w * (b.s - a.s), a.t + w * (b.t - a.t), label});
      }
    } else if (eb < 0) {
      // Entering: the crossing point starts what is left of edge a→b. (If b lies on the line,
      // b itself is the entry and is kept in its own turn.)
      const double w = ea / (ea - eb);
      kept.push_back({a.s + w * (b.s - a.s), a.t + w * (b.t - a.t), a.edge_label});
    }
  }
  vertices_.assign(kept.begin(), kept.end());
  return true;
}

int ChartPolygon::farthest_exterior_vertex(double radius) const {
  int farthest = -1;
  double largest = radius * radius * (1.0 + 1e-9);
  for (std::size_t i = 0; i < vertices_.size(); ++i) {
    const double r2 = vertices_[i].s * vertices_[i].s + vertices_[i].t * vertices_[i].t;
    if (r2 > largest) {
      largest = r2;
      farthest = static_cast<int>(i);
    }
  }
  return farthest;
}

}  // namespace tessera
