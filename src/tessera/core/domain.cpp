// SPDX-License-Identifier: MIT
#include "tessera/core/domain.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "tessera/core/error.h"

namespace tessera {

Domain Domain::box(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                   const std::vector<std::string>& coordinate_names) {
  TESSERA_CHECK(lower.size() == upper.size(), "box bounds have sizes " << lower.size() << " and "
                                                                      << upper.size());
  const int n = static_cast<int>(lower.size());
  Domain domain(n);
  for (int i = 0; i < n; ++i) {
    const std::string name =
        i < static_cast<int>(coordinate_names.size()) ? coordinate_names[i] : "x" + std::to_string(i);
    TESSERA_CHECK(!std::isnan(lower(i)) && !std::isnan(upper(i)),
                  "box bound of coordinate " << name << " is NaN");
    TESSERA_CHECK(lower(i) <= upper(i), "box is empty: lower bound " << lower(i)
                                                                     << " of coordinate " << name
                                                                     << " exceeds upper bound "
                                                                     << upper(i));
    Eigen::VectorXd normal = Eigen::VectorXd::Zero(n);
    Eigen::VectorXd point = Eigen::VectorXd::Zero(n);
    if (std::isfinite(lower(i))) {
      normal(i) = 1.0;
      point(i) = lower(i);
      std::ostringstream label;
      label << name << " >= " << lower(i);
      domain.add_half_space(normal, point, label.str());
    }
    if (std::isfinite(upper(i))) {
      normal(i) = -1.0;
      point(i) = upper(i);
      std::ostringstream label;
      label << name << " <= " << upper(i);
      domain.add_half_space(normal, point, label.str());
    }
  }
  return domain;
}

void Domain::add_half_space(const Eigen::VectorXd& normal, const Eigen::VectorXd& point,
                            std::string label) {
  if (dimension_ == 0) {
    dimension_ = static_cast<int>(normal.size());
  }
  TESSERA_CHECK(normal.size() == dimension_ && point.size() == dimension_,
                "half-space has normal of size " << normal.size() << " and point of size "
                                                 << point.size() << ", expected " << dimension_);
  TESSERA_CHECK(normal.allFinite() && point.allFinite(), "half-space '" << label
                                                                        << "' has a non-finite "
                                                                           "normal or point");
  const double length = normal.norm();
  TESSERA_CHECK(length > 0.0, "half-space '" << label << "' has a zero normal vector");
  HalfSpace half_space{normal / length, point, std::move(label), {}};
  // At large n the domain is a few bounds on parameters: their distances are asked for at every
  // vertex, projection and cut, and a dense dot product was 3 % of a covering (bvp, n = 10⁴).
  const Eigen::Index nonzeros = (half_space.normal.array() != 0.0).count();
  if (nonzeros <= dimension_ / 8) {
    for (int i = 0; i < dimension_; ++i) {
      if (half_space.normal(i) != 0.0) {
        half_space.support.push_back(i);
      }
    }
  }
  half_spaces_.push_back(std::move(half_space));
}

Domain Domain::scaled(const Eigen::VectorXd& weights) const {
  TESSERA_CHECK(half_spaces_.empty() || weights.size() == dimension_,
                "metric has " << weights.size() << " weights, the domain is in R^" << dimension_);
  Domain result = *this;
  std::vector<double> squared_lengths;
  for (HalfSpace& h : result.half_spaces_) {
    h.normal = h.normal.cwiseQuotient(weights);  // the same nonzero entries: the support stays
    h.point = h.point.cwiseProduct(weights);
    squared_lengths.push_back(h.normal.squaredNorm());
  }
  if (space_ && !squared_lengths.empty()) {
    space_->sum(squared_lengths.data(), static_cast<int>(squared_lengths.size()));
  }
  for (std::size_t k = 0; k < squared_lengths.size(); ++k) {
    result.half_spaces_[k].normal /= std::sqrt(squared_lengths[k]);
  }
  return result;
}

Domain Domain::distributed(std::shared_ptr<const AmbientSpace> space) const {
  TESSERA_CHECK(space && (half_spaces_.empty() || space->dimension() == dimension_),
                "Domain::distributed: the domain is in R^" << dimension_ << ", the space in R^"
                                                           << (space ? space->dimension() : 0));
  Domain rows(space->local_rows());
  const int first = space->first_row();
  const int count = space->local_rows();
  for (const HalfSpace& h : half_spaces_) {
    HalfSpace local{h.normal.segment(first, count), h.point.segment(first, count), h.label, {}};
    for (int i : h.support) {
      if (space->holds_row(i)) {
        local.support.push_back(i - first);
      }
    }
    // A sparse normal none of whose entries lies here: keep a support (empty rows sum to 0),
    // marked by an index past the end, so that the dense dot is not taken instead.
    if (!h.support.empty() && local.support.empty()) {
      local.support.push_back(-1);
    }
    rows.half_spaces_.push_back(std::move(local));
  }
  rows.space_ = std::move(space);
  return rows;
}

double Domain::partial_signed_distance(int k, const Eigen::Ref<const Eigen::VectorXd>& x) const {
  const HalfSpace& h = half_spaces_[k];
  if (h.support.empty()) {
    return h.normal.dot(x - h.point);
  }
  double distance = 0.0;
  for (int i : h.support) {
    if (i >= 0) {
      distance += h.normal(i) * (x(i) - h.point(i));
    }
  }
  return distance;
}

std::vector<double> Domain::signed_distances(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  std::vector<double> distances(half_spaces_.size());
  for (int k = 0; k < static_cast<int>(half_spaces_.size()); ++k) {
    distances[static_cast<std::size_t>(k)] = partial_signed_distance(k, x);
  }
  if (space_ && !distances.empty()) {
    space_->sum(distances.data(), static_cast<int>(distances.size()));
  }
  return distances;
}

double Domain::signed_distance(int k, const Eigen::Ref<const Eigen::VectorXd>& x) const {
  double distance = partial_signed_distance(k, x);
  if (space_) {
    space_->sum(&distance, 1);
  }
  return distance;
}

Eigen::MatrixXd Domain::signed_distances(const Eigen::Ref<const Eigen::MatrixXd>& points,
                                         const std::vector<int>& columns) const {
  const int K = static_cast<int>(half_spaces_.size());
  Eigen::MatrixXd distances(K, static_cast<Eigen::Index>(columns.size()));
  for (std::size_t j = 0; j < columns.size(); ++j) {
    for (int k = 0; k < K; ++k) {
      distances(k, static_cast<Eigen::Index>(j)) = partial_signed_distance(k, points.col(columns[j]));
    }
  }
  if (space_ && distances.size() > 0) {
    space_->sum(distances.data(), static_cast<int>(distances.size()));
  }
  return distances;
}

BoundaryDistance Domain::boundary_distance(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  BoundaryDistance result;
  result.signed_distance = std::numeric_limits<double>::infinity();
  const std::vector<double> summed = space_ ? signed_distances(x) : std::vector<double>();
  for (int k = 0; k < static_cast<int>(half_spaces_.size()); ++k) {
    const double d = space_ ? summed[static_cast<std::size_t>(k)] : partial_signed_distance(k, x);
    if (d < result.signed_distance) {
      result.signed_distance = d;
      result.nearest_half_space = k;
    }
  }
  return result;
}

bool Domain::contains(const Eigen::Ref<const Eigen::VectorXd>& x, double tolerance) const {
  const std::vector<double> summed = space_ ? signed_distances(x) : std::vector<double>();
  for (int k = 0; k < static_cast<int>(half_spaces_.size()); ++k) {
    const double d = space_ ? summed[static_cast<std::size_t>(k)] : partial_signed_distance(k, x);
    if (d < -tolerance) {
      return false;
    }
  }
  return true;
}

bool Domain::segment_meets_interior(const Eigen::Ref<const Eigen::VectorXd>& x,
                                    const Eigen::Ref<const Eigen::VectorXd>& y,
                                    double margin) const {
  // The signed distances are affine along the segment, d_k(t) = d_k(x) + t (d_k(y) − d_k(x)):
  // each face keeps the part of t ∈ [0, 1] where d_k(t) > margin.
  double lower = 0.0;
  double upper = 1.0;
  const std::vector<double> from = space_ ? signed_distances(x) : std::vector<double>();
  const std::vector<double> to = space_ ? signed_distances(y) : std::vector<double>();
  for (int k = 0; k < static_cast<int>(half_spaces_.size()); ++k) {
    const auto j = static_cast<std::size_t>(k);
    const double at_x = (space_ ? from[j] : partial_signed_distance(k, x)) - margin;
    const double at_y = (space_ ? to[j] : partial_signed_distance(k, y)) - margin;
    if (at_x <= 0 && at_y <= 0) {
      return false;
    }
    if (at_x < 0 || at_y < 0) {
      const double crossing = at_x / (at_x - at_y);
      if (at_x < 0) {
        lower = std::max(lower, crossing);
      } else {
        upper = std::min(upper, crossing);
      }
    }
    if (lower >= upper) {
      return false;
    }
  }
  return true;
}

double Domain::band_width(const Eigen::Ref<const Eigen::VectorXd>& x,
                          const Eigen::Ref<const Eigen::MatrixXd>& T, double reach) const {
  // Faces nearly parallel to the plane (‖Tᵀb‖ below this) are not crossed by it nearby.
  constexpr double kMinCrossing = 0.1;
  struct NearFace {
    double distance;           // within the plane
    Eigen::Vector2d inward;    // unit, in T's coordinates
  };
  std::vector<NearFace> near;
  const int K = static_cast<int>(half_spaces_.size());
  // Tᵀb_k of every face (summed over the ranks at once when distributed).
  std::vector<double> projections(2 * static_cast<std::size_t>(K), 0.0);
  const std::vector<double> distances = signed_distances(x);  // each face's, once
  for (int k = 0; k < K; ++k) {
    const HalfSpace& face = half_spaces_[k];
    if (!space_ && distances[static_cast<std::size_t>(k)] > reach) {
      continue;  // not needed below (a distributed domain sums them all at once)
    }
    Eigen::Vector2d projected = Eigen::Vector2d::Zero();
    if (face.support.empty()) {
      projected = T.transpose() * face.normal;
    } else {
      for (int i : face.support) {
        if (i >= 0) {
          projected += face.normal(i) * T.row(i).transpose();
        }
      }
    }
    projections[2 * static_cast<std::size_t>(k)] = projected(0);
    projections[2 * static_cast<std::size_t>(k) + 1] = projected(1);
  }
  if (space_ && K > 0) {
    space_->sum(projections.data(), 2 * K);
  }
  for (int k = 0; k < K; ++k) {
    const double d = std::max(0.0, distances[static_cast<std::size_t>(k)]);
    if (d > reach) {
      continue;  // within the plane it is at least as far
    }
    const Eigen::Vector2d projected(projections[2 * static_cast<std::size_t>(k)],
                                    projections[2 * static_cast<std::size_t>(k) + 1]);
    const double length = projected.norm();
    if (length < kMinCrossing || d / length > reach) {
      continue;
    }
    near.push_back({d / length, projected / length});
  }
  double width = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < near.size(); ++i) {
    for (std::size_t j = i + 1; j < near.size(); ++j) {
      if (near[i].inward.dot(near[j].inward) < -0.5) {
        width = std::min(width, near[i].distance + near[j].distance);
      }
    }
  }
  return width;
}

void Domain::intersect_with(const Domain& other) {
  if (other.half_spaces_.empty()) {
    return;
  }
  if (dimension_ == 0) {
    dimension_ = other.dimension_;
  }
  TESSERA_CHECK(other.dimension_ == dimension_, "cannot intersect domains of dimension "
                                                    << dimension_ << " and " << other.dimension_);
  half_spaces_.insert(half_spaces_.end(), other.half_spaces_.begin(), other.half_spaces_.end());
}

std::string Domain::describe() const {
  if (half_spaces_.empty()) {
    return "unbounded";
  }
  std::ostringstream out;
  for (std::size_t k = 0; k < half_spaces_.size(); ++k) {
    out << (k ? ", " : "") << (half_spaces_[k].label.empty() ? "half-space" : half_spaces_[k].label);
  }
  return out.str();
}

}  // namespace tessera
