// SPDX-License-Identifier: MIT
#include "tessera/geometry/mesh_validation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <sstream>
#include <utility>

#include "tessera/core/describe.h"
#include "tessera/core/error.h"
#include "tessera/core/scaled_problem.h"
#include "tessera/geometry/detail/mesh_validation_checks.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_topology.h"

namespace tessera {
namespace {

using detail::DefectRecorder;
using detail::GeometricInput;
using detail::MeshView;
using detail::TriangleShapes;

constexpr std::size_t max_listed_indices = 8;  // per example line, e.g. triangles of an edge

std::string triangle_text(int t, const Triangle& tri) {
  std::ostringstream out;
  out << "triangle " << t << " = (" << tri[0] << ", " << tri[1] << ", " << tri[2] << ")";
  return out.str();
}

// "7, 9, 31" or "7, 9, 31, ... (12 in all)"
template <class Range, class Map>
std::string index_list(const Range& indices, Map map) {
  std::ostringstream out;
  std::size_t i = 0;
  for (auto index : indices) {
    if (i == max_listed_indices) {
      out << ", ... (" << std::size(indices) << " in all)";
      break;
    }
    out << (i == 0 ? "" : ", ") << map(index);
    ++i;
  }
  return out.str();
}

// Union-find over triangle corners (corner 3t + k is vertex tri[k] of triangle t), used to
// group the triangles around each vertex into fans.
class CornerSets {
 public:
  explicit CornerSets(std::size_t size) : parent_(size) {
    for (std::size_t i = 0; i < size; ++i) {
      parent_[i] = static_cast<int>(i);
    }
  }
  int find(int c) {
    while (parent_[c] != c) {
      parent_[c] = parent_[parent_[c]];  // path halving
      c = parent_[c];
    }
    return c;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) {
      parent_[std::max(a, b)] = std::min(a, b);
    }
  }

 private:
  std::vector<int> parent_;
};

int corner(const std::vector<Triangle>& triangles, int t, int v) {
  const Triangle& tri = triangles[t];
  return 3 * t + (tri[0] == v ? 0 : (tri[1] == v ? 1 : 2));
}

}  // namespace

std::string_view to_string(MeshDefectKind kind) {
  switch (kind) {
    case MeshDefectKind::IndexOutOfRange:
      return "index out of range";
    case MeshDefectKind::RepeatedIndex:
      return "repeated index";
    case MeshDefectKind::DuplicateTriangle:
      return "duplicate triangle";
    case MeshDefectKind::NonManifoldEdge:
      return "non-manifold edge";
    case MeshDefectKind::NonManifoldVertex:
      return "non-manifold vertex";
    case MeshDefectKind::InconsistentOrientation:
      return "inconsistent orientation";
    case MeshDefectKind::UnreferencedVertex:
      return "unreferenced vertex";
    case MeshDefectKind::DegenerateTriangle:
      return "degenerate triangle";
    case MeshDefectKind::NonFiniteCoordinate:
      return "non-finite coordinate";
    case MeshDefectKind::FlippedTriangle:
      return "flipped triangle";
    case MeshDefectKind::OverlappingTriangles:
      return "overlapping triangles";
    case MeshDefectKind::VertexOutsideDomain:
      return "vertex outside domain";
  }
  return "unknown defect";
}

int MeshValidation::count(MeshDefectKind kind) const {
  for (const MeshDefect& defect : defects) {
    if (defect.kind == kind) {
      return defect.count;
    }
  }
  return 0;
}

