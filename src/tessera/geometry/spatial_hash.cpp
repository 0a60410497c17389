// SPDX-License-Identifier: MIT
#include "tessera/geometry/spatial_hash.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>

#include "tessera/core/error.h"
#include "tessera/core/parallel_for.h"
#include "tessera/geometry/principal_view.h"

namespace tessera {
namespace {

constexpr int view_dimension = 3;
using ViewPoint = std::array<double, view_dimension>;

struct ViewBox {
  ViewPoint lower;
  ViewPoint upper;
  double extent() const {
    double e = 0.0;
    for (int j = 0; j < view_dimension; ++j) {
      e = std::max(e, upper[j] - lower[j]);
    }
    return e;
  }
};

bool boxes_overlap(const ViewBox& a, const ViewBox& b) {
  for (int j = 0; j < view_dimension; ++j) {
    if (a.upper[j] < b.lower[j] || b.upper[j] < a.lower[j]) {
      return false;
    }
  }
  return true;
}

// The enlarged boxes in R^n overlap; O(n), computed from the vertices so that no n×N box
// array is stored (n may be 10⁵).
bool ambient_boxes_overlap(const Eigen::Ref<const Eigen::MatrixXd>& points, const Triangle& a,
                           double margin_a, const Triangle& b, double margin_b) {
  // Triangles with a common vertex overlap without looking: most candidate pairs are such
  // neighbours, and at large n this O(n) scan was 7 % of a front run's time (bvp, n = 3002).
  for (int v : a) {
    if (v == b[0] || v == b[1] || v == b[2]) {
      return true;
    }
  }
  const double margin = margin_a + margin_b;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const double a_lower = std::min({points(i, a[0]), points(i, a[1]), points(i, a[2])});
    const double a_upper = std::max({points(i, a[0]), points(i, a[1]), points(i, a[2])});
    const double b_lower = std::min({points(i, b[0]), points(i, b[1]), points(i, b[2])});
    const double b_upper = std::max({points(i, b[0]), points(i, b[1]), points(i, b[2])});
    if (a_upper + margin < b_lower || b_upper + margin < a_lower) {
      return false;
    }
  }
  return true;
}

// 64-bit mix of (level, cell coordinates) (SplitMix64's finaliser). Two cells with the same
// key only add candidates, which the box tests then reject, so the key need not be injective.
std::uint64_t cell_key(int level, const std::array<std::int64_t, view_dimension>& cell) {
  std::uint64_t h = static_cast<std::uint64_t>(level) * 0x9e3779b97f4a7c15ULL;
  for (std::int64_t c : cell) {
    h ^= static_cast<std::uint64_t>(c) + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
    h ^= h >> 30;
    h *= 0xbf58476d1ce4e5b9ULL;
    h ^= h >> 27;
    h *= 0x94d049bb133111ebULL;
    h ^= h >> 31;
  }
  return h;
}

// Open-addressing table from cell keys to singly linked lists of entries (triangles).
class CellTable {
 public:
  explicit CellTable(std::size_t entries) {
    const std::size_t size = std::bit_ceil(std::max<std::size_t>(16, 2 * entries));
    mask_ = size - 1;
    keys_.resize(size);
    heads_.assign(size, -1);
    next_.reserve(entries);
    triangle_.reserve(entries);
  }
  void insert(std::uint64_t key, int triangle) {
    const std::size_t slot = find_slot(key);
    keys_[slot] = key;
    next_.push_back(heads_[slot]);
    triangle_.push_back(triangle);
    heads_[slot] = static_cast<int>(triangle_.size()) - 1;
  }
  /// First entry of the cell, −1 if empty; then next(entry) until −1.
  int first(std::uint64_t key) const { return heads_[find_slot(key)]; }
  int next(int entry) const { return next_[entry]; }
  int triangle(int entry) const { return triangle_[entry]; }

 private:
  std::size_t find_slot(std::uint64_t key) const {
    std::size_t slot = key & mask_;
    while (heads_[slot] != -1 && keys_[slot] != key) {
      slot = (slot + 1) & mask_;
    }
    return slot;
  }
  std::size_t mask_ = 0;
  std::vector<std::uint64_t> keys_;
  std::vector<int> heads_;
  std::vector<int> next_;
  std::vector<int> triangle_;
};

}  // namespace

