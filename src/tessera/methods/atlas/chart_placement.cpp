// SPDX-License-Identifier: MIT
// The atlas's placement of a new chart: where its centre goes to cover an uncovered corner of a
// chart's polygon (Henderson's rule on the disk, or towards a hexagonal packing), and the move
// of a centre near ∂S onto M ∩ ∂S.
#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "tessera/core/face_projection.h"
#include "tessera/methods/atlas/atlas_builder.h"

namespace tessera::detail {

// Centres that fall near a face of the domain are moved onto M ∩ face (onto M ∩ both faces
// near a corner), so that the atlas carries a row of charts exactly on ∂S and clipping finds
// the boundary already there instead of cutting slivers. A point already taken by a chart
// (a corner reached twice) is left where it was.
void AtlasBuilder::snap_to_domain_boundary(Eigen::VectorXd& y, double radius,
                                           const Linearization& near) {
  if (domain_.is_unbounded() || options_.boundary_snap <= 0) {
    return;
  }
  std::vector<int> faces;
  for (int k = 0; k < static_cast<int>(domain_.half_spaces().size()); ++k) {
    if (std::abs(domain_.signed_distance(k, y)) < options_.boundary_snap * radius) {
      faces.push_back(k);
    }
  }
  if (faces.empty() || static_cast<int>(faces.size()) > 2 ||
      static_cast<int>(faces.size()) + n_ - 2 > n_) {
    return;
  }
  Eigen::VectorXd snapped = y;
  if (!project_onto_faces(problem_, domain_, faces, snapped, options_.boundary_snap * radius * 2,
                          options_.corrector, nullptr, &near)) {
    return;
  }
  index_.candidates(snapped, 0.1 * radius, candidates_);
  for (int m : candidates_) {
    if (space_->distance(center(m), snapped) < 0.2 * radius) {
      return;
    }
  }
  y = snapped;
}

// Where to centre the chart that covers the uncovered polygon vertex v of chart c, in c's
// tangent coordinates.
//  - Disk (Henderson): on the disk boundary towards v. Neighbouring centres end up R to 2R
//    apart, the triangles' circumradii are mostly well below R, all angles near or above 30°.
//  - Hexagonal: towards the packing in which every polygon vertex lies on three disk
//    boundaries (centres √3·R apart). Next to a neighbour a, the new centre is the apex of the
//    isosceles triangle on c–a with sides hexagonal_side·R; in a gap between two neighbours,
//    at v itself; from a chart with no neighbour yet, hexagonal_side·R towards v.
Eigen::Vector2d AtlasBuilder::child_position(int c, int vertex) const {
  const auto& vertices = charts_[c].polygon.vertices();
  const int m = static_cast<int>(vertices.size());
  const auto& v = vertices[vertex];
  const Eigen::Vector2d at(v.s, v.t);
  const double R = charts_[c].radius;
  if (options_.placement == AtlasPlacement::Disk) {
    return R * at.normalized();
  }
  const double side = options_.hexagonal_side * R;
  const int before = vertices[(vertex + m - 1) % m].edge_label;
  const int after = v.edge_label;
  Eigen::Vector2d p;
  if (before >= 0 && after >= 0) {
    p = at;
  } else if (before >= 0 || after >= 0) {
    const int a = before >= 0 ? before : after;
    const Eigen::Vector2d pa = space_->tangent_coordinates(tangent(c), center(a) - center(c));
    const double spacing = pa.norm();
    const Eigen::Vector2d middle = 0.5 * pa;
    Eigen::Vector2d normal = Eigen::Vector2d(-pa(1), pa(0)).normalized();
    if (normal.dot(at - middle) < 0) {
      normal = -normal;
    }
    const double height =
        spacing < 2 * side ? std::sqrt(side * side - 0.25 * spacing * spacing) : 0.0;
    p = middle + height * normal;
  } else {
    p = side * at.normalized();
  }
  // Disks must overlap their parent's (distance < 2R) and the step must make progress.
  const double distance = p.norm();
  if (distance > 1.9 * R) {
    p *= 1.9 * R / distance;
  } else if (distance < 0.5 * R) {
    p = 0.5 * R * at.normalized();
  }
  return p;
}

}  // namespace tessera::detail