std::string MeshValidation::report() const {
  std::ostringstream out;
  out << "mesh in R^" << ambient_dimension << ": " << triangle_count << " triangles, "
      << vertex_count << " vertices (" << referenced_vertex_count << " referenced), " << edge_count
      << " edges\n";
  out << "topology: " << component_count << (component_count == 1 ? " component" : " components")
      << ", Euler characteristic " << euler_characteristic << ", ";
  if (is_closed()) {
    out << "closed";
  } else {
    out << boundary_edge_count
        << (boundary_edge_count == 1 ? " boundary edge in " : " boundary edges in ")
        << boundary_loop_count << (boundary_loop_count == 1 ? " loop" : " loops");
    if (!boundary_loop_vertex_counts.empty()) {
      out << " of " << index_list(boundary_loop_vertex_counts, [](int n) { return n; })
          << " vertices";
    }
  }
  if (is_orientable) {
    out << ", orientable";
  } else {
    out << ", non-orientable (" << non_orientable_component_count
        << (non_orientable_component_count == 1 ? " component)" : " components)");
  }
  if (genus >= 0) {
    out << ", genus " << genus;
  }
  out << "\n";
  if (is_geometry_checked && is_cut_short()) {
    out << "geometry: cut short by a stop request (";
    for (std::size_t i = 0; i < checks_cut_short.size(); ++i) {
      out << (i ? "; " : "") << checks_cut_short[i];
    }
    out << "); the domain checked\n";
  } else if (is_geometry_checked) {
    out << "geometry: orientation along M, overlaps on M and the domain checked";
    if (unoriented_triangle_count > 0) {
      out << " (" << unoriented_triangle_count
          << (unoriented_triangle_count == 1 ? " triangle" : " triangles")
          << " not oriented: DF singular at the centroid)";
    }
    if (crossing_pair_count > 0) {
      out << " (" << crossing_pair_count
          << (crossing_pair_count == 1 ? " pair" : " pairs")
          << " of triangles where components cross: sheets of M crossing, not a double covering)";
    }
    out << "\n";
  } else {
    out << "geometry: not checked (no problem given)\n";
  }
  if (is_valid()) {
    out << (is_cut_short() ? "valid as far as checked: no defects found\n" : "valid: no defects\n");
    return out.str();
  }
  out << "invalid:\n";
  for (const MeshDefect& defect : defects) {
    out << "  " << to_string(defect.kind) << ": " << defect.count << "\n";
    for (const std::string& example : defect.examples) {
      out << "    " << example << "\n";
    }
    if (defect.count > static_cast<int>(defect.examples.size())) {
      out << "    ... and " << defect.count - static_cast<int>(defect.examples.size()) << " more\n";
    }
  }
  return out.str();
}

namespace {

void check_options(const ValidationOptions& options) {
  TESSERA_CHECK(options.degenerate_area_ratio >= 0,
                "ValidationOptions::degenerate_area_ratio = " << options.degenerate_area_ratio
                                                              << " must be >= 0");
  TESSERA_CHECK(options.max_examples >= 0,
                "ValidationOptions::max_examples = " << options.max_examples << " must be >= 0");
}

// The combinatorial checks, then the geometric ones if `geometry` is given.
// `measured` (null: all): the vertices whose coordinates, and the triangles around them whose
// shapes, are checked (validate_around); the others are taken as finite and well shaped.
MeshValidation validate_mesh(const TriangleMesh& mesh, const ValidationOptions& options,
                             const GeometricInput* geometry,
                             const std::vector<std::uint8_t>* measured = nullptr) {
  TESSERA_ASSERT(measured == nullptr || geometry == nullptr);
  using Kind = MeshDefectKind;
  DefectRecorder recorder(options.max_examples);
  MeshValidation result;
  const int vertex_count = mesh.vertex_count();
  const std::vector<Triangle>& triangles = mesh.triangles();
  const auto points = mesh.points();
  // A split mesh (SPMD): every rank holds its rows of the points and reduces through the space.
  const AmbientSpace& space = mesh.space();
  result.ambient_dimension = space.dimension();
  result.vertex_count = vertex_count;
  result.triangle_count = mesh.triangle_count();
  // " near (x, y, z)": the mean of the given vertices that exist and are finite, so that every
  // message names a place, not only indices ("" if there is none).
  auto near = [&](std::initializer_list<int> vertices) -> std::string {
    Eigen::VectorXd sum = Eigen::VectorXd::Zero(mesh.ambient_dimension());
    int used = 0;
    for (int v : vertices) {
      if (v >= 0 && v < vertex_count && space.all_finite(points.col(v))) {
        sum += points.col(v);
        ++used;
      }
    }
    return used == 0 ? std::string() : " near " + describe_point(sum / used, space);
  };

  // Malformed triangles (index out of range, repeated index) have no well-defined edges; they
  // are reported and left out of the topology. `kept` maps topology triangles back to mesh
  // triangles, and stays empty (the identity) in the common case that all are well-formed.
  std::vector<std::uint8_t> is_referenced(vertex_count, 0);
  std::vector<int> kept;
  bool is_every_triangle_well_formed = true;
  for (int t = 0; t < result.triangle_count; ++t) {
    const Triangle& tri = triangles[t];
    bool is_out_of_range = false;
    int bad_index = 0;  // the first index out of range, which may well be negative
    for (int v : tri) {
      if (v >= 0 && v < vertex_count) {
        is_referenced[v] = 1;
      } else if (!is_out_of_range) {
        is_out_of_range = true;
        bad_index = v;
      }
    }
    const bool is_repeated = tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0];
    if (is_out_of_range || is_repeated) {
      if (is_every_triangle_well_formed) {
        is_every_triangle_well_formed = false;
        for (int s = 0; s < t; ++s) {
          kept.push_back(s);
        }
      }
    } else if (!is_every_triangle_well_formed) {
      kept.push_back(t);
    }
    if (is_out_of_range) {
      recorder.record(Kind::IndexOutOfRange, [&] {
        std::ostringstream out;
        out << triangle_text(t, tri) << near({tri[0], tri[1], tri[2]}) << " has index " << bad_index
            << " outside [0, " << vertex_count << ")";
        return out.str();
      });
    } else if (is_repeated) {
      recorder.record(Kind::RepeatedIndex, [&] {
        const int v = tri[0] == tri[1] || tri[0] == tri[2] ? tri[0] : tri[1];
        return triangle_text(t, tri) + near({tri[0], tri[1], tri[2]}) + " repeats vertex " +
               std::to_string(v);
      });
    }
  }
  std::vector<Triangle> well_formed;
  if (!is_every_triangle_well_formed) {
    well_formed.reserve(kept.size());
    for (int t : kept) {
      well_formed.push_back(triangles[t]);
    }
  }
  const MeshTopology topology(vertex_count, is_every_triangle_well_formed
                                                ? std::span<const Triangle>(triangles)
                                                : std::span<const Triangle>(well_formed));
  auto original = [&](int t) { return is_every_triangle_well_formed ? t : kept[t]; };
  const std::vector<Triangle>& topology_triangles = topology.triangles();

