// SPDX-License-Identifier: MIT
// Ctrl-C during a run: while C++ works no Python code runs that could raise KeyboardInterrupt,
// so a C handler sets a flag that the methods poll (MethodSettings::stop_requested) and the run
// returns its valid partial mesh. Installed only where Python's own handler would raise
// KeyboardInterrupt (the main thread, default handler), and restored afterwards. The handler
// counts: a second Ctrl-C cannot cut the run shorter (after the first the run only finishes what
// keeps the partial mesh trustworthy, its validation, and the report), so the package raises
// Interrupted and hands the second to Python as a pending KeyboardInterrupt
// (raise_with_pending_interrupt), which a handler of Interrupted then meets.
#pragma once

#include <csignal>

namespace tessera::python {

class InterruptHandler {
 public:
  /// Installs the handler if `wanted` and Python's own SIGINT handler is the default one in the
  /// main thread; counts from zero either way.
  explicit InterruptHandler(bool wanted);
  ~InterruptHandler();
  InterruptHandler(const InterruptHandler&) = delete;
  InterruptHandler& operator=(const InterruptHandler&) = delete;

  bool is_requested() const;
  /// How many Ctrl-C came since the handler was made.
  int count() const;

 private:
  bool installed_ = false;
  struct sigaction previous_ {};
};

}  // namespace tessera::python
