// SPDX-License-Identifier: MIT
// The rows of `tessera ddt --all-criteria` and Malcolm's published errors beside them
// (--compare-report), shared by the CLI (apps/tessera/ddt_command.cpp) and the bindings
// (python/src/ddt.cpp).
#pragma once

#include <cstddef>
#include <iterator>

#include "tessera/methods/planar/franke_functions.h"
#include "tessera/methods/planar/swap_criterion.h"

namespace tessera {

/// One row of the --all-criteria table: a criterion with its cost-vector ordering.
struct AllCriteriaRow {
  const char* criterion;  ///< as --criterion spells it
  CostOrdering ordering;
  const char* norm;  ///< as --norm spells it
};

/// Malcolm's table rows: DELAUNAY, MWT-3D, ABN-1, ABN-2, JND-1, JND-2, PF-1, PF-2, PD-1, PD-2,
/// EQUID (equid needs a function: its criterion uses the second derivatives).
inline constexpr AllCriteriaRow kAllCriteriaRows[] = {
    {"delaunay", CostOrdering::L2, "l2"}, {"mwt3d", CostOrdering::L2, "l2"},
    {"abn", CostOrdering::L1, "l1"},      {"abn", CostOrdering::L2, "l2"},
    {"jnd", CostOrdering::L1, "l1"},      {"jnd", CostOrdering::L2, "l2"},
    {"pf", CostOrdering::L1, "l1"},       {"pf", CostOrdering::L2, "l2"},
    {"pd", CostOrdering::L1, "l1"},       {"pd", CostOrdering::L2, "l2"},
    {"equid", CostOrdering::L2, "l2"}};
inline constexpr std::size_t kAllCriteriaRowCount = std::size(kAllCriteriaRows);

// Malcolm's Tables 1 (33 points) and 2 (100 points): mean pointwise error, rows in the order of
// kAllCriteriaRows; columns F1, F2, F7, F8, F9.
inline constexpr double kMalcolmTable1[11][5] = {
    {0.04886, 0.01604, 0.06866, 0.15210, 0.05042}, {0.05813, 0.01585, 0.06019, 0.09926, 0.04826},
    {0.04033, 0.00619, 0.04210, 0.13123, 0.04633}, {0.03964, 0.00610, 0.04096, 0.07723, 0.04702},
    {0.04033, 0.01176, 0.04562, 0.10457, 0.04639}, {0.04532, 0.01107, 0.04922, 0.10456, 0.04635},
    {0.04285, 0.00618, 0.04342, 0.14730, 0.04650}, {0.04661, 0.01190, 0.05737, 0.15113, 0.04683},
    {0.05255, 0.00618, 0.04267, 0.11505, 0.04737}, {0.05379, 0.01188, 0.04790, 0.11513, 0.04750},
    {0.04541, 0.00614, 0.06601, 0.10472, 0.04697}};
inline constexpr double kMalcolmTable2[11][5] = {
    {0.01637, 0.00419, 0.02707, 0.04033, 0.01492}, {0.02002, 0.00366, 0.02869, 0.01884, 0.01249},
    {0.01546, 0.00145, 0.02027, 0.01390, 0.01101}, {0.01550, 0.00147, 0.01727, 0.02839, 0.01075},
    {0.01571, 0.00145, 0.02207, 0.02961, 0.01097}, {0.01533, 0.00151, 0.02099, 0.03034, 0.01079},
    {0.01563, 0.00145, 0.01881, 0.03011, 0.01137}, {0.01634, 0.00182, 0.02000, 0.03162, 0.01115},
    {0.01600, 0.00145, 0.02374, 0.02557, 0.01113}, {0.01670, 0.00152, 0.02576, 0.02505, 0.01079},
    {0.02070, 0.00358, 0.02675, 0.03805, 0.01639}};

/// Malcolm's mean error for row `row` of kAllCriteriaRows and `function`, from Table 1
/// (`points` = 33) or Table 2 (`points` = 100).
inline double malcolm_table_value(int points, std::size_t row, FrankeFunction function) {
  int column = 0;
  switch (function) {
    case FrankeFunction::F1:
      column = 0;
      break;
    case FrankeFunction::F2:
      column = 1;
      break;
    case FrankeFunction::F7:
      column = 2;
      break;
    case FrankeFunction::F8:
      column = 3;
      break;
    case FrankeFunction::F9:
      column = 4;
      break;
  }
  return points == 100 ? kMalcolmTable2[row][column] : kMalcolmTable1[row][column];
}

/// The report prints 5 decimals: a value within half a unit of the last one of the spread
/// [lowest, highest] of the sweep orders counts as in it.
inline bool is_in_spread(double value, double lowest, double highest) {
  return value >= lowest - 0.5e-5 && value <= highest + 0.5e-5;
}

}  // namespace tessera