  result.referenced_vertex_count = topology.referenced_vertex_count();
  result.edge_count = topology.edge_count();
  result.boundary_edge_count = static_cast<int>(topology.boundary_edges().size());
  result.boundary_loop_count = topology.boundary_loop_count();
  for (int i = 0; i < result.boundary_loop_count; ++i) {
    result.boundary_loop_vertex_counts.push_back(
        static_cast<int>(topology.boundary_loop(i).size()));
  }
  result.component_count = topology.component_count();
  result.euler_characteristic = topology.euler_characteristic();

  const auto is_measured = [&](int v) { return measured == nullptr || (*measured)[v] != 0; };
  std::vector<std::uint8_t> is_finite(vertex_count, 1);
  // Which vertices have a coordinate that is not finite, on any rank (one reduction for all).
  std::vector<double> not_finite(static_cast<std::size_t>(vertex_count), 0.0);
  for (int v = 0; v < vertex_count; ++v) {
    not_finite[static_cast<std::size_t>(v)] = is_measured(v) && !points.col(v).allFinite();
  }
  if (space.is_distributed() && vertex_count > 0) {
    space.sum(not_finite.data(), vertex_count);
  }
  for (int v = 0; v < vertex_count; ++v) {
    if (not_finite[static_cast<std::size_t>(v)] > 0) {
      is_finite[v] = 0;
      recorder.record(Kind::NonFiniteCoordinate, [&] {
        std::ostringstream out;
        out << "vertex " << v << " = ";
        if (space.is_distributed()) {
          out << describe_point(points.col(v), space);
        } else {
          out << "(" << index_list(points.col(v), [](double x) { return x; }) << ")";
        }
        return out.str();
      });
    }
  }
  for (int v = 0; v < vertex_count; ++v) {
    if (!is_referenced[v]) {
      recorder.record(Kind::UnreferencedVertex, [&] {
        return "vertex " + std::to_string(v) + " at " + describe_point(points.col(v), space) +
               " is in no triangle";
      });
    }
  }

