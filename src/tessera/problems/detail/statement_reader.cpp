// SPDX-License-Identifier: MIT
#include "tessera/problems/detail/statement_reader.h"

#include <algorithm>
#include <sstream>

#include "tessera/core/error.h"

namespace tessera::detail {

std::vector<Statement> read_statements(const std::string& text) {
  std::vector<Statement> statements;
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    line = line.substr(0, line.find_last_not_of(" \t\r") + 1);
    // Tabs become one space each so that the caret under the echoed line stays aligned.
    std::replace(line.begin(), line.end(), '\t', ' ');
    const std::string content = line.substr(0, line.find('#'));
    Statement statement;
    statement.line = number;
    statement.source_line = line;
    for (std::size_t i = 0; i < content.size();) {
      if (content[i] == ' ') {
        ++i;
        continue;
      }
      const std::size_t end = std::min(content.find(' ', i), content.size());
      statement.words.push_back({content.substr(i, end - i), static_cast<int>(i) + 1});
      i = end;
    }
    if (statement.words.empty()) {
      continue;
    }
    statement.keyword = statement.words.front();
    statement.words.erase(statement.words.begin());
    const std::size_t rest_start =
        statement.words.empty() ? content.size()
                                : static_cast<std::size_t>(statement.words.front().column - 1);
    statement.rest = content.substr(rest_start);
    statement.rest = statement.rest.substr(0, statement.rest.find_last_not_of(' ') + 1);
    statement.rest_column = static_cast<int>(rest_start) + 1;
    statements.push_back(std::move(statement));
  }
  return statements;
}

void throw_at(const std::string& source, const Statement& statement, const std::string& message,
              int column) {
  std::ostringstream out;
  out << source << ":" << statement.line;
  if (column > 0) {
    out << ":" << column;
  }
  out << ": " << message << "\n    " << statement.source_line;
  if (column > 0) {
    out << "\n    " << std::string(static_cast<std::size_t>(column - 1), ' ') << "^";
  }
  throw InvalidArgument(out.str());
}

}  // namespace tessera::detail
