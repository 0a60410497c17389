// SPDX-License-Identifier: MIT
#include "tessera/methods/covering.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <new>
#include <optional>
#include <sstream>
#include <utility>

#include "tessera/core/counted_problem.h"
#include "tessera/core/describe.h"
#include "tessera/core/domain.h"
#include "tessera/core/error.h"
#include "tessera/core/factorisation_cache.h"
#include "tessera/core/linearization.h"
#include "tessera/core/process_memory.h"
#include "tessera/core/scaled_problem.h"
#include "tessera/geometry/bezier_patch.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/geometry/pinched_vertices.h"
#include "tessera/methods/common/clip_to_domain.h"
#include "tessera/methods/common/local_repair.h"
#include "tessera/methods/common/boundary_notches.h"
#include "tessera/methods/common/refine_to_tolerance.h"
#include "tessera/methods/improvement/edge_swap.h"
#include "tessera/methods/start_point.h"

namespace tessera {

void CoveringOptions::validate_common(const char* owner) const {
  TESSERA_CHECK(std::isfinite(tolerance) && tolerance >= 0,
                owner << "::tolerance = " << tolerance << " must be a finite number >= 0");
  TESSERA_CHECK(std::isfinite(step) && step > 0,
                owner << "::step = " << step << " must be a finite number > 0");
  TESSERA_CHECK(max_vertices >= 3,
                owner << "::max_vertices = " << max_vertices << " must be at least 3");
  TESSERA_CHECK(
      std::isfinite(max_start_distance) && max_start_distance >= 0,
      owner << "::max_start_distance = " << max_start_distance << " must be a finite number >= 0");
}

namespace {

void fail(CoveringSummary& summary, CoveringTermination termination, const std::string& message) {
  if (summary.is_complete()) {
    summary.termination = termination;
    summary.message = message;
  } else {
    summary.notes.push_back(message);
  }
}

// Step 5: the mesh clipped to S, snapping and collapsing at the build's boundary edge length.
// \return false if a stop request ended it (the mesh is valid and inside S, its boundary
// ragged where the clipping did not get to).
bool clip(const CoveringContext& context, const CoveringOptions& options, CoveringResult& result,
          std::string& refusal) {
  ClipOptions clip;
  clip.snap_distance = context.boundary_snap_fraction * context.boundary_edge_length;
  clip.min_boundary_edge = 0.2 * context.boundary_edge_length;
  clip.corrector = options.corrector;
  // After a stop in the build, no projection at all (and the request is not polled again).
  clip.stop_requested = result.summary.termination == CoveringTermination::Interrupted
                            ? StopRequest([] { return true; })
                            : options.stop_requested;
  const ClipSummary clipped = clip_to_domain(context.problem, context.domain, result.mesh, clip);
  result.summary.clipped_half_spaces = clipped.half_spaces_crossed;
  refusal = clipped.message;
  if (clipped.interrupted) {
    fail(result.summary, CoveringTermination::Interrupted,
         "interrupted while clipping to the domain: the triangles outside the faces not yet "
         "clipped were removed, so the boundary there is ragged, not on M ∩ ∂S");
    return false;
  }
  return true;
}

// Post-condition of a completed run, checked rather than assumed: on a closed surface the mesh
// has no boundary; in a bounded domain every boundary edge lies on ∂S, i.e. both its ends lie
// on one face or on two adjacent ones (a corner the clipping cut). Both ends on ∂S is not
// enough: where M ∩ S is a band narrower than the mesh's edges, an edge can run across the band
// from one face to the opposite one, and a missing row of triangles there cuts the mesh in two
// with every boundary vertex on ∂S (seen on bvp:points=1000). Anything else is a hole in the
// covering, reported with its place.
//
// A split mesh (each rank its rows of every vertex, the domain cut to them) measures in two
// reductions: the endpoints' distances to the faces, then the angles between the faces that
// the endpoints lie on; the verdict is taken on those sums, the same on every rank.
void check_coverage(const Domain& domain, double step, CoveringResult& result) {
  if (!result.summary.is_complete() || result.mesh.triangle_count() == 0) {
    return;
  }
  const TriangleMesh& mesh = result.mesh;
  const AmbientSpace& space = mesh.space();
  const MeshTopology topology(mesh);
  const double tolerance = 1e-6 * (1.0 + step);
  const int faces = domain.is_unbounded() ? 0 : static_cast<int>(domain.half_spaces().size());
  const std::vector<int>& boundary = topology.boundary_edges();
  // 1. Every boundary vertex's distance to every face (entry (k, 2i + j): endpoint j of the
  //    boundary edge i).
  std::vector<int> endpoints;
  endpoints.reserve(2 * boundary.size());
  for (int e : boundary) {
    endpoints.push_back(topology.edge(e)[0]);
    endpoints.push_back(topology.edge(e)[1]);
  }
  const Eigen::MatrixXd distance =
      faces > 0 ? domain.signed_distances(mesh.points(), endpoints) : Eigen::MatrixXd();
  const auto is_on = [&](int k, std::size_t i, int j) {
    return std::abs(distance(k, static_cast<Eigen::Index>(2 * i + j))) <= tolerance;
  };
  // 2. For each pair of faces (k, l) that some edge's ends lie on, b_k·b_l and ‖b_k‖², ‖b_l‖².
  std::map<std::pair<int, int>, int> pair_index;
  for (std::size_t i = 0; i < boundary.size(); ++i) {
    for (int k = 0; k < faces; ++k) {
      for (int l = 0; l < faces && is_on(k, i, 0); ++l) {
        if (is_on(l, i, 1)) {
          pair_index.emplace(std::make_pair(k, l), 0);
          pair_index.emplace(std::make_pair(k, k), 0);
          pair_index.emplace(std::make_pair(l, l), 0);
        }
      }
    }
  }
  std::vector<double> products;
  for (auto& [pair, index] : pair_index) {
    index = static_cast<int>(products.size());
    const Eigen::VectorXd& nk = domain.half_spaces()[pair.first].normal;
    const Eigen::VectorXd& nl = domain.half_spaces()[pair.second].normal;
    // ‖b‖² as squaredNorm: its root is b.norm() to the bit, in one process.
    products.push_back(pair.first == pair.second ? nk.squaredNorm() : nk.dot(nl));
  }
  if (!products.empty()) {
    space.sum(products.data(), static_cast<int>(products.size()));
  }
  const auto product = [&](int k, int l) { return products[pair_index.at({k, l})]; };
  for (std::size_t i = 0; i < boundary.size(); ++i) {
    // Never on two opposite faces (normals more than 120° apart).
    bool on_boundary = false;
    for (int k = 0; k < faces && !on_boundary; ++k) {
      if (!is_on(k, i, 0)) {
        continue;
      }
      for (int l = 0; l < faces && !on_boundary; ++l) {
        on_boundary = is_on(l, i, 1) && product(k, l) > -0.5 * std::sqrt(product(k, k)) *
                                                           std::sqrt(product(l, l));
      }
    }
    if (!on_boundary) {
      const int v = topology.edge(boundary[i])[0];
      const int w = topology.edge(boundary[i])[1];
      fail(result.summary, CoveringTermination::TriangulationFailed,
           "the mesh has a hole: its boundary edge from " + describe_point(mesh.point(v), space) +
               " to " + describe_point(mesh.point(w), space) +
               (domain.is_unbounded() ? " lies on M, which is closed"
                                      : " does not lie on one face of the domain"));
      return;
    }
  }
}

// A triangle with every corner inside S can still cover a part of M outside S: where S cuts a
// hole into M smaller than the triangle (a cap of the sphere cut off by a face of a box, at a
// step larger than the cap), clipping sees no edge across the face and the mesh covers the hole
// over (the front on the sphere in [-0.97, 0.97]³ at h = 0.49: χ −2 for −4, "completed"). The
// centroid of such a triangle projects onto M beyond the face. Looked for where it can happen:
// a triangle with all corners strictly inside S and one within `snap_distance` of a face and a
// quarter of its longest edge (clipping snaps vertices that near onto the face unless that
// would fold a triangle, as it would around such a hole). Each centroid is projected by the
// chord from a factorisation at its corner nearest the face. On sparse problems, where M meets
// a face at a shallow angle, many triangles qualify (bvp:points=60 near ε = 0.3: 3566 of them,
// 0.21 factorisations per vertex), which costs nothing at n = 3 and too much at a PDE's n.
// There the check needs a tolerance and looks only within twice of it from the face: a
// triangle whose corners are all farther than d from the face, and under which M crosses the
// face, is at least d from M there, which refinement to the tolerance does not leave. Without
// a tolerance, the Euler characteristic, where known, catches a hole covered over.
//
// A split mesh measures the vertices' distances to the faces, their norms and the triangles'
// edges first, in two reductions, and decides on those sums; only the centroids that qualify
// are projected (collective calls, the same on every rank).
void check_holes_covered_over(const ImplicitProblem& problem, const Domain& domain,
                              double snap_distance, double tolerance,
                              const CorrectorOptions& corrector, CoveringResult& result) {
  if (!result.summary.is_complete() || domain.is_unbounded()) {
    return;
  }
  if (problem.has_sparse_jacobian()) {
    if (tolerance <= 0) {
      return;
    }
    snap_distance = std::min(snap_distance, 2.0 * tolerance);
  }
  const TriangleMesh& mesh = result.mesh;
  const AmbientSpace& space = mesh.space();
  const int faces = static_cast<int>(domain.half_spaces().size());
  const int vertex_count = mesh.vertex_count();
  const int triangle_count = mesh.triangle_count();
  // Every vertex's distance to every face; then every vertex's ‖x‖² and every triangle's
  // squared edges (their roots are Eigen's norms to the bit, in one process).
  std::vector<int> vertices(static_cast<std::size_t>(vertex_count));
  for (int v = 0; v < vertex_count; ++v) {
    vertices[static_cast<std::size_t>(v)] = v;
  }
  const Eigen::MatrixXd distance = domain.signed_distances(mesh.points(), vertices);
  std::vector<double> squared(static_cast<std::size_t>(vertex_count + 3 * triangle_count));
  for (int v = 0; v < vertex_count; ++v) {
    squared[static_cast<std::size_t>(v)] = mesh.point(v).squaredNorm();
  }
  for (int t = 0; t < triangle_count; ++t) {
    const Triangle& tri = mesh.triangle(t);
    for (int r = 0; r < 3; ++r) {
      squared[static_cast<std::size_t>(vertex_count + 3 * t + r)] =
          (mesh.point(tri[r]) - mesh.point(tri[(r + 1) % 3])).squaredNorm();
    }
  }
  if (!squared.empty()) {
    space.sum(squared.data(), static_cast<int>(squared.size()));
  }
  FactorisationCache factorisations(8, std::size_t{64} << 20);
  for (int index = 0; index < triangle_count; ++index) {
    const Triangle& t = mesh.triangle(index);
    double longest = 0.0;
    for (int r = 0; r < 3; ++r) {
      longest = std::max(
          longest, std::sqrt(squared[static_cast<std::size_t>(vertex_count + 3 * index + r)]));
    }
    for (int k = 0; k < faces; ++k) {
      int nearest = -1;
      double smallest = std::numeric_limits<double>::infinity();
      bool inside = true;
      for (int v : t) {
        const double d = distance(k, v);
        inside = inside && d > 1e-9 * (1.0 + std::sqrt(squared[static_cast<std::size_t>(v)]));
        if (d < smallest) {
          smallest = d;
          nearest = v;
        }
      }
      if (!inside || smallest >= std::min(0.25 * longest, snap_distance)) {
        continue;
      }
      const Linearization* frozen = factorisations.find(nearest);
      if (frozen == nullptr) {
        frozen = factorisations.factor(nearest, problem, mesh.point(nearest));
      }
      if (frozen == nullptr || !frozen->is_factored()) {
        continue;
      }
      Eigen::VectorXd x = (mesh.point(t[0]) + mesh.point(t[1]) + mesh.point(t[2])) / 3.0;
      CorrectorOptions options = corrector;
      options.max_displacement = longest;
      if (!project_chord(problem, *frozen, x, options).is_success()) {
        continue;
      }
      const double beyond = -domain.signed_distance(k, x);
      if (beyond > 1e-3 * longest) {
        std::ostringstream message;
        message << "the mesh covers a part of M outside the domain: the triangle with corners "
                << describe_point(mesh.point(t[0]), space) << ", "
                << describe_point(mesh.point(t[1]), space) << ", "
                << describe_point(mesh.point(t[2]), space) << " lies inside the face '"
                << domain.half_spaces()[k].label << "', but M under it reaches "
                << describe_point(x, space) << ", " << beyond
                << " beyond it (M ∩ S has a hole there smaller than the triangle; try a "
                   "smaller step)";
        fail(result.summary, CoveringTermination::TriangulationFailed, message.str());
        return;
      }
    }
  }
}

// The cubic patches of a method that has them, rebuilt for the final triangles: refinement and
// repair change triangles, and a patch depends only on its triangle's vertices and tangent
// planes (Hohmann eq. 3.5), so patches of neighbours still share their edge curves.
void rebuild_patches(const ImplicitProblem& problem, CoveringResult& result) {
  if (problem.space()->is_distributed()) {
    // A patch's control points are n-vectors and its interpolation reduces them with Eigen
    // directly: on a split mesh each rank would build a patch of its own rows alone. The
    // patches belong to the bezier method, which does not run split; the mesh stands without.
    result.patches.clear();
    result.summary.notes.push_back(
        "no cubic patches: the problem is distributed, and patches are built in one process only");
    return;
  }
  const TriangleMesh& mesh = result.mesh;
  std::vector<Eigen::MatrixXd> tangents(mesh.vertex_count());
  Linearization linearization;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    if (!linearization.factor(problem, mesh.point(v))) {
      // No tangent plane at a vertex (DF rank deficient): no patch can be built there.
      result.patches.clear();
      result.summary.notes.push_back("no cubic patches: DF is rank deficient at the vertex " +
                                     describe_point(mesh.point(v)));
      return;
    }
    tangents[v] = linearization.tangent_basis();
  }
  result.patches.clear();
  result.patches.reserve(mesh.triangle_count());
  for (const Triangle& triangle : mesh.triangles()) {
    Eigen::MatrixXd corners(mesh.ambient_dimension(), 3);
    std::array<Eigen::MatrixXd, 3> bases;
    for (int i = 0; i < 3; ++i) {
      corners.col(i) = mesh.point(triangle[i]);
      bases[i] = tangents[triangle[i]];
    }
    result.patches.push_back(CubicBezierPatch::interpolate_triangle_on_manifold(
        corners, bases, result.patch_edge_length_factor));
  }
}

std::string describe_triangle(const TriangleMesh& mesh, int t) {
  const Triangle& triangle = mesh.triangle(t);
  const Eigen::VectorXd centroid =
      (mesh.point(triangle[0]) + mesh.point(triangle[1]) + mesh.point(triangle[2])) / 3.0;
  return "near " + describe_point(centroid, mesh.space());
}

// Step 7: geometric validation. Flipped and overlapping triangles are first repaired locally
// (removed with the fans around them, the hole triangulated again in M's tangent plane) and
// the mesh validated again; what cannot be repaired so, and triangles with a vertex outside S,
// are removed (with the fans that removal pinches) and the run fails with their places: the
// rest is a valid partial mesh. A defect is never returned as a success.
// \return the number of new triangles (the last ones of the mesh) made by a repair.
int validate_and_repair(const ImplicitProblem& problem, const Domain& domain,
                        CoveringResult& result) {
  TriangleMesh& mesh = result.mesh;
  result.validation.reset();
  if (mesh.triangle_count() == 0) {
    return 0;
  }
  const MeshValidation validation = validate(mesh, problem, domain);
  if (validation.is_valid()) {
    result.validation = validation;
    return 0;
  }
  if (validation.vertices_outside_domain.empty() &&
      (!validation.flipped_triangles.empty() || !validation.overlapping_triangle_pairs.empty()) &&
      validation.defects.size() ==
          static_cast<std::size_t>((validation.flipped_triangle_count > 0) +
                                   (validation.overlapping_pair_count > 0))) {
    std::vector<int> defective = validation.flipped_triangles;
    for (const auto& [s, t] : validation.overlapping_triangle_pairs) {
      defective.push_back(s);
      defective.push_back(t);
    }
    for (int rings : {1, 2}) {
      TriangleMesh repaired = mesh;
      const LocalRepair repair = repair_locally(problem, repaired, defective, rings);
      MeshValidation check;
      if (repair.is_repaired && (check = validate(repaired, problem, domain)).is_valid()) {
        mesh = std::move(repaired);
        result.validation = std::move(check);
        result.summary.removed_triangles += repair.removed_triangles;
        result.summary.repaired_holes += repair.filled_holes;
        result.summary.notes.push_back(
            "the final check found " + std::to_string(validation.flipped_triangle_count) +
            " flipped triangle(s) and " + std::to_string(validation.overlapping_pair_count) +
            " overlapping pair(s), e.g. " +
            (validation.defects.front().examples.empty()
                 ? std::string("(no example)")
                 : validation.defects.front().examples.front()) +
            "; they were removed with their neighbours and " + std::to_string(repair.filled_holes) +
            " hole(s) were triangulated again");
        return repair.added_triangles;
      }
    }
  }
  if (validation.flipped_triangles.empty() && validation.overlapping_triangle_pairs.empty() &&
      validation.vertices_outside_domain.empty()) {
    // A combinatorial defect: a method's bug, not repairable here. Report it, never hide it.
    const MeshDefect& defect = validation.defects.front();
    fail(result.summary, CoveringTermination::TriangulationFailed,
         "the final check found the mesh not valid: " + std::to_string(defect.count) + " " +
             std::string(to_string(defect.kind)) +
             (defect.examples.empty() ? "" : ", e.g. " + defect.examples.front()));
    return 0;
  }
  std::vector<bool> keep(mesh.triangle_count(), true);
  std::vector<std::string> places;
  auto drop = [&](int t, const char* why) {
    if (keep[t]) {
      keep[t] = false;
      if (places.size() < 3) {
        places.push_back(std::string(why) + " triangle " + describe_triangle(mesh, t));
      }
    }
  };
  for (int t : validation.flipped_triangles) {
    drop(t, "a flipped");
  }
  for (const auto& [s, t] : validation.overlapping_triangle_pairs) {
    drop(s, "an overlapping");
    drop(t, "an overlapping");
  }
  if (!validation.vertices_outside_domain.empty()) {
    std::vector<bool> outside(mesh.vertex_count(), false);
    for (int v : validation.vertices_outside_domain) {
      outside[v] = true;
    }
    for (int t = 0; t < mesh.triangle_count(); ++t) {
      for (int v : mesh.triangle(t)) {
        if (outside[v]) {
          drop(t, "a");
          break;
        }
      }
    }
  }
  const int before = mesh.triangle_count();
  // Dropping triangles can pinch a vertex (two fans left meeting there): the fans are judged
  // on what is kept, and the largest kept.
  std::vector<int> kept_index;
  std::vector<Triangle> kept_triangles;
  for (int t = 0; t < before; ++t) {
    if (keep[t]) {
      kept_index.push_back(t);
      kept_triangles.push_back(mesh.triangle(t));
    }
  }
  const std::vector<bool> kept_fans = keep_largest_fans(mesh.vertex_count(), kept_triangles);
  for (std::size_t k = 0; k < kept_index.size(); ++k) {
    keep[kept_index[k]] = kept_fans[k];
  }
  // Patches still match the triangles only if nothing reshaped the mesh since the build;
  // otherwise they are rebuilt at the end anyway.
  if (static_cast<int>(result.patches.size()) == before) {
    std::vector<CubicBezierPatch> patches;
    for (int t = 0; t < before; ++t) {
      if (keep[t]) {
        patches.push_back(result.patches[t]);
      }
    }
    result.patches = std::move(patches);
  }
  mesh.keep_triangles(keep);
  // A drop can pinch a vertex again; keep_largest_fans repeats until none is left, so one
  // more pass over the kept triangles only confirms.
  const int removed = before - mesh.triangle_count();
  result.summary.removed_triangles += removed;
  std::ostringstream message;
  message << "the final check found " << validation.flipped_triangle_count
          << " flipped triangle(s), " << validation.overlapping_pair_count
          << " overlapping pair(s) and " << validation.vertex_outside_domain_count
          << " vertex(es) outside the domain; " << removed
          << " triangle(s) were removed, leaving holes: ";
  for (std::size_t i = 0; i < places.size(); ++i) {
    message << (i ? "; " : "") << places[i];
  }
  fail(result.summary, CoveringTermination::TriangulationFailed, message.str());
  return 0;
}

// The result's points back in the problem's own coordinates x = W⁻¹ y.
void unscale(const Eigen::VectorXd& weights, CoveringResult& result) {
  TriangleMesh& mesh = result.mesh;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    mesh.mutable_point(v).array() /= weights.array();
  }
  for (CubicBezierPatch& patch : result.patches) {
    patch = CubicBezierPatch(weights.cwiseInverse().asDiagonal() * patch.control_points());
  }
}

}  // namespace