  for (int e = 0; e < topology.edge_count(); ++e) {
    if (!topology.is_manifold_edge(e)) {
      recorder.record(Kind::NonManifoldEdge, [&] {
        const auto on_edge = topology.edge_triangles(e);
        std::ostringstream out;
        out << "edge (" << topology.edge(e)[0] << ", " << topology.edge(e)[1] << ")"
            << near({topology.edge(e)[0], topology.edge(e)[1]}) << " has " << on_edge.size()
            << " triangles: " << index_list(on_edge, original);
        return out.str();
      });
    }
  }

  // Two triangles with the same vertex set share all their edges, so comparing each triangle
  // with the earlier triangles on its first edge finds every duplicate in O(N).
  auto sorted = [](Triangle tri) {
    std::sort(tri.begin(), tri.end());
    return tri;
  };
  for (int t = 0; t < topology.triangle_count(); ++t) {
    const Triangle vertices = sorted(topology_triangles[t]);
    for (int u : topology.edge_triangles(topology.triangle_edges(t)[0])) {
      if (u >= t) {
        break;
      }
      if (sorted(topology_triangles[u]) == vertices) {
        recorder.record(Kind::DuplicateTriangle, [&] {
          const Triangle& tri = topology_triangles[t];
          return triangle_text(original(t), tri) + near({tri[0], tri[1], tri[2]}) + " repeats " +
                 triangle_text(original(u), topology_triangles[u]);
        });
        break;
      }
    }
  }

  // Fans: the corners at a vertex are joined across every edge at that vertex that has two or
  // more triangles. A manifold vertex has one fan; a bow tie has two or more.
  CornerSets corners(topology_triangles.size() * 3);
  for (int e = 0; e < topology.edge_count(); ++e) {
    const auto on_edge = topology.edge_triangles(e);
    for (std::size_t i = 1; i < on_edge.size(); ++i) {
      for (int v : topology.edge(e)) {
        corners.unite(corner(topology_triangles, on_edge[0], v),
                      corner(topology_triangles, on_edge[i], v));
      }
    }
  }
  std::vector<int> fan_count(vertex_count, 0);
  for (int c = 0; c < static_cast<int>(topology_triangles.size() * 3); ++c) {
    if (corners.find(c) == c) {
      ++fan_count[topology_triangles[c / 3][c % 3]];
    }
  }
  for (int v = 0; v < vertex_count; ++v) {
    if (fan_count[v] > 1) {
      recorder.record(Kind::NonManifoldVertex, [&] {
        std::vector<std::pair<int, int>> fan_and_triangle;  // only for the few examples
        for (int t : topology.vertex_triangles(v)) {
          fan_and_triangle.emplace_back(corners.find(corner(topology_triangles, t, v)), t);
        }
        std::sort(fan_and_triangle.begin(), fan_and_triangle.end());
        std::ostringstream out;
        out << "vertex " << v << near({v}) << " is shared by " << fan_count[v]
            << " fans of triangles that share no edge there: ";
        for (std::size_t i = 0; i < fan_and_triangle.size(); ++i) {
          const bool is_new_fan =
              i == 0 || fan_and_triangle[i].first != fan_and_triangle[i - 1].first;
          out << (i == 0 ? "{" : (is_new_fan ? "}, {" : ", "))
              << original(fan_and_triangle[i].second);
        }
        out << "}";
        return out.str();
      });
    }
  }

  const OrientationAssignment orientation = topology.orientation_assignment();
  for (std::uint8_t is_orientable : orientation.is_component_orientable) {
    result.non_orientable_component_count += is_orientable ? 0 : 1;
  }
  result.is_orientable = result.non_orientable_component_count == 0;
  for (int e = 0; e < topology.edge_count(); ++e) {
    if (topology.is_orientation_consistent(e)) {
      continue;
    }
    const auto on_edge = topology.edge_triangles(e);
    if (!orientation.is_component_orientable[topology.component_of(on_edge[0])]) {
      continue;  // unavoidable, as on a Möbius strip
    }
    recorder.record(Kind::InconsistentOrientation, [&] {
      const Triangle& tri = topology_triangles[on_edge[0]];
      const auto [a, b] = topology.edge(e);
      const bool is_forward = (tri[0] == a && tri[1] == b) || (tri[1] == a && tri[2] == b) ||
                              (tri[2] == a && tri[0] == b);
      std::ostringstream out;
      out << "triangles " << original(on_edge[0]) << " and " << original(on_edge[1])
          << " both traverse edge (" << a << ", " << b << ")" << near({a, b}) << " from "
          << (is_forward ? a : b) << " to " << (is_forward ? b : a)
          << "; orient_consistently() repairs this";
      return out.str();
    });
  }

