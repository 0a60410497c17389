// SPDX-License-Identifier: MIT
// A fill-reducing column ordering for the sparse LU of a bordered Jacobian: nested dissection
// (METIS) of the symmetrised pattern, with the quasi-dense columns (the parameters') last.
#pragma once

#include <Eigen/SparseCore>
#include <vector>

namespace tessera::detail {

/// Whether this build has METIS (TESSERA_HAS_METIS); without it `nested_dissection_ordering`
/// returns nothing and Eigen's SparseLU keeps COLAMD.
bool has_nested_dissection();

/// The elimination order of A's columns: `order[k]` is the column eliminated k-th.
///
/// Why: on the Jacobian of a discretised 2-D PDE, COLAMD (an ordering of AᵀA for any pivoting)
/// leaves about twice the fill of a nested dissection of A + Aᵀ, which partial pivoting keeps
/// where the diagonal dominates, as it does for the discretised operators tessera factors
/// (bench/history/RESULTS-log.md section 9: bratu2d N = 316, fill 10.6 M → 5.6 M). The graph leaves
/// out the quasi-dense columns, more than max(16, 10√n) entries as in AMD (the parameters λ, ε of a
/// PDE, which every equation contains), and their rows; they are ordered last. So the border rows
/// e_iᵀ, whose rows are those of the parameters, change nothing in the graph, and the ordering of
/// the last graph (per thread) serves every border: METIS runs once per pattern.
///
/// \pre A is square and compressed.
/// \return n column indices, a permutation; empty when METIS is absent or fails.
std::vector<int> nested_dissection_ordering(const Eigen::SparseMatrix<double>& A);

}  // namespace tessera::detail
