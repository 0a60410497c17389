// SPDX-License-Identifier: MIT
#include "tessera/core/detail/nested_dissection.h"

#include <algorithm>
#include <cmath>

#ifdef TESSERA_HAS_METIS
#include <metis.h>
#endif

namespace tessera::detail {

#ifndef TESSERA_HAS_METIS

bool has_nested_dissection() { return false; }
std::vector<int> nested_dissection_ordering(const Eigen::SparseMatrix<double>&) { return {}; }

#else

bool has_nested_dissection() { return true; }

namespace {

// The adjacency (CSR, no self loops, sorted, no duplicates) of the graph of A + Aᵀ on the
// columns kept, and the order METIS gave it.
struct OrderedGraph {
  std::vector<idx_t> offsets;
  std::vector<idx_t> neighbours;
  std::vector<int> kept;   // graph vertex → column
  std::vector<int> dense;  // the quasi-dense columns, in increasing order
  std::vector<int> order;
};

}  // namespace

std::vector<int> nested_dissection_ordering(const Eigen::SparseMatrix<double>& A) {
  const int n = static_cast<int>(A.cols());
  if (n == 0 || A.rows() != A.cols() || !A.isCompressed()) {
    return {};
  }
  // Degree of every column in A + Aᵀ (counted with repetitions; only the threshold needs it).
  std::vector<int> degree(n, 0);
  for (int column = 0; column < n; ++column) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, column); it; ++it) {
      if (it.row() != column) {
        ++degree[column];
        ++degree[it.row()];
      }
    }
  }
  const double dense_degree = std::max(16.0, 10.0 * std::sqrt(static_cast<double>(n)));
  OrderedGraph graph;
  std::vector<int> vertex_of(n, -1);
  for (int column = 0; column < n; ++column) {
    if (degree[column] > dense_degree) {
      graph.dense.push_back(column);
    } else {
      vertex_of[column] = static_cast<int>(graph.kept.size());
      graph.kept.push_back(column);
    }
  }
  const int m = static_cast<int>(graph.kept.size());
  // Edges both ways, bucketed by vertex, then sorted and made unique per vertex.
  std::vector<idx_t> count(m + 1, 0);
  const auto for_each_edge = [&](auto&& visit) {
    for (int column = 0; column < n; ++column) {
      const int b = vertex_of[column];
      if (b < 0) {
        continue;
      }
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, column); it; ++it) {
        const int a = vertex_of[it.row()];
        if (a >= 0 && a != b) {
          visit(a, b);
          visit(b, a);
        }
      }
    }
  };
  for_each_edge([&](int a, int) { ++count[a + 1]; });
  for (int v = 0; v < m; ++v) {
    count[v + 1] += count[v];
  }
  std::vector<idx_t> neighbours(count[m]);
  std::vector<idx_t> fill(count.begin(), count.end() - 1);
  for_each_edge([&](int a, int b) { neighbours[fill[a]++] = b; });
  graph.offsets.assign(1, 0);
  graph.offsets.reserve(m + 1);
  graph.neighbours.reserve(neighbours.size());
  for (int v = 0; v < m; ++v) {
    auto first = neighbours.begin() + count[v];
    auto last = neighbours.begin() + count[v + 1];
    std::sort(first, last);
    last = std::unique(first, last);
    graph.neighbours.insert(graph.neighbours.end(), first, last);
    graph.offsets.push_back(static_cast<idx_t>(graph.neighbours.size()));
  }

  // The last graph this thread ordered: a covering factors one pattern with many borders.
  thread_local OrderedGraph last;
  if (last.offsets == graph.offsets && last.neighbours == graph.neighbours &&
      last.kept == graph.kept && last.dense == graph.dense && !last.order.empty()) {
    return last.order;
  }

  std::vector<int> order;
  order.reserve(n);
  if (m > 0) {
    idx_t vertices = m;
    idx_t options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_SEED] = 1;  // the same ordering, hence the same mesh, on every run
    std::vector<idx_t> permutation(m), inverse(m);
    // METIS reads the graph but takes non-const pointers.
    if (METIS_NodeND(&vertices, graph.offsets.data(), graph.neighbours.data(), nullptr, options,
                     permutation.data(), inverse.data()) != METIS_OK) {
      return {};
    }
    for (int k = 0; k < m; ++k) {
      order.push_back(graph.kept[permutation[k]]);  // METIS: permutation[new] = old
    }
  }
  order.insert(order.end(), graph.dense.begin(), graph.dense.end());
  graph.order = order;
  last = std::move(graph);
  return order;
}

#endif

}  // namespace tessera::detail
