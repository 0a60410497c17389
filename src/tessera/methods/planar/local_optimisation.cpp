// SPDX-License-Identifier: MIT
// Lawson's local optimisation procedure (LOP): swap diagonals of strictly convex
// quadrilaterals until every edge is locally optimal for a criterion.
#include "tessera/methods/planar/local_optimisation.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <random>
#include <sstream>

#include "tessera/core/error.h"

namespace tessera {
namespace {

struct Tolerance {
  double relative = 0.0;
  double absolute = 0.0;
  // True if a and b differ by more than rounding could explain.
  bool is_distinct(double a, double b) const {
    return std::abs(a - b) > relative * std::max(std::abs(a), std::abs(b)) + absolute;
  }
};

// The outcome of comparing the other diagonal with the present one.
enum class Preference { Better, Equal, Worse };

Preference compare(double after, double before, const Tolerance& tolerance) {
  if (!tolerance.is_distinct(after, before)) {
    return Preference::Equal;
  }
  return after < before ? Preference::Better : Preference::Worse;
}

// Compares cost vectors in `ordering` (lower is better).
Preference compare(std::vector<double>& after, std::vector<double>& before, CostOrdering ordering,
                   const Tolerance& tolerance) {
  switch (ordering) {
    case CostOrdering::L1: {
      double sum_after = 0.0;
      double sum_before = 0.0;
      for (double s : after) {
        sum_after += std::abs(s);
      }
      for (double s : before) {
        sum_before += std::abs(s);
      }
      return compare(sum_after, sum_before, tolerance);
    }
    case CostOrdering::L2: {
      double sum_after = 0.0;
      double sum_before = 0.0;
      for (double s : after) {
        sum_after += s * s;
      }
      for (double s : before) {
        sum_before += s * s;
      }
      return compare(std::sqrt(sum_after), std::sqrt(sum_before), tolerance);
    }
    case CostOrdering::Lexicographic: {
      std::sort(after.begin(), after.end(), std::greater<>());
      std::sort(before.begin(), before.end(), std::greater<>());
      for (std::size_t i = 0; i < std::min(after.size(), before.size()); ++i) {
        if (tolerance.is_distinct(after[i], before[i])) {
          return after[i] < before[i] ? Preference::Better : Preference::Worse;
        }
      }
      return Preference::Equal;
    }
  }
  return Preference::Equal;
}

int local_edge(const PlanarTriangulation& triangulation, int t, int from, int to) {
  const Triangle& tri = triangulation.triangle(t);
  for (int k = 0; k < 3; ++k) {
    if (tri[k] == from && tri[(k + 1) % 3] == to) {
      return k;
    }
  }
  TESSERA_ASSERT(false);
  return -1;
}

// Far vertex across the directed edge from→to of triangle t, or -1 on the boundary.
int far_vertex(const PlanarTriangulation& triangulation, int t, int from, int to) {
  const int k = local_edge(triangulation, t, from, to);
  return triangulation.is_interior_edge(t, k) ? triangulation.quadrilateral(t, k).d : -1;
}

class Optimiser {
 public:
  Optimiser(PlanarTriangulation& triangulation, const SwapCriterion& criterion,
            const LocalOptimisationOptions& options)
      : triangulation_(triangulation),
        criterion_(criterion),
        options_(options),
        tolerance_{options.relative_tolerance, options.absolute_tolerance} {}

