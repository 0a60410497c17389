// SPDX-License-Identifier: MIT
// The atlas builder's state as bytes (AtlasCheckpointing): what it is, how it is checked.
//
// Everything that decides the build's later steps is saved exactly (doubles as their bits):
// every chart (centre, radius, polygon with its edge labels, parent, orientation, σ_min,
// queued and eligible flags, the radius it was indexed with), the tangent bases still held and
// the frames of the retired ones, the queue in its order, the chart being worked on with the
// counts that decide its next child, the counters that decide (min_radius, the budget of kept
// factorisations, the caps) and the work done. The chart index is rebuilt by inserting the
// charts again in their order with the same refits, which gives the same index. Kept
// factorisations are a cache: the guide basis each was made with is saved, and a resumed build
// factors again with it, which gives the same bits.
//
// A state begins with a fingerprint of its run: the problem's name and n, F at two fixed points
// near the start (bit for bit), the start, the domain's half-spaces and the options that decide
// the atlas. Continuing with any of them different is refused, naming it.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace tessera {

/// Saving the atlas's build while it runs, and continuing a saved build (docs/checkpoints.md).
/// A build continued from a state gives the same atlas, bit for bit, as the build that was
/// never stopped.
struct AtlasCheckpointing {
  /// Asked before each child a chart places (the builder's state is whole there); true: the
  /// state goes to `save` now. Empty: only the stop and the end of the build save.
  std::function<bool()> is_due;
  /// Receives the builder's whole state (binary, atlas_checkpoint.h) when `is_due` says so,
  /// when a stop request ends the build (before the mesh is made) and when the build ends
  /// complete. Empty: nothing is saved.
  std::function<void(std::string state)> save;
  /// A state that `save` received, to continue from; null: start afresh. It must come from the
  /// same problem, start, domain and options (else InvalidArgument naming what differs).
  std::shared_ptr<const std::string> resume_from;
  /// `resume_from` is continued into a larger domain (`tessera extend`, docs/checkpoints.md):
  /// the domain may differ from the checkpoint's if it contains it (each of its faces parallel
  /// to one of the old domain's and no nearer to it; InvalidArgument otherwise), and every
  /// chart whose polygon is still open is queued again, so that the charts left outside the
  /// old domain's margin grow into the new one. The charts there are kept as they are.
  bool extend = false;
  /// At a stop the state is saved only up to this size: writing it delays the partial mesh
  /// (measured at n = 10⁴: about 0.5 s per 100 MB, made and written), and a batch system's
  /// grace period is short. A larger state is not saved at the stop; the last periodic
  /// checkpoint stands (a note says so). At n = 10⁵ this is about 600 charts.
  double max_bytes_at_stop = 512.0 * 1024 * 1024;
};

/// The version of the atlas's state; a state of another version is refused.
inline constexpr std::uint32_t kAtlasStateVersion = 1;

/// What a saved state says of its run, read without continuing it (`tessera extend` checks
/// its new tolerance against the old one). \throw InvalidArgument if it is not a state.
struct AtlasStateHeader {
  std::string problem;
  int dimension = 0;
  int charts = 0;
  double tolerance = 0.0;  ///< the tolerance the charts were sized for (AtlasOptions)
  double step = 0.0;
};
AtlasStateHeader read_atlas_state_header(const std::string& state);

}  // namespace tessera