CoveringResult run_covering(const std::string& method, const ImplicitProblem& user_problem,
                            const Eigen::VectorXd& user_start, const Domain& user_domain,
                            const CoveringOptions& options, const CoveringBuild& build) {
  // 1. Input. A distributed problem (SPMD, docs/cluster.md) runs on this rank's rows: the start
  //    and the mesh hold them, the domain is cut to them, and every rank runs this skeleton
  //    alike.
  options.validate_common(method.c_str());
  const int n = user_problem.ambient_dimension();
  const std::shared_ptr<const AmbientSpace> space = user_problem.space();
  const bool is_distributed = space->is_distributed();
  const int rows = space->local_rows();
  if (is_distributed) {
    TESSERA_CHECK(user_domain.is_unbounded() ||
                      (user_domain.is_distributed() ? user_domain.ambient_dimension() == rows
                                                    : user_domain.ambient_dimension() == n),
                  "domain has " << user_domain.ambient_dimension() << " rows, but the problem '"
                                << user_problem.name() << "' is distributed: give its domain in R^"
                                << n << " or this rank's " << rows << " rows of it "
                                << "(Domain::distributed)");
    TESSERA_CHECK(user_start.size() == rows,
                  "start point has " << user_start.size() << " rows here, but the problem '"
                                     << user_problem.name() << "' is distributed and holds "
                                     << rows << " of its n = " << n << " on this rank");
    // Its metric is its own business (petsc::ScaledPetscProblem presents the metric's
    // coordinates): ScaledProblem cannot scale rows it does not hold.
    TESSERA_CHECK(metric_weights(user_problem).size() == 0,
                  "the distributed problem '" << user_problem.name()
                      << "' has a metric; work in the metric's coordinates "
                         "(petsc::ScaledPetscProblem) and give the start and the domain in them");
  } else {
    TESSERA_CHECK(user_domain.is_unbounded() || user_domain.ambient_dimension() == n,
                  "domain is in R^" << user_domain.ambient_dimension()
                                    << " but the problem is in R^" << n);
    TESSERA_CHECK(user_start.size() == n,
                  "start point has " << user_start.size() << " coordinates, the problem n = " << n);
  }
  const auto clock_start = std::chrono::steady_clock::now();
  // 2. The problem's metric (CoordinateBlock): the methods cover M̃ = W M in y = W x, so that
  //    steps, radii, the tolerance and every distance are lengths in the metric, and counting.
  //    (A distributed problem has none, checked above.)
  const Eigen::VectorXd weights = is_distributed ? Eigen::VectorXd() : metric_weights(user_problem);
  const bool is_weighted = weights.size() > 0;
  std::optional<ScaledProblem> scaled;
  if (is_weighted) {
    scaled.emplace(user_problem, weights);
  }
  // A distributed problem's domain given in R^n is cut to this rank's rows.
  const bool cuts_domain =
      is_distributed && !user_domain.is_unbounded() && !user_domain.is_distributed();
  const Domain converted_domain = is_weighted  ? scale_domain(user_domain, weights)
                               : cuts_domain ? user_domain.distributed(space)
                                             : Domain();
  const Domain& domain = is_weighted || cuts_domain ? converted_domain : user_domain;
  const Eigen::VectorXd start = is_weighted ? weights.cwiseProduct(user_start) : user_start;
  const CountedProblem problem(is_weighted ? static_cast<const ImplicitProblem&>(*scaled)
                                           : user_problem);
  // The result's mesh: this rank's rows of its points for a distributed problem.
  const auto empty_mesh = [&] {
    TriangleMesh mesh(rows);
    if (is_distributed) {
      mesh.set_space(space);
    }
    return mesh;
  };
  // Blocks of one and a half states or more (tangent bases, factors) come from the system and
  // go back when freed; single states, the most frequent, are reused from the heap.
  if (n >= kReleaseHeapDimension) {
    map_large_blocks(sizeof(double) * static_cast<std::size_t>(rows) * 3 / 2);
  }
  CoveringResult result;
  result.mesh = empty_mesh();
  CoveringSummary& summary = result.summary;
  // Each step's work is the counters' growth since the last step ended.
  std::vector<PhaseWork> phases;
  WorkCounts counted_so_far;
  auto phase_start = clock_start;
  auto end_phase = [&](const char* name) {
    const auto now = std::chrono::steady_clock::now();
    const WorkCounts counts = problem.counts();
    if (counts.function_evaluations > counted_so_far.function_evaluations ||
        counts.jacobian_evaluations > counted_so_far.jacobian_evaluations) {
      phases.push_back({name, counts - counted_so_far,
                        std::chrono::duration<double>(now - phase_start).count()});
    }
    counted_so_far = counts;
    phase_start = now;
    // What the stage freed (factorisations, bases, the atlas's charts) goes back to the system;
    // then all that is resident counts, nothing of the atlas's boundary being held.
    if (n >= kReleaseHeapDimension) {
      release_free_heap();
    }
    const double resident = static_cast<double>(resident_bytes());
    summary.resident_peak_bytes = std::max(summary.resident_peak_bytes, resident);
    summary.resident_beyond_boundary_peak_bytes =
        std::max(summary.resident_beyond_boundary_peak_bytes, resident);
  };
  auto finish = [&] {
    end_phase("finish");
    if (is_weighted) {
      unscale(weights, result);
    }
    summary.method = method;
    summary.tolerance = options.tolerance;
    summary.vertex_count = result.mesh.vertex_count();
    summary.triangle_count = result.mesh.triangle_count();
    summary.function_evaluations = problem.function_evaluations();
    summary.jacobian_evaluations = problem.jacobian_evaluations();
    summary.factorisations = problem.factorisations();
    summary.factorisation_seconds = problem.factorisation_seconds();
    summary.work_by_phase = phases;
    summary.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  };
  // 3. The start on M inside S: a failure there is an outcome (StartFailed), not an exception,
  //    so that callers always get a summary.
  std::optional<StartPoint> start_point;
  try {
    const double max_start_distance =
        options.max_start_distance > 0 ? options.max_start_distance : 10.0 * options.step;
    start_point = project_start_point(problem, start, domain, max_start_distance);
  } catch (const ComputationFailed& failure) {
    summary.termination = CoveringTermination::StartFailed;
    summary.message = failure.what();
    finish();
    return result;
  }
  end_phase("start");
  // 4. The method's build, and 5. clipping to S.
  CoveringContext context{problem, domain, *start_point};
  try {
    summary.method = method;
    build(context, result);
    end_phase("build");
    if (!domain.is_unbounded() && context.boundary_edge_length > 0 &&
        result.mesh.triangle_count() > 0) {
      std::string refusal;
      const bool clipped = clip(context, options, result, refusal);
      if (clipped && !refusal.empty() && context.retry_if_clipping_fails) {
        context.attempt = 1;
        result = CoveringResult();
        result.mesh = empty_mesh();
        summary.method = method;
        build(context, result);
        clip(context, options, result, refusal);
        summary.notes.push_back(
            "the first mesh left a configuration at the domain boundary "
            "that the clipping refused; built again without snapping");
      }
      if (!refusal.empty()) {
        fail(summary, CoveringTermination::ProjectionFailed, refusal);
      } else if (summary.termination != CoveringTermination::Interrupted) {
        // Up to 5 boundary edge lengths: at coarse steps on bratu2d (0.8 for N = 20, 316) the
        // notch next to the face λ = 0.5 needs an edge of 4.6 (refinement then splits it).
        const NotchClosing notches = close_boundary_notches(problem, domain, result.mesh,
                                                            5.0 * context.boundary_edge_length);
        if (notches.added_triangles > 0) {
          summary.notes.push_back(
              "closed " + std::to_string(notches.added_triangles) +
              " notch(es) in the boundary with a triangle each: the build left M ∩ S uncovered "
              "next to a boundary vertex inside S");
        }
      }
      if (context.swap_after_clipping && result.mesh.triangle_count() > 0 &&
          summary.termination != CoveringTermination::Interrupted) {
        // Clipping leaves poor angles at ∂S that swaps in the tangent planes repair. A stop
        // request ends them (the mesh is valid after every swap): they are an improvement.
        ImprovementOptions swaps;
        swaps.stop_requested = options.stop_requested;
        if (improve_by_edge_swaps(result.mesh, problem, swaps).interrupted) {
          fail(summary, CoveringTermination::Interrupted,
               "interrupted while improving the angles at the domain boundary");
        }
      }
    }
    end_phase("clip");
  } catch (const std::bad_alloc&) {
    // Whatever the build held is gone; the summary still says what happened.
    result.mesh = empty_mesh();
    result.patches.clear();
    fail(summary, CoveringTermination::ProjectionFailed,
         "out of memory (n = " + std::to_string(n) +
             "): the problem's Jacobian factorisation or the mesh did not fit; try a coarser "
             "tolerance or step, or fewer unknowns");
  }
  // 6. The distance bound, checked on every triangle and enforced by bisection on M. Not after
  //    a stop request: the user wants the partial mesh now, and at large n the bisection costs
  //    factorisations (minutes at n = 10⁵); validity is still checked below.
  const int triangles_built = result.mesh.triangle_count();
  bool is_interrupted = summary.termination == CoveringTermination::Interrupted;
  if (is_interrupted && options.tolerance > 0 && result.mesh.triangle_count() > 0) {
    summary.notes.push_back("interrupted: the tolerance " + std::to_string(options.tolerance) +
                            " was not enforced on the partial mesh (no triangle was checked)");
  }
  if (options.tolerance > 0 && result.mesh.triangle_count() > 0 && !is_interrupted) {
    ToleranceRefinementOptions refine;
    refine.tolerance = options.tolerance;
    refine.corrector = options.corrector;
    refine.stop_requested = options.stop_requested;
    const ToleranceRefinement refined =
        refine_to_tolerance(problem, domain, result.mesh, {}, refine);
    summary.refined_edges += refined.split_edges;
    summary.max_sampled_distance = refined.max_distance;
    if (refined.interrupted) {
      // A stop during the check (minutes at n = 10⁵): the mesh is as valid as before it. The
      // largest distance of the triangles checked is no bound for the mesh: reported unknown
      // (−1), as for a stop before the check.
      summary.max_sampled_distance = -1.0;
      fail(summary, CoveringTermination::Interrupted,
           "interrupted during the tolerance check, after " + std::to_string(refined.rounds) +
               " round(s) of bisection");
      summary.notes.push_back("interrupted: the tolerance " + std::to_string(options.tolerance) +
                              " was enforced on part of the mesh only");
      is_interrupted = true;
    } else if (refined.remaining > 0) {
      std::ostringstream message;
      message << refined.remaining << " triangle(s) are still farther than the tolerance "
              << options.tolerance << " from M after " << refined.rounds
              << " rounds of bisection; the farthest sample, " << refined.max_distance
              << " from M, is at " << describe_point(refined.worst_point, *space);
      fail(summary, CoveringTermination::ProjectionFailed, message.str());
    }
    end_phase("refine");
  }
  // 7. Geometric validity, no holes, then the patches for the final triangles. Triangles made
  //    by a repair are held to the tolerance too, and what refinement makes is validated.
  const int repaired = validate_and_repair(problem, domain, result);
  end_phase("validate");
  if (repaired > 0 && options.tolerance > 0 && !is_interrupted) {
    std::vector<int> added;
    for (int t = result.mesh.triangle_count() - repaired; t < result.mesh.triangle_count(); ++t) {
      added.push_back(t);
    }
    ToleranceRefinementOptions refine;
    refine.tolerance = options.tolerance;
    refine.corrector = options.corrector;
    const ToleranceRefinement refined =
        refine_to_tolerance(problem, domain, result.mesh, added, refine);
    summary.refined_edges += refined.split_edges;
    summary.max_sampled_distance = std::max(summary.max_sampled_distance, refined.max_distance);
    if (refined.split_edges > 0) {
      validate_and_repair(problem, domain, result);
    }
  }
  check_coverage(domain, options.step, result);
  check_holes_covered_over(problem, domain,
                           context.boundary_snap_fraction * context.boundary_edge_length,
                           options.tolerance, options.corrector, result);
  if (!result.patches.empty() &&
      (result.mesh.triangle_count() != triangles_built || summary.refined_edges > 0 ||
       summary.removed_triangles > 0 ||
       static_cast<int>(result.patches.size()) != result.mesh.triangle_count())) {
    rebuild_patches(problem, result);
  }
  end_phase("patches");
  // 8. The summary.
  finish();
  return result;
}

}  // namespace tessera