  // How the other diagonal of the quadrilateral of (t, k) compares with the present one.
  Preference preference(int t, int k) {
    const EdgeQuadrilateral q = triangulation_.quadrilateral(t, k);
    before_.clear();
    after_.clear();
    if (criterion_.kind() == SwapCriterion::Kind::TriangleAngles) {
      // Max-min angle: compare the six angles, smallest first (negated, so lower is better).
      append_angles(before_, q.a, q.b, q.c);
      append_angles(before_, q.b, q.a, q.d);
      append_angles(after_, q.c, q.a, q.d);
      append_angles(after_, q.d, q.b, q.c);
      return compare(after_, before_, CostOrdering::Lexicographic, tolerance_);
    }
    // After the swap the diagonal runs d→c with (d, c, a) on its left and (c, d, b) on its right.
    before_.push_back(cost({q.a, q.b, q.c, q.d}));
    after_.push_back(cost({q.d, q.c, q.a, q.b}));
    if (options_.test == SwapTest::Global) {
      const int u = triangulation_.neighbour(t, k);
      // Each outer edge keeps its outer triangle; its inner triangle changes from the old
      // one to the new one, whose third vertex is the other end of the new diagonal.
      add_outer_edge(far_vertex(triangulation_, t, q.b, q.c), q.b, q.c, q.a, q.d);
      add_outer_edge(far_vertex(triangulation_, t, q.c, q.a), q.c, q.a, q.b, q.d);
      add_outer_edge(far_vertex(triangulation_, u, q.a, q.d), q.a, q.d, q.b, q.c);
      add_outer_edge(far_vertex(triangulation_, u, q.d, q.b), q.d, q.b, q.a, q.c);
    }
    return compare(after_, before_, options_.ordering, tolerance_);
  }

 private:
  double cost(const EdgeQuadrilateral& q) const {
    return criterion_.edge_cost(triangulation_, q, options_.ordering);
  }
  void append_angles(std::vector<double>& out, int a, int b, int c) const {
    for (double angle : criterion_.triangle_angles(triangulation_, a, b, c)) {
      out.push_back(-angle);
    }
  }
  // The outer edge from→to with outer vertex `outer` (-1: boundary, no cost), inner vertex
  // `inner_before` before the swap and `inner_after` after it.
  void add_outer_edge(int outer, int from, int to, int inner_before, int inner_after) {
    if (outer < 0) {
      return;
    }
    before_.push_back(cost({from, to, inner_before, outer}));
    after_.push_back(cost({from, to, inner_after, outer}));
  }