std::vector<std::pair<int, int>> nearby_triangle_pairs(
    const Eigen::Ref<const Eigen::MatrixXd>& points, std::span<const Triangle> triangles,
    std::span<const double> margins, std::shared_ptr<const AmbientSpace> space) {
  TESSERA_CHECK(margins.size() == triangles.size(),
                "nearby_triangle_pairs: " << margins.size() << " margins for " << triangles.size()
                                          << " triangles");
  const int triangle_count = static_cast<int>(triangles.size());
  // The view is fitted to a sample of the points (the spread is what the grid needs) and every
  // vertex is projected once: at large n these are the O(n) parts of the search.
  PrincipalView view = space && space->is_distributed()
                           ? PrincipalView(space)
                           : PrincipalView(static_cast<int>(points.rows()));
  view.fit_sample(static_cast<int>(points.cols()), [&](int v) { return points.col(v); });
  const Eigen::Matrix3Xd projected = view.project(points);
  std::vector<ViewBox> boxes(triangle_count);
  double smallest_extent = std::numeric_limits<double>::infinity();
  double largest_coordinate = 0.0;
  for (int t = 0; t < triangle_count; ++t) {
    if (margins[t] < 0) {
      continue;
    }
    ViewBox& box = boxes[t];
    box.lower.fill(std::numeric_limits<double>::infinity());
    box.upper.fill(-std::numeric_limits<double>::infinity());
    for (int v : triangles[t]) {
      const ViewPoint y{projected(0, v), projected(1, v), projected(2, v)};
      for (int j = 0; j < view_dimension; ++j) {
        box.lower[j] = std::min(box.lower[j], y[j] - margins[t]);
        box.upper[j] = std::max(box.upper[j], y[j] + margins[t]);
        largest_coordinate =
            std::max({largest_coordinate, std::abs(box.lower[j]), std::abs(box.upper[j])});
      }
    }
    if (box.extent() > 0) {
      smallest_extent = std::min(smallest_extent, box.extent());
    }
  }
  // The finest cell side c: the smallest box, but not below 1e-12 of the coordinates' scale,
  // so that cell coordinates x/c stay far inside the range of 64-bit integers.
  const double finest_cell =
      std::isfinite(smallest_extent)
          ? std::max(smallest_extent, 1e-12 * std::max(1.0, largest_coordinate))
          : 1.0;
  std::vector<int> level(triangle_count, -1);
  int level_count = 0;
  for (int t = 0; t < triangle_count; ++t) {
    if (margins[t] < 0) {
      continue;
    }
    // The smallest ℓ with c·2^ℓ ≥ extent; the box then touches at most 2 cells per axis.
    const double ratio = boxes[t].extent() / finest_cell;
    level[t] = ratio <= 1.0 ? 0 : static_cast<int>(std::ceil(std::log2(ratio)));
    while (std::ldexp(finest_cell, level[t]) < boxes[t].extent()) {
      ++level[t];  // log2 rounding
    }
    level_count = std::max(level_count, level[t] + 1);
  }
  std::vector<std::uint8_t> is_level_used(level_count, 0);
  for (int t = 0; t < triangle_count; ++t) {
    if (level[t] >= 0) {
      is_level_used[level[t]] = 1;
    }
  }
  std::vector<int> used_levels;
  for (int l = 0; l < level_count; ++l) {
    if (is_level_used[l]) {
      used_levels.push_back(l);
    }
  }

  // Each triangle is stored once, in the cell of its level that holds its box's lower corner.
  // A partner t on level l ≥ level(s) whose box meets s's box has its lower corner in
  // [s.lower − side, s.upper] (its extent is at most the side), at most 3 cells per axis.
  auto cell_of = [&](const ViewBox& box, int l) {
    const double side = std::ldexp(finest_cell, l);
    std::array<std::int64_t, view_dimension> cell;
    for (int j = 0; j < view_dimension; ++j) {
      cell[j] = static_cast<std::int64_t>(std::floor(box.lower[j] / side));
    }
    return cell_key(l, cell);
  };
  // Calls visit(key) for each cell of level l where a partner of `box` can be stored.
  auto for_each_cell = [&](const ViewBox& box, int l, auto&& visit) {
    const double side = std::ldexp(finest_cell, l);
    std::array<std::int64_t, view_dimension> first;
    std::array<std::int64_t, view_dimension> last;
    for (int j = 0; j < view_dimension; ++j) {
      first[j] = static_cast<std::int64_t>(std::floor(box.lower[j] / side)) - 1;
      last[j] = static_cast<std::int64_t>(std::floor(box.upper[j] / side));
    }
    std::array<std::int64_t, view_dimension> cell;
    for (cell[0] = first[0]; cell[0] <= last[0]; ++cell[0]) {
      for (cell[1] = first[1]; cell[1] <= last[1]; ++cell[1]) {
        for (cell[2] = first[2]; cell[2] <= last[2]; ++cell[2]) {
          visit(cell_key(l, cell));
        }
      }
    }
  };

  CellTable table(static_cast<std::size_t>(triangle_count));
  for (int t = 0; t < triangle_count; ++t) {
    if (level[t] >= 0) {
      table.insert(cell_of(boxes[t], level[t]), t);
    }
  }

  // A split mesh: each rank tests its rows of the ambient boxes, and a pair is kept where no
  // rank separates it (one reduction over all candidates at the end).
  const bool split = space != nullptr && space->is_distributed();
  // Dedupes the cells that share a key: per thread, the stamp of the last triangle s whose
  // search met t, (call, s), so that no entry of an earlier call matches (kept between calls:
  // 8 bytes a triangle per thread).
  static std::atomic<std::uint64_t> calls{0};
  const std::uint64_t call = calls.fetch_add(1, std::memory_order_relaxed) + 1;
  // The partners of triangle s, appended to `found` (with each candidate's verdict in
  // `separated` for a split mesh).
  const auto partners_of = [&](int s, std::vector<std::pair<int, int>>& found,
                               std::vector<double>& separated) {
    thread_local std::vector<std::uint64_t> last_seen_by;
    if (last_seen_by.size() < static_cast<std::size_t>(triangle_count)) {
      last_seen_by.resize(static_cast<std::size_t>(triangle_count), 0);
    }
    const std::uint64_t stamp = (call << 32) | static_cast<std::uint32_t>(s);
    for (int l : used_levels) {
      if (l < level[s]) {
        continue;
      }
      for_each_cell(boxes[s], l, [&](std::uint64_t key) {
        for (int entry = table.first(key); entry != -1; entry = table.next(entry)) {
          const int t = table.triangle(entry);
          // Each pair once: by its member on the finer level, or by the smaller index.
          std::uint64_t& seen = last_seen_by[static_cast<std::size_t>(t)];
          if (level[t] != l || (level[t] == level[s] && t <= s) || seen == stamp) {
            continue;
          }
          seen = stamp;
          if (!boxes_overlap(boxes[s], boxes[t])) {
            continue;
          }
          const bool overlap =
              ambient_boxes_overlap(points, triangles[s], margins[s], triangles[t], margins[t]);
          if (split) {
            found.emplace_back(std::min(s, t), std::max(s, t));
            separated.push_back(overlap ? 0.0 : 1.0);
          } else if (overlap) {
            found.emplace_back(std::min(s, t), std::max(s, t));
          }
        }
      });
    }
  };
  // The table is only read from here on: blocks of triangles look for their partners on
  // threads, and the blocks' pairs are joined in order, as one loop over s finds them. (A split
  // mesh's ambient test is a sum over the ranks: one thread, in order.)
  constexpr int kTrianglesPerBlock = 4096;
  const int blocks = (triangle_count + kTrianglesPerBlock - 1) / kTrianglesPerBlock;
  std::vector<std::vector<std::pair<int, int>>> block_pairs(static_cast<std::size_t>(blocks));
  std::vector<std::vector<double>> block_separated(static_cast<std::size_t>(blocks));
  parallel_for(blocks, split ? 1 : thread_count(), [&](int b) {
    const int end = std::min(triangle_count, (b + 1) * kTrianglesPerBlock);
    for (int s = b * kTrianglesPerBlock; s < end; ++s) {
      if (level[s] >= 0) {
        partners_of(s, block_pairs[static_cast<std::size_t>(b)],
                    block_separated[static_cast<std::size_t>(b)]);
      }
    }
  });
  std::vector<std::pair<int, int>> pairs;
  std::vector<double> separated;  // per candidate pair (split meshes): ranks that separate it
  for (int b = 0; b < blocks; ++b) {
    const auto& found = block_pairs[static_cast<std::size_t>(b)];
    pairs.insert(pairs.end(), found.begin(), found.end());
    const auto& verdicts = block_separated[static_cast<std::size_t>(b)];
    separated.insert(separated.end(), verdicts.begin(), verdicts.end());
  }
  if (split && !pairs.empty()) {
    space->sum(separated.data(), static_cast<int>(separated.size()));
    std::size_t kept = 0;
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      if (separated[k] == 0.0) {
        pairs[kept++] = pairs[k];
      }
    }
    pairs.resize(kept);
  }
  return pairs;
}

}  // namespace tessera
