// SPDX-License-Identifier: MIT
#include "tessera/core/factorisation_cache.h"

#include <limits>
#include <utility>

namespace tessera {

bool FactorisationLenders::borrow(const ImplicitProblem& problem,
                                  const Eigen::Ref<const Eigen::VectorXd>& y, double edge_length,
                                  Linearization& out) const {
  if (lenders_.empty() || !(edge_length > 0)) {
    return false;
  }
  const AmbientSpace& space = *problem.space();
  const Linearization* nearest = nullptr;
  double nearest_distance = std::numeric_limits<double>::infinity();
  for (auto it = lenders_.rbegin(); it != lenders_.rend(); ++it) {  // newest first on ties
    const double distance = space.distance(it->linearization->point(), y);
    if (distance < nearest_distance) {
      nearest_distance = distance;
      nearest = it->linearization.get();
    }
  }
  return borrow_nearby(problem, *nearest, y, edge_length, out);
}

void FactorisationLenders::keep(const ImplicitProblem& problem, Linearization&& factored,
                                Linearization& out) {
  if (!worth_sharing(factored)) {
    out = std::move(factored);
    return;
  }
  auto lender = std::make_shared<Linearization>(std::move(factored));
  Linearization at_point;
  // Its own point and basis: the oblique correction is the identity, the solves the lender's.
  if (!at_point.borrow(problem, *lender, lender->point(), lender->tangent_basis())) {
    out = std::move(*lender);  // not reached (a basis is never oblique to itself): not kept
    return;
  }
  lender->release_assembly();  // kept for its solves only
  const std::size_t bytes = lender->memory_bytes();
  push(problem, std::move(lender), bytes);
  out = std::move(at_point);
}

void FactorisationLenders::lend(const ImplicitProblem& problem, const Linearization& factored) {
  if (!worth_sharing(factored) || factored.solves_from_elsewhere()) {
    return;
  }
  auto view = std::make_shared<Linearization>();
  if (view->borrow(problem, factored, factored.point(), factored.tangent_basis())) {
    push(problem, std::move(view), factored.memory_bytes());
  }
}

void FactorisationLenders::push(const ImplicitProblem& problem,
                                std::shared_ptr<const Linearization> lender, std::size_t bytes) {
  while (!lenders_.empty() &&
         (lenders_.size() >= max_count_ || (lenders_.size() >= 2 && bytes_ > max_bytes_))) {
    bytes_ -= lenders_.front().bytes;
    lenders_.pop_front();
  }
  if (problem.space()->is_distributed()) {
    bytes = static_cast<std::size_t>(problem.space()->maximum(static_cast<double>(bytes)));
  }
  bytes_ += bytes;
  lenders_.push_back({std::move(lender), bytes});
}

}  // namespace tessera