  PlanarTriangulation& triangulation_;
  const SwapCriterion& criterion_;
  const LocalOptimisationOptions& options_;
  Tolerance tolerance_;
  std::vector<double> before_;
  std::vector<double> after_;
};

std::string ordering_suffix(CostOrdering ordering) {
  switch (ordering) {
    case CostOrdering::L1:
      return "-1";
    case CostOrdering::L2:
      return "-2";
    case CostOrdering::Lexicographic:
      return "-lex";
  }
  return "";
}

}  // namespace

bool LocalOptimisationOptions::is_valid(std::string* why) const {
  std::ostringstream message;
  if (!(relative_tolerance >= 0 && relative_tolerance < 1)) {
    message << "LocalOptimisationOptions::relative_tolerance = " << relative_tolerance
            << " must be in [0, 1)";
  } else if (!(absolute_tolerance >= 0 && std::isfinite(absolute_tolerance))) {
    message << "LocalOptimisationOptions::absolute_tolerance = " << absolute_tolerance
            << " must be finite and >= 0";
  } else if (max_sweeps < 1) {
    message << "LocalOptimisationOptions::max_sweeps = " << max_sweeps << " must be >= 1";
  } else {
    return true;
  }
  if (why != nullptr) {
    *why = message.str();
  }
  return false;
}

std::string LocalOptimisationSummary::brief_report() const {
  std::ostringstream out;
  out << criterion << ": " << swaps << " swaps in " << sweeps << " sweeps, "
      << (is_locally_optimal() ? "locally optimal" : "stopped at the sweep limit");
  return out.str();
}

LocalOptimisationSummary optimise_locally(PlanarTriangulation& triangulation,
                                          const LocalOptimisationOptions& options) {
  return optimise_locally(triangulation, *make_criterion(options.criterion), options);
}

LocalOptimisationSummary optimise_locally(PlanarTriangulation& triangulation,
                                          const SwapCriterion& criterion,
                                          const LocalOptimisationOptions& options) {
  std::string why;
  TESSERA_CHECK(options.is_valid(&why), why);
  LocalOptimisationSummary summary;
  summary.criterion = criterion.name();
  if (criterion.kind() == SwapCriterion::Kind::EdgeCost) {
    summary.criterion += ordering_suffix(options.ordering);
    summary.criterion += options.test == SwapTest::Global ? " global" : " local";
  }
  Optimiser optimiser(triangulation, criterion, options);
  // Swapping on equal costs (strategies i and ii) can undo itself, so it is confined: to the
  // first sweeps, until a sweep swaps only on equalities (i), or to one sweep after the
  // strict swaps have run out (ii). Every other sweep swaps on strict improvement only.
  std::vector<int> order(triangulation.triangle_count());
  std::iota(order.begin(), order.end(), 0);
  if (options.sweep_order_seed != 0) {
    std::mt19937 generator(options.sweep_order_seed);
    std::shuffle(order.begin(), order.end(), generator);
  }
  bool is_equal_allowed = options.strategy == SwapStrategy::EqualFirst;
  bool is_equal_sweep_done = false;
  for (;;) {
    if (summary.sweeps == options.max_sweeps) {
      summary.termination = LocalOptimisationTermination::SweepLimit;
      break;
    }
    ++summary.sweeps;
    int swaps_in_sweep = 0;
    int equal_swaps_in_sweep = 0;
    for (const int t : order) {  // swaps keep triangle indices, so the order stays valid
      for (int k = 0; k < 3; ++k) {
        if (!triangulation.is_swap_valid(t, k)) {
          continue;
        }
        const Preference preference = optimiser.preference(t, k);
        if (preference == Preference::Better ||
            (is_equal_allowed && preference == Preference::Equal)) {
          triangulation.swap(t, k);
          ++swaps_in_sweep;
          equal_swaps_in_sweep += preference == Preference::Equal ? 1 : 0;
          break;  // "jump to the next triangle in the list" (Malcolm 5(b))
        }
      }
    }
    summary.swaps += swaps_in_sweep;
    summary.equal_swaps += equal_swaps_in_sweep;
    if (is_equal_allowed) {
      if (options.strategy == SwapStrategy::EqualSweep || swaps_in_sweep == equal_swaps_in_sweep) {
        is_equal_allowed = false;
      }
      continue;
    }
    if (swaps_in_sweep == 0) {
      if (options.strategy == SwapStrategy::EqualSweep && !is_equal_sweep_done) {
        is_equal_allowed = true;
        is_equal_sweep_done = true;
        continue;
      }
      summary.termination = LocalOptimisationTermination::LocallyOptimal;
      break;
    }
  }
  TESSERA_EXPENSIVE_ASSERT(triangulation.is_valid());
  return summary;
}

std::vector<double> triangulation_costs(const PlanarTriangulation& triangulation,
                                        const SwapCriterion& criterion, CostOrdering norm) {
  std::vector<double> costs;
  for (int t = 0; t < triangulation.triangle_count(); ++t) {
    const Triangle& tri = triangulation.triangle(t);
    if (criterion.kind() == SwapCriterion::Kind::TriangleAngles) {
      for (double angle : criterion.triangle_angles(triangulation, tri[0], tri[1], tri[2])) {
        costs.push_back(-angle);
      }
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      // Each interior edge once: from the triangle that traverses it upwards.
      if (triangulation.is_interior_edge(t, k) && tri[k] < tri[(k + 1) % 3]) {
        costs.push_back(
            criterion.edge_cost(triangulation, triangulation.quadrilateral(t, k), norm));
      }
    }
  }
  std::sort(costs.begin(), costs.end(), std::greater<>());
  return costs;
}

double total_cost(const PlanarTriangulation& triangulation, const SwapCriterion& criterion,
                  CostOrdering ordering) {
  const std::vector<double> costs = triangulation_costs(triangulation, criterion, ordering);
  switch (ordering) {
    case CostOrdering::L1: {
      double sum = 0.0;
      for (double s : costs) {
        sum += std::abs(s);
      }
      return sum;
    }
    case CostOrdering::L2: {
      double sum = 0.0;
      for (double s : costs) {
        sum += s * s;
      }
      return std::sqrt(sum);
    }
    case CostOrdering::Lexicographic:
      return costs.empty() ? 0.0 : costs.front();
  }
  return 0.0;
}

}  // namespace tessera
