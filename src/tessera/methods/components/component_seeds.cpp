// SPDX-License-Identifier: MIT
#include "tessera/methods/components/component_seeds.h"

#include <cmath>
#include <limits>

#include "tessera/core/error.h"

namespace tessera {
namespace {

// The first `count` primes (the Halton bases).
std::vector<int> primes(int count) {
  std::vector<int> found;
  for (int candidate = 2; static_cast<int>(found.size()) < count; ++candidate) {
    bool is_prime = true;
    for (int p : found) {
      if (p * p > candidate) {
        break;
      }
      if (candidate % p == 0) {
        is_prime = false;
        break;
      }
    }
    if (is_prime) {
      found.push_back(candidate);
    }
  }
  return found;
}

// The radical inverse of `index` in `base`: its digits mirrored about the point, in [0, 1).
double radical_inverse(long index, int base) {
  double value = 0.0;
  double digit_weight = 1.0 / base;
  while (index > 0) {
    value += static_cast<double>(index % base) * digit_weight;
    index /= base;
    digit_weight /= base;
  }
  return value;
}

}  // namespace

SeededBox seeded_box(const Domain& domain) {
  SeededBox box;
  if (domain.is_unbounded()) {
    return box;
  }
  const int n = domain.ambient_dimension();
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  Eigen::VectorXd lower = Eigen::VectorXd::Constant(n, -kInfinity);
  Eigen::VectorXd upper = Eigen::VectorXd::Constant(n, kInfinity);
  for (const HalfSpace& face : domain.half_spaces()) {
    if ((face.normal.array() != 0.0).count() != 1) {
      continue;
    }
    int axis = 0;
    face.normal.cwiseAbs().maxCoeff(&axis);
    // b·(x − p) ≥ 0 with b = ±e_axis: x_axis ≥ p_axis or x_axis ≤ p_axis.
    if (face.normal(axis) > 0) {
      lower(axis) = std::max(lower(axis), face.point(axis));
    } else {
      upper(axis) = std::min(upper(axis), face.point(axis));
    }
  }
  for (int i = 0; i < n; ++i) {
    if (std::isfinite(lower(i)) && std::isfinite(upper(i)) && upper(i) > lower(i)) {
      box.coordinates.push_back(i);
    }
  }
  const int d = static_cast<int>(box.coordinates.size());
  box.lower.resize(d);
  box.upper.resize(d);
  for (int k = 0; k < d; ++k) {
    box.lower(k) = lower(box.coordinates[k]);
    box.upper(k) = upper(box.coordinates[k]);
  }
  return box;
}

Eigen::MatrixXd halton_seeds(const SeededBox& box, const Eigen::VectorXd& reference, int count) {
  TESSERA_CHECK(!box.is_empty(), "halton_seeds: the box seeds no coordinate");
  TESSERA_CHECK(count >= 1, "halton_seeds: count = " << count << " must be at least 1");
  const int d = static_cast<int>(box.coordinates.size());
  const std::vector<int> bases = primes(d);
  Eigen::MatrixXd seeds = reference.replicate(1, count);
  for (int j = 0; j < count; ++j) {
    for (int k = 0; k < d; ++k) {
      // Index j + 1: the point of index 0 is the box's lower corner in every base.
      const double u = radical_inverse(j + 1, bases[static_cast<std::size_t>(k)]);
      seeds(box.coordinates[static_cast<std::size_t>(k)], j) =
          box.lower(k) + u * (box.upper(k) - box.lower(k));
    }
  }
  return seeds;
}

double seed_spacing(const SeededBox& box, int count, const Eigen::VectorXd& weights) {
  const int d = static_cast<int>(box.coordinates.size());
  if (d == 0 || count < 1) {
    return 0.0;
  }
  double log_volume = 0.0;
  for (int k = 0; k < d; ++k) {
    const double w =
        weights.size() > 0 ? weights(box.coordinates[static_cast<std::size_t>(k)]) : 1.0;
    log_volume += std::log(w * (box.upper(k) - box.lower(k)));
  }
  return std::exp((log_volume - std::log(static_cast<double>(count))) / d);
}

}  // namespace tessera
