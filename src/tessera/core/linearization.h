// SPDX-License-Identifier: MIT
// Factorisation of the Jacobian J = DF(x) at one point: minimum-norm solves of J·dx = r and an
// orthonormal basis of the tangent space ker J. Dense (QR of Jᵀ, Brodzik–Rheinboldt eq. 2.6)
// or sparse (LU of the bordered matrix [J; Tᵀ]) depending on the problem.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <memory>

#include "tessera/core/implicit_problem.h"

namespace tessera {

class LinearizationBackend;
class AmbientSpace;
class CountedProblem;

/// The linearisation of F at a point x.
///
/// Dense problems: column-pivoted Householder QR of Jᵀ = (Q1, Q2)(R; 0); Q2 spans ker J and
/// dx = Q1 R⁻ᵀ r is the minimum-norm solution of J dx = r.
/// Sparse problems (n up to 10⁶): sparse LU of the bordered n×n matrix A = [J; Tᵣᵀ], where Tᵣ
/// is a reference tangent basis (the neighbour's, or a fixed pseudo-random one at the start).
/// Then ker J = span A⁻¹[0; I₂] and the minimum-norm solution is the A⁻¹[r; 0] solution with
/// its ker-J component removed. Both give the same answers to rounding.
class Linearization {
 public:
  Linearization();
  ~Linearization();
  Linearization(Linearization&&) noexcept;
  Linearization& operator=(Linearization&&) noexcept;
  Linearization(const Linearization& other);
  Linearization& operator=(const Linearization& other);

  /// Evaluates J at x and factors it. `reference_tangent` (n×2, may be null) orients the tangent
  /// basis: the returned basis T satisfies det(Tᵀ Tᵣ) > 0 and, for sparse problems, borders J.
  /// \return false if J is numerically rank deficient (rank < n−2) or not finite; the
  ///         factorisation is then unusable.
  bool factor(const ImplicitProblem& problem, const Eigen::Ref<const Eigen::VectorXd>& x,
              const Eigen::MatrixXd* reference_tangent = nullptr);

  /// A linearisation at y from another point's factorisation (issue 30): the solves of `near`'s
  /// factorisation, shared, not copied, with the exact tangent basis `tangent` of M at y (from
  /// tangent_basis_near). solve_minimum_norm then returns J_s⁺r plus the vector of ker J_s that
  /// makes it orthogonal to `tangent`: the solution of the bordered system [J_s; tangentᵀ]
  /// dx = [r; 0], a rank-two change of near's border (Sherman–Morrison–Woodbury with two inner
  /// products). A chord iteration with it converges to y's own pointOnDisk point (F = 0,
  /// tangentᵀ(x − x₀) = 0), only at a rate set by the distance to near's point instead of zero.
  /// No factorisation is made.
  /// \return false (nothing changed) if near is not factored or `tangent` is too oblique to
  ///         near's solver basis (|det(tangentᵀ T_s)| < min_cosine).
  bool borrow(const ImplicitProblem& problem, const Linearization& near,
              const Eigen::Ref<const Eigen::VectorXd>& y, const Eigen::MatrixXd& tangent,
              double min_cosine = 0.5);
  /// Whether the solves come from a factorisation borrowed (borrow), of this point or another.
  bool is_borrowed() const { return solver_tangent_.size() > 0; }
  /// Whether they come from another point's: borrowed, and factored elsewhere.
  bool solves_from_elsewhere() const { return is_borrowed() && solver_point_ != point_; }
  /// The factorisation the solves use, to tell shared ones apart (null if none): equal for a
  /// factorisation and every linearisation that borrowed it.
  const void* factorisation_identity() const { return backend_.get(); }
  /// The point whose DF was factored (point() unless borrowed).
  const Eigen::VectorXd& factored_point() const {
    return is_borrowed() ? solver_point_ : point_;
  }

