// SPDX-License-Identifier: MIT
#include "cli_support.h"

#include <cmath>
#include <exception>
#include <string>

namespace tessera::app {

const CLI::Validator& finite_positive() {
  static const CLI::Validator validator(
      [](std::string& text) -> std::string {
        try {
          std::size_t used = 0;
          const double value = std::stod(text, &used);
          if (used == text.size() && std::isfinite(value) && value > 0) {
            return {};
          }
        } catch (const std::exception&) {
        }
        return "'" + text + "' is not a finite number > 0";
      },
      "POSITIVE", "finite positive number");
  return validator;
}

}  // namespace tessera::app
