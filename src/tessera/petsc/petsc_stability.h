// SPDX-License-Identifier: MIT
// `mesh --stability` on the PETSc backend: at every vertex the eigenvalues of the pencil
// (s·D_uF, B) nearest 0 on the ranks with SLEPc, and for a symmetric s·D_uF the exact count of
// unstable ones from the inertia of its distributed LDLᵀ (MUMPS). The counterpart of
// compute_stability (methods/stability/vertex_stability.h); docs/algorithms/stability.md.
#pragma once

#include "tessera/geometry/triangle_mesh.h"
#include "tessera/methods/stability/vertex_stability.h"
#include "tessera/petsc/petsc_problem.h"

namespace tessera::petsc {

/// Whether this tessera was built with SLEPc (Debian's slepc-dev): without it
/// compute_distributed_stability throws.
bool has_slepc();

/// The stability of every vertex of `mesh`, computed on the ranks of `problem`'s communicator.
///
/// The mesh's points are this rank's rows of each vertex (a split mesh, mesh.space() the
/// problem's split, as the covering leaves it on the PETSc backend) or whole n-vectors on every
/// rank (a mesh of a ReplicatedProblem); either way in the problem's own coordinates x, not the
/// metric's. At every vertex, in compute_stability's order (stability_vertex_order):
///
/// - A = s·D_uF: the rows of F and the state columns of `problem`'s Jacobian (MatCreateSubMatrix:
///   each rank the rows it owns), times the sign; B from the dynamics, on the same rows.
/// - A symmetric (MatIsSymmetric, to 10⁻¹² ‖A‖∞) and B diagonal and positive: the count of
///   unstable eigenvalues is the number of positive ones of A (Sylvester's law), from the
///   inertia of its LDLᵀ by MUMPS (MatGetInertia; null pivots detected at 10⁻¹³ ‖A‖: a vertex
///   on a fold to rounding goes the general way); the k eigenvalues nearest 0 by SLEPc's
///   Krylov–Schur on the same factorisation (shift-invert at 0, generalised Hermitian). Certain.
/// - Otherwise: the k eigenvalues nearest 0 by shift-invert Krylov–Schur with MUMPS's LU
///   (generalised when B ≠ I); the count is of those (is_certain false), as the serial
///   shift-invert Arnoldi.
/// - At most options.dense_state_limit states: A and B gathered to every rank and every
///   eigenvalue computed (dense_stability), as the serial computation does.
///
/// Each iteration starts from the previous vertex's eigenvectors. Every rank returns the same
/// result (SLEPc's eigenvalues and MUMPS's inertia are the same on all ranks). Collective.
/// \pre the dynamics' parameters are two coordinates; the mesh's points have the problem's
///      local rows (split) or n entries.
/// \throw InvalidArgument if the problem declares no dynamics, they are invalid, the mesh does
///        not fit the problem, or tessera was built without SLEPc (the message says how to get
///        it).
StabilityResult compute_distributed_stability(const PetscProblem& problem, const TriangleMesh& mesh,
                                              const StabilityOptions& options = {});

}  // namespace tessera::petsc