  bool is_factored() const { return factored_; }
  /// The point x the factorisation belongs to (n-vector).
  const Eigen::VectorXd& point() const { return point_; }
  /// T: n×2, orthonormal columns spanning ker J.
  const Eigen::MatrixXd& tangent_basis() const { return tangent_; }
  /// dx with J dx = rhs and dx ⟂ ker J (the minimum-norm solution). \pre is_factored().
  void solve_minimum_norm(const Eigen::Ref<const Eigen::VectorXd>& rhs,
                          Eigen::Ref<Eigen::VectorXd> dx) const;
  /// The minimum-norm solves of several right-hand sides (the columns of rhs, (n−2)×k) in one
  /// call: points projected from the same factorisation in lockstep, or a tangent basis. For
  /// sparse problems one sweep over the LU serves all columns, about 2.4× cheaper per column than
  /// separate solves at k = 4 (KLU on bvp, bench/history/RESULTS-log.md section 10, seventh step).
  /// \pre is_factored().
  void solve_minimum_norm_columns(const Eigen::Ref<const Eigen::MatrixXd>& rhs,
                                  Eigen::Ref<Eigen::MatrixXd> dx) const;
  /// Heap bytes this factorisation holds (factors, Jacobian, point, basis), approximately: what
  /// a covering weighs when it decides how many factorisations to keep. A borrowed one counts
  /// the shared factors too (factorisation_identity tells where they are counted twice).
  std::size_t memory_bytes() const;
  /// Frees what only factoring needed (for sparse problems DF and the bordered matrix, about
  /// half of the bytes at large n); solves and the tangent basis are unchanged. A copy made
  /// afterwards is not factored. For factorisations kept for their solves.
  void release_assembly();
  /// What guides the border of the next factorisation made without a reference tangent (sparse
  /// problems: the last basis factored); empty if none. A factorisation depends on it, so a
  /// checkpoint keeps it and a resumed build sets it in a new object
  /// (set_border_guide(problem, guide): the backend `factor` would make, with that guide).
  Eigen::MatrixXd border_guide() const;
  void set_border_guide(const ImplicitProblem& problem, const Eigen::MatrixXd& guide);
  /// nnz(L + U) / nnz(A) of the sparse factorisation (0 where unknown: dense, or a backend
  /// that does not say). See LinearizationBackend::fill_ratio.
  double fill_ratio() const;
  /// Estimate of the reciprocal condition number of J (smallest/largest |R_ii|), in (0, 1].
  double reciprocal_condition() const { return reciprocal_condition_; }

