// SPDX-License-Identifier: MIT
// The process's own memory: what it holds resident, and giving the C heap's free pages back.
// At large n a covering allocates and frees n-sized blocks (tangent bases, factorisations) all
// the time; issue 9 bounds the memory that stays, so the run measures it and returns the rest.
#pragma once

#include <cstddef>

namespace tessera {

/// The process's resident set in bytes (Linux: /proc/self/statm); 0 where it is not known.
/// A read of a small file: cheap enough to call once per chart or per phase, not per step.
std::size_t resident_bytes();

/// Returns the free pages inside the C heap to the system (glibc's malloc_trim; elsewhere
/// nothing). At large n the tangent bases and factorisations a covering frees are n-sized
/// blocks that glibc keeps in its heap, so that the resident memory grows like everything the
/// run ever held instead of what it holds (the atlas on bvp:points=10000: 248 of 408 MB of heap
/// free at the end of the build). It walks the free lists: call it every so many steps.
void release_free_heap();

/// Asks the C library to map blocks of `bytes` or more (at least its default, 128 KB, at most
/// 32 MB) straight from the system and to unmap them when they are freed, and to return the
/// heap's top once that much of it is free (glibc: mallopt's mmap threshold, mmap count and trim
/// threshold; elsewhere nothing). Why: superlu_dist, which PETSc links and so the CLI, turns
/// both off for the whole process when it is loaded (mallopt in its constructor), and glibc's
/// own default raises the threshold past every block size freed once; either way the
/// n-sized blocks a covering frees stay in the heap, and resident memory grows like everything
/// the run ever held. Process-wide and not undone: a covering at large n sets it once.
void map_large_blocks(std::size_t bytes);

/// Dimensions from which a covering returns the free heap between its stages: below it the
/// blocks freed are too small to matter and the walk would cost more than it returns.
inline constexpr int kReleaseHeapDimension = 1000;

}  // namespace tessera