  // Per topology triangle, for the geometric checks: area, longest edge, and whether it can be
  // judged at all (finite and not degenerate).
  TriangleShapes shapes(topology.triangle_count());
  for (int t = 0; t < topology.triangle_count(); ++t) {
    const Triangle& tri = topology_triangles[t];
    if (!is_finite[tri[0]] || !is_finite[tri[1]] || !is_finite[tri[2]]) {
      continue;  // reported as a non-finite coordinate
    }
    shapes.is_finite[t] = 1;
    if (!is_measured(tri[0]) && !is_measured(tri[1]) && !is_measured(tri[2])) {
      continue;  // unchanged since it was found well shaped
    }
    const auto [area, longest_squared] = triangle_area_and_longest_squared(mesh, tri);
    shapes.area[t] = area;
    shapes.longest_edge[t] = std::sqrt(longest_squared);
    shapes.is_degenerate[t] = area <= options.degenerate_area_ratio * longest_squared ? 1 : 0;
    if (shapes.is_degenerate[t]) {
      recorder.record(Kind::DegenerateTriangle, [&] {
        std::ostringstream out;
        out << triangle_text(original(t), tri) << near({tri[0], tri[1], tri[2]}) << " has area "
            << area << " (longest edge " << std::sqrt(longest_squared) << ")";
        return out.str();
      });
    }
  }

  result.index_out_of_range_count = recorder.count(Kind::IndexOutOfRange);
  result.repeated_index_count = recorder.count(Kind::RepeatedIndex);
  result.duplicate_triangle_count = recorder.count(Kind::DuplicateTriangle);
  result.non_manifold_edge_count = recorder.count(Kind::NonManifoldEdge);
  result.non_manifold_vertex_count = recorder.count(Kind::NonManifoldVertex);
  result.inconsistent_orientation_count = recorder.count(Kind::InconsistentOrientation);
  result.unreferenced_vertex_count = recorder.count(Kind::UnreferencedVertex);
  result.degenerate_triangle_count = recorder.count(Kind::DegenerateTriangle);
  result.non_finite_vertex_count = recorder.count(Kind::NonFiniteCoordinate);
  if (geometry != nullptr) {
    std::vector<int> original_index(topology.triangle_count());
    for (int t = 0; t < topology.triangle_count(); ++t) {
      original_index[t] = original(t);
    }
    const MeshView view{mesh, topology, original_index, shapes, is_finite};
    detail::CheckStop stop(options.stop_requested, mesh.space());
    detail::check_orientation(view, *geometry, options, stop, recorder, result);
    detail::check_overlaps(view, *geometry, options, stop, recorder, result);
    detail::check_domain(view, *geometry, options, recorder, result);
    result.is_geometry_checked = true;
    result.flipped_triangle_count = recorder.count(Kind::FlippedTriangle);
    result.overlapping_pair_count = recorder.count(Kind::OverlappingTriangles);
    result.vertex_outside_domain_count = recorder.count(Kind::VertexOutsideDomain);
  }
  result.defects = recorder.take_present();

  // For a closed orientable surface each component has chi_i = 2 - 2 g_i.
  if (result.is_closed() && result.is_orientable && result.is_manifold() &&
      is_every_triangle_well_formed) {
    result.genus = result.component_count - result.euler_characteristic / 2;
  }
  return result;
}

}  // namespace

MeshValidation validate(const TriangleMesh& mesh, const ValidationOptions& options) {
  check_options(options);
  return validate_mesh(mesh, options, nullptr);
}

MeshValidation validate_around(const TriangleMesh& mesh, std::span<const int> changed,
                               const ValidationOptions& options) {
  check_options(options);
  std::vector<std::uint8_t> measured(static_cast<std::size_t>(mesh.vertex_count()), 0);
  for (int v : changed) {
    TESSERA_CHECK(v >= 0 && v < mesh.vertex_count(),
                  "validate_around: vertex " << v << " is not in the mesh of "
                                             << mesh.vertex_count() << " vertices");
    measured[static_cast<std::size_t>(v)] = 1;
  }
  return validate_mesh(mesh, options, nullptr, &measured);
}

