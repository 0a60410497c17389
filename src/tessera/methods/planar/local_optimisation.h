// SPDX-License-Identifier: MIT
// Lawson's local optimisation procedure (LOP): swap diagonals of strictly convex
// quadrilaterals until every edge is locally optimal for a criterion.
#pragma once

#include <string>
#include <vector>

#include "tessera/methods/planar/planar_triangulation.h"
#include "tessera/methods/planar/swap_criterion.h"

namespace tessera {

/// When a swap is made (Malcolm section 5(c)). "Equal" means equal within the tolerances.
enum class SwapStrategy {
  Strict,      ///< only on strict improvement; stop after a sweep without swaps
  EqualFirst,  ///< (i): also on equal costs until a sweep whose swaps are all on equalities,
               ///< then strictly until a sweep without swaps
  EqualSweep,  ///< (ii): strictly until a sweep without swaps, then one sweep that also swaps on
               ///< equal costs, then strictly again until a sweep without swaps
};

struct LocalOptimisationOptions {
  CriterionKind criterion = CriterionKind::AngleBetweenNormals;  ///< ABN: best in Malcolm's tables
  CostOrdering ordering =
      CostOrdering::L2;              ///< "ABN-2"; ignored by the max-min angle criteria,
                                     ///< which always compare sorted angles lexicographically
  SwapTest test = SwapTest::Global;  ///< the global test makes every swap lower the total cost
  SwapStrategy strategy = SwapStrategy::Strict;  ///< the simplest; the report does not say
                                                 ///< which of (i), (ii) its tables used
  /// A swap is made only if it improves the compared cost by more than this fraction of it, so
  /// that rounding cannot make two diagonals each look better than the other (cycling).
  double relative_tolerance = 1e-10;
  /// ... and by more than this absolute amount, in the units of the costs (radians for ABN
  /// and the angle criteria, the values' units for PF and PD, values per length for JND,
  /// lengths for MWT). Without it, data that are exactly linear would be swapped on rounding
  /// noise (all ABN costs are then about 1e-16). Data far from O(1) scale may need their own.
  double absolute_tolerance = 1e-12;
  /// Hard stop. With the global test the total cost falls at every swap, so the procedure ends
  /// on its own; the local test has no such guarantee and may need the cap.
  int max_sweeps = 1000;
  /// The order of the triangle list in each sweep: 0 is index order (the report: "going
  /// through the list sequentially"); any other value a fixed pseudo-random permutation drawn
  /// with that seed. The report's results depend on this order, which it does not give.
  unsigned sweep_order_seed = 0;
  bool is_valid(std::string* why) const;
};

enum class LocalOptimisationTermination {
  LocallyOptimal,  ///< a sweep made no swap: every edge is locally optimal (within tolerance)
  SweepLimit,      ///< max_sweeps sweeps were made and the last one still swapped
};

struct LocalOptimisationSummary {
  LocalOptimisationTermination termination = LocalOptimisationTermination::LocallyOptimal;
  int sweeps = 0;  ///< passes over the triangle list, the last one (with no swap) included
  int swaps = 0;
  int equal_swaps = 0;  ///< swaps made on equal costs (strategies EqualFirst, EqualSweep)
  bool is_locally_optimal() const {
    return termination == LocalOptimisationTermination::LocallyOptimal;
  }
  /// e.g. "abn-2 global: 37 swaps in 4 sweeps, locally optimal".
  std::string brief_report() const;
  std::string criterion;  ///< name and ordering, e.g. "abn-2 global"
};

/// Runs Lawson's LOP on `triangulation` (Malcolm section 3): sweeps over the triangles in
/// index order, and for each interior edge of a triangle whose quadrilateral is strictly
/// convex swaps the diagonal when the criterion strictly prefers the other one; after a swap
/// the sweep moves on to the next triangle. Ends after a sweep without swaps.
///
/// \param triangulation updated in place; stays valid (orientation, boundary, vertices kept)
///        whatever the outcome.
/// \throw InvalidArgument if the options are invalid.
/// \return summary; reaching max_sweeps is reported there (SweepLimit), not thrown.
/// \see \cite malcolm_1990 sections 3 and 5; \cite dyn_levin_rippa_1990.
LocalOptimisationSummary optimise_locally(PlanarTriangulation& triangulation,
                                          const LocalOptimisationOptions& options = {});
/// Same with a criterion of the caller's own (the options' `criterion` is ignored).
LocalOptimisationSummary optimise_locally(PlanarTriangulation& triangulation,
                                          const SwapCriterion& criterion,
                                          const LocalOptimisationOptions& options = {});

/// The costs that the LOP compares, for the whole triangulation: for an edge-cost criterion
/// the cost of every interior edge; for a max-min angle criterion the negated angles of every
/// triangle (so that lower is better for both). Sorted into non-increasing order.
std::vector<double> triangulation_costs(const PlanarTriangulation& triangulation,
                                        const SwapCriterion& criterion, CostOrdering norm);

/// Total cost in `ordering`: the l1 sum or the l2 norm of triangulation_costs(); for the
/// lexicographic ordering, the largest entry (the first one compared).
double total_cost(const PlanarTriangulation& triangulation, const SwapCriterion& criterion,
                  CostOrdering ordering);

}  // namespace tessera
