// SPDX-License-Identifier: MIT
#include "tessera/methods/common/clip_to_domain.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

#include "tessera/core/face_projection.h"
#include "tessera/core/linearization.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/geometry/mesh_validation.h"

namespace tessera {

namespace {

// A vertex already at the corner point x of M ∩ (the faces), or −1. Two vertices snapped or cut
// onto the same corner would make a zero-area triangle.
int find_corner(const TriangleMesh& mesh, const std::vector<std::vector<int>>& vertex_faces,
                const std::vector<int>& faces, const Eigen::VectorXd& x) {
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    if (vertex_faces[v] == faces && (mesh.point(v) - x).norm() <= 1e-8 * (1 + x.norm())) {
      return v;
    }
  }
  return -1;
}

std::vector<int> common_faces(const std::vector<int>& a, const std::vector<int>& b) {
  std::vector<int> result;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(result));
  return result;
}

}  // namespace

namespace {

using FaceSets = std::vector<std::vector<int>>;  // per vertex: sorted faces it lies on

// Clips to face k. Returns false (with `message` set) if a cut point cannot be found.
bool clip_to_face(const ImplicitProblem& problem, const Domain& domain, int k, double snap_distance,
                  const CorrectorOptions& corrector, TriangleMesh& mesh, FaceSets& on_faces,
                  ClipSummary& summary) {
  ClipOptions options;
  options.snap_distance = snap_distance;
  options.corrector = corrector;
  const int vertex_count = mesh.vertex_count();
  std::vector<double> d(vertex_count);
  for (int v = 0; v < vertex_count; ++v) {
    d[v] = std::binary_search(on_faces[v].begin(), on_faces[v].end(), k)
               ? 0.0
               : domain.signed_distance(k, mesh.point(v));
  }
  {
    TriangleMesh work = mesh;
    auto work_faces = on_faces;
    // 1. Snap vertices near the face onto M ∩ face. Where that point is a corner of M ∩ S
    //    (two faces meet) and a vertex already sits there, the edge to it is collapsed
    //    instead: two vertices a hair apart at a corner would make needles.
    std::vector<std::vector<int>> vertex_triangles(vertex_count);
    for (int t = 0; t < work.triangle_count(); ++t) {
      for (int v : work.triangle(t)) {
        vertex_triangles[v].push_back(t);
      }
    }
    const auto are_adjacent = [&](int a, int b) {
      for (int t : vertex_triangles[a]) {
        const Triangle& tri = work.triangle(t);
        if (tri[0] == b || tri[1] == b || tri[2] == b) {
          return true;
        }
      }
      return false;
    };
    std::vector<int> collapse_into(vertex_count, -1);
    for (int v = 0; v < vertex_count; ++v) {
      if (d[v] == 0.0 || std::abs(d[v]) >= options.snap_distance) {
        continue;
      }
      std::vector<int> faces = work_faces[v];
      faces.push_back(k);
      std::sort(faces.begin(), faces.end());
      Eigen::VectorXd x = work.point(v);
      const bool is_corner =
          static_cast<int>(faces.size()) + problem.equation_count() == problem.ambient_dimension();
      if (!project_onto_faces(problem, domain, faces, x, 3 * options.snap_distance,
                              options.corrector) ||
          !domain.contains(x, 1e-9)) {
        continue;
      }
      const int occupant = is_corner ? find_corner(work, work_faces, faces, x) : -1;
      if (occupant >= 0) {
        if (are_adjacent(v, occupant) && collapse_into[occupant] < 0) {
          collapse_into[v] = occupant;
          d[v] = 0.0;
        }
        continue;
      }
      work.mutable_point(v) = x;
      work_faces[v] = faces;
      d[v] = 0.0;
      ++summary.snapped_vertices;
    }
    std::vector<Triangle> collapsed;
    for (Triangle t : work.triangles()) {
      for (int& v : t) {
        v = collapse_into[v] >= 0 ? collapse_into[v] : v;
      }
      if (t[0] != t[1] && t[1] != t[2] && t[2] != t[0]) {
        collapsed.push_back(t);
      }
    }
    work.set_triangles(std::move(collapsed));
    // 2. Cut points on the edges that still cross the face.
    std::map<std::pair<int, int>, int> cut_vertex;
    for (const Triangle& t : work.triangles()) {
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
        const double s = d[u] / (d[u] - d[w]);
        Eigen::VectorXd x = (1 - s) * work.point(u) + s * work.point(w);
        std::vector<int> faces = common_faces(work_faces[u], work_faces[w]);
        faces.push_back(k);
        std::sort(faces.begin(), faces.end());
        const double edge_length = (work.point(u) - work.point(w)).norm();
        if (!project_onto_faces(problem, domain, faces, x, edge_length, options.corrector)) {
          std::ostringstream message;
          message << "cannot clip the mesh to the face '" << domain.half_spaces()[k].label
                  << "': no point of M on the face near edge (" << u << ", " << w
                  << "); the mesh is left unclipped there";
          summary.message = message.str();
          return false;
        }
        // A cut point that lands next to an earlier face belongs at the corner where the two
        // faces meet (left where it is, it would make a needle with that corner).
        if (static_cast<int>(faces.size()) + problem.equation_count() <
            problem.ambient_dimension()) {
          for (int j = 0; j < k; ++j) {
            if (std::binary_search(faces.begin(), faces.end(), j) ||
                std::abs(domain.signed_distance(j, x)) >= options.snap_distance) {
              continue;
            }
            std::vector<int> corner_faces = faces;
            corner_faces.push_back(j);
            std::sort(corner_faces.begin(), corner_faces.end());
            Eigen::VectorXd corner = x;
            if (project_onto_faces(problem, domain, corner_faces, corner, 3 * options.snap_distance,
                                   options.corrector) &&
                domain.contains(corner, 1e-9)) {
              x = corner;
              faces = corner_faces;
              break;
            }
          }
        }
        // Where the face meets an earlier face, M ∩ both is a point (a corner of the clipped
        // surface): reuse the corner vertex if one is already there, else the corner doubles.
        const int existing =
            static_cast<int>(faces.size()) + problem.equation_count() == problem.ambient_dimension()
                ? find_corner(work, work_faces, faces, x)
                : -1;
        if (existing >= 0) {
          cut_vertex[key] = existing;
          continue;
        }
        cut_vertex[key] = work.add_vertex(x);
        work_faces.push_back(faces);
        d.push_back(0.0);
        ++summary.cut_edges;
      }
    }
    const auto cut = [&](int u, int w) { return cut_vertex.at(std::minmax(u, w)); };
    // 3. Split the triangles and keep the parts inside.
    std::vector<Triangle> kept;
    const auto add_polygon = [&](std::vector<int> polygon) {
      polygon.erase(std::unique(polygon.begin(), polygon.end()), polygon.end());
      while (polygon.size() > 1 && polygon.front() == polygon.back()) {
        polygon.pop_back();
      }
      if (polygon.size() == 3) {
        kept.push_back({polygon[0], polygon[1], polygon[2]});
      } else if (polygon.size() == 4) {
        const double diagonal_02 = std::min(min_angle(work, {polygon[0], polygon[1], polygon[2]}),
                                            min_angle(work, {polygon[0], polygon[2], polygon[3]}));
        const double diagonal_13 = std::min(min_angle(work, {polygon[0], polygon[1], polygon[3]}),
                                            min_angle(work, {polygon[1], polygon[2], polygon[3]}));
        if (diagonal_02 >= diagonal_13) {
          kept.push_back({polygon[0], polygon[1], polygon[2]});
          kept.push_back({polygon[0], polygon[2], polygon[3]});
        } else {
          kept.push_back({polygon[0], polygon[1], polygon[3]});
          kept.push_back({polygon[1], polygon[2], polygon[3]});
        }
      }
    };
    for (const Triangle& t : work.triangles()) {
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
      add_polygon(polygon);
    }
    // 4. Compact: drop vertices no longer used.
    std::vector<int> new_index(work.vertex_count(), -1);
    TriangleMesh clipped(work.ambient_dimension());
    std::vector<std::vector<int>> clipped_faces;
    for (Triangle& t : kept) {
      for (int& v : t) {
        if (new_index[v] < 0) {
          new_index[v] = clipped.add_vertex(work.point(v));
          clipped_faces.push_back(work_faces[v]);
        }
        v = new_index[v];
      }
    }
    clipped.set_triangles(std::move(kept));
    mesh = std::move(clipped);
    on_faces = std::move(clipped_faces);
  }
  return true;
}

