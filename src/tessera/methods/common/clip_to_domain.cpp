// SPDX-License-Identifier: MIT
#include "tessera/methods/common/clip_to_domain.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

#include "tessera/core/ambient_space.h"
#include "tessera/core/describe.h"
#include "tessera/core/error.h"
#include "tessera/core/face_projection.h"
#include "tessera/core/linearization.h"
#include "tessera/core/process_memory.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/geometry/pinched_vertices.h"
#include "tessera/methods/common/detail/clip_measures.h"
#include "tessera/methods/common/detail/orientation_guard.h"

namespace tessera {

namespace {

using detail::common_faces;
using detail::compact;
using detail::Corners;
using detail::corners;
using detail::describe_face;
using detail::faces_of_vertices;
using detail::FaceSets;
using detail::find_corner;
using detail::is_stop_requested;
using detail::lengths;
using detail::min_angles;
using detail::OrientationGuard;
using detail::vertex_neighbours;

// A split mesh (SPMD, docs/cluster.md): the points are this rank's rows of a distributed
// problem's space, the domain is cut to the same rows, and every length, distance and tangent
// coordinate below is summed over the ranks, so that every rank takes the same branch. The
// passes batch their reductions (a pass's partial sums in one AmbientSpace::sum); in one process
// the sums do nothing and the expressions are the serial code's own.

// What an attempt at clipping changed, to undo it: the mesh's vertex count and triangles
// before, and the old place of every vertex it moved (a copy of the mesh would be most of the
// memory at large n).
struct ClipUndo {
  int vertex_count = 0;
  std::vector<Triangle> triangles;
  std::vector<std::pair<int, Eigen::VectorXd>> moved;
  std::vector<int> merged_into;  // vertices that took over a collapsed vertex's triangles

