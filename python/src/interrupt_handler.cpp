// SPDX-License-Identifier: MIT
#include "interrupt_handler.h"

#include <pybind11/pybind11.h>

#include <atomic>

namespace py = pybind11;

namespace tessera::python {
namespace {

static_assert(std::atomic<int>::is_always_lock_free, "the signal handler's counter");
std::atomic<int> interrupt_signals{0};

extern "C" void request_interrupt(int) { interrupt_signals.fetch_add(1); }

}  // namespace

InterruptHandler::InterruptHandler(bool wanted) {
  interrupt_signals.store(0);
  if (!wanted) {
    return;
  }
  const py::module_ threading = py::module_::import("threading");
  const py::module_ signal = py::module_::import("signal");
  const bool is_main_thread =
      threading.attr("current_thread")().is(threading.attr("main_thread")());
  if (!is_main_thread ||
      !signal.attr("getsignal")(signal.attr("SIGINT")).is(signal.attr("default_int_handler"))) {
    return;
  }
  struct sigaction action {};
  action.sa_handler = request_interrupt;
  sigemptyset(&action.sa_mask);
  installed_ = sigaction(SIGINT, &action, &previous_) == 0;
}

InterruptHandler::~InterruptHandler() {
  if (installed_) {
    sigaction(SIGINT, &previous_, nullptr);
  }
}

bool InterruptHandler::is_requested() const { return interrupt_signals.load() > 0; }

int InterruptHandler::count() const { return interrupt_signals.load(); }

}  // namespace tessera::python
