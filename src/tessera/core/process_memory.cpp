// SPDX-License-Identifier: MIT
#include "tessera/core/process_memory.h"

#include <algorithm>
#include <cstdio>

#if defined(__GLIBC__)
#include <malloc.h>
#endif
#if defined(__linux__)
#include <unistd.h>
#endif

namespace tessera {

std::size_t resident_bytes() {
#if defined(__linux__)
  std::FILE* file = std::fopen("/proc/self/statm", "r");
  if (file == nullptr) {
    return 0;
  }
  unsigned long size_pages = 0;
  unsigned long resident_pages = 0;
  const int read = std::fscanf(file, "%lu %lu", &size_pages, &resident_pages);
  std::fclose(file);
  if (read != 2) {
    return 0;
  }
  static const long page = sysconf(_SC_PAGESIZE);
  return static_cast<std::size_t>(resident_pages) * static_cast<std::size_t>(page > 0 ? page : 4096);
#else
  return 0;
#endif
}

void map_large_blocks(std::size_t bytes) {
#if defined(__GLIBC__)
  constexpr std::size_t kDefault = std::size_t{128} << 10;  // glibc's M_MMAP_THRESHOLD default
  constexpr std::size_t kLargest = std::size_t{32} << 20;   // its largest on 64-bit systems
  const int threshold = static_cast<int>(std::clamp(bytes, kDefault, kLargest));
  mallopt(M_MMAP_MAX, 65536);  // glibc's default count of mapped blocks
  mallopt(M_MMAP_THRESHOLD, threshold);
  mallopt(M_TRIM_THRESHOLD, threshold);
#else
  (void)bytes;
#endif
}

void release_free_heap() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

}  // namespace tessera
