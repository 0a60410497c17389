// SPDX-License-Identifier: MIT
// Which charts' disks may overlap a given disk: a hash grid per radius level (section 6.1's
// quadtree replaced by hashing; O(1) per query for bounded local density, whatever N).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "tessera/geometry/principal_view.h"

namespace tessera {

/// Disks (centre in R^n, radius) bucketed by a 3-D view of the centre (PrincipalView), one grid
/// per power-of-two radius level so that small disks are found in small cells even when other
/// parts of M carry large ones. The view is refitted to the centres as the atlas grows.
class ChartIndex {
 public:
  /// For centres given as this rank's rows of `space` (all of R^n in one process): the view of a
  /// centre is then a reduction, the same on every rank.
  explicit ChartIndex(std::shared_ptr<const AmbientSpace> space);

  void insert(int chart, const Eigen::Ref<const Eigen::VectorXd>& center, double radius);
  /// (chart, radius) of every insert, in order: inserting them again into a new index, with the
  /// same refits, gives the same index (the same candidates in the same order).
  const std::vector<std::pair<int, double>>& inserted() const { return inserted_; }

  /// Whether the view should be refitted now (the number of disks doubled since the last fit).
  bool refit_due() { return schedule_.due(static_cast<int>(inserted_.size())); }
  /// Refits the view to the principal directions of the centres and rehashes every disk.
  /// `centers` (n × count) holds the centre of chart c in column c for every inserted c.
  void refit(const Eigen::Ref<const Eigen::MatrixXd>& centers);

  /// Charts whose disk might overlap the disk (center, radius): a superset of those with
  /// ‖c_j − center‖ < r_j + radius. Appended to `out` (cleared first), in no fixed order.
  void candidates(const Eigen::Ref<const Eigen::VectorXd>& center, double radius,
                  std::vector<int>& out) const;

 private:
  struct Entry {
    int chart;
    double x, y, z;  ///< projected centre, to discard far candidates before the n-D test
  };
  // The occupied cells of a level: open addressing on the cell's key, each cell's disks in the
  // order they were inserted. (std::unordered_map's lookups, a division and two cache misses
  // each, were a tenth of a torus's build: a query looks into 8 to 27 cells.)
  class CellTable {
   public:
    /// The cell's disks, null if it holds none.
    const std::vector<Entry>* find(std::int64_t key) const;
    std::vector<Entry>& operator[](std::int64_t key);
    std::size_t size() const { return cells_.size(); }
    const std::vector<std::vector<Entry>>& cells() const { return cells_; }

   private:
    std::size_t slot_of(std::int64_t key) const;
    void grow();
    std::vector<std::int64_t> keys_;
    std::vector<int> cell_at_;  // per slot: index into cells_, −1 where empty
    std::vector<std::vector<Entry>> cells_;
    int shift_ = 64;
  };
  struct Level {
    double cell_size = 0.0;   ///< 4 × the largest radius of the level
    double max_radius = 0.0;  ///< 2^(level+1): no disk of the level is larger
    CellTable cells;
  };
  static std::int64_t key(std::int64_t i, std::int64_t j, std::int64_t k);
  void hash(int chart, const Eigen::Ref<const Eigen::VectorXd>& center, double radius);

  PrincipalView view_;
  RefitSchedule schedule_;
  std::vector<std::pair<int, double>> inserted_;  // (chart, radius) in insertion order
  std::unordered_map<int, Level> levels_;  // by floor(log2(radius))
};

}  // namespace tessera
