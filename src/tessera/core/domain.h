// SPDX-License-Identifier: MIT
// Polyhedral domain S = ∩ {x : b_k·(x − p_k) ≥ 0} (Brodzik & Rheinboldt, eq. 2.2).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "tessera/core/ambient_space.h"

namespace tessera {

/// One closed half-space {x : normal·(x − point) ≥ 0}; `normal` is stored with unit length.
struct HalfSpace {
  Eigen::VectorXd normal;  ///< n-vector, unit length (normalised on construction by Domain)
  Eigen::VectorXd point;   ///< n-vector, a point on the bounding hyperplane
  std::string label;       ///< for messages, e.g. "x >= -1.5"
  /// Indices of the normal's nonzero entries when they are few (a bound on a coordinate has
  /// one): signed distances then cost O(1) instead of O(n). Empty: use the whole normal.
  std::vector<int> support;
};

/// The nearest bounding hyperplane of a point (the paper's Chkbnd).
struct BoundaryDistance {
  double signed_distance = 0.0;  ///< min_k b_k·(x − p_k); > 0 strictly inside, ≤ 0 outside/on
  int nearest_half_space = -1;   ///< index k of the minimiser, −1 if the domain is unbounded
};

/// An intersection of half-spaces in R^n. The empty list is the whole space.
class Domain {
 public:
  Domain() = default;
  explicit Domain(int ambient_dimension) : dimension_(ambient_dimension) {}

  /// The axis-aligned box [lower, upper] as 2n half-spaces; a bound of ±infinity is skipped.
  /// \throw InvalidArgument if lower(i) > upper(i) for some i (the message names i).
  static Domain box(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                    const std::vector<std::string>& coordinate_names = {});

  /// Adds {x : normal·(x − point) ≥ 0}. \throw InvalidArgument for a zero normal or wrong size.
  void add_half_space(const Eigen::VectorXd& normal, const Eigen::VectorXd& point,
                      std::string label = {});

  /// The rows of each normal and point: n, or this rank's rows of a distributed domain.
  int ambient_dimension() const { return dimension_; }
  /// This rank's rows of the domain, for points split over the ranks of `space` (SPMD): the
  /// normals and points cut to the rows held, every distance summed over the ranks (a
  /// collective call, made on every rank, the same bits everywhere). \pre a domain in R^n
  /// with n = space->dimension().
  Domain distributed(std::shared_ptr<const AmbientSpace> space) const;
  /// The domain W S for W = diag(weights) (scale_domain, core/scaled_problem.h), on the same
  /// rows: {x : b·(x − p) ≥ 0} becomes {y : (W⁻¹b)·(y − W p) ≥ 0}, the normals of unit length
  /// again (a distributed domain's over the ranks: collective). \pre weights.size() ==
  /// ambient_dimension(), all finite and > 0.
  Domain scaled(const Eigen::VectorXd& weights) const;
  bool is_distributed() const { return space_ != nullptr; }
  bool is_unbounded() const { return half_spaces_.empty(); }
  const std::vector<HalfSpace>& half_spaces() const { return half_spaces_; }

  /// Chkbnd: distance to the nearest bounding hyperplane, signed (> 0 inside).
  BoundaryDistance boundary_distance(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  /// Signed distance b_k·(x − p_k) to one bounding hyperplane.
  double signed_distance(int k, const Eigen::Ref<const Eigen::VectorXd>& x) const;
  /// signed_distance(k, points.col(columns[j])) as entry (k, j) of a K × columns.size() matrix:
  /// for a distributed domain summed over the ranks in one call, so that a pass over many
  /// points costs one reduction (in one process the same numbers, face by face).
  Eigen::MatrixXd signed_distances(const Eigen::Ref<const Eigen::MatrixXd>& points,
                                   const std::vector<int>& columns) const;
  /// x ∈ S (closed), with a tolerance on the signed distances.
  bool contains(const Eigen::Ref<const Eigen::VectorXd>& x, double tolerance = 0.0) const;
  /// Whether the segment from x to y passes through the interior of S, by more than
  /// `margin` from every face (clipping of the parameter interval by each half-space).
  /// Always true for the unbounded domain.
  bool segment_meets_interior(const Eigen::Ref<const Eigen::VectorXd>& x,
                              const Eigen::Ref<const Eigen::VectorXd>& y,
                              double margin = 0.0) const;

  /// The width of S across x within the plane x + span(T) (T: n×2, orthonormal columns): the
  /// smallest t_k + t_l over pairs of faces that the plane crosses from nearly opposite sides
  /// (their normals' directions in the plane at more than 120°), t_k = max(0, d_k)/‖Tᵀb_k‖ the
  /// distance from x to face k within the plane. Where M ∩ S is a band, this is its width near
  /// x (to first order). Faces farther than `reach` within the plane are not considered; +∞
  /// if no pair is within reach (also for the unbounded domain).
  double band_width(const Eigen::Ref<const Eigen::VectorXd>& x,
                    const Eigen::Ref<const Eigen::MatrixXd>& T, double reach) const;

  /// Intersection of two domains. \pre same ambient dimension.
  void intersect_with(const Domain& other);

  /// A one-line description, e.g. "box [-1.5,1.5]^3" or "2 half-spaces".
  std::string describe() const;

  /// This rank's part of the signed distance b_k·(x − p_k): the distance itself in one process
  /// (the same bits as signed_distance), a partial sum over the rows held here for a
  /// distributed domain. Summing the parts of many points and faces in one AmbientSpace::sum
  /// is how the passes over a split mesh ask for distances (one reduction per pass, not per
  /// point). Not collective.
  double partial_signed_distance(int k, const Eigen::Ref<const Eigen::VectorXd>& x) const;

 private:
  // All signed distances of x, summed over the ranks once (distributed domains; one process
  // asks partial_signed_distance face by face, without allocating).
  std::vector<double> signed_distances(const Eigen::Ref<const Eigen::VectorXd>& x) const;

  int dimension_ = 0;
  std::vector<HalfSpace> half_spaces_;
  std::shared_ptr<const AmbientSpace> space_;  // null: in one process
};

}  // namespace tessera
