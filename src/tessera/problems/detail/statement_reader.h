// SPDX-License-Identifier: MIT
// Line-based "keyword word word …" text, with '#' comments, and errors that point at a column.
#pragma once

#include <string>
#include <vector>

namespace tessera::detail {

/// One whitespace-separated word of a line and where it starts (1-based column).
struct Word {
  std::string text;
  int column = 0;
};

/// One non-blank line `keyword word word …`, comment removed.
struct Statement {
  int line = 0;             ///< 1-based line number
  std::string source_line;  ///< the line as written (tabs as spaces), for the excerpt in messages
  Word keyword;
  std::vector<Word> words;  ///< the words after the keyword
  std::string rest;         ///< everything after the keyword, trimmed, e.g. an expression
  int rest_column = 0;      ///< column of the first character of `rest` (past the end if empty)
};

/// Splits `text` into statements: '#' starts a comment, blank and comment-only lines are
/// skipped, CR LF line ends and tabs are accepted (a tab counts as one column).
std::vector<Statement> read_statements(const std::string& text);

/// Throws InvalidArgument with "source:line[:column]: message", then the line and, if
/// column > 0, a caret under that column, the way compilers report errors.
[[noreturn]] void throw_at(const std::string& source, const Statement& statement,
                           const std::string& message, int column = 0);

}  // namespace tessera::detail
