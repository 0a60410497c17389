// SPDX-License-Identifier: MIT
// The characters of a name in a problem file, an expression or a view ("u_16_16", "lambda"):
// ASCII letters, digits and '_', not starting with a digit. Locale-independent on purpose: a
// problem file means the same on every machine.
#pragma once

namespace tessera::detail {

inline bool is_name_start(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
inline bool is_name_char(char c) { return is_name_start(c) || (c >= '0' && c <= '9'); }

}  // namespace tessera::detail
