// SPDX-License-Identifier: MIT
#include "tessera/problems/detail/statement_reader.h"

#include <gtest/gtest.h>

#include "tessera/core/error.h"

namespace {

using tessera::detail::read_statements;
using tessera::detail::throw_at;

TEST(StatementReader, SkipsCommentsAndBlankLinesAndKeepsLineNumbersAndColumns) {
  const auto statements =
      read_statements("# header\r\n\r\n  start 0\t1  # comment\r\n   \nequation x + y\nstep\n");
  ASSERT_EQ(statements.size(), 3u);
  EXPECT_EQ(statements[0].line, 3);
  EXPECT_EQ(statements[0].keyword.text, "start");
  EXPECT_EQ(statements[0].keyword.column, 3);
  ASSERT_EQ(statements[0].words.size(), 2u);
  EXPECT_EQ(statements[0].words[1].text, "1");
  EXPECT_EQ(statements[0].words[1].column, 11);  // the tab counts as one column
  EXPECT_EQ(statements[0].rest, "0 1");
  EXPECT_EQ(statements[0].source_line, "  start 0 1  # comment");
  EXPECT_EQ(statements[1].line, 5);
  EXPECT_EQ(statements[1].rest, "x + y");
  EXPECT_EQ(statements[1].rest_column, 10);
  EXPECT_TRUE(statements[2].rest.empty());
  EXPECT_TRUE(statements[2].words.empty());
}

TEST(StatementReader, ErrorsPointAtTheColumn) {
  const auto statements = read_statements("\nequation x + w\n");
  try {
    throw_at("f.tsr", statements[0], "unknown name 'w'", 14);
    FAIL() << "no exception";
  } catch (const tessera::InvalidArgument& error) {
    EXPECT_STREQ(error.what(),
                 "f.tsr:2:14: unknown name 'w'\n"
                 "    equation x + w\n"
                 "                 ^");
  }
  try {
    throw_at("f.tsr", statements[0], "too long");
    FAIL() << "no exception";
  } catch (const tessera::InvalidArgument& error) {
    EXPECT_STREQ(error.what(), "f.tsr:2: too long\n    equation x + w");
  }
}

}  // namespace
