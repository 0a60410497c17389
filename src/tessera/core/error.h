// SPDX-License-Identifier: MIT
// Exceptions and checks: contract violations throw with a message a user can act on.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace tessera {

/// A caller passed something that breaks a documented precondition (bad option, bad shape,
/// malformed file). The message names the value and the rule it breaks.
///
/// what() is the message alone: it is what the command line prints after "tessera: error:" and
/// what Python's ValueError says, and the user needs the rule, not tessera's source file. The
/// place in the source that found the mistake (TESSERA_CHECK's file:line) is kept in
/// source_location() for a bug report; with the environment variable TESSERA_DEBUG=1 (any
/// value but empty and "0") what() ends with it too, e.g. "... must be > 0 (domain.cpp:24)".
class InvalidArgument : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
  /// `source_location`: "file.cpp:line" of the check that threw, or empty.
  InvalidArgument(const std::string& message, std::string source_location);
  /// "file.cpp:line" of the TESSERA_CHECK that threw; empty for other throws.
  const std::string& source_location() const { return source_location_; }

 private:
  std::string source_location_;
};

/// A computation could not do what was asked (for example a front that meets itself in a way
/// the method cannot close). The message says where and why.
class ComputationFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An internal invariant does not hold: a bug in tessera, never the user's fault.
class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

/// True if the environment variable TESSERA_DEBUG is set to something other than "" or "0":
/// messages of InvalidArgument then end with the source location of the check that threw.
bool is_debug_messages();

namespace detail {
[[noreturn]] void throw_invalid_argument(const std::string& message, const char* file, int line);
[[noreturn]] void throw_internal_error(const std::string& condition, const char* file, int line);
}  // namespace detail

}  // namespace tessera

/// TESSERA_CHECK(cond, stream-expression): throws InvalidArgument naming the broken rule.
///   TESSERA_CHECK(h > 0, "FrontOptions::step = " << h << " must be > 0");
#define TESSERA_CHECK(condition, message_stream)                                  \
  do {                                                                            \
    if (!(condition)) {                                                           \
      std::ostringstream tessera_check_message_;                                  \
      tessera_check_message_ << message_stream;                                   \
      ::tessera::detail::throw_invalid_argument(tessera_check_message_.str(),     \
                                                __FILE__, __LINE__);              \
    }                                                                             \
  } while (false)

/// Internal invariants: always on (they are cheap); expensive ones are opt-in.
#define TESSERA_ASSERT(condition)                                                  \
  do {                                                                             \
    if (!(condition)) {                                                            \
      ::tessera::detail::throw_internal_error(#condition, __FILE__, __LINE__);     \
    }                                                                              \
  } while (false)

#ifdef TESSERA_EXPENSIVE_CHECKS
#define TESSERA_EXPENSIVE_ASSERT(condition) TESSERA_ASSERT(condition)
#else
#define TESSERA_EXPENSIVE_ASSERT(condition) \
  do {                                      \
  } while (false)
#endif
