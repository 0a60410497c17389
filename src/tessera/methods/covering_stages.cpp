// SPDX-License-Identifier: MIT
// The stages of run_covering, each with its contract in covering_stages.h.
#include "tessera/methods/covering_stages.h"

#include <algorithm>
#include <array>
#include <sstream>
#include <utility>
#include <vector>

#include "tessera/core/counted_problem.h"
#include "tessera/core/describe.h"
#include "tessera/core/domain.h"
#include "tessera/core/error.h"
#include "tessera/core/linearization.h"
#include "tessera/geometry/bezier_patch.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/geometry/pinched_vertices.h"
#include "tessera/methods/common/boundary_notches.h"
#include "tessera/methods/common/clip_to_domain.h"
#include "tessera/methods/common/local_repair.h"
#include "tessera/methods/common/refine_to_tolerance.h"
#include "tessera/methods/covering_checks.h"
#include "tessera/methods/improvement/edge_swap.h"

namespace tessera::detail {

namespace {

// The mesh clipped to S once, snapping and collapsing at the build's boundary edge length; after
// a stop request (`after_stop`) with no projection at all, the request not polled again.
// \return false if a stop request ended it (the mesh is valid and inside S, its boundary
// ragged where the clipping did not get to).
bool clip_once(CoveringRun& run, bool after_stop) {
  const CoveringContext& context = *run.context;
  CoveringResult& result = run.result;
  ClipOptions clip;
  clip.snap_distance = context.boundary_snap_fraction * context.boundary_edge_length;
  clip.min_boundary_edge = 0.2 * context.boundary_edge_length;
  clip.corrector = run.options.corrector;
  clip.stop_requested = after_stop ? StopRequest([] { return true; }) : run.options.stop_requested;
  const ClipSummary clipped = clip_to_domain(run.problem, run.domain, result.mesh, clip);
  result.summary.clipped_half_spaces = clipped.half_spaces_crossed;
  run.clip_refusal = clipped.message;
  if (clipped.interrupted) {
    result.summary.record_failure(
        CoveringTermination::Interrupted,
        "interrupted while clipping to the domain: the triangles outside the faces not yet "
        "clipped were removed, so the boundary there is ragged, not on M ∩ ∂S");
    return false;
  }
  return true;
}

// Clips (clip_once in the given form) and, if the clipping refused the mesh and the method asked
// for it, builds again (attempt 1) and clips once more, in the form the new build's termination
// calls for. A refusal left is the run's failure.
bool clip_and_retry(CoveringRun& run, bool after_stop) {
  CoveringContext& context = *run.context;
  CoveringResult& result = run.result;
  if (run.domain.is_unbounded() || !(context.boundary_edge_length > 0) ||
      result.mesh.triangle_count() == 0) {
    return false;
  }
  run.is_clipped = true;
  const bool clipped = clip_once(run, after_stop);
  if (clipped && !run.clip_refusal.empty() && context.retry_if_clipping_fails) {
    context.attempt = 1;
    result = CoveringResult();
    result.mesh = run.empty_mesh;
    result.summary.method = run.method;
    run.build(context, result);
    clip_once(run, run.is_stopped());
    result.summary.notes.push_back(
        "the first mesh left a configuration at the domain boundary "
        "that the clipping refused; built again without snapping");
  }
  if (!run.clip_refusal.empty()) {
    result.summary.record_failure(CoveringTermination::ProjectionFailed, run.clip_refusal);
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

// Keeps the patches of the kept triangles, when the patches still match the triangles one to
// one (nothing reshaped the mesh since the build; otherwise they are rebuilt at the end anyway).
void keep_patches(CoveringResult& result, const std::vector<bool>& keep) {
  if (result.patches.size() != keep.size()) {
    return;
  }
  std::vector<CubicBezierPatch> patches;
  for (std::size_t t = 0; t < keep.size(); ++t) {
    if (keep[t]) {
      patches.push_back(result.patches[t]);
    }
  }
  result.patches = std::move(patches);
}

// Removes the triangles not kept. Dropping triangles can pinch a vertex (two fans left meeting
// there): the fans are judged on what is kept, and the largest kept (keep_largest_fans repeats
// until no vertex is pinched, so the topology stays sound).
// \return the number of triangles removed.
int drop_triangles(CoveringResult& result, std::vector<bool>& keep) {
  TriangleMesh& mesh = result.mesh;
  const int before = mesh.triangle_count();
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
  keep_patches(result, keep);
  mesh.keep_triangles(keep);
  return before - mesh.triangle_count();
}

// Triangles still farther than the tolerance from M after the bisection rounds are not part
// of what the run can vouch for: a triangle that spans two sheets of M across a narrow gap (a
// front edge that jumped the trough's gap, stress seed 2037 case 332) is folded against M and
// covers the other sheet twice, and no check of the mesh alone can tell it from a curved
// piece. They are removed, leaving holes the failure message places. The run has failed
// (ProjectionFailed) either way; what is kept is within the tolerance.
void drop_far_triangles(const ToleranceRefinement& refined, double tolerance,
                        CoveringRun& run) {
  CoveringResult& result = run.result;
  CoveringSummary& summary = result.summary;
  std::ostringstream message;
  message << refined.remaining << " triangle(s) are still farther than the tolerance "
          << tolerance << " from M after " << refined.rounds
          << " rounds of bisection; the farthest sample, " << refined.max_distance
          << " from M, is at " << describe_point(refined.worst_point, *run.problem.space());
  std::vector<bool> keep(result.mesh.triangle_count(), true);
  for (int t : refined.far_triangles) {
    keep[static_cast<std::size_t>(t)] = false;
  }
  const int removed = drop_triangles(result, keep);
  summary.removed_triangles += removed;
  message << "; " << removed << " triangle(s) were removed with them, leaving holes";
  summary.record_failure(CoveringTermination::ProjectionFailed, message.str());
}

// Removes degenerate triangles (area <= options.degenerate_area_ratio·(longest edge)², as
// validate judges them) that lie on the boundary and cover nothing: three vertices of a straight
// piece of ∂(M ∩ S) (whitney_pleat's M ∩ {x = 1.5} is a line; a bezier front closing along it
// left the ear (corner, p, q) with area 3e-18, stress seed 2026 case 1049). Such a triangle is
// removed when that keeps every vertex manifold: an ear (two boundary edges) leaves its tip
// unreferenced; one boundary edge (the long one) makes its apex a boundary vertex, allowed only
// if the apex was interior. Repeats, since one removal can expose the next collinear ear.
// \return the number removed.
int remove_degenerate_boundary_triangles(CoveringResult& result, const ValidationOptions& options) {
  TriangleMesh& mesh = result.mesh;
  int removed = 0;
  for (bool changed = true; changed;) {
    changed = false;
    const MeshTopology topology(mesh.vertex_count(), mesh.triangles());
    std::vector<bool> is_boundary_vertex(mesh.vertex_count(), false);
    for (int e = 0; e < topology.edge_count(); ++e) {
      if (topology.is_boundary_edge(e)) {
        for (int v : topology.edge(e)) {
          is_boundary_vertex[v] = true;
        }
      }
    }
    std::vector<bool> keep(mesh.triangle_count(), true);
    std::vector<bool> touched(mesh.vertex_count(), false);
    for (int t = 0; t < mesh.triangle_count(); ++t) {
      const Triangle& tri = mesh.triangle(t);
      const auto [area, longest_squared] = triangle_area_and_longest_squared(mesh, tri);
      if (!(area <= options.degenerate_area_ratio * longest_squared) ||
          touched[tri[0]] || touched[tri[1]] || touched[tri[2]]) {
        continue;
      }
      int boundary_edges = 0;
      int apex = -1;  // the vertex opposite the one boundary edge
      for (int k = 0; k < 3; ++k) {
        const int e = topology.find_edge(tri[k], tri[(k + 1) % 3]);
        if (e >= 0 && topology.is_boundary_edge(e)) {
          ++boundary_edges;
          apex = tri[(k + 2) % 3];
        }
      }
      if (boundary_edges == 0 || (boundary_edges == 1 && is_boundary_vertex[apex])) {
        continue;
      }
      keep[t] = false;
      touched[tri[0]] = touched[tri[1]] = touched[tri[2]] = true;  // one per fan per pass
      changed = true;
      ++removed;
    }
    if (changed) {
      keep_patches(result, keep);
      mesh.keep_triangles(keep);
    }
  }
  return removed;
}

// A check cut short by a stop request makes the run Interrupted (a note if it had failed
// before), saying what was not judged: the mesh is valid only as far as it was checked.
void note_cut_short(const MeshValidation& validation, CoveringSummary& summary) {
  if (!validation.is_cut_short()) {
    return;
  }
  std::string what;
  for (const std::string& cut : validation.checks_cut_short) {
    what += (what.empty() ? "" : "; ") + cut;
  }
  summary.record_failure(CoveringTermination::Interrupted,
                         "interrupted during the final check, which was cut short: " + what);
}

// The geometric validation of stage::validate_and_repair (its contract in covering_stages.h).
// `is_stopped`: a stop request ended an earlier stage; `stop`: the checks' grace stop.
// \return the number of new triangles (the last ones of the mesh) made by a repair.
int validate_and_repair_mesh(const ImplicitProblem& problem, const Domain& domain,
                             CoveringResult& result, bool is_stopped = false,
                             const StopRequest& stop = {}) {
  TriangleMesh& mesh = result.mesh;
  result.validation.reset();
  if (mesh.triangle_count() == 0) {
    return 0;
  }
  ValidationOptions options;
  options.stop_requested = stop;
  MeshValidation validation = validate(mesh, problem, domain, options);
  if (validation.degenerate_triangle_count > 0) {
    if (const int removed = remove_degenerate_boundary_triangles(result, ValidationOptions());
        removed > 0) {
      result.summary.removed_triangles += removed;
      result.summary.notes.push_back(
          "the final check found " + std::to_string(validation.degenerate_triangle_count) +
          " degenerate triangle(s); " + std::to_string(removed) +
          " of them, on the boundary and of zero area (three vertices on a straight piece of "
          "the boundary), were removed");
      validation = validate(mesh, problem, domain, options);
    }
  }
  note_cut_short(validation, result.summary);
  if (validation.is_valid()) {
    result.validation = validation;
    return 0;
  }
  // After a stop there is no time for a repair (it projects, and validates again in full):
  // the defects found are removed below.
  is_stopped = is_stopped || validation.is_cut_short();
  if (!is_stopped && validation.vertices_outside_domain.empty() &&
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
  // Dropping triangles can expose a defect the dropped ones hid (a fan that overlaps itself once
  // its flipped triangle is gone: stress seed 2034, cstr bezier case 965), so the check and the
  // drop repeat, a few rounds at most, unless a stop left no time for another check.
  constexpr int kDropRounds = 3;
  std::vector<std::string> places;
  int removed = 0;
  const MeshValidation found = validation;
  for (int round = 0; round < kDropRounds; ++round) {
    std::vector<bool> keep(mesh.triangle_count(), true);
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
    removed += drop_triangles(result, keep);
    // The topology is sound after drop_triangles; the geometry is judged again below.
    if (is_stopped || round + 1 == kDropRounds || mesh.triangle_count() == 0) {
      break;
    }
    validation = validate(mesh, problem, domain, options);
    if (validation.is_cut_short() || (validation.flipped_triangles.empty() &&
                                      validation.overlapping_triangle_pairs.empty() &&
                                      validation.vertices_outside_domain.empty())) {
      result.validation = validation;
      break;
    }
  }
  result.summary.removed_triangles += removed;
  std::ostringstream message;
  message << "the final check found " << found.flipped_triangle_count
          << " flipped triangle(s), " << found.overlapping_pair_count
          << " overlapping pair(s) and " << found.vertex_outside_domain_count
          << " vertex(es) outside the domain; " << removed
          << " triangle(s) were removed, leaving holes: ";
  for (std::size_t i = 0; i < places.size(); ++i) {
    message << (i ? "; " : "") << places[i];
  }
  result.summary.record_failure(CoveringTermination::TriangulationFailed, message.str());
  if (is_stopped) {
    // What is left, judged as far as the grace allows, so that the report need not validate
    // it again in full (minutes at large n) and says what was not judged.
    result.validation = validate(mesh, problem, domain, options);
  }
  return 0;
}

}  // namespace

namespace stage {

bool start(CoveringRun& run) {
  const CoveringOptions& options = run.options;
  try {
    const double max_start_distance =
        options.max_start_distance > 0 ? options.max_start_distance : 10.0 * options.step;
    run.start_point = project_start_point(run.problem, run.start, run.domain, max_start_distance);
  } catch (const ComputationFailed& failure) {
    run.result.summary.termination = CoveringTermination::StartFailed;
    run.result.summary.message = failure.what();
    return false;
  }
  return true;
}

bool build(CoveringRun& run) {
  run.context.emplace(CoveringContext{run.problem, run.domain, *run.start_point});
  run.result.summary.method = run.method;
  run.build(*run.context, run.result);
  return true;
}

bool clip(CoveringRun& run) { return clip_and_retry(run, /*after_stop=*/false); }

bool clip_after_stop(CoveringRun& run) { return clip_and_retry(run, /*after_stop=*/true); }

bool close_notches(CoveringRun& run) {
  if (!run.is_clipped || !run.clip_refusal.empty()) {
    return false;
  }
  // Up to 5 boundary edge lengths: at coarse steps on bratu2d (0.8 for N = 20, 316) the notch
  // next to the face λ = 0.5 needs an edge of 4.6 (refinement then splits it).
  const NotchClosing notches = close_boundary_notches(run.problem, run.domain, run.result.mesh,
                                                      5.0 * run.context->boundary_edge_length);
  if (notches.added_triangles > 0) {
    run.result.summary.notes.push_back(
        "closed " + std::to_string(notches.added_triangles) +
        " notch(es) in the boundary with a triangle each: the build left M ∩ S uncovered next to "
        "a boundary vertex inside S");
  }
  return true;
}

bool swap(CoveringRun& run) {
  if (!run.is_clipped || !run.context->swap_after_clipping ||
      run.result.mesh.triangle_count() == 0) {
    return false;
  }
  // Clipping leaves poor angles at ∂S that swaps in the tangent planes repair. A stop request
  // ends them (the mesh is valid after every swap): they are an improvement.
  ImprovementOptions swaps;
  swaps.stop_requested = run.options.stop_requested;
  if (improve_by_edge_swaps(run.result.mesh, run.problem, swaps).interrupted) {
    run.result.summary.record_failure(
        CoveringTermination::Interrupted,
        "interrupted while improving the angles at the domain boundary");
  }
  return true;
}

bool refine(CoveringRun& run) {
  const CoveringOptions& options = run.options;
  CoveringSummary& summary = run.result.summary;
  run.triangles_before_refinement = run.result.mesh.triangle_count();
  if (options.tolerance <= 0 || run.result.mesh.triangle_count() == 0) {
    return false;
  }
  ToleranceRefinementOptions refinement;
  refinement.tolerance = options.tolerance;
  refinement.corrector = options.corrector;
  refinement.stop_requested = options.stop_requested;
  const ToleranceRefinement refined =
      refine_to_tolerance(run.problem, run.domain, run.result.mesh, {}, refinement);
  summary.refined_edges += refined.split_edges;
  summary.max_sampled_distance = refined.max_distance_within;
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
    run.is_refinement_stopped = true;
  } else if (refined.remaining > 0) {
    drop_far_triangles(refined, options.tolerance, run);
  }
  return true;
}

bool note_tolerance_not_enforced(CoveringRun& run) {
  run.triangles_before_refinement = run.result.mesh.triangle_count();
  if (run.options.tolerance > 0 && run.result.mesh.triangle_count() > 0) {
    run.result.summary.notes.push_back(
        "interrupted: the tolerance " + std::to_string(run.options.tolerance) +
        " was not enforced on the partial mesh (no triangle was checked)");
  }
  return false;
}

bool validate_and_repair(CoveringRun& run) {
  run.repaired_triangles = validate_and_repair_mesh(run.problem, run.domain, run.result,
                                                    run.is_stopped(), run.checks_stop());
  return true;
}

bool refine_repaired(CoveringRun& run) {
  TriangleMesh& mesh = run.result.mesh;
  if (run.repaired_triangles <= 0 || run.options.tolerance <= 0) {
    return false;
  }
  std::vector<int> added;
  for (int t = mesh.triangle_count() - run.repaired_triangles; t < mesh.triangle_count(); ++t) {
    added.push_back(t);
  }
  // No stop request: the run was not stopped before, and a repair's few triangles are checked
  // in full.
  ToleranceRefinementOptions refinement;
  refinement.tolerance = run.options.tolerance;
  refinement.corrector = run.options.corrector;
  const ToleranceRefinement refined =
      refine_to_tolerance(run.problem, run.domain, mesh, added, refinement);
  CoveringSummary& summary = run.result.summary;
  summary.refined_edges += refined.split_edges;
  summary.max_sampled_distance =
      std::max(summary.max_sampled_distance, refined.max_distance_within);
  if (refined.remaining > 0) {
    drop_far_triangles(refined, run.options.tolerance, run);
  }
  if (refined.split_edges > 0 || refined.remaining > 0) {
    validate_and_repair_mesh(run.problem, run.domain, run.result, false, run.checks_stop());
  }
  return true;
}

bool check_coverage(CoveringRun& run) {
  const CoveringContext& context = *run.context;
  detail::check_coverage(run.domain, run.options.step, run.result);
  check_holes_covered_over(
      run.problem, run.domain, context.boundary_snap_fraction * context.boundary_edge_length,
      run.options.tolerance, run.options.corrector, run.checks_stop(), run.result);
  return true;
}

bool patches(CoveringRun& run) {
  const CoveringResult& result = run.result;
  if (result.patches.empty() ||
      (!result.patches_need_rebuild &&
       result.mesh.triangle_count() == run.triangles_before_refinement &&
       result.summary.refined_edges <= 0 && result.summary.removed_triangles <= 0 &&
       static_cast<int>(result.patches.size()) == result.mesh.triangle_count())) {
    return false;
  }
  rebuild_patches(run.problem, run.result);
  return true;
}

bool skip(CoveringRun& /*run*/) { return false; }

}  // namespace stage

}  // namespace tessera::detail