// Collapses boundary edges shorter than `min_length`: the vertex on fewer faces moves into the
// other (a corner or face vertex stays where it is, on M ∩ ∂S). A collapse is kept only if it
// raises the smallest angle among the triangles around the moved vertex and the result is valid.
int collapse_short_boundary_edges(TriangleMesh& mesh, const FaceSets& on_faces, double min_length) {
  int collapsed = 0;
  bool changed = true;
  std::set<std::pair<int, int>> rejected;  // each edge is judged once: O(N) per collapse
  while (changed) {
    changed = false;
    const MeshTopology topology(mesh);
    for (int e : topology.boundary_edges()) {
      auto [a, b] = topology.edge(e);
      if ((mesh.point(a) - mesh.point(b)).norm() >= min_length || !rejected.insert({a, b}).second) {
        continue;
      }
      if (on_faces[b].size() > on_faces[a].size()) {
        std::swap(a, b);  // keep a, the vertex on more faces
      }
      std::vector<Triangle> triangles;
      double worst_before = std::numbers::pi;
      double worst_after = std::numbers::pi;
      for (Triangle t : mesh.triangles()) {
        const bool has_a = t[0] == a || t[1] == a || t[2] == a;
        const bool has_b = t[0] == b || t[1] == b || t[2] == b;
        if (has_b) {
          worst_before = std::min(worst_before, min_angle(mesh, t));
        }
        if (has_a && has_b) {
          continue;  // the triangle on the collapsed edge disappears
        }
        if (has_b) {
          for (int& v : t) {
            v = v == b ? a : v;
          }
          worst_after = std::min(worst_after, min_angle(mesh, t));
        }
        triangles.push_back(t);
      }
      if (worst_after <= worst_before) {
        continue;  // only collapses that improve the worst angle around b
      }
      // The moved-away vertex is left unreferenced until the final compaction; every other
      // defect rejects the collapse.
      const MeshValidation validation = validate(TriangleMesh(mesh.points(), triangles));
      if (validation.defects.size() !=
          static_cast<std::size_t>(validation.unreferenced_vertex_count > 0 ? 1 : 0)) {
        continue;
      }
      mesh.set_triangles(std::move(triangles));
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
  ClipSummary summary;
  const int face_count = static_cast<int>(domain.half_spaces().size());
  FaceSets on_faces(mesh.vertex_count());
  for (int k = 0; k < face_count; ++k) {
    bool crosses = false;
    for (int v = 0; v < mesh.vertex_count() && !crosses; ++v) {
      crosses = !std::binary_search(on_faces[v].begin(), on_faces[v].end(), k) &&
                domain.signed_distance(k, mesh.point(v)) < 0;
    }
    if (!crosses) {
      continue;
    }
    ++summary.half_spaces_crossed;
    // Snapping keeps needles away but, where the mesh is coarse next to a corner of the
    // domain, can pull two vertices onto each other; then clip again without snapping. A clip
    // that would still leave an invalid mesh is refused: the mesh stays unclipped there.
    bool done = false;
    for (const double snap : {options.snap_distance, 0.0}) {
      TriangleMesh attempt = mesh;
      FaceSets attempt_faces = on_faces;
      ClipSummary attempt_summary;
      if (!clip_to_face(problem, domain, k, snap, options.corrector, attempt, attempt_faces,
                        attempt_summary)) {
        summary.message = attempt_summary.message;
        return summary;
      }
      if (validate(attempt).is_valid()) {
        mesh = std::move(attempt);
        on_faces = std::move(attempt_faces);
        summary.snapped_vertices += attempt_summary.snapped_vertices;
        summary.cut_edges += attempt_summary.cut_edges;
        done = true;
        break;
      }
    }
    if (!done) {
      summary.message = "clipping to the face '" + domain.half_spaces()[k].label +
                        "' would leave an invalid mesh; the mesh is left unclipped there "
                        "(try a smaller step)";
      return summary;
    }
  }
  if (options.min_boundary_edge > 0 && summary.half_spaces_crossed > 0) {
    summary.collapsed_edges =
        collapse_short_boundary_edges(mesh, on_faces, options.min_boundary_edge);
    // Collapsing leaves the moved-away vertices unused: drop them.
    std::vector<int> new_index(mesh.vertex_count(), -1);
    TriangleMesh compact(mesh.ambient_dimension());
    std::vector<Triangle> triangles = mesh.triangles();
    for (Triangle& t : triangles) {
      for (int& v : t) {
        if (new_index[v] < 0) {
          new_index[v] = compact.add_vertex(mesh.point(v));
        }
        v = new_index[v];
      }
    }
    compact.set_triangles(std::move(triangles));
    mesh = std::move(compact);
  }
  return summary;
}

}  // namespace tessera
