// SPDX-License-Identifier: MIT
// OpenMP behind parallel_for: the one file of the library that sees it (docs/threads.md says
// why OpenMP and not oneTBB). Without OpenMP the loops run on the calling thread.
#include "tessera/core/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <exception>
#include <limits>
#include <mutex>
#include <string>
#include <thread>

#ifdef TESSERA_HAS_OPENMP
#include <omp.h>
#endif

#include "tessera/core/error.h"
#include "tessera/core/implicit_problem.h"

namespace tessera {
namespace {

// 0: not set (the environment's or every core).
std::atomic<int> chosen_count{0};

// A positive integer from the environment variable `name`, else 0.
int from_environment(const char* name) {
  const char* value = std::getenv(name);
  if (value == nullptr || *value == '\0') {
    return 0;
  }
  char* end = nullptr;
  const long count = std::strtol(value, &end, 10);
  // OMP_NUM_THREADS may be a list ("4,2", one count per nesting level): its first entry.
  if (end == value || count <= 0 || count > std::numeric_limits<int>::max()) {
    return 0;
  }
  return static_cast<int>(count);
}

int default_count() {
  // Read once: the environment does not change under a running process.
  static const int count = [] {
    if (const int tessera = from_environment("TESSERA_THREADS"); tessera > 0) {
      return tessera;
    }
    if (const int openmp = from_environment("OMP_NUM_THREADS"); openmp > 0) {
      return openmp;
    }
    return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  }();
  return count;
}

// Indices handed out to a free thread at a time: small enough that a few slow points (a
// projection that needs 50 iterations) do not hold the loop up, large enough that handing out
// costs nothing beside a projection.
constexpr int kBlock = 16;

}  // namespace

int thread_count() {
  const int chosen = chosen_count.load(std::memory_order_relaxed);
  return chosen > 0 ? chosen : default_count();
}

void set_thread_count(int count) {
  TESSERA_CHECK(count >= 0, "thread count = " << count << " must be >= 0 (0: the default)");
  chosen_count.store(count, std::memory_order_relaxed);
}

ThreadCountScope::ThreadCountScope(int count)
    : saved_(chosen_count.load(std::memory_order_relaxed)), is_set_(count != 0) {
  if (is_set_) {
    set_thread_count(count);
  }
}

ThreadCountScope::~ThreadCountScope() {
  if (is_set_) {
    chosen_count.store(saved_, std::memory_order_relaxed);
  }
}

int threads_for(const ImplicitProblem& problem) {
  return problem.is_thread_safe() && !problem.has_sparse_jacobian() ? thread_count() : 1;
}

void parallel_for(int count, int threads, const std::function<void(int)>& body) {
  // Indices are handed out kBlock at a time, fewer where the loop is short: a loop over a few
  // blocks of heavy work (the validation's rounds of pair blocks: two on two threads) must not
  // become one thread's.
  threads = std::max(1, std::min(threads, count));
  const int chunk = std::clamp(count / (4 * threads), 1, kBlock);
#ifdef TESSERA_HAS_OPENMP
  if (threads > 1) {
    // The smallest index whose body threw, and its exception; the indices above it are skipped
    // once it is known (a serial loop would not have reached them).
    std::atomic<int> failed_at{std::numeric_limits<int>::max()};
    std::exception_ptr failure;
    std::mutex failure_mutex;
#pragma omp parallel for num_threads(threads) schedule(dynamic, chunk)
    for (int i = 0; i < count; ++i) {
      if (i > failed_at.load(std::memory_order_relaxed)) {
        continue;
      }
      try {
        body(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failure_mutex);
        if (i < failed_at.load(std::memory_order_relaxed)) {
          failed_at.store(i, std::memory_order_relaxed);
          failure = std::current_exception();
        }
      }
    }
    if (failure) {
      std::rethrow_exception(failure);
    }
    return;
  }
#endif
  for (int i = 0; i < count; ++i) {
    body(i);
  }
}

}  // namespace tessera
