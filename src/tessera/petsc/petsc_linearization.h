// SPDX-License-Identifier: MIT
// The linearisation of F at a point on distributed vectors: a factorisation of the bordered
// Jacobian A = [DF(x); e_iᵀ; e_jᵀ] by PETSc (MUMPS by default), the orthonormal tangent basis
// of ker DF(x) and minimum-norm solves of DF(x)·dx = r. tessera::Linearization's sparse
// backend, distributed; the two give the same answers to rounding (tests/petsc).
#pragma once

#include <array>
#include <cstddef>

#include "tessera/petsc/petsc_problem.h"

namespace tessera::petsc {

/// Two distributed n-vectors: a tangent basis T = (t₀, t₁) of M at a point.
using TangentPair = std::array<Owned<Vec>, 2>;

/// The linearisation of F at one point x, collective over the problem's communicator.
///
/// The border rows are coordinate rows e_iᵀ, e_jᵀ chosen from a reference tangent as PITCON
/// does (i the coordinate in which the tangent plane moves most, j the one that completes the
/// best-conditioned pair): A is then exactly as sparse as DF, and a distributed direct solver
/// factors it like the PDE's own Jacobian. Without a reference the two last coordinates are
/// tried (the parameters of a parametrised system). Unlike the serial backend there is no
/// dense pseudo-random border as the last resort: two dense rows of length n on one rank do not
/// scale; `factor` then fails and says so in `last_failure`.
///
/// The solver is PETSc's KSP: by default KSPPREONLY with an LU factorisation by MUMPS (PETSc's
/// own LU on one rank when MUMPS is missing); PETSc's options (-ksp_type gmres -pc_type bjacobi,
/// -mat_mumps_icntl_14 50, …) override it at the first factorisation. With an iterative KSP a
/// "factorisation" is the preconditioner's set-up and every solve iterates.
class DistributedLinearization {
 public:
  explicit DistributedLinearization(const PetscProblem& problem);
  /// A copy factors its own copy of the bordered matrix (a numerical factorisation, no
  /// evaluation of DF; not counted in factorisations()). Collective.
  DistributedLinearization(const DistributedLinearization& other);
  DistributedLinearization& operator=(const DistributedLinearization&) = delete;

  /// Evaluates DF at x and factors the bordered matrix. The returned basis is oriented like
  /// `reference` (det(Tᵀ Tᵣ) > 0) when one is given. Reuses the symbolic analysis while the
  /// border stays in the same columns.
  /// \return false if DF(x) is not finite or the bordered matrix is singular for every border
  ///         tried; the linearisation is then unusable.
  bool factor(Vec x, const TangentPair* reference = nullptr);

  bool is_factored() const { return is_factored_; }
  /// The point of the factorisation.
  Vec point() const { return point_; }
  /// T, orthonormal (Euclidean inner product of the vectors), spanning ker DF(point).
  const TangentPair& tangent_basis() const { return tangent_; }
  /// dx with DF·dx = r and dx ⟂ ker DF, for r in entries 0 … n−3 of `rhs` (entries n−2, n−1
  /// are ignored). `rhs` and `dx` may not be the same vector. \pre is_factored().
  void solve_minimum_norm(Vec rhs, Vec dx) const;

  /// Bytes of the factors and the bordered matrix, averaged over the ranks: the same number on
  /// every rank, so that budgets built on it decide alike (MUMPS's INFOG(9), INFOG(10); 0 before
  /// the first factorisation). Collective.
  std::size_t memory_bytes() const;
  /// X = A⁻¹ B for the bordered matrix A and the k columns of B (dense matrices with the
  /// problem's row layout): one multi-column solve, which MUMPS does in one sweep over its
  /// factors. With B's entries n−2, n−1 zero, X's columns solve DF·x = b; they are not
  /// projected (the caller removes their ker-DF components). \pre is_factored().
  void solve_bordered_columns(Mat B, Mat X) const;
  /// Numerical factorisations so far (each a PCSetUp of the bordered matrix).
  long factorisations() const { return factorisations_; }
  /// Symbolic analyses so far (a new border column pattern).
  long analyses() const { return analyses_; }
  /// Why the last `factor` failed, empty after a success.
  const std::string& last_failure() const { return last_failure_; }

 private:
  bool factor_with_border(PetscInt i, PetscInt j);
  // (i, j): the border to factor with; (best_i, best_j): the serial backend's choice, which a
  // kept border may differ from.
  void choose_border(const TangentPair& guide, PetscInt& i, PetscInt& j, PetscInt& best_i,
                     PetscInt& best_j) const;
  bool express_in_coordinates(PetscInt i, PetscInt j);
  bool orthonormalise_tangent();
  void make_solver();

  const PetscProblem& problem_;
  const PetscInt n_;
  Owned<Mat> bordered_;  // [DF; e_iᵀ; e_jᵀ]
  Owned<KSP> solver_;
  Owned<Vec> point_;
  TangentPair tangent_;
  Owned<Vec> unit_;     // scratch: e_{n−2} or e_{n−1}
  mutable Owned<Vec> rhs_;  // scratch: the right-hand side with its border entries zeroed
  PetscInt border_i_ = -1;  // columns of the border rows in bordered_'s pattern
  PetscInt border_j_ = -1;
  int border_changes_ = 0;  // since bordered_ was made
  bool has_basis_ = false;  // tangent_ holds the last good basis (guides the next border)
  long factorisations_ = 0;
  long analyses_ = 0;
  bool is_factored_ = false;
  std::string last_failure_;
};

/// Sets entries n−2 and n−1 of v (the border rows) to 0.
void zero_border_entries(Vec v);

}  // namespace tessera::petsc
