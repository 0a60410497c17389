// SPDX-License-Identifier: MIT
// The problem interface: a smooth map F: R^n -> R^(n-2) and its Jacobian, dense or sparse.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tessera/core/dynamics.h"

namespace tessera {

class AmbientSpace;
class JacobianProduct;
class LinearizationBackend;

/// A named range of coordinates, e.g. the grid values u of a discretised PDE.
///
/// Blocks give M's coordinates their meaning beyond names: the views (`max:u`, `norm:u`) and the
/// metric in which tessera measures M. A grid function u on N points is a vector whose Euclidean
/// norm grows like √N under refinement while the function it represents does not; with
/// `weight` = √h (one dimension, h the mesh width) or h (two dimensions) the weighted norm
/// approximates the continuous L² norm, and the surface, its step and tolerance no longer
/// depend on the grid (AUTO and COCO scale discretised states the same way).
struct CoordinateBlock {
  std::string name;  ///< e.g. "u"; unique among a problem's blocks and coordinate names
  int first = 0;     ///< index of the block's first coordinate
  int size = 1;      ///< number of coordinates, first … first + size − 1
  /// Factor of these coordinates in the norm tessera measures M in: ‖x‖² = Σ (w_i x_i)² with
  /// w_i = weight inside a block and 1 elsewhere. Must be finite and > 0.
  double weight = 1.0;
};

/// An implicitly defined two-dimensional manifold M = {x in R^n : F(x) = 0}.
///
/// Implement `ambient_dimension`, `evaluate` and one of `jacobian` / `sparse_jacobian`.
/// Problems with large n (discretised PDEs) override `has_sparse_jacobian` to return true and
/// implement `sparse_jacobian`; the solvers then never form a dense (n-2)×n matrix.
///
/// Evaluations are called from one thread at a time per problem object unless the problem says
/// it is thread-safe (is_thread_safe); implementations should be free of side effects apart
/// from caching.
class ImplicitProblem {
 public:
  virtual ~ImplicitProblem() = default;

  /// n, the dimension of the ambient space. The manifold has dimension 2, so F has n-2 components.
  virtual int ambient_dimension() const = 0;
  int equation_count() const { return ambient_dimension() - 2; }

  /// F(x). \pre x.size() == n, F.size() == n-2. Non-finite values are allowed and are treated
  /// by the solvers as "x is outside the domain of F".
  virtual void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                        Eigen::Ref<Eigen::VectorXd> F) const = 0;

  /// J = DF(x), dense (n-2)×n. The default converts `sparse_jacobian`.
  virtual void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                        Eigen::Ref<Eigen::MatrixXd> J) const;

  /// True if `sparse_jacobian` is the natural (efficient) form of the Jacobian.
  virtual bool has_sparse_jacobian() const { return false; }

  /// J = DF(x), sparse (n-2)×n, compressed column storage. The default converts `jacobian`.
  virtual void sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                               Eigen::SparseMatrix<double>& J) const;

  /// Whether `evaluate`, `jacobian`, `sparse_jacobian` and `make_linearization_backend` may be
  /// called from several threads at once, each with its own arguments; then the data-parallel
  /// steps (the tolerance check, the validation, the report's distances) run on threads
  /// (parallel_for.h). False, the default, keeps every call on one thread: a callback into
  /// Python (the GIL), a distributed problem (collective MPI calls) or one with a cache must
  /// not be called concurrently. The catalogue's problems and problem files are pure functions
  /// and say true; decorators forward their inner problem's.
  virtual bool is_thread_safe() const { return false; }

  /// Short identifier, e.g. "sphere". Used in reports and file headers.
  virtual std::string name() const { return "problem"; }

  /// Names of the n coordinates; the default is x0 … x{n-1} (x, y, z when n = 3).
  virtual std::vector<std::string> coordinate_names() const;

  /// Named ranges of coordinates and their weights in the metric (see CoordinateBlock); the
  /// default is none: M is measured in the Euclidean norm of R^n.
  virtual std::vector<CoordinateBlock> coordinate_blocks() const { return {}; }

  /// The dynamics B·u' = ±F(u, p) whose steady states M is (core/dynamics.h): which two
  /// coordinates are the parameters, the sign and the mass matrix. Nothing (the default): F is
  /// not declared the right-hand side of an evolution equation, and stability cannot be asked.
  /// Decorators that keep the coordinates forward it; ScaledProblem does not (its coordinates are
  /// the metric's, and stability is computed in the problem's own).
  virtual std::optional<Dynamics> dynamics() const { return std::nullopt; }

  /// Where the problem's vectors live and how they are reduced (AmbientSpace): R^n in one
  /// process by default. A distributed problem (src/tessera/petsc) returns its split over the
  /// ranks; then `evaluate` and the solvers see the local rows only. Decorators forward their
  /// inner problem's.
  virtual std::shared_ptr<const AmbientSpace> space() const;
  /// DF(y)·V for a problem whose Jacobian is no Eigen matrix (petsc::DistributedProblem), for
  /// tangent_basis_near; null (the default): `jacobian` / `sparse_jacobian` give it.
  virtual const JacobianProduct* as_jacobian_product() const { return nullptr; }
  /// The same M in its metric's coordinates y = W x (CoordinateBlock), where the problem
  /// provides it itself: a distributed problem cannot be wrapped in ScaledProblem, so the PETSc
  /// backend pairs it with its scaled twin. Null (the default): ScaledProblem gives it.
  virtual const ImplicitProblem* metric_problem() const { return nullptr; }

  /// The factorisation the problem brings for Linearization, or null (the default): tessera's
  /// dense QR or sparse bordered LU, as has_sparse_jacobian says. Decorators forward.
  virtual std::unique_ptr<LinearizationBackend> make_linearization_backend() const;
};

/// The n weights w of the problem's metric ‖x‖² = Σ (w_i x_i)², from its coordinate blocks;
/// empty when every weight is 1 (the Euclidean norm).
/// \throw InvalidArgument if a block lies outside 0 … n−1, overlaps another or has a weight
///        that is not finite and > 0.
Eigen::VectorXd metric_weights(const ImplicitProblem& problem);

/// Default coordinate names for dimension n: x, y, z for n = 3, otherwise x0 … x{n-1}.
std::vector<std::string> default_coordinate_names(int n);

}  // namespace tessera
