// SPDX-License-Identifier: MIT
#include "tessera/core/process_memory.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace {

// The resident set follows pages touched and given back.
TEST(ProcessMemory, ResidentBytesFollowTouchedPages) {
#if !defined(__linux__)
  GTEST_SKIP() << "resident_bytes reads /proc/self/statm";
#else
  const std::size_t before = tessera::resident_bytes();
  ASSERT_GT(before, 0u);
  constexpr std::size_t kBytes = std::size_t{64} << 20;
  auto* block = static_cast<char*>(std::malloc(kBytes));
  ASSERT_NE(block, nullptr);
  std::memset(block, 1, kBytes);
  EXPECT_GE(tessera::resident_bytes(), before + kBytes / 2);
  std::free(block);
#endif
}

// After map_large_blocks, a block above the threshold is mapped from the system and goes back
// when freed, even in a process where a library turned mapping off (superlu_dist does, when
// PETSc is linked): the atlas's freed tangent bases and factors must not stay in the heap.
TEST(ProcessMemory, LargeBlocksAreMappedAndGoBackWhenFreed) {
#if !defined(__GLIBC__) || defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "needs glibc's own allocator (mallinfo2)";
#else
  mallopt(M_MMAP_MAX, 0);  // as superlu_dist's constructor does
  tessera::map_large_blocks(std::size_t{256} << 10);
  const std::size_t mapped_before = mallinfo2().hblkhd;
  constexpr std::size_t kBytes = std::size_t{1} << 20;
  void* block = std::malloc(kBytes);
  ASSERT_NE(block, nullptr);
  EXPECT_GE(mallinfo2().hblkhd, mapped_before + kBytes);
  std::free(block);
  EXPECT_EQ(mallinfo2().hblkhd, mapped_before);
  // Smaller blocks stay in the heap, where the next of their size reuses them.
  void* small = std::malloc(std::size_t{64} << 10);
  EXPECT_EQ(mallinfo2().hblkhd, mapped_before);
  std::free(small);
#endif
}

}  // namespace
