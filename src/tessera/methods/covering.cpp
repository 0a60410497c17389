// SPDX-License-Identifier: MIT
#include "tessera/methods/covering.h"

#include <chrono>
#include <cmath>
#include <memory>
#include <new>
#include <optional>
#include <sstream>
#include <utility>

#include "tessera/core/counted_problem.h"
#include "tessera/core/describe.h"
#include "tessera/core/domain.h"
#include "tessera/core/error.h"
#include "tessera/core/linearization.h"
#include "tessera/core/process_memory.h"
#include "tessera/core/scaled_problem.h"
#include "tessera/geometry/bezier_patch.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/geometry/pinched_vertices.h"
#include "tessera/methods/common/boundary_notches.h"
#include "tessera/methods/common/clip_to_domain.h"
#include "tessera/methods/common/local_repair.h"
#include "tessera/methods/common/refine_to_tolerance.h"
#include "tessera/methods/covering_checks.h"
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
    result.summary.record_failure(
        CoveringTermination::Interrupted,
        "interrupted while clipping to the domain: the triangles outside the faces not yet "
        "clipped were removed, so the boundary there is ragged, not on M ∩ ∂S");
    return false;
  }
  return true;
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
    result.summary.record_failure(
        CoveringTermination::TriangulationFailed,
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
  result.summary.record_failure(CoveringTermination::TriangulationFailed, message.str());
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
                                     << user_problem.name() << "' is distributed and holds " << rows
                                     << " of its n = " << n << " on this rank");
    // Its metric is its own business (petsc::ScaledPetscProblem presents the metric's
    // coordinates): ScaledProblem cannot scale rows it does not hold.
    TESSERA_CHECK(metric_weights(user_problem).size() == 0,
                  "the distributed problem '"
                      << user_problem.name()
                      << "' has a metric; work in the metric's coordinates "
                         "(petsc::ScaledPetscProblem) and give the start and the domain in them");
  } else {
    TESSERA_CHECK(
        user_domain.is_unbounded() || user_domain.ambient_dimension() == n,
        "domain is in R^" << user_domain.ambient_dimension() << " but the problem is in R^" << n);
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
  const Domain converted_domain = is_weighted   ? scale_domain(user_domain, weights)
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
    summary.note_resident_memory(0.0);
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
        summary.record_failure(CoveringTermination::ProjectionFailed, refusal);
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
          summary.record_failure(CoveringTermination::Interrupted,
                                 "interrupted while improving the angles at the domain boundary");
        }
      }
    }
    end_phase("clip");
  } catch (const std::bad_alloc&) {
    // Whatever the build held is gone; the summary still says what happened.
    result.mesh = empty_mesh();
    result.patches.clear();
    summary.record_failure(
        CoveringTermination::ProjectionFailed,
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
      summary.record_failure(CoveringTermination::Interrupted,
                             "interrupted during the tolerance check, after " +
                                 std::to_string(refined.rounds) + " round(s) of bisection");
      summary.notes.push_back("interrupted: the tolerance " + std::to_string(options.tolerance) +
                              " was enforced on part of the mesh only");
      is_interrupted = true;
    } else if (refined.remaining > 0) {
      std::ostringstream message;
      message << refined.remaining << " triangle(s) are still farther than the tolerance "
              << options.tolerance << " from M after " << refined.rounds
              << " rounds of bisection; the farthest sample, " << refined.max_distance
              << " from M, is at " << describe_point(refined.worst_point, *space);
      summary.record_failure(CoveringTermination::ProjectionFailed, message.str());
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
  detail::check_coverage(domain, options.step, result);
  detail::check_holes_covered_over(problem, domain,
                                   context.boundary_snap_fraction * context.boundary_edge_length,
                                   options.tolerance, options.corrector, result);
  if (!result.patches.empty() &&
      (result.patches_need_rebuild || result.mesh.triangle_count() != triangles_built ||
       summary.refined_edges > 0 || summary.removed_triangles > 0 ||
       static_cast<int>(result.patches.size()) != result.mesh.triangle_count())) {
    rebuild_patches(problem, result);
  }
  end_phase("patches");
  // 8. The summary.
  finish();
  return result;
}

}  // namespace tessera