  explicit ClipUndo(const TriangleMesh& mesh)
      : vertex_count(mesh.vertex_count()), triangles(mesh.triangles()) {}
  void move(TriangleMesh& mesh, int v, const Eigen::VectorXd& x) {
    moved.emplace_back(v, mesh.point(v));
    mesh.mutable_point(v) = x;
  }
  void undo(TriangleMesh& mesh) {
    mesh.set_triangles(std::move(triangles));
    mesh.truncate_vertices(vertex_count);
    for (auto it = moved.rbegin(); it != moved.rend(); ++it) {
      mesh.mutable_point(it->first) = it->second;
    }
  }
};

// Clips to face k, in place; the cut-away vertices are left unreferenced (compacted by the
// caller once the result is accepted). Returns false (with `message` set) if a cut point cannot
// be found or a triangle would fold; `undo` then restores the mesh.
bool clip_to_face(const ImplicitProblem& problem, const Domain& domain, int k, double snap_distance,
                  const ClipOptions& options, TriangleMesh& mesh, FaceSets& on_faces,
                  ClipSummary& summary, ClipUndo& undo) {
  // Only the new vertices come out of these projections: Gauss–Newton may keep its
  // factorisation while it contracts (sparse problems).
  CorrectorOptions corrector = options.corrector;
  corrector.reuse_factorisation = true;
  const std::shared_ptr<const AmbientSpace> shared_space = problem.space();
  const AmbientSpace& space = *shared_space;
  const auto is_stopped = [&] {
    summary.interrupted =
        summary.interrupted || is_stop_requested(options.stop_requested, space);
    return summary.interrupted;
  };
  const int n = problem.ambient_dimension();
  const int m = problem.equation_count();
  OrientationGuard guard(problem, mesh, vertex_neighbours(mesh));
  const int vertex_count = mesh.vertex_count();
  // Every vertex's distance to the face and, after them, the squared norms of the vertices not
  // on it, for the on-face tolerance (one reduction on a split mesh).
  std::vector<double> d(2 * static_cast<std::size_t>(vertex_count), 0.0);
  for (int v = 0; v < vertex_count; ++v) {
    if (!std::binary_search(on_faces[v].begin(), on_faces[v].end(), k)) {
      d[v] = domain.partial_signed_distance(k, mesh.point(v));
      d[vertex_count + v] = mesh.point(v).squaredNorm();
    }
  }
  if (space.is_distributed() && vertex_count > 0) {
    space.sum(d.data(), 2 * vertex_count);
  }
  std::vector<int> onto_face;  // vertices on the face to kOnFaceTolerance, not yet recorded
  for (int v = 0; v < vertex_count; ++v) {
    if (!std::binary_search(on_faces[v].begin(), on_faces[v].end(), k) &&
        std::abs(d[v]) <= kOnFaceTolerance * (1.0 + std::sqrt(d[vertex_count + v]))) {
      onto_face.push_back(v);
      d[v] = 0.0;
    }
  }
  d.resize(vertex_count);
  {
    // Room for the cut vertices (at most one per edge across the face, fewer than the
    // triangles across it), so that adding them does not double the mesh's storage.
    int across = 0;
    for (const Triangle& t : mesh.triangles()) {
      const double low = std::min({d[t[0]], d[t[1]], d[t[2]]});
      const double high = std::max({d[t[0]], d[t[1]], d[t[2]]});
      across += low < 0 && high > 0 ? 1 : 0;
    }
    mesh.reserve(vertex_count + 2 * across + 16, mesh.triangle_count() + 2 * across + 16);
  }
  auto work_faces = on_faces;
  // A vertex on the face to kOnFaceTolerance lies on it, as faces_of_vertices counts them before
  // the first face: it is recorded there and put on it exactly. Vertices that an earlier face's
  // clipping put on M ∩ that face are the ones: where the two faces coincide on M (bounds on
  // twin coordinates of symmetric states, u25 ≤ 20 and u26 ≤ 20 of an even grid) they lie
  // across this face by rounding, ±4e-16, with either sign. Counted as across, each got a cut
  // point a rounding error away (a needle that folds, "would fold the triangle") or a cut
  // projected onto both faces at once (singular): issue 34, python/examples/bvp_scipy.py.
  for (int v : onto_face) {
    std::vector<int>& faces = work_faces[v];
    faces.insert(std::upper_bound(faces.begin(), faces.end(), k), k);
    Eigen::VectorXd x = mesh.point(v);
    place_on_faces(domain, faces, x, space);
    undo.move(mesh, v, x);
  }
  // After v moves onto the face, only triangles with another vertex strictly inside are kept;
  // the others (all corners on or outside the face) are dropped by step 3 whatever their shape.
  const auto is_kept_without = [&](const Triangle& t, int v) {
    for (int u : t) {
      if (u != v && d[u] > 0) {
        return true;
      }
    }
    return false;
  };
  // 1. Snap vertices near the face onto M ∩ face. Where that point is a corner of M ∩ S
  //    (two faces meet) and a vertex already sits there, the edge to it is collapsed
  //    instead: two vertices a hair apart at a corner would make needles. A snap that would
  //    fold a triangle around the vertex (two neighbours snapped onto nearly the same point of
  //    M ∩ face, or a face meeting M at a shallow angle) is not made; the cut handles it.
  std::vector<std::vector<int>> vertex_triangles(vertex_count);
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    for (int v : mesh.triangle(t)) {
      vertex_triangles[v].push_back(t);
    }
  }
  const auto are_adjacent = [&](int a, int b) {
    for (int t : vertex_triangles[a]) {
      const Triangle& tri = mesh.triangle(t);
      if (tri[0] == b || tri[1] == b || tri[2] == b) {
        return true;
      }
    }
    return false;
  };
  // True if moving v to x (and, if `merged` ≥ 0, identifying it with `merged`) keeps every
  // kept triangle around v oriented.
  const auto star_keeps_orientation = [&](int v, const Eigen::VectorXd& x, int merged) {
    for (int t : vertex_triangles[v]) {
      const Triangle& tri = mesh.triangle(t);
      if (!is_kept_without(tri, v) ||
          (merged >= 0 && (tri[0] == merged || tri[1] == merged || tri[2] == merged))) {
        continue;
      }
      const Corners before = corners(mesh, tri);
      Corners after = before;
      for (int r = 0; r < 3; ++r) {
        if (tri[r] == v) {
          after[r] = x;
        }
      }
      if (!guard.keeps_orientation(v, mesh.point(v), before, after)) {
        return false;
      }
    }
    return true;
  };
  std::vector<int> collapse_into(vertex_count, -1);
  // How far v is from the face along the mesh: |d| over the fastest rate at which d changes
  // along v's edges. Where the face meets M at a shallow angle a vertex at ambient distance
  // |d| < snap_distance can lie many snap distances from M ∩ face; such vertices are skipped
  // before their tangent plane is factored.
  const auto distance_along_mesh = [&](int v) {
    std::vector<std::pair<int, int>> edges;
    for (int t : vertex_triangles[v]) {
      for (int w : mesh.triangle(t)) {
        if (w != v) {
          edges.emplace_back(w, v);
        }
      }
    }
    const std::vector<double> length = lengths(mesh, space, edges);  // one reduction
    double rate = 0.0;
    for (std::size_t i = 0; i < edges.size(); ++i) {
      if (length[i] > 0) {
        rate = std::max(rate, std::abs(d[v] - d[edges[i].first]) / length[i]);
      }
    }
    return rate > 0 ? std::abs(d[v]) / rate : std::numeric_limits<double>::infinity();
  };
  for (int v = 0; v < vertex_count; ++v) {
    if (d[v] == 0.0 || std::abs(d[v]) >= snap_distance ||
        distance_along_mesh(v) >= 3 * snap_distance) {
      continue;
    }
    if (is_stopped()) {
      summary.message = "interrupted";
      return false;
    }
    std::vector<int> faces = work_faces[v];
    faces.push_back(k);
    std::sort(faces.begin(), faces.end());
    Eigen::VectorXd x = mesh.point(v);
    const bool is_corner = static_cast<int>(faces.size()) + m == n;
    if (!project_onto_faces(problem, domain, faces, x, 3 * snap_distance, corrector, nullptr,
                            guard.at_vertex(v, x)) ||
        !domain.contains(x, 1e-9)) {
      continue;
    }
    const int occupant = is_corner ? find_corner(mesh, space, work_faces, faces, x) : -1;
    if (occupant >= 0) {
      if (are_adjacent(v, occupant) && collapse_into[occupant] < 0 &&
          star_keeps_orientation(v, mesh.point(occupant), occupant)) {
        collapse_into[v] = occupant;
        undo.move(mesh, v, mesh.point(occupant));  // later checks see where v went
        undo.merged_into.push_back(occupant);
        d[v] = 0.0;
      }
      continue;
    }
    if (!star_keeps_orientation(v, x, -1)) {
      continue;
    }
    undo.move(mesh, v, x);
    work_faces[v] = faces;
    d[v] = 0.0;
    ++summary.snapped_vertices;
  }
  std::vector<Triangle> collapsed;
  for (Triangle t : mesh.triangles()) {
    for (int& v : t) {
      v = collapse_into[v] >= 0 ? collapse_into[v] : v;
    }
    if (t[0] != t[1] && t[1] != t[2] && t[2] != t[0]) {
      collapsed.push_back(t);
    }
  }
  mesh.set_triangles(std::move(collapsed));
  // 2. Cut points on the edges that still cross the face.
  std::map<std::pair<int, int>, int> cut_vertex;
  for (const Triangle& t : mesh.triangles()) {
    for (int r = 0; r < 3; ++r) {
      int u = t[r];
      int w = t[(r + 1) % 3];
      if (!((d[u] > 0 && d[w] < 0) || (d[u] < 0 && d[w] > 0))) {
        continue;
      }
      const auto key = std::minmax(u, w);
      if (cut_vertex.count(key)) {
        continue;
      }
      if (is_stopped()) {
        summary.message = "interrupted";
        return false;
      }
      const double s = d[u] / (d[u] - d[w]);
      Eigen::VectorXd x = (1 - s) * mesh.point(u) + s * mesh.point(w);
      std::vector<int> faces = common_faces(work_faces[u], work_faces[w]);
      faces.push_back(k);
      std::sort(faces.begin(), faces.end());
      const double edge_length = space.distance(mesh.point(u), mesh.point(w));
      const int inside = d[u] > 0 ? u : w;
      const Linearization* near = guard.at_vertex(inside, mesh.point(inside));
      if (!project_onto_faces(problem, domain, faces, x, edge_length, corrector, nullptr, near)) {
        std::ostringstream message;
        message << "cannot clip the mesh to the face " << describe_face(domain, k)
                << ": no point of M on the face near the edge from "
                << describe_point(mesh.point(u), space) << " to "
                << describe_point(mesh.point(w), space);
        summary.message = message.str();
        return false;
      }
      // A cut point next to (or across) an earlier face belongs at the corner where the two
      // faces meet: left where it is, it would make a needle with that corner, or lie outside
      // S. Earlier faces are done, so a point outside one of them would stay outside.
      // The distances to the earlier faces: one reduction, again when x moves to a corner.
      std::vector<double> to_earlier(static_cast<std::size_t>(k));
      const auto measure_earlier = [&] {
        for (int j = 0; j < k; ++j) {
          to_earlier[j] = domain.partial_signed_distance(j, x);
        }
        if (space.is_distributed() && k > 0) {
          space.sum(to_earlier.data(), k);
        }
      };
      measure_earlier();
      for (int j = 0; j < k; ++j) {
        const double distance = to_earlier[j];
        if (std::binary_search(faces.begin(), faces.end(), j) ||
            (distance >= snap_distance && distance >= 0)) {
          continue;
        }
        std::vector<int> corner_faces = faces;
        corner_faces.push_back(j);
        std::sort(corner_faces.begin(), corner_faces.end());
        Eigen::VectorXd corner = x;
        if (static_cast<int>(corner_faces.size()) + m <= n &&
            project_onto_faces(problem, domain, corner_faces, corner,
                               std::max(3 * snap_distance, edge_length), corrector, nullptr,
                               near) &&
            domain.contains(corner, 1e-9)) {
          x = corner;
          faces = corner_faces;
          measure_earlier();
          continue;
        }
        if (distance < 0) {
          std::ostringstream message;
          message << "cannot clip the mesh to the face " << describe_face(domain, k)
                  << ": the cut point " << describe_point(x, space) << " lies outside the face "
                  << describe_face(domain, j) << " by " << -distance
                  << " and M has no corner point on both faces near it";
          summary.message = message.str();
          return false;
        }
      }
      // Where the face meets an earlier face, M ∩ both is a point (a corner of the clipped
      // surface): reuse the corner vertex if one is already there, else the corner doubles.
      const int existing = static_cast<int>(faces.size()) + m == n
                               ? find_corner(mesh, space, work_faces, faces, x)
                               : -1;
      if (existing >= 0) {
        cut_vertex[key] = existing;
        continue;
      }
      cut_vertex[key] = mesh.add_vertex(x);
      work_faces.push_back(faces);
      d.push_back(0.0);
      ++summary.cut_edges;
    }
  }
  const auto cut = [&](int u, int w) { return cut_vertex.at(std::minmax(u, w)); };
  // 3. Split the triangles and keep the parts inside. Each part must keep the orientation of
  //    the triangle it comes from (a cut point far along a face that meets M at a shallow
  //    angle can land beyond the rest of the triangle): of a quadrilateral's two diagonals
  //    only those whose both halves keep it are candidates.
  std::vector<Triangle> kept;
  std::string fold;
  const auto add_polygon = [&](const Triangle& parent, std::vector<int> polygon) {
    polygon.erase(std::unique(polygon.begin(), polygon.end()), polygon.end());
    while (polygon.size() > 1 && polygon.front() == polygon.back()) {
      polygon.pop_back();
    }
    const Corners before = corners(mesh, parent);
    int reference = parent[0];
    for (int r = 0; r < 3; ++r) {
      if (d[parent[r]] > 0) {
        reference = parent[r];
        break;
      }
    }
    const auto fits = [&](const Triangle& child) {
      return guard.keeps_orientation(reference, mesh.point(reference), before,
                                     corners(mesh, child));
    };
    if (polygon.size() == 3) {
      const Triangle child{polygon[0], polygon[1], polygon[2]};
      if (fits(child)) {
        kept.push_back(child);
        return;
      }
    } else if (polygon.size() == 4) {
      const std::array<std::array<Triangle, 2>, 2> splits{
          {{{{polygon[0], polygon[1], polygon[2]}, {polygon[0], polygon[2], polygon[3]}}},
           {{{polygon[0], polygon[1], polygon[3]}, {polygon[1], polygon[2], polygon[3]}}}}};
      int best = -1;
      double best_angle = -1.0;
      for (int i = 0; i < 2; ++i) {
        const auto& split = splits[i];
        if (!fits(split[0]) || !fits(split[1])) {
          continue;
        }
        const std::vector<double> angles = min_angles(mesh, space, {split[0], split[1]});
        const double angle = std::min(angles[0], angles[1]);
        if (angle > best_angle) {
          best = i;
          best_angle = angle;
        }
      }
      if (best >= 0) {
        kept.push_back(splits[best][0]);
        kept.push_back(splits[best][1]);
        return;
      }
    } else {
      return;  // fewer than three distinct corners: nothing of the triangle is inside
    }
    if (fold.empty()) {
      std::ostringstream message;
      message << "clipping to the face " << describe_face(domain, k)
              << " would fold the triangle with corners " << describe_point(before[0], space)
              << ", " << describe_point(before[1], space) << ", "
              << describe_point(before[2], space);
      fold = message.str();
    }
  };
  for (const Triangle& t : mesh.triangles()) {
    int outside = 0;
    int inside = 0;
    for (int v : t) {
      outside += d[v] < 0 ? 1 : 0;
      inside += d[v] > 0 ? 1 : 0;
    }
    if (outside == 0) {
      if (inside > 0) {
        kept.push_back(t);
      }
      continue;
    }
    if (inside == 0) {
      continue;
    }
    // Walk the triangle's edges in order, keeping inside/on vertices and inserting cut points.
    std::vector<int> polygon;
    for (int r = 0; r < 3; ++r) {
      const int u = t[r];
      const int w = t[(r + 1) % 3];
      if (d[u] >= 0) {
        polygon.push_back(u);
      }
      if ((d[u] > 0 && d[w] < 0) || (d[u] < 0 && d[w] > 0)) {
        polygon.push_back(cut(u, w));
      }
    }
    add_polygon(t, polygon);
  }
  if (!fold.empty()) {
    summary.message = fold;
    return false;
  }
  mesh.set_triangles(std::move(kept));
  on_faces = std::move(work_faces);
  return true;
}

// Where face k cannot be clipped, the triangles with a vertex outside it are removed (and, where
// that pinches a vertex, the smaller fans): the mesh stays valid and inside S, its boundary
// there ragged instead of on M ∩ ∂S.
void drop_outside(const Domain& domain, const AmbientSpace& space, int k, TriangleMesh& mesh,
                  FaceSets& on_faces) {
  // Which vertices are inside the face (one reduction on a split mesh).
  std::vector<double> distance(static_cast<std::size_t>(mesh.vertex_count()), 0.0);
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    if (!std::binary_search(on_faces[v].begin(), on_faces[v].end(), k)) {
      distance[v] = domain.partial_signed_distance(k, mesh.point(v));
    }
  }
  if (space.is_distributed() && !distance.empty()) {
    space.sum(distance.data(), static_cast<int>(distance.size()));
  }
  std::vector<Triangle> inside;
  for (const Triangle& t : mesh.triangles()) {
    bool is_inside = true;
    for (int v : t) {
      is_inside = is_inside && distance[v] >= 0;  // 0 on the face
    }
    if (is_inside) {
      inside.push_back(t);
    }
  }
  const std::vector<bool> keep = keep_largest_fans(mesh.vertex_count(), inside);
  mesh.set_triangles(std::move(inside));
  compact(mesh, on_faces, keep);
}

