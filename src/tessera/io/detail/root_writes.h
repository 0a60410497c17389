// SPDX-License-Identifier: MIT
// Internal to the io layer: the files of a split mesh are written by the root alone, and its
// failure becomes every rank's, so that no rank goes on to a collective call the root has
// left (docs/cluster.md).
#pragma once

#include <exception>
#include <string>
#include <string_view>
#include <utility>

#include "tessera/core/ambient_space.h"
#include "tessera/io/detail/file_buffer.h"

namespace tessera::io_detail {

/// Whether `failed` holds on any rank of `space` (collective: one maximum).
inline bool any_rank_failed(const AmbientSpace& space, bool failed) {
  return space.maximum(failed ? 1.0 : 0.0) > 0.0;
}

/// Collective: if any rank holds an error, the root rethrows its own and the others throw
/// InvalidArgument "<format> file '<path>': …" saying that the root failed.
inline void throw_if_root_failed(const AmbientSpace& space, const std::exception_ptr& error,
                                 std::string_view format, const std::string& path) {
  if (!any_rank_failed(space, error != nullptr)) {
    return;
  }
  if (error) {
    std::rethrow_exception(error);
  }
  throw_file_error(format, path,
                   "not written: rank 0, which writes the files of a split mesh, failed (its "
                   "message says why)");
}

/// Runs `write` on the root of a split space only; collective as throw_if_root_failed.
template <class Write>
void write_on_root(const AmbientSpace& space, std::string_view format, const std::string& path,
                   Write&& write) {
  std::exception_ptr error;
  if (space.is_root()) {
    try {
      std::forward<Write>(write)();
    } catch (...) {
      error = std::current_exception();
    }
  }
  throw_if_root_failed(space, error, format, path);
}

}  // namespace tessera::io_detail
