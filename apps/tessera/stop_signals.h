// SPDX-License-Identifier: MIT
// SIGINT and SIGTERM during `tessera mesh` (a batch system's time limit sends SIGTERM, then
// SIGKILL after a grace period): the first asks the run to stop and write its files, the second
// is only counted (the files are being written), the third ends the process at once. The stage
// that the first one came in is kept for the summary (docs/stopping.md).
#pragma once

#include <csignal>
#include <string_view>

namespace tessera::app {

/// The stages of `tessera mesh` as the summary's "stop" names them: the covering's steps as its
/// progress reports them (CoveringProgress::stage; the start's projection counts to the build),
/// then everything after the covering (distances, curves, files).
enum class RunStage : int { Build, Clip, Refine, Validate, Patches, Report };

/// "build", "clip", "refine", "validate", "patches", "report".
std::string_view to_string(RunStage stage);

/// The stage of a progress report's name (CoveringProgress::stage); Build for any other.
RunStage stage_of_progress(std::string_view progress_stage);

/// Installs the handlers for its lifetime and restores the previous ones after. One at a time.
class StopSignals {
 public:
  /// \param notify  write a line to stderr on the first and the second signal (not with -q).
  explicit StopSignals(bool notify);
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  /// The stage now running, for a signal that comes during it. Lock-free (a relaxed atomic).
  static void enter(RunStage stage);
  /// Whether a signal came; what the methods poll (MethodSettings::stop_requested).
  static bool is_requested();
  /// Signals received so far (the third one never returns).
  static int count();
  /// "SIGTERM" or "SIGINT": the first signal; empty if none came.
  static std::string_view first_signal();
  /// The stage the first signal came in.
  static RunStage stage_at_stop();

 private:
  struct sigaction previous_int_ = {};
  struct sigaction previous_term_ = {};
};

}  // namespace tessera::app