 private:
  void make_backend(const ImplicitProblem& problem);
  // Shared between a factorisation and the linearisations that borrowed it (never changed while
  // shared: factor() makes a new one then); a copy of an unshared one clones it.
  std::shared_ptr<LinearizationBackend> backend_;
  Eigen::VectorXd point_;
  Eigen::MatrixXd tangent_;
  // Borrowed only (empty otherwise): the solver's basis and point, (tangentᵀ T_s)⁻¹, and the
  // space its inner products reduce over.
  Eigen::MatrixXd solver_tangent_;
  Eigen::VectorXd solver_point_;
  Eigen::Matrix2d oblique_ = Eigen::Matrix2d::Zero();
  std::shared_ptr<const AmbientSpace> space_;
  void make_orthogonal_to_tangent(Eigen::Ref<Eigen::MatrixXd> dx) const;
  double reciprocal_condition_ = 0.0;
  bool factored_ = false;
  // The run's counter of solves, where the problem factored or borrowed with is one (its
  // lifetime is the run's, which outlasts the linearisations it makes).
  const CountedProblem* counted_ = nullptr;
  void count_solves(long columns) const;
};

/// The tangent basis of M at a point y near `near`'s point, without factoring DF(y): the chord
/// iteration T ← T − J⁺(DF(y)·T) from near's basis, with near's factorisation J⁺, converges to
/// a basis of ker DF(y) as fast as the chord corrector converges from near's point to y. One
/// evaluation of DF(y) and two solves per step; at large n a fraction of a factorisation.
/// \param T  n×2, on success orthonormal with columns spanning ker DF(y) (to `tolerance`
///        relative to ‖DF(y)‖), oriented like near's basis.
/// \param angle_tolerance  where > 0, the iteration also stops once its corrections bound the
///        distance of T from its limit (in radians, from the contraction seen) by this: a test
///        that does not depend on the scale of DF, which the residual's does (bvp at n = 10⁴:
///        ‖DF‖ ≈ 10¹⁰, so a residual of 10⁻¹⁰‖DF‖ left T a thousandth of a radian off).
/// \return false if DF(y) is not finite or the iteration does not reach the tolerance within
///         `max_iterations` steps (y too far from near's point); then factor at y instead.
bool tangent_basis_near(const ImplicitProblem& problem, const Linearization& near,
                        const Eigen::Ref<const Eigen::VectorXd>& y, Eigen::MatrixXd& T,
                        double tolerance = 1e-9, int max_iterations = 4,
                        double angle_tolerance = 0.0);

/// Whether points near `factored` should borrow its factorisation (Linearization::borrow)
/// instead of factoring their own: where its LU fills in, nnz(L + U) > 2·nnz(A) (2-D grids),
/// a factorisation costs many solves. A banded 1-D one (fill 1.2) costs about a dozen, and there
/// borrowing halved the factorisations but cost time (bvp:points=10000: 24.8 → 31.3 s). Decided
/// from the pattern alone, so the same run to run and on any machine. Issue 30. The environment
/// variable TESSERA_SHARE_FACTORISATIONS=off turns sharing off: the PETSc backend does not share
/// yet (it reports no fill), so that is how a serial run gives a PETSc run's mesh.
bool worth_sharing(const Linearization& factored);

/// `out` becomes a linearisation at y that borrows near's factorisation, if the tangent iteration
/// from near converges (tangent_basis_near, judged by its steps: within 10⁻⁷ rad in at most 8
/// steps, a contraction of about 0.1 or less, so that chords from near stay short). Its basis is
/// the one a factorisation at y guided by near's basis would give (coordinate_tangent_basis),
/// oriented like near's: the same frame an own factorisation gives, not the iteration's, which
/// drifts from point to point. No factorisation is made. \return false (out unchanged) if the
/// iteration does not converge.
bool borrow_factorisation(const ImplicitProblem& problem, const Linearization& near,
                          const Eigen::Ref<const Eigen::VectorXd>& y, Linearization& out);

/// borrow_factorisation for points visited in turn (the tolerance check's anchors, the corners
/// of ∂S), where the last factorisation may be far: tried only where it is worth sharing and y
/// lies within four `edge_length`s (the local edge length of the mesh) of near's factored
/// point, so that a borrow that would not converge costs nothing. \return false (out unchanged)
/// otherwise.
bool borrow_nearby(const ImplicitProblem& problem, const Linearization& near,
                   const Eigen::Ref<const Eigen::VectorXd>& y, double edge_length,
                   Linearization& out);

/// Minimum-norm solution of J·dx = rhs for a dense J (m×n, m ≤ n) by column-pivoted QR of Jᵀ.
/// \return false (dx untouched) if J has rank < m.
bool solve_minimum_norm_dense(const Eigen::Ref<const Eigen::MatrixXd>& J,
                              const Eigen::Ref<const Eigen::VectorXd>& rhs,
                              Eigen::Ref<Eigen::VectorXd> dx);

/// Flips the second column of T if needed so that det(Tᵀ·reference) > 0: keeps frames of
/// neighbouring points consistently oriented.
void align_tangent_basis(Eigen::MatrixXd& T, const Eigen::MatrixXd& reference);
/// The same for local rows of a distributed space (the product Tᵀ·reference reduced over ranks).
void align_tangent_basis(Eigen::MatrixXd& T, const Eigen::MatrixXd& reference,
                         const AmbientSpace& space);

}  // namespace tessera
