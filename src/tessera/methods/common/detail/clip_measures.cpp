// SPDX-License-Identifier: MIT
#include "tessera/methods/common/detail/clip_measures.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "tessera/core/face_projection.h"
#include "tessera/geometry/mesh_quality.h"

namespace tessera::detail {

// The lengths ‖point(u) − point(w)‖ of the pairs (u, w): one reduction on a split mesh.
std::vector<double> lengths(const TriangleMesh& mesh, const AmbientSpace& space,
                            const std::vector<std::pair<int, int>>& pairs) {
  std::vector<double> result(pairs.size());
  if (!space.is_distributed()) {
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      result[i] = (mesh.point(pairs[i].first) - mesh.point(pairs[i].second)).norm();
    }
    return result;
  }
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    result[i] = (mesh.point(pairs[i].first) - mesh.point(pairs[i].second)).squaredNorm();
  }
  if (!result.empty()) {
    space.sum(result.data(), static_cast<int>(result.size()));
  }
  for (double& length : result) {
    length = std::sqrt(length);
  }
  return result;
}

// min_angle of each triangle: one reduction (their sides) on a split mesh.
std::vector<double> min_angles(const TriangleMesh& mesh, const AmbientSpace& space,
                               const std::vector<Triangle>& triangles) {
  std::vector<double> result(triangles.size());
  if (!space.is_distributed()) {
    for (std::size_t i = 0; i < triangles.size(); ++i) {
      result[i] = min_angle(mesh, triangles[i]);
    }
    return result;
  }
  std::vector<std::pair<int, int>> sides;
  for (const Triangle& t : triangles) {
    sides.insert(sides.end(), {{t[1], t[0]}, {t[2], t[1]}, {t[0], t[2]}});
  }
  const std::vector<double> side = lengths(mesh, space, sides);
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    result[i] = min_angle_of_sides(side[3 * i], side[3 * i + 1], side[3 * i + 2]);
  }
  return result;
}

// Whether the caller asked to stop: a rank's own request, so on a split mesh the largest over
// the ranks (a request seen by one rank stops them all at the same place). The options are the
// same on every rank: without a callback there is nothing to agree on.
bool is_stop_requested(const std::function<bool()>& stop_requested, const AmbientSpace& space) {
  if (!stop_requested) {
    return false;
  }
  const bool requested = stop_requested();
  return space.is_distributed() ? space.maximum(requested ? 1.0 : 0.0) > 0.0 : requested;
}

// A vertex already at the corner point x of M ∩ (the faces), or −1. Two vertices snapped or cut
// onto the same corner would make a zero-area triangle.
int find_corner(const TriangleMesh& mesh, const AmbientSpace& space, const FaceSets& vertex_faces,
                const std::vector<int>& faces, const Eigen::VectorXd& x) {
  if (!space.is_distributed()) {
    for (int v = 0; v < mesh.vertex_count(); ++v) {
      if (vertex_faces[v] == faces && (mesh.point(v) - x).norm() <= 1e-8 * (1 + x.norm())) {
        return v;
      }
    }
    return -1;
  }
  // The vertices on the same faces (replicated) and their distances to x, summed at once.
  std::vector<int> candidates;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    if (vertex_faces[v] == faces) {
      candidates.push_back(v);
    }
  }
  std::vector<double> parts(candidates.size() + 1);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    parts[i] = (mesh.point(candidates[i]) - x).squaredNorm();
  }
  parts.back() = x.squaredNorm();
  space.sum(parts.data(), static_cast<int>(parts.size()));
  const double tolerance = 1e-8 * (1 + std::sqrt(parts.back()));
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (std::sqrt(parts[i]) <= tolerance) {
      return candidates[i];
    }
  }
  return -1;
}

std::vector<int> common_faces(const std::vector<int>& a, const std::vector<int>& b) {
  std::vector<int> result;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(result));
  return result;
}

// Records which bounding hyperplanes each vertex already lies on (to kOnFaceTolerance, relative
// to 1 + |x|) and puts it on them exactly: the methods' own boundary snapping (the atlas's chart
// centres, refinement midpoints) leaves vertices there to corrector tolerance, and they must
// count as on the face, not across it.
FaceSets faces_of_vertices(const Domain& domain, const AmbientSpace& space, TriangleMesh& mesh) {
  FaceSets on_faces(mesh.vertex_count());
  const int faces = static_cast<int>(domain.half_spaces().size());
  if (!space.is_distributed()) {
    for (int v = 0; v < mesh.vertex_count(); ++v) {
      Eigen::VectorXd x = mesh.point(v);
      for (int k = 0; k < faces; ++k) {
        if (std::abs(domain.signed_distance(k, x)) <= kOnFaceTolerance * (1.0 + x.norm())) {
          on_faces[v].push_back(k);
        }
      }
      if (!on_faces[v].empty()) {
        place_on_faces(domain, on_faces[v], x);
        mesh.mutable_point(v) = x;
      }
    }
    return on_faces;
  }
  // Every vertex's distances to the faces and its squared norm, summed at once.
  const auto stride = static_cast<std::size_t>(faces + 1);
  std::vector<double> parts(stride * static_cast<std::size_t>(mesh.vertex_count()));
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    double* row = parts.data() + stride * static_cast<std::size_t>(v);
    for (int k = 0; k < faces; ++k) {
      row[k] = domain.partial_signed_distance(k, mesh.point(v));
    }
    row[faces] = mesh.point(v).squaredNorm();
  }
  if (!parts.empty()) {
    space.sum(parts.data(), static_cast<int>(parts.size()));
  }
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    const double* row = parts.data() + stride * static_cast<std::size_t>(v);
    for (int k = 0; k < faces; ++k) {
      if (std::abs(row[k]) <= kOnFaceTolerance * (1.0 + std::sqrt(row[faces]))) {
        on_faces[v].push_back(k);
      }
    }
    if (!on_faces[v].empty()) {
      Eigen::VectorXd x = mesh.point(v);
      place_on_faces(domain, on_faces[v], x, space);
      mesh.mutable_point(v) = x;
    }
  }
  return on_faces;
}

std::string describe_face(const Domain& domain, int k) {
  return "'" + domain.half_spaces()[k].label + "'";
}

// Keeps the triangles with keep[t] and the vertices they use, in place (no second copy of the
// mesh, which at large n is most of the memory), with the vertices' face sets.
void compact(TriangleMesh& mesh, FaceSets& on_faces, const std::vector<bool>& keep) {
  const std::vector<int> new_index = mesh.keep_triangles(keep);
  FaceSets kept_faces(mesh.vertex_count());
  for (std::size_t v = 0; v < new_index.size(); ++v) {
    if (new_index[v] >= 0) {
      kept_faces[new_index[v]] = std::move(on_faces[v]);
    }
  }
  on_faces = std::move(kept_faces);
}

}  // namespace tessera::detail
