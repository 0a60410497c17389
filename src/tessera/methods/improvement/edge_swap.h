// SPDX-License-Identifier: MIT
// Mesh improvement on M: Lawson-style edge swaps judged in the tangent plane of M, with a
// Delaunay-type, a normal-angle or a midpoint-distance criterion (Malcolm's data-dependent
// triangulation, carried from the plane to a surface in R^n).
#pragma once

#include <functional>

#include <string>

#include "tessera/core/implicit_problem.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

/// What an edge swap must improve. Each criterion compares the two triangles on the edge
/// before the swap with the two after it; nothing else changes.
enum class ImprovementCriterion {
  /// Delaunay-type: maximise the smallest of the six angles of the two triangles. The angles
  /// are those of the triangles in R^n (what measure_quality reports), so a swap never lowers
  /// the mesh's minimum angle.
  MaxMinAngle,
  /// Minimise the angle between the planes of the two triangles. n = 3: the angle between the
  /// oriented normals, in [0, π]. n > 3: the largest principal angle between the two
  /// triangles' 2-planes, in [0, π/2] (principal angles do not see orientation).
  NormalAngle,
  /// Minimise the distance to M of the diagonal's midpoint (projected with
  /// project_gauss_newton): the edge that runs closer to M wins.
  MidpointDistance,
};

/// "angle", "normal", "distance".
const char* to_string(ImprovementCriterion criterion);

struct ImprovementOptions {
  ImprovementCriterion criterion = ImprovementCriterion::MaxMinAngle;
  /// Hard stop. A sweep visits every interior edge once; Lawson's procedure for the
  /// Delaunay-type criterion needs few sweeps, and the other criteria are local, so they may
  /// cycle without the tolerance below: the cap makes termination certain.
  int max_sweeps = 50;
  /// A swap is made only if the criterion improves by more than this fraction of its old
  /// value (angle: new > old·(1 + tol); normal angle, distance: new < old·(1 − tol)). Rounding
  /// can then never make two configurations each look better than the other.
  double relative_tolerance = 1e-6;
  /// The quadrilateral a, d, b, c is strictly convex in the tangent plane if each of the four
  /// triangles abc, bad, cad, dbc there has signed area > ratio·(longest quad side or diagonal)²
  /// with the orientation of the old triangles. 1e-6 rejects near-flat corners (a swap there
  /// would make a sliver) while an equilateral triangle has ratio 0.43.
  double min_area_ratio = 1e-6;
  /// Polled once per edge the criterion is asked about; true ends the swaps there, with the
  /// swaps made so far (each checked) kept. Empty: never stopped. A covering passes its own
  /// (Ctrl-C): at large n a swap's checks cost factorisations.
  std::function<bool()> stop_requested;
  /// Measure the mesh's shape before and after for the summary (min_angle_degrees_before …):
  /// a pass over the triangles each. A caller that discards the summary (the atlas's own
  /// improvement) leaves them out: at 10⁶ vertices six such passes were 0.4 s.
  bool measure_shapes = true;

  /// \throw InvalidArgument naming the first option that is out of range.
  void validate() const;
};

struct ImprovementSummary {
  int swaps = 0;
  int sweeps = 0;
  bool converged = false;  ///< the last sweep made no swap (false: max_sweeps was hit)
  bool interrupted = false;  ///< stop_requested ended the swaps
  int interior_edges = 0;
  // Refusals are summed over all sweeps (an edge refused in every sweep counts every time).
  // The criterion is evaluated before the geometric checks, so the two counters below count
  // only swaps that the criterion wanted.
  int rejected_non_convex = 0;            ///< wanted, refused: quad not strictly convex
  int rejected_existing_edge = 0;         ///< the other diagonal (c, d) is already an edge
  int rejected_projection_failed = 0;     ///< an edge midpoint could not be projected onto M
  double min_angle_degrees_before = 0.0;  ///< in R^n, as measure_shape
  double min_angle_degrees_after = 0.0;
  double fraction_angles_below_30_before = 0.0;
  double fraction_angles_below_30_after = 0.0;
  /// e.g. "12 swaps in 3 sweeps (converged); min angle 23.1° -> 27.4°".
  std::string brief_report() const;
};

/// Why an edge may or may not be swapped (geometry and combinatorics only, no criterion).
enum class SwapCheck {
  Allowed,
  NotAnEdge,                ///< no triangle has the edge
  BoundaryEdge,             ///< one triangle: never swapped, the boundary stays as it is
  NonManifoldEdge,          ///< more than two triangles
  InconsistentOrientation,  ///< the two triangles traverse the edge alike
  ExistingEdge,             ///< the other diagonal is already an edge (swap would be non-manifold)
  NonConvex,                ///< the quadrilateral is not strictly convex in the tangent plane
  ProjectionFailed,         ///< the edge midpoint could not be projected onto M / J lost rank there
};

const char* to_string(SwapCheck check);

/// Checks whether edge {a, b} (triangles (a, b, c) and (b, a, d)) may be replaced by {c, d}:
/// an interior, manifold, consistently oriented edge whose quadrilateral a, d, b, c is strictly
/// convex in the tangent plane of M at the projection of the edge midpoint (T from
/// Linearization::factor there), and also, with the same orientation, in the tangent planes at
/// its four corners (bases aligned with T): the midpoint's plane alone lets a swap fold the mesh
/// over where M curves across a large quadrilateral. Strict convexity with the old triangles'
/// orientation is what makes the new triangles (c, a, d), (d, b, c) keep that orientation.
/// O(triangle count) (linear search for the edge) plus five factorisations of J.
SwapCheck check_edge_swap(const TriangleMesh& mesh, const ImplicitProblem& problem, int a, int b,
                          const ImprovementOptions& options = {});

/// Swaps edge {a, b} if check_edge_swap allows it, whatever the criterion says; the new
/// triangles (c, a, d) and (d, b, c) keep the orientation of the old ones. For tests and tools.
/// \return the check's verdict; the mesh is changed only if it is Allowed.
SwapCheck swap_edge(TriangleMesh& mesh, const ImplicitProblem& problem, int a, int b,
                    const ImprovementOptions& options = {});

/// Lawson-style sweeps: every interior edge whose swap check_edge_swap allows and that
/// improves options.criterion strictly is swapped, until a sweep swaps nothing or
/// options.max_sweeps is reached. The criterion is evaluated first and the geometric checks
/// (a projection and five factorisations of J) only for swaps it wants; the swaps made are the
/// same as with the checks first, since a swap needs both. Vertices do not move; boundary edges are
/// never swapped; the number of vertices, edges and triangles, the Euler characteristic, the
/// boundary and the orientation are kept, so a valid mesh stays valid. \pre
/// mesh.ambient_dimension() == problem.ambient_dimension() (else InvalidArgument). \see Malcolm,
/// "Data dependent triangulation" (docs/papers), sections on swap criteria;
///      Lawson's local optimisation procedure.
ImprovementSummary improve_by_edge_swaps(TriangleMesh& mesh, const ImplicitProblem& problem,
                                         const ImprovementOptions& options = {});

}  // namespace tessera
