// SPDX-License-Identifier: MIT
#include "tessera/core/error.h"

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <utility>

namespace tessera {
namespace {

std::string message_for_user(const std::string& message, const std::string& source_location) {
  if (source_location.empty() || !is_debug_messages()) {
    return message;
  }
  return message + " (" + source_location + ")";
}

std::string file_and_line(const char* file, int line) {
  return std::filesystem::path(file).filename().string() + ":" + std::to_string(line);
}

}  // namespace

bool is_debug_messages() {
  const char* value = std::getenv("TESSERA_DEBUG");
  return value != nullptr && std::strcmp(value, "") != 0 && std::strcmp(value, "0") != 0;
}

InvalidArgument::InvalidArgument(const std::string& message, std::string source_location)
    : std::invalid_argument(message_for_user(message, source_location)),
      source_location_(std::move(source_location)) {}

namespace detail {

void throw_invalid_argument(const std::string& message, const char* file, int line) {
  // The user sees the rule alone; the source location stays in the exception for a bug report
  // (and in the message with TESSERA_DEBUG=1).
  throw InvalidArgument(message, file_and_line(file, line));
}

void throw_internal_error(const std::string& condition, const char* file, int line) {
  // A bug in tessera, never the user's fault: here the source location is what the report to
  // the maintainers needs, so it stays in the message.
  throw InternalError("internal error: assertion '" + condition + "' failed at " +
                      file_and_line(file, line) + "; please report this");
}

}  // namespace detail
}  // namespace tessera