// Collapses boundary edges shorter than `min_length`: the vertex on fewer faces moves into the
// other (a corner or face vertex stays where it is, on M ∩ ∂S). A collapse is kept only if it
// raises the smallest angle among the triangles around the moved vertex, keeps each of them
// oriented and the result is valid.
int collapse_short_boundary_edges(const ImplicitProblem& problem, TriangleMesh& mesh,
                                  const FaceSets& on_faces, double min_length) {
  const std::shared_ptr<const AmbientSpace> shared_space = problem.space();
  const AmbientSpace& space = *shared_space;
  OrientationGuard guard(problem, mesh, vertex_neighbours(mesh));
  int collapsed = 0;
  bool changed = true;
  std::set<std::pair<int, int>> rejected;  // each edge is judged once: O(N) per collapse
  while (changed) {
    changed = false;
    const MeshTopology topology(mesh);
    // Collapses move no point: the boundary edges' lengths are measured once per topology
    // (one reduction on a split mesh).
    std::vector<std::pair<int, int>> boundary;
    for (int e : topology.boundary_edges()) {
      boundary.emplace_back(topology.edge(e)[0], topology.edge(e)[1]);
    }
    const std::vector<double> boundary_length = lengths(mesh, space, boundary);
    for (std::size_t i = 0; i < boundary.size(); ++i) {
      auto [a, b] = boundary[i];
      if (boundary_length[i] >= min_length || !rejected.insert({a, b}).second) {
        continue;
      }
      if (on_faces[b].size() > on_faces[a].size()) {
        std::swap(a, b);  // keep a, the vertex on more faces
      }
      // b's triangles before and after (b replaced by a), their angles measured at once.
      std::vector<Triangle> triangles;
      std::vector<Triangle> measured;  // b's triangles, then the reshaped ones
      std::vector<std::pair<Triangle, Triangle>> reshaped;
      for (Triangle t : mesh.triangles()) {
        const bool has_a = t[0] == a || t[1] == a || t[2] == a;
        const bool has_b = t[0] == b || t[1] == b || t[2] == b;
        if (has_b) {
          measured.push_back(t);
        }
        if (has_a && has_b) {
          continue;  // the triangle on the collapsed edge disappears
        }
        if (has_b) {
          const Triangle old = t;
          for (int& v : t) {
            v = v == b ? a : v;
          }
          reshaped.emplace_back(old, t);
        }
        triangles.push_back(t);
      }
      const std::size_t around_b = measured.size();
      for (const auto& [old, now] : reshaped) {
        measured.push_back(now);
      }
      const std::vector<double> angles = min_angles(mesh, space, measured);
      double worst_before = std::numbers::pi;
      double worst_after = std::numbers::pi;
      for (std::size_t j = 0; j < angles.size(); ++j) {
        double& worst = j < around_b ? worst_before : worst_after;
        worst = std::min(worst, angles[j]);
      }
      bool keeps_orientation = true;
      for (const auto& [old, now] : reshaped) {
        keeps_orientation =
            keeps_orientation &&
            guard.keeps_orientation(a, mesh.point(a), corners(mesh, old), corners(mesh, now));
      }
      if (worst_after <= worst_before || !keeps_orientation) {
        continue;  // only collapses that improve the worst angle around b and fold nothing
      }
      // The moved-away vertex is left unreferenced until the final compaction; every other
      // defect rejects the collapse.
      // (judged on the mesh itself with the new triangles: a copy of its points per candidate
      // would cost more than the collapse at large n)
      std::vector<Triangle> before = mesh.triangles();
      mesh.set_triangles(std::move(triangles));
      const std::array<int, 1> around{a};  // b's triangles are a's now
      if (!validate_around(mesh, around).is_valid_but_unreferenced()) {
        mesh.set_triangles(std::move(before));
        continue;
      }
      ++collapsed;
      changed = true;
      break;  // the topology changed: rebuild it
    }
  }
  return collapsed;
}

}  // namespace

