// SPDX-License-Identifier: MIT
// The last few factorisations of DF, by key (a mesh vertex): where one point's factorisation
// serves the points around it (chord iterations, tangent_basis_near), a short cache saves
// factoring again, and a bound on its bytes keeps it small at large n.
#pragma once

#include <cstddef>
#include <deque>

#include "tessera/core/ambient_space.h"
#include "tessera/core/linearization.h"

namespace tessera {

class FactorisationCache {
 public:
  /// At most `max_count` entries and, beyond the newest two, `max_bytes` of them.
  FactorisationCache(std::size_t max_count, std::size_t max_bytes)
      : max_count_(max_count), max_bytes_(max_bytes) {}

  /// The entry for `key`, factored or not (DF rank deficient there); null if there is none.
  const Linearization* find(int key) const {
    for (const Entry& entry : entries_) {
      if (entry.key == key) {
        return &entry.linearization;
      }
    }
    return nullptr;
  }

  /// The entry made last, factored; null if there is none or it is not factored.
  const Linearization* newest() const {
    return entries_.empty() || !entries_.back().linearization.is_factored()
               ? nullptr
               : &entries_.back().linearization;
  }

  /// Factors DF at x as the entry for `key`, dropping the oldest entries over the bounds.
  /// \return the entry, or null where DF is rank deficient. Valid until the next factor().
  const Linearization* factor(int key, const ImplicitProblem& problem,
                              const Eigen::Ref<const Eigen::VectorXd>& x) {
    while (!entries_.empty() && (entries_.size() >= max_count_ ||
                                 (entries_.size() >= 2 && bytes_ > max_bytes_))) {
      bytes_ -= entries_.front().bytes;
      entries_.pop_front();
    }
    entries_.push_back({key, Linearization(), 0});
    Linearization& linearization = entries_.back().linearization;
    const bool is_factored = linearization.factor(problem, x);
    linearization.release_assembly();  // kept for its solves only
    // The bytes decide which entries are dropped, so for a distributed problem (each rank holds
    // its part of a factorisation) every rank must count the same: the largest part.
    std::size_t bytes = linearization.memory_bytes();
    if (const auto space = problem.space(); space->is_distributed()) {
      bytes = static_cast<std::size_t>(space->maximum(static_cast<double>(bytes)));
    }
    entries_.back().bytes = bytes;
    bytes_ += bytes;
    return is_factored ? &linearization : nullptr;
  }

 private:
  std::size_t max_count_;
  std::size_t max_bytes_;
  std::size_t bytes_ = 0;
  struct Entry {
    int key;
    Linearization linearization;
    std::size_t bytes;  // as counted when it was made
  };
  std::deque<Entry> entries_;  // oldest first
};

}  // namespace tessera
