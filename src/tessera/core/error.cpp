// SPDX-License-Identifier: MIT
#include "tessera/core/error.h"

#include <filesystem>

namespace tessera::detail {

void throw_invalid_argument(const std::string& message, const char* file, int line) {
  // The user sees the rule first; the source location helps when they report it.
  throw InvalidArgument(message + " (" + std::filesystem::path(file).filename().string() + ":" +
                        std::to_string(line) + ")");
}

void throw_internal_error(const std::string& condition, const char* file, int line) {
  throw InternalError("internal error: assertion '" + condition + "' failed at " +
                      std::filesystem::path(file).filename().string() + ":" +
                      std::to_string(line) + "; please report this");
}

}  // namespace tessera::detail
