// SPDX-License-Identifier: MIT
#include "tessera/core/point_storage.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <new>
#include <utility>

#include "tessera/core/error.h"

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#define TESSERA_POINT_STORAGE_MREMAP 1
#endif

namespace tessera {

PointStorage::PointStorage(const PointStorage& other) : dimension_(other.dimension_) {
  reserve(other.columns_);
  columns_ = other.columns_;
  if (columns_ > 0) {
    std::memcpy(data_, other.data_,
                static_cast<std::size_t>(columns_) * dimension_ * sizeof(double));
  }
}

PointStorage::PointStorage(PointStorage&& other) noexcept
    : dimension_(other.dimension_),
      columns_(std::exchange(other.columns_, 0)),
      capacity_(std::exchange(other.capacity_, 0)),
      data_(std::exchange(other.data_, nullptr)),
      mapped_bytes_(std::exchange(other.mapped_bytes_, 0)) {}

PointStorage& PointStorage::operator=(const PointStorage& other) {
  if (this != &other) {
    *this = PointStorage(other);
  }
  return *this;
}

PointStorage& PointStorage::operator=(PointStorage&& other) noexcept {
  if (this != &other) {
    release();
    dimension_ = other.dimension_;
    columns_ = std::exchange(other.columns_, 0);
    capacity_ = std::exchange(other.capacity_, 0);
    data_ = std::exchange(other.data_, nullptr);
    mapped_bytes_ = std::exchange(other.mapped_bytes_, 0);
  }
  return *this;
}

PointStorage::~PointStorage() { release(); }

void PointStorage::release() {
#if defined(TESSERA_POINT_STORAGE_MREMAP)
  if (mapped_bytes_ > 0) {
    munmap(data_, mapped_bytes_);
  } else {
    std::free(data_);
  }
#else
  std::free(data_);
#endif
  data_ = nullptr;
  capacity_ = 0;
  mapped_bytes_ = 0;
}

// Room for `capacity_columns` columns (more or fewer than now, never fewer than columns_).
void PointStorage::grow_to(std::size_t capacity_columns) {
  const std::size_t column_bytes = static_cast<std::size_t>(dimension_) * sizeof(double);
  const std::size_t bytes = capacity_columns * column_bytes;
#if defined(TESSERA_POINT_STORAGE_MREMAP)
  if (bytes >= kMappedBytes || mapped_bytes_ > 0) {
    // Once mapped, an array stays mapped (at least kMappedBytes long): growing and shrinking
    // move or drop pages, never copy them.
    static const std::size_t page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
    const std::size_t length = (std::max(bytes, kMappedBytes) + page - 1) / page * page;
    void* mapped = MAP_FAILED;
    if (mapped_bytes_ > 0) {
      mapped = mremap(data_, mapped_bytes_, length, MREMAP_MAYMOVE);
    } else {
      mapped = mmap(nullptr, length, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
      if (mapped != MAP_FAILED && data_ != nullptr) {
        std::memcpy(mapped, data_, static_cast<std::size_t>(columns_) * column_bytes);
        std::free(data_);
      }
    }
    if (mapped == MAP_FAILED) {
      throw std::bad_alloc();
    }
    data_ = static_cast<double*>(mapped);
    mapped_bytes_ = length;
    capacity_ = length / column_bytes;
    return;
  }
#endif
  void* grown = std::realloc(data_, std::max<std::size_t>(bytes, 1));
  if (grown == nullptr) {
    throw std::bad_alloc();
  }
  data_ = static_cast<double*>(grown);
  capacity_ = capacity_columns;
}

void PointStorage::reserve(int columns) {
  if (dimension_ > 0 && static_cast<std::size_t>(columns) > capacity_) {
    grow_to(static_cast<std::size_t>(columns));
  }
}

void PointStorage::push_back(const Eigen::Ref<const Eigen::VectorXd>& x) {
  TESSERA_CHECK(x.size() == dimension_,
                "point has " << x.size() << " coordinates, the storage is in R^" << dimension_);
  if (static_cast<std::size_t>(columns_) == capacity_) {
    grow_to(std::max<std::size_t>(16, 2 * capacity_));
  }
  column(columns_++) = x;
}

void PointStorage::resize(int columns) {
  TESSERA_CHECK(columns >= 0, "PointStorage::resize(" << columns << "): must be >= 0");
  if (dimension_ == 0) {
    columns_ = columns;
    return;
  }
  if (static_cast<std::size_t>(columns) > capacity_) {
    grow_to(static_cast<std::size_t>(columns));
  } else if (mapped_bytes_ > 0 && static_cast<std::size_t>(columns) < capacity_ / 2) {
    columns_ = std::min(columns_, columns);
    grow_to(static_cast<std::size_t>(columns));  // give the pages back
  }
  columns_ = columns;
}

void PointStorage::move_column(int from, int to) {
  if (from != to) {
    std::memmove(data_ + static_cast<std::ptrdiff_t>(to) * dimension_,
                 data_ + static_cast<std::ptrdiff_t>(from) * dimension_,
                 static_cast<std::size_t>(dimension_) * sizeof(double));
  }
}

}  // namespace tessera
