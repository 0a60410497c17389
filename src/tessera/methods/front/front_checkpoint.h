// SPDX-License-Identifier: MIT
// The advancing front's state as bytes (FrontCheckpointing): what it is, how it is checked.
//
// Everything that decides the front's later steps is saved exactly (doubles as their bits),
// between two steps, where the state is whole: every vertex ever made (its point, its type,
// removed ones included, since indices decide), every triangle slot (removed ones too), each
// vertex's incident triangles in their order, the FIFO queue in its order, the proximity grid's
// view and refit schedule (its cells are rebuilt by inserting the live vertices again, which
// gives the same answers: queries sort their ids), the smallest-gap order (its keys' bits),
// layers, deferral counts, the cached tangent bases, the step and the counters. The two
// factorisations the builder reuses from vertex to vertex are a cache: what guides their next
// border (sparse problems) is saved instead, and the resumed build factors with it.
//
// A state begins with the run's fingerprint (run_fingerprint.h): the problem, F at two fixed
// points, the start, the domain and the options that decide the front. Continuing with any of
// them different is refused, naming it.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace tessera {

/// Saving the front's build while it runs, and continuing a saved build (docs/checkpoints.md).
/// A build continued from a state gives the same mesh, bit for bit, as the build that was
/// never stopped.
struct FrontCheckpointing {
  /// Asked after each step of the front (a frontal vertex processed); true: the state goes to
  /// `save` now. Empty: only the stop and the end of the build save.
  std::function<bool()> is_due;
  /// Receives the builder's whole state (binary, front_checkpoint.h) when `is_due` says so, when
  /// a stop request ends the build (before the mesh is made) and when the build ends complete.
  /// Empty: nothing is saved.
  std::function<void(std::string state)> save;
  /// A state that `save` received, to continue from; null: start afresh. It must come from the
  /// same problem, start, domain and options (else InvalidArgument naming what differs).
  std::shared_ptr<const std::string> resume_from;
  /// At a stop the state is saved only up to this size (the atlas's rule: writing it delays the
  /// partial mesh). A larger state is not saved at the stop; the last periodic checkpoint stands.
  double max_bytes_at_stop = 512.0 * 1024 * 1024;
};

/// The version of the front's state; a state of another version is refused.
inline constexpr std::uint32_t kFrontStateVersion = 1;

}  // namespace tessera
