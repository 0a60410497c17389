// SPDX-License-Identifier: MIT
// Data-parallel loops over indices on threads, whose results never depend on the thread count,
// and the thread count itself (docs/threads.md).
#pragma once

#include <functional>

namespace tessera {

class ImplicitProblem;

/// The threads that parallel loops may use in this process: set_thread_count's, else the
/// environment's TESSERA_THREADS, else OMP_NUM_THREADS, else every core. At least 1.
int thread_count();

/// Sets thread_count() for the whole process (the CLI's --threads); 0 goes back to the default.
/// \throw InvalidArgument if count < 0.
void set_thread_count(int count);

/// Sets thread_count() for a scope (one call from Python with threads=), and back after.
class ThreadCountScope {
 public:
  /// \param count  threads; 0 leaves the count as it is.
  explicit ThreadCountScope(int count);
  ~ThreadCountScope();
  ThreadCountScope(const ThreadCountScope&) = delete;
  ThreadCountScope& operator=(const ThreadCountScope&) = delete;

 private:
  int saved_;
  bool is_set_;
};

/// The threads a loop that evaluates `problem` (F, DF, factorisations) may use: thread_count(),
/// or 1 where the problem is not thread-safe (ImplicitProblem::is_thread_safe: Python callbacks,
/// the PETSc backend) or has a sparse Jacobian. Sparse problems are the large-n ones: their
/// loops share factorisations between neighbouring points in a fixed order (one LU serves a
/// vertex's ring), each ~50 MB at n = 10⁵, so threads would multiply the memory and the
/// factorisations; a dense problem's points are independent, which the loops rely on.
int threads_for(const ImplicitProblem& problem);

/// Calls body(i) for every i in [0, count), on up to `threads` threads (1: in order, on the
/// calling thread). Deterministic when each body(i) writes only its own results (the i-th entry
/// of a vector sized before) and reads nothing another index writes: then the results are the
/// same bits whatever the thread count. Reductions are the caller's, after the loop, in index
/// order (floating-point sums depend on their order).
///
/// If bodies throw, the exception of the smallest index is rethrown after the loop (the one a
/// serial loop would have thrown; the indices above it may or may not have run), so that the
/// error too does not depend on the thread count.
/// \param threads  at most this many threads (threads_for(problem) or thread_count()); the
///                 indices are handed out in small blocks as threads become free.
void parallel_for(int count, int threads, const std::function<void(int)>& body);

}  // namespace tessera
