// SPDX-License-Identifier: MIT
// The last few factorisations of DF, by key (a mesh vertex): where one point's factorisation
// serves the points around it (chord iterations, tangent_basis_near), a short cache saves
// factoring again, and a bound on its bytes keeps it small at large n.
#pragma once

#include <cstddef>
#include <deque>
#include <memory>

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
    Linearization linearization;
    const bool is_factored = linearization.factor(problem, x);
    const Linearization* kept = keep(key, problem, std::move(linearization));
    return is_factored ? kept : nullptr;
  }

  /// Keeps `linearization` (factored, borrowed or rank deficient) as the entry for `key`, as
  /// factor() does. A borrowed one weighs its own vectors only: its factors are counted where
  /// they were made. \return the entry. Valid until the next factor() or keep().
  const Linearization* keep(int key, const ImplicitProblem& problem,
                            Linearization&& linearization) {
    while (!entries_.empty() &&
           (entries_.size() >= max_count_ || (entries_.size() >= 2 && bytes_ > max_bytes_))) {
      bytes_ -= entries_.front().bytes;
      entries_.pop_front();
    }
    const bool is_borrowed = linearization.is_borrowed();
    if (!is_borrowed) {
      linearization.release_assembly();  // kept for its solves only
    }
    entries_.push_back({key, std::move(linearization), 0});
    const Linearization& kept = entries_.back().linearization;
    // The bytes decide which entries are dropped, so for a distributed problem (each rank holds
    // its part of a factorisation) every rank must count the same: the largest part.
    std::size_t bytes = is_borrowed
                            ? 5 * sizeof(double) *
                                  static_cast<std::size_t>(kept.point().size())  // point, two bases
                            : kept.memory_bytes();
    if (const auto space = problem.space(); space->is_distributed()) {
      bytes = static_cast<std::size_t>(space->maximum(static_cast<double>(bytes)));
    }
    entries_.back().bytes = bytes;
    bytes_ += bytes;
    return &kept;
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

/// Own factorisations of DF kept for nearby points to borrow (Linearization::borrow, issue 30):
/// points visited along M (spatially_ordered) each borrow from the nearest kept one within
/// reach instead of factoring, and only the last factorisation is not always the nearest (a
/// Hilbert curve folds back past points it visited a while ago). The newest `max_count`, and
/// beyond the newest two at most `max_bytes` of them.
class FactorisationLenders {
 public:
  FactorisationLenders(std::size_t max_count, std::size_t max_bytes)
      : max_count_(max_count), max_bytes_(max_bytes) {}

  /// `out` becomes a linearisation at y that borrows the factorisation of the kept lender
  /// nearest y (borrow_nearby: worth sharing, within four `edge_length`s, tangent iteration
  /// converges). One try, at the nearest only: a failed try costs an evaluation of DF and up to
  /// eight steps of two solves. \return false (out unchanged) if none is near enough.
  bool borrow(const ImplicitProblem& problem, const Eigen::Ref<const Eigen::VectorXd>& y,
              double edge_length, Linearization& out) const;

  /// Keeps `factored` (own, factored at its point) as a lender where it is worth sharing
  /// (worth_sharing), dropping the oldest over the bounds, and makes `out` borrow it at its own
  /// point (the same solves, no copy of the factors). Otherwise `out` is `factored` itself.
  void keep(const ImplicitProblem& problem, Linearization&& factored, Linearization& out);

  /// Keeps a view of `factored` (own, factored at its point) as a lender where it is worth
  /// sharing: its factors shared, not copied, and held while the view is kept.
  void lend(const ImplicitProblem& problem, const Linearization& factored);

 private:
  std::size_t max_count_;
  std::size_t max_bytes_;
  std::size_t bytes_ = 0;
  void push(const ImplicitProblem& problem, std::shared_ptr<const Linearization> lender,
            std::size_t bytes);
  struct Lender {
    std::shared_ptr<const Linearization> linearization;
    std::size_t bytes;
  };
  std::deque<Lender> lenders_;  // oldest first
};

}  // namespace tessera
