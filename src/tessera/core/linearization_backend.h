// SPDX-License-Identifier: MIT
// The factorisation behind a Linearization: tessera's dense (QR) and sparse (bordered LU) ones
// live in linearization.cpp; a problem may bring its own (the PETSc backend's distributed one)
// through ImplicitProblem::make_linearization_backend.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <memory>

namespace tessera {

class ImplicitProblem;

/// One factorisation of DF at a point, and the solves from it. Vectors are the local rows of
/// the problem's AmbientSpace (all n rows in one process).
class LinearizationBackend {
 public:
  virtual ~LinearizationBackend() = default;
  virtual std::unique_ptr<LinearizationBackend> clone() const = 0;
  /// Factors DF(x); fills an orthonormal tangent basis (local rows × 2, oriented by the caller).
  /// `reference` (may be null) guides the choice of border. Returns false if DF(x) is singular
  /// or not finite.
  virtual bool factor(const ImplicitProblem& problem, const Eigen::Ref<const Eigen::VectorXd>& x,
                      const Eigen::MatrixXd* reference, Eigen::MatrixXd& tangent,
                      double& reciprocal_condition) = 0;
  /// dx with DF·dx = rhs and dx ⟂ ker DF. rhs: the local rows of F; dx: the local rows of x.
  virtual void solve(const Eigen::Ref<const Eigen::VectorXd>& rhs, const Eigen::MatrixXd& tangent,
                     Eigen::Ref<Eigen::VectorXd> dx) const = 0;
  /// The same for several right-hand sides at once (rhs: local rows of F × k, dx: local rows of
  /// x × k). A sparse LU solves k columns in one sweep over its factors, which at large n is
  /// cheaper per column than k sweeps (the triangular solves are latency-bound); this default
  /// solves them one by one.
  virtual void solve_columns(const Eigen::Ref<const Eigen::MatrixXd>& rhs,
                             const Eigen::MatrixXd& tangent, Eigen::Ref<Eigen::MatrixXd> dx) const {
    for (Eigen::Index j = 0; j < rhs.cols(); ++j) {
      solve(rhs.col(j), tangent, dx.col(j));
    }
  }
  /// Numerical factorisations made so far (a sparse factor() may try more than one border).
  long factorisations() const { return factorisations_; }
  /// Evaluations of DF the backend made itself, not through ImplicitProblem::jacobian or
  /// sparse_jacobian (0 for tessera's own backends).
  long own_jacobian_evaluations() const { return own_jacobian_evaluations_; }
  /// What guides the border of the next factorisation made without a reference (sparse: the
  /// last basis factored); empty for none, and for backends without a border. A checkpoint
  /// keeps it, so that a new object borders as the old one would have.
  virtual Eigen::MatrixXd border_guide() const { return {}; }
  virtual void set_border_guide(const Eigen::MatrixXd& /*guide*/) {}
  /// nnz(L + U) / nnz(A) of the last sparse factorisation, where the backend knows it (0
  /// otherwise): how many solves' worth a factorisation costs grows with it, and it depends on
  /// the pattern only, so decisions made from it are deterministic.
  virtual double fill_ratio() const { return 0.0; }
  /// Heap bytes held (the factors, the Jacobian), approximately, on this rank.
  virtual std::size_t memory_bytes() const = 0;
  /// Drops what only factoring needed (the Jacobian, the assembled matrix): solves still work,
  /// a clone is not factored. For factorisations kept for later solves at large n.
  virtual void release_assembly() {}
  /// Whether clone() is factored too (false after release_assembly of a backend that refactors
  /// to copy).
  virtual bool clones_factorisation() const { return true; }

 protected:
  long factorisations_ = 0;
  long own_jacobian_evaluations_ = 0;
};

}  // namespace tessera