MeshValidation validate(const TriangleMesh& mesh, const ImplicitProblem& problem,
                        const Domain& domain, const ValidationOptions& options) {
  check_options(options);
  TESSERA_CHECK(options.min_tangent_cosine >= 0 && options.min_tangent_cosine <= 1,
                "ValidationOptions::min_tangent_cosine = " << options.min_tangent_cosine
                                                           << " must lie in [0, 1]");
  TESSERA_CHECK(
      options.overlap_area_ratio >= 0,
      "ValidationOptions::overlap_area_ratio = " << options.overlap_area_ratio << " must be >= 0");
  TESSERA_CHECK(options.overlap_sheet_depth_ratio > 0,
                "ValidationOptions::overlap_sheet_depth_ratio = "
                    << options.overlap_sheet_depth_ratio << " must be > 0");
  TESSERA_CHECK(options.overlap_same_point_ratio >= 0,
                "ValidationOptions::overlap_same_point_ratio = " << options.overlap_same_point_ratio
                                                                 << " must be >= 0");
  TESSERA_CHECK(options.crossing_plane_cosine >= 0 && options.crossing_plane_cosine <= 1,
                "ValidationOptions::crossing_plane_cosine = " << options.crossing_plane_cosine
                                                              << " must lie in [0, 1]");
  TESSERA_CHECK(options.crossing_alignment >= 0 && options.crossing_alignment <= 1,
                "ValidationOptions::crossing_alignment = " << options.crossing_alignment
                                                           << " must lie in [0, 1]");
  TESSERA_CHECK(options.domain_tolerance_ratio >= 0,
                "ValidationOptions::domain_tolerance_ratio = " << options.domain_tolerance_ratio
                                                               << " must be >= 0");
  if (const ImplicitProblem* twin = problem.metric_problem();
      twin != nullptr && problem.space()->is_distributed() && metric_weights(problem).size() > 0) {
    // A distributed problem in x (the PETSc backend's, whose mesh came back to x): judged in
    // the metric's coordinates by its twin there, as the covering judged it and as one process
    // judges it below (the report of a run without a valid mesh threw here until 2026-11-28).
    const AmbientSpace& space = *problem.space();
    const Eigen::VectorXd weights =
        metric_weights(problem).segment(space.first_row(), space.local_rows());
    TriangleMesh scaled_mesh = mesh;
    for (int v = 0; v < scaled_mesh.vertex_count(); ++v) {
      scaled_mesh.mutable_point(v).array() *= weights.array();
    }
    return validate(scaled_mesh, *twin, scale_domain(domain, weights), options);
  }
  check_mesh_of_problem(mesh, problem, "validate");
  TESSERA_CHECK(domain.is_unbounded() || domain.ambient_dimension() == mesh.ambient_dimension(),
                "the domain (" << domain.describe() << ") is in R^" << domain.ambient_dimension()
                               << " but the mesh is in R^" << mesh.ambient_dimension());
  if (problem.space()->is_distributed()) {
    // SPMD: each rank holds its rows of the points, the domain and the problem's vectors.
    TESSERA_CHECK(domain.is_unbounded() || domain.is_distributed(),
                  "validate: problem '" << problem.name()
                                        << "' is distributed; so must the domain be "
                                           "(Domain::distributed)");
    const GeometricInput geometry{problem, domain};
    return validate_mesh(mesh, options, &geometry);
  }
  const Eigen::VectorXd weights = metric_weights(problem);
  if (weights.size() > 0) {
    // Judged in the metric's coordinates y = W x, as the covering methods built the mesh: the
    // overlap and same-point tests compare lengths.
    const ScaledProblem scaled(problem, weights);
    const Domain scaled_domain = scale_domain(domain, weights);
    const TriangleMesh scaled_mesh(weights.asDiagonal() * mesh.points(), mesh.triangles());
    const GeometricInput geometry{scaled, scaled_domain};
    return validate_mesh(scaled_mesh, options, &geometry);
  }
  const GeometricInput geometry{problem, domain};
  return validate_mesh(mesh, options, &geometry);
}

}  // namespace tessera
