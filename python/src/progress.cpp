// SPDX-License-Identifier: MIT
#include "progress.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>

#include "tessera/core/error.h"

namespace tessera::python {
namespace {

// Away from a terminal: nothing before this (mode "auto"), then a line per stage and one per
// kLineInterval, enough to see that a run of minutes lives without filling a log.
constexpr double kQuietSeconds = 5.0;
constexpr double kLineInterval = 10.0;

bool is_terminal(const py::object& stream) {
  try {
    return !stream.is_none() && stream.attr("isatty")().cast<bool>();
  } catch (const py::error_already_set&) {
    return false;  // a replaced sys.stderr without isatty, or a closed one
  }
}

}  // namespace

ProgressReporter::ProgressReporter(py::object progress) {
  if (progress.is_none()) {
    return;
  }
  if (py::isinstance<py::str>(progress)) {
    const std::string mode = progress.cast<std::string>();
    TESSERA_CHECK(mode == "auto" || mode == "always",
                  "progress = '" << mode << "' must be 'auto', 'always', None or a callable");
    mode_ = mode == "auto" ? Mode::Auto : Mode::Always;
    is_terminal_ = is_terminal(py::module_::import("sys").attr("stderr"));
    return;
  }
  TESSERA_CHECK(PyCallable_Check(progress.ptr()) != 0,
                "progress must be a callable, True, False or None, not "
                    << py::str(py::type::of(progress).attr("__name__")).cast<std::string>());
  mode_ = Mode::Callable;
  callable_ = std::move(progress);
}

ProgressCallback ProgressReporter::callback() {
  if (mode_ == Mode::None) {
    return {};
  }
  return [this](const CoveringProgress& progress) {
    py::gil_scoped_acquire gil;
    report(progress);
  };
}

void ProgressReporter::report(const CoveringProgress& progress) {
  if (error_) {
    return;  // the run stops at its next poll (MethodSettings::stop_requested)
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  const std::string stage(progress.stage);
  if (mode_ == Mode::Callable) {
    try {
      callable_(py::dict(py::arg("stage") = stage, py::arg("vertex_count") = progress.vertex_count,
                         py::arg("triangle_count") = progress.triangle_count,
                         py::arg("front_size") = progress.front_size,
                         py::arg("seconds") = seconds));
    } catch (py::error_already_set& error) {
      error_.emplace(std::move(error));
    }
    return;
  }
  // As the CLI's status line (apps/tessera/mesh_command.cpp), with the time.
  char text[160];
  if (progress.stage == "build") {
    std::snprintf(text, sizeof text, "%d vertices, %d triangles, front %d (%.0f s)",
                  progress.vertex_count, progress.triangle_count, progress.front_size, seconds);
  } else {
    std::snprintf(text, sizeof text, "%s: %d vertices, %d triangles (%.0f s)", stage.c_str(),
                  progress.vertex_count, progress.triangle_count, seconds);
  }
  if (is_terminal_) {
    print(std::string("  ") + text, true);
    return;
  }
  const bool is_new_stage = stage != last_stage_;
  last_stage_ = stage;
  if ((mode_ == Mode::Auto && seconds < kQuietSeconds) ||
      (!is_new_stage && last_line_seconds_ >= 0 && seconds - last_line_seconds_ < kLineInterval)) {
    return;
  }
  last_line_seconds_ = seconds;
  print(std::string("tessera: ") + (progress.stage == "build" ? "build: " : "") + text, false);
}

// Writes to sys.stderr, where a notebook shows it (C's stderr goes to the kernel's log there).
// A failing write (a closed stream) is dropped: progress never stops a run.
void ProgressReporter::print(const std::string& line, bool is_status_line) {
  try {
    const py::object stream = py::module_::import("sys").attr("stderr");
    if (stream.is_none()) {
      return;
    }
    if (is_status_line) {
      std::string padded = "\r" + line;
      if (line.size() < status_width_) {
        padded.append(status_width_ - line.size(), ' ');  // over the longer line before
      }
      status_width_ = std::max(status_width_, line.size());
      stream.attr("write")(padded);
    } else {
      stream.attr("write")(line + "\n");
    }
    stream.attr("flush")();
  } catch (py::error_already_set& error) {
    // A stream written in Python (a notebook's) runs Python's signal handlers: a Ctrl-C that
    // Python handles itself (handle_interrupt=False) stops the run as the callable's would.
    if (error.matches(PyExc_KeyboardInterrupt) && !error_) {
      error_.emplace(std::move(error));
    }
  }
}

void ProgressReporter::finish() {
  if (last_line_seconds_ >= 0) {
    // A log that heard of the run hears that it ended.
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
    char text[64];
    std::snprintf(text, sizeof text, "tessera: finished after %.0f s", seconds);
    last_line_seconds_ = -1.0;
    print(text, false);
  }
  if (status_width_ == 0) {
    return;
  }
  try {
    const py::object stream = py::module_::import("sys").attr("stderr");
    stream.attr("write")("\r" + std::string(status_width_, ' ') + "\r");
    stream.attr("flush")();
  } catch (const py::error_already_set&) {
    // the run is over: nothing is left to stop
  }
  status_width_ = 0;
}

void ProgressReporter::raise_error() {
  if (error_) {
    py::error_already_set error = std::move(*error_);
    error_.reset();
    throw error;
  }
}

}  // namespace tessera::python
