// SPDX-License-Identifier: MIT
#include "stop_signals.h"

#include <unistd.h>

#include <atomic>
#include <cstring>

namespace tessera::app {
namespace {

// Everything the handler touches is a lock-free atomic, and write() is async-signal-safe.
std::atomic<int> signals_received{0};
std::atomic<int> first_signal_number{0};
std::atomic<int> current_stage{static_cast<int>(RunStage::Build)};
std::atomic<int> stage_of_first{static_cast<int>(RunStage::Build)};
std::atomic<bool> notifies{true};

void write_note(const char* text) {
  if (notifies.load()) {
    const ssize_t ignored = ::write(STDERR_FILENO, text, std::strlen(text));
    static_cast<void>(ignored);
  }
}

extern "C" void on_stop_signal(int signal) {
  const int count = signals_received.fetch_add(1) + 1;
  if (count == 1) {
    first_signal_number.store(signal);
    stage_of_first.store(current_stage.load(std::memory_order_relaxed));
    write_note(
        "\ntessera: stop requested: the run ends at its next vertex, projection or check and "
        "writes the valid partial mesh and the summary\n");
  } else if (count == 2) {
    // A second Ctrl-C or a batch system's repeated SIGTERM used to kill the run here, before
    // anything was written; the files come first now.
    write_note(
        "\ntessera: still writing the files of the stopped run; a third signal ends the "
        "process at once (files already written stay whole)\n");
  } else {
    // The default action (termination), now: files are replaced by a rename, so none is left
    // truncated, but those not yet written are not written.
    std::signal(signal, SIG_DFL);
    std::raise(signal);
  }
}

struct sigaction stop_action() {
  struct sigaction action = {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  // Writes and reads interrupted by the signal go on (the files are being written).
  action.sa_flags = SA_RESTART;
  return action;
}

}  // namespace

std::string_view to_string(RunStage stage) {
  switch (stage) {
    case RunStage::Build:
      return "build";
    case RunStage::Clip:
      return "clip";
    case RunStage::Refine:
      return "refine";
    case RunStage::Validate:
      return "validate";
    case RunStage::Patches:
      return "patches";
    case RunStage::Report:
      return "report";
  }
  return "build";
}

RunStage stage_of_progress(std::string_view progress_stage) {
  for (const RunStage stage : {RunStage::Clip, RunStage::Refine, RunStage::Validate,
                               RunStage::Patches, RunStage::Report}) {
    if (progress_stage == to_string(stage)) {
      return stage;
    }
  }
  return RunStage::Build;
}

StopSignals::StopSignals(bool notify) {
  signals_received.store(0);
  first_signal_number.store(0);
  current_stage.store(static_cast<int>(RunStage::Build));
  stage_of_first.store(static_cast<int>(RunStage::Build));
  notifies.store(notify);
  const struct sigaction action = stop_action();
  sigaction(SIGINT, &action, &previous_int_);
  sigaction(SIGTERM, &action, &previous_term_);
}

StopSignals::~StopSignals() {
  sigaction(SIGINT, &previous_int_, nullptr);
  sigaction(SIGTERM, &previous_term_, nullptr);
}

void StopSignals::enter(RunStage stage) {
  current_stage.store(static_cast<int>(stage), std::memory_order_relaxed);
}

bool StopSignals::is_requested() { return signals_received.load() > 0; }

int StopSignals::count() { return signals_received.load(); }

std::string_view StopSignals::first_signal() {
  switch (first_signal_number.load()) {
    case SIGTERM:
      return "SIGTERM";
    case SIGINT:
      return "SIGINT";
    default:
      return "";
  }
}

RunStage StopSignals::stage_at_stop() { return static_cast<RunStage>(stage_of_first.load()); }

}  // namespace tessera::app
