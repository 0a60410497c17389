// SPDX-License-Identifier: MIT
#include "tessera/geometry/pinched_vertices.h"

#include <algorithm>

namespace tessera {

std::vector<bool> keep_largest_fans(int vertex_count, const std::vector<Triangle>& triangles) {
  std::vector<bool> keep(triangles.size(), true);
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<std::vector<int>> around(vertex_count);
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      if (keep[t]) {
        for (int v : triangles[t]) {
          around[v].push_back(static_cast<int>(t));
        }
      }
    }
    for (int v = 0; v < vertex_count; ++v) {
      const auto& fan = around[v];
      if (fan.size() < 2) {
        continue;
      }
      // Components of the triangles at v, joined across the edges through v; numbered in the
      // order of their first triangle.
      std::vector<int> component(fan.size(), -1);
      int components = 0;
      for (std::size_t i = 0; i < fan.size(); ++i) {
        if (component[i] >= 0) {
          continue;
        }
        std::vector<std::size_t> stack{i};
        component[i] = components;
        while (!stack.empty()) {
          const std::size_t k = stack.back();
          stack.pop_back();
          for (std::size_t j = 0; j < fan.size(); ++j) {
            if (component[j] >= 0) {
              continue;
            }
            bool shares_edge = false;
            for (int p : triangles[fan[k]]) {
              for (int q : triangles[fan[j]]) {
                shares_edge = shares_edge || (p == q && p != v);
              }
            }
            if (shares_edge) {
              component[j] = components;
              stack.push_back(j);
            }
          }
        }
        ++components;
      }
      if (components < 2) {
        continue;
      }
      std::vector<int> sizes(components, 0);
      for (int c : component) {
        ++sizes[c];
      }
      const int largest =
          static_cast<int>(std::max_element(sizes.begin(), sizes.end()) - sizes.begin());
      for (std::size_t i = 0; i < fan.size(); ++i) {
        if (component[i] != largest) {
          keep[fan[i]] = false;
          changed = true;
        }
      }
    }
  }
  return keep;
}

}  // namespace tessera
