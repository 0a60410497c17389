// SPDX-License-Identifier: MIT
// Points of R^n as the columns of one contiguous n×N array that grows without copying.
#pragma once

#include <Eigen/Core>
#include <cstddef>

namespace tessera {

/// The columns of an n×N column-major array of doubles, appended one at a time.
///
/// At large n the points are most of a run's memory, and a std::vector that doubles its
/// capacity holds the old and the new array at once while it copies: twice the points, and the
/// copy's time. Here an array of at least kMappedBytes is a mapping of its own that grows by
/// moving pages (mremap on Linux), never by copying them, and pages of capacity not yet
/// written cost no memory. Smaller arrays, and other systems, grow by realloc.
///
/// Copies are deep; a move hands the array over (the atlas's chart centres become the mesh's
/// vertices so, without a copy).
class PointStorage {
 public:
  /// Arrays of this many bytes or more are mapped (Linux).
  static constexpr std::size_t kMappedBytes = std::size_t{1} << 22;

  PointStorage() = default;
  explicit PointStorage(int dimension) : dimension_(dimension) {}
  PointStorage(const PointStorage& other);
  PointStorage(PointStorage&& other) noexcept;
  PointStorage& operator=(const PointStorage& other);
  PointStorage& operator=(PointStorage&& other) noexcept;
  ~PointStorage();

  int dimension() const { return dimension_; }
  int size() const { return columns_; }
  bool empty() const { return columns_ == 0; }
  const double* data() const { return data_; }
  double* data() { return data_; }

  Eigen::Map<const Eigen::MatrixXd> matrix() const { return {data_, dimension_, columns_}; }
  Eigen::Map<const Eigen::VectorXd> column(int j) const {
    return {data_ + static_cast<std::ptrdiff_t>(j) * dimension_, dimension_};
  }
  Eigen::Map<Eigen::VectorXd> column(int j) {
    return {data_ + static_cast<std::ptrdiff_t>(j) * dimension_, dimension_};
  }

  /// Appends x as the last column. \pre x.size() == dimension().
  void push_back(const Eigen::Ref<const Eigen::VectorXd>& x);
  /// Room for `columns` columns in all without moving the array again.
  void reserve(int columns);
  /// Keeps the first `columns` columns (or appends uninitialised ones). A large array that
  /// shrinks returns its pages to the system.
  void resize(int columns);
  /// Moves column `from` to `to` (≤ from): compaction in place.
  void move_column(int from, int to);

 private:
  void grow_to(std::size_t capacity_columns);
  void release();

  int dimension_ = 0;
  int columns_ = 0;
  std::size_t capacity_ = 0;      // in columns
  double* data_ = nullptr;
  std::size_t mapped_bytes_ = 0;  // the mapping's length; 0 if the array is malloc'ed
};

}  // namespace tessera
