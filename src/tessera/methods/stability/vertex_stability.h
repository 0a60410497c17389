// SPDX-License-Identifier: MIT
// Which steady states are stable: at every vertex of a mesh of M, the eigenvalues of the pencil
// (s·D_uF, B) of the problem's dynamics B·u' = s·F(u, p) that decide stability.
// docs/algorithms/stability.md has the method and what each count is sure of.
#pragma once

#include <complex>
#include <limits>
#include <string>
#include <vector>

#include "tessera/core/implicit_problem.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

struct StabilityOptions {
  /// Sparse problems: how many eigenvalues nearest 0 shift-invert Lanczos/Arnoldi computes (as
  /// pde2path's default, about 6). Dense problems compute all.
  int eigenvalue_count = 6;
  /// Sparse problems with at most this many states are solved as dense ones (all eigenvalues):
  /// below it a dense QR algorithm costs less than a sparse factorisation and an iteration.
  int dense_state_limit = 50;
  /// The Krylov subspace of the Lanczos/Arnoldi iteration (0: max(2k + 1, 16), bounded by the
  /// number of states). With the previous vertex's eigenvectors as the start, the first
  /// factorisation usually converges: about m + 1 solves per vertex (bench/RESULTS.md,
  /// "Stability": 13–16 cost the same, 20 10 % more, 30 twice as much on bvp:points=10000).
  int subspace_size = 0;
  /// Relative accuracy of the Ritz values (Spectra's tolerance).
  double tolerance = 1e-10;
  /// Restarts of the implicitly restarted Arnoldi/Lanczos method before a vertex is given up.
  int max_restarts = 200;
};

/// The stability of one steady state.
struct VertexStability {
  /// Eigenvalues with positive real part among those examined (see is_certain); −1: the
  /// eigenvalue computation failed at this vertex (`message` says why).
  int unstable_count = -1;
  /// The largest real part among the computed eigenvalues (NaN when it failed).
  double leading_real_part = std::numeric_limits<double>::quiet_NaN();
  /// True when unstable_count counts every eigenvalue: dense problems (all eigenvalues
  /// computed) and symmetric sparse ones (the inertia of s·D_uF by Sylvester's law). False:
  /// the count is of the computed eigenvalues, those with |μ| ≤ examined_radius.
  bool is_certain = false;
  /// Every eigenvalue with |μ| ≤ examined_radius was computed (infinity when all were).
  double examined_radius = std::numeric_limits<double>::infinity();
  /// The computed finite eigenvalues, by decreasing real part.
  std::vector<std::complex<double>> eigenvalues;
  std::string message;  ///< why it failed, empty otherwise

  bool has_failed() const { return unstable_count < 0; }
};

/// What compute_stability found and what it cost.
struct StabilityResult {
  std::vector<VertexStability> vertices;  ///< one per mesh vertex
  /// "dense", "sparse symmetric (inertia)" or "sparse (shift-invert Arnoldi)": how the counts
  /// were made.
  std::string method;
  int eigenvalue_count = 0;     ///< k for the sparse methods; 0 for dense (all)
  int stable_count = 0;         ///< vertices with unstable_count == 0
  std::vector<int> index_counts;  ///< index_counts[i]: vertices with i unstable eigenvalues
  int failed_count = 0;           ///< vertices where the computation failed
  int uncertain_count = 0;        ///< vertices whose count is not certain (is_certain false)
  long factorisations = 0;        ///< of s·D_uF − σB (sparse)
  long solves = 0;                ///< with those factorisations (sparse)
  long jacobian_evaluations = 0;
  double seconds = 0.0;
};

/// The stability of every vertex of `mesh` (points of M in the problem's coordinates).
///
/// - Dense problems (and sparse ones with few states): all eigenvalues of the pencil by the
///   QR algorithm (B = I) or the QZ algorithm (infinite eigenvalues of a singular B dropped).
/// - Sparse problems with s·D_uF symmetric and B diagonal and positive: the count from the
///   inertia of an LDLᵀ factorisation (certain), the k eigenvalues nearest 0 by shift-invert
///   Lanczos with the same factorisation.
/// - Other sparse problems: the k eigenvalues nearest 0 by shift-invert Arnoldi on
///   (s·D_uF)⁻¹·B with a sparse LU; the count is of those (not certain).
///
/// Vertices are visited in breadth-first order over the mesh's edges and each iteration starts
/// from the previous vertex's eigenvectors, so neighbours' spectra help each other.
/// \throw InvalidArgument if the problem declares no dynamics (the message says how to declare
///        them) or its dynamics are invalid, or if the mesh is not in R^n.
StabilityResult compute_stability(const ImplicitProblem& problem, const TriangleMesh& mesh,
                                  const StabilityOptions& options = {});

/// The eigenvalues of the pencil at one point x of M (in the problem's coordinates), as
/// compute_stability computes them for a vertex.
VertexStability stability_at(const ImplicitProblem& problem, const Eigen::VectorXd& x,
                             const StabilityOptions& options = {});

/// Every finite eigenvalue of the pencil (A, B) by the QR algorithm (`has_identity_mass`: B = I,
/// `B` unread) or the QZ algorithm (an eigenvalue infinite when |β| ≤ 10⁻¹³(|α| + |β|), and
/// dropped): what compute_stability does for dense problems. The count is certain.
/// \param A  m×m, s·D_uF.   \param B  m×m mass matrix.
VertexStability dense_stability(const Eigen::MatrixXd& A, const Eigen::SparseMatrix<double>& B,
                                bool has_identity_mass);

/// Fills result's stable_count, index_counts, failed_count and uncertain_count from its
/// vertices (for a computation elsewhere: the PETSc backend's).
void count_stability_classes(StabilityResult& result);

/// Adds the conjugate of every complex eigenvalue whose conjugate is not among `values` (it fell
/// just outside the k an Arnoldi method returned): a pair counts as one.
void complete_conjugate_pairs(std::vector<std::complex<double>>& values);

/// The order compute_stability visits the vertices in: breadth first over the mesh's edges,
/// component by component, so that each eigenvalue iteration starts from a neighbour's
/// eigenvectors. Also the PETSc backend's order (petsc_stability.h).
std::vector<int> stability_vertex_order(const TriangleMesh& mesh);

}  // namespace tessera
