// SPDX-License-Identifier: MIT
// Quality of a mesh of M: how far it is from M (at vertices, and at points the method did not
// produce: triangle centroids and edge midpoints), its angles and its area.
#pragma once

#include <functional>
#include <limits>
#include <utility>

#include "tessera/core/implicit_problem.h"
#include "tessera/core/linearization.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

/// Summary statistics of one measured quantity.
struct Statistic {
  double max = 0.0;
  double mean = 0.0;
  int count = 0;       ///< values measured
  int population = 0;  ///< values there are; count < population means a uniform sample
};

struct QualityOptions {
  /// Distances to M are measured at no more than this many vertices, triangle centroids and
  /// edge midpoints each, drawn uniformly with a fixed seed (0: all of them). Each is a
  /// Gauss–Newton projection, a few factorisations of DF: at large n the full report would cost
  /// more than the covering. The largest of s uniform samples exceeds the q-quantile of the
  /// population with probability 1 − q^s (for s = 300: the 99th percentile with 95 %).
  /// The residual |F| is evaluated at every vertex whatever this is. With 0 and no time budget,
  /// a sparse problem's points are measured vertex by vertex, each with the triangles and edges
  /// whose first corner it is, from its one factorisation.
  int max_samples = 0;
  /// Time for the distances, in seconds: the samples (vertices, centroids and midpoints in turn,
  /// each kind in random order) are measured until it is spent, and then at least
  /// kMinDistanceSamples of each kind. Every prefix of a random order is a uniform sample, so
  /// the counts say what was measured and the quantile statement above holds for them. At
  /// n = 10⁵ a sample costs about a factorisation (0.3–0.5 s). Infinite: no limit.
  double max_seconds = std::numeric_limits<double>::infinity();
  /// Polled before every distance sample on one thread, before every block of samples on
  /// several (the first kMinDistanceSamples of each kind, then 4096 rounds per thread: some
  /// 50 ms at n = 3); true ends the measurement with what was measured (the counts say how much).
  /// Ctrl-C during the report at large n. Polled on the calling thread only.
  std::function<bool()> stop_requested;
  /// In a distributed run (every rank measuring the same samples, each a collective
  /// projection): this rank's wish to stop, spent budget or stop request, in; the decision
  /// every rank takes, out (true if any rank wants to stop). Empty: this process decides.
  std::function<bool(bool)> decide_together;
};

/// Samples of each kind measured whatever QualityOptions::max_seconds says (the largest of 30
/// exceeds the 90th percentile with probability 96 %).
inline constexpr int kMinDistanceSamples = 30;

struct MeshQuality {
  Statistic vertex_residual;    ///< |F(x)| at the vertices
  Statistic vertex_distance;    ///< distance of the vertices to M
  Statistic centroid_distance;  ///< distance of the triangle centroids to M
  Statistic midpoint_distance;  ///< distance of the edge midpoints to M
  int failed_projections = 0;   ///< points whose projection onto M did not converge
  double min_angle_degrees = 0.0;
  double max_angle_degrees = 0.0;
  double fraction_angles_below_30 = 0.0;  ///< share of all triangle angles below 30°
  double area = 0.0;                      ///< sum of the triangle areas in R^n
  double min_edge_length = 0.0;
  double max_edge_length = 0.0;
};

/// Measures `mesh` against M = {F = 0}. Distances are ‖x − P(x)‖, where P is the Gauss–Newton
/// projection with minimum-norm steps: it converges to a point of M whose offset from x is
/// normal to M up to O(‖x − P(x)‖²), so it measures the distance to that order. For sparse
/// problems centroids and midpoints are projected by the chord from the factorisation at a
/// corner (offset normal to M there, the same order; P where it does not converge), which
/// costs solves instead of factorisations. O(N) projections (or options.max_samples per kind).
/// Lengths, angles, areas and distances are measured in the problem's metric (CoordinateBlock
/// weights), the norm the covering methods use. One code path for every backend: a split mesh
/// of a distributed problem (TriangleMesh::set_space) is measured in the problem's
/// metric_problem(), every sum reduced over the ranks, and gives the serial report.
/// \throw InvalidArgument if the mesh and the problem live in different dimensions.
MeshQuality measure_quality(const TriangleMesh& mesh, const ImplicitProblem& problem,
                            const QualityOptions& options = {});

/// Checks that `mesh` lives where `problem` does: the same n and, for a distributed problem,
/// this rank's rows of every point (TriangleMesh::set_space) in a Euclidean metric (a
/// distributed problem's metric is the PETSc problem's business: petsc::ScaledPetscProblem).
/// \throw InvalidArgument naming `caller` and what is wrong.
void check_mesh_of_problem(const TriangleMesh& mesh, const ImplicitProblem& problem,
                           const char* caller);

/// P(x): the projection onto M that measure_quality() and validate() use, Gauss–Newton with
/// minimum-norm steps to ‖dx‖ ≤ 1e-13·(1 + ‖x‖) and ‖F‖ ≤ 1e-11 (distances down to ~1e-12 must
/// be resolved). The offset x − P(x) is normal to M up to O(‖x − P(x)‖²).
/// \param x n-vector, overwritten with P(x) (with the last iterate if it fails).
/// \param workspace reused between calls; afterwards it holds DF and its tangent basis at the
///        last iterate, within the tolerance of P(x).
/// \return false if the iteration did not converge.
bool project_onto_manifold(const ImplicitProblem& problem, Eigen::Ref<Eigen::VectorXd> x,
                           Linearization& workspace);

/// Angles, areas and edge lengths only, in R^n (no problem needed).
MeshQuality measure_shape(const TriangleMesh& mesh);
/// Angles, areas and edge lengths in the problem's metric, as measure_quality() measures them
/// (the distances left unmeasured).
/// \throw InvalidArgument as measure_quality().
MeshQuality measure_shape(const TriangleMesh& mesh, const ImplicitProblem& problem);

/// Angle (radians) at `apex` of the triangle (apex, p, q) in R^n, as atan2(|u ∧ w|, u·w):
/// accurate near 0 and π, where acos of the cosine is not.
double corner_angle(const Eigen::Ref<const Eigen::VectorXd>& apex,
                    const Eigen::Ref<const Eigen::VectorXd>& p,
                    const Eigen::Ref<const Eigen::VectorXd>& q);

/// Smallest angle (radians) of triangle t of `mesh`.
double min_angle(const TriangleMesh& mesh, const Triangle& t);
/// Smallest angle (radians) of the triangle with side lengths a, b, c (opposite the shortest
/// side), by Kahan's formula, accurate for needles and caps; 0 for a degenerate triangle. Three
/// passes over R^n for the lengths instead of nine for three corner angles.
double min_angle_of_sides(double a, double b, double c);

/// Sum of the triangle areas in R^n.
double surface_area(const TriangleMesh& mesh);

/// Area of the triangle `tri` of `mesh` in R^n and its longest edge squared, accurate for thin
/// triangles (base times height over the longest edge: no cancellation), over the ranks of a
/// split mesh.
std::pair<double, double> triangle_area_and_longest_squared(const TriangleMesh& mesh,
                                                            const Triangle& tri);

}  // namespace tessera
