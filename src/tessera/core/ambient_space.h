// SPDX-License-Identifier: MIT
// Where the n-vectors of a covering live and how they are measured: in one process, or split
// over the ranks of a distributed problem (src/tessera/petsc), with global reductions that
// every rank computes identically.
#pragma once

#include <Eigen/Core>
#include <memory>

namespace tessera {

/// The ambient space R^n as the covering code holds it.
///
/// In one process (the default of every ImplicitProblem) an n-vector is an Eigen vector of n
/// entries and F(x) one of n − 2. A distributed problem splits every n-vector over the ranks
/// of a communicator: each rank holds the contiguous rows [first_row, first_row + local_rows)
/// of every point, tangent vector and direction, and F(x) in local_equations rows, and every
/// rank runs the same covering code on its rows (SPMD). What the covering decides must then
/// come from global reductions, which this class provides, identical to the bit on every rank
/// (AmbientSpace implementations add the ranks' partial sums in rank order), so that every
/// rank takes the same branch.
///
/// Code that reduces an n-vector with Eigen directly (x.norm(), a.dot(b), Tᵀv) is correct in
/// one process only. The code paths that accept distributed problems (method atlas, the
/// correctors, the linearisation) reduce through these functions; with one process they are
/// Eigen's own reductions, so serial results do not change.
class AmbientSpace {
 public:
  /// R^n in one process.
  explicit AmbientSpace(int dimension);
  virtual ~AmbientSpace() = default;

  /// n.
  int dimension() const { return dimension_; }
  /// The global index of this rank's first row.
  int first_row() const { return first_row_; }
  /// Rows of an n-vector held here (n in one process).
  int local_rows() const { return local_rows_; }
  /// Rows of F(x) held here (n − 2 in one process; a distributed problem keeps F in the rows of
  /// x, its last two rows zero).
  int local_equations() const { return local_equations_; }
  virtual bool is_distributed() const { return false; }
  /// Whether global row i is held here.
  bool holds_row(int i) const { return i >= first_row_ && i < first_row_ + local_rows_; }

  /// Replaces values[0 … count) by their sums over the ranks (in one process: unchanged).
  virtual void sum(double* values, int count) const;
  /// The largest of the ranks' values.
  virtual double maximum(double value) const { return value; }
  /// Replaces values[0 … count) by their maxima over the ranks, entry by entry (exact: no
  /// rounding; a minimum is −maximum(−v)). One call for a pass's many maxima (a view's max:u of
  /// every vertex).
  virtual void maximum(double* values, int count) const;
  /// Whether this is the rank that writes files (rank 0; true in one process).
  virtual bool is_root() const { return true; }
  /// Gathers `count` n-vectors to the root: `local` holds this rank's rows of them
  /// (local_rows() × count, column-major), `whole` (n × count, column-major) receives all n
  /// rows on the root and is not touched elsewhere (it may be null there). Collective; in one
  /// process a copy. For output only (write_states_npy of a split mesh): the caller bounds
  /// n × count to a few MB, so that the root never holds every vertex's n-vector.
  virtual void gather_to_root(const double* local, int count, double* whole) const;

  // Reductions of local rows, built on `sum`.
  double dot(const Eigen::Ref<const Eigen::VectorXd>& a, const Eigen::Ref<const Eigen::VectorXd>& b) const;
  double squared_norm(const Eigen::Ref<const Eigen::VectorXd>& a) const;
  double norm(const Eigen::Ref<const Eigen::VectorXd>& a) const;
  /// ‖a − b‖.
  double distance(const Eigen::Ref<const Eigen::VectorXd>& a,
                  const Eigen::Ref<const Eigen::VectorXd>& b) const;
  /// Aᵀ B for A (rows × k) and B (rows × l), k·l ≤ 64: tangent coordinates Tᵀv, Gram matrices.
  Eigen::MatrixXd products(const Eigen::Ref<const Eigen::MatrixXd>& A,
                           const Eigen::Ref<const Eigen::MatrixXd>& B) const;
  /// Tᵀ v for a tangent basis T (rows × 2).
  Eigen::Vector2d tangent_coordinates(const Eigen::Ref<const Eigen::MatrixXd>& T,
                                      const Eigen::Ref<const Eigen::VectorXd>& v) const;
  /// Frobenius norm of a local block of columns (the ranks' rows of an n × k matrix).
  double frobenius_norm(const Eigen::Ref<const Eigen::MatrixXd>& A) const;
  /// Whether every entry on every rank is finite.
  bool all_finite(const Eigen::Ref<const Eigen::MatrixXd>& A) const;
  /// x_i (a global index) on every rank.
  double coordinate(const Eigen::Ref<const Eigen::VectorXd>& x, int i) const;

 protected:
  AmbientSpace(int dimension, int first_row, int local_rows, int local_equations);

 private:
  int dimension_;
  int first_row_;
  int local_rows_;
  int local_equations_;
};

}  // namespace tessera