ClipSummary clip_to_domain(const ImplicitProblem& problem, const Domain& domain, TriangleMesh& mesh,
                           const ClipOptions& options) {
  const std::shared_ptr<const AmbientSpace> shared_space = problem.space();
  const AmbientSpace& space = *shared_space;
  const bool split = space.is_distributed();
  if (split) {
    check_mesh_of_problem(mesh, problem, "clip_to_domain");
    TESSERA_CHECK(domain.is_unbounded() || domain.is_distributed(),
                  "clip_to_domain: problem '" << problem.name()
                                              << "' is distributed; so must the domain be "
                                                 "(Domain::distributed)");
  }
  ClipSummary summary;
  const int face_count = static_cast<int>(domain.half_spaces().size());
  FaceSets on_faces = faces_of_vertices(domain, space, mesh);
  for (int k = 0; k < face_count; ++k) {
    if (summary.interrupted) {
      // No more projections after a stop: the triangles outside the faces left are removed.
      drop_outside(domain, space, k, mesh, on_faces);
      continue;
    }
    bool crosses = false;
    if (!split) {
      for (int v = 0; v < mesh.vertex_count() && !crosses; ++v) {
        crosses = !std::binary_search(on_faces[v].begin(), on_faces[v].end(), k) &&
                  domain.signed_distance(k, mesh.point(v)) < 0;
      }
    } else {
      // Every vertex's distance at once: one reduction.
      std::vector<double> distance(static_cast<std::size_t>(mesh.vertex_count()), 0.0);
      for (int v = 0; v < mesh.vertex_count(); ++v) {
        if (!std::binary_search(on_faces[v].begin(), on_faces[v].end(), k)) {
          distance[v] = domain.partial_signed_distance(k, mesh.point(v));
        }
      }
      if (!distance.empty()) {
        space.sum(distance.data(), static_cast<int>(distance.size()));
      }
      crosses = std::any_of(distance.begin(), distance.end(), [](double d) { return d < 0; });
    }
    if (!crosses) {
      continue;
    }
    ++summary.half_spaces_crossed;
    // Snapping keeps needles away but, where the mesh is coarse next to a corner of the
    // domain, can pull two vertices onto each other; then clip again without snapping. Where
    // neither gives a valid mesh, the triangles across the face are dropped and the run says so.
    bool done = false;
    std::string failure;
    for (const double snap : {options.snap_distance, 0.0}) {
      // Each attempt works on the mesh itself and is undone if it fails. At large n the last
      // attempt's factorisations and tangent planes (up to OrientationGuard's bounds) go back
      // to the system first: kept by glibc, five faces' worth held 214 MB at n = 10⁴.
      if (mesh.ambient_dimension() >= kReleaseHeapDimension) {
        release_free_heap();
      }
      ClipUndo undo(mesh);
      FaceSets attempt_faces = on_faces;
      ClipSummary attempt_summary;
      if (!clip_to_face(problem, domain, k, snap, options, mesh, attempt_faces, attempt_summary,
                        undo)) {
        undo.undo(mesh);
        if (attempt_summary.interrupted) {
          summary.interrupted = true;
          break;
        }
        failure = attempt_summary.message;
        continue;
      }
      // The vertices cut away are unreferenced until the compaction below. Judged where the
      // attempt moved or added vertices (every new triangle has one): a whole validation per
      // face costs O(n) per triangle at large n.
      std::vector<int> changed;
      for (const auto& [v, old_place] : undo.moved) {
        changed.push_back(v);
      }
      changed.insert(changed.end(), undo.merged_into.begin(), undo.merged_into.end());
      for (int v = undo.vertex_count; v < mesh.vertex_count(); ++v) {
        changed.push_back(v);
      }
      const MeshValidation validation = validate_around(mesh, changed);
      if (validation.is_valid_but_unreferenced()) {
        compact(mesh, attempt_faces, std::vector<bool>(mesh.triangle_count(), true));
        on_faces = std::move(attempt_faces);
        summary.snapped_vertices += attempt_summary.snapped_vertices;
        summary.cut_edges += attempt_summary.cut_edges;
        done = true;
        break;
      }
      undo.undo(mesh);
      failure = "clipping to the face " + describe_face(domain, k) +
                " would leave an invalid mesh: " + validation.report();
    }
    if (!done) {
      drop_outside(domain, space, k, mesh, on_faces);
      if (summary.message.empty() && !summary.interrupted) {
        summary.message = failure +
                          "; the triangles across that face were removed instead (try a smaller "
                          "step)";
      }
    }
  }
  if (options.min_boundary_edge > 0 && summary.half_spaces_crossed > 0 && !summary.interrupted) {
    summary.collapsed_edges =
        collapse_short_boundary_edges(problem, mesh, on_faces, options.min_boundary_edge);
    // Collapsing leaves the moved-away vertices unused: drop them.
    mesh.keep_triangles(std::vector<bool>(mesh.triangle_count(), true));
  }
  return summary;
}

}  // namespace tessera
