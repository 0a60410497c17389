// SPDX-License-Identifier: MIT
// Progress of tessera.mesh for Python: the records of a run (CoveringProgress) handed to a
// callable, or printed on sys.stderr as the CLI prints them. The run calls the callback from
// its own thread with the GIL released; the reporter takes the GIL for each record.
#pragma once

#include <pybind11/pybind11.h>

#include <chrono>
#include <optional>
#include <string>

#include "tessera/methods/covering_result.h"

namespace tessera::python {

namespace py = pybind11;

class ProgressReporter {
 public:
  /// `progress`: None (no progress), a callable (called with each record, a dict with "stage",
  /// "vertex_count", "triangle_count", "front_size" and "seconds" since the run began), or one of
  /// the strings "auto" and "always": printed on sys.stderr. On a terminal a status line, redrawn
  /// for each record and cleared at the end ("auto" and "always" alike); elsewhere (a log, a
  /// notebook) one line per stage and one every 10 s, with "auto" only once the run has lasted
  /// 5 s, so that short runs print nothing, and a last line with the run's time.
  /// \pre the GIL is held.
  /// \throw InvalidArgument if `progress` is none of these.
  explicit ProgressReporter(py::object progress);
  /// Clears the status line (an exception may have ended the run). \pre the GIL is held.
  ~ProgressReporter() { finish(); }
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;

  /// The callback for MethodSettings::progress; empty if there is no progress to report. It
  /// refers to this reporter, which must outlive the run.
  ProgressCallback callback();
  /// Whether the callable raised (the run should stop; the exception is raised afterwards).
  bool has_error() const { return error_.has_value(); }
  /// Raises what the callable raised, if it did. \pre the GIL is held.
  void raise_error();
  /// Clears the status line a terminal shows, or ends the lines printed elsewhere with the
  /// run's time. \pre the GIL is held.
  void finish();

 private:
  void report(const CoveringProgress& progress);  // with the GIL
  void print(const std::string& line, bool is_status_line);

  enum class Mode { None, Callable, Auto, Always };
  Mode mode_ = Mode::None;
  py::object callable_;
  bool is_terminal_ = false;
  std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
  double last_line_seconds_ = -1.0;  // when the last line (not a status line) was printed
  std::string last_stage_;
  std::size_t status_width_ = 0;  // of the status line on the terminal, 0: none shown
  std::optional<py::error_already_set> error_;
};

}  // namespace tessera::python
