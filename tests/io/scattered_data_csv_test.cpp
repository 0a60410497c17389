// SPDX-License-Identifier: MIT
// Scattered data CSV files: headers, value columns, and messages that name the line.
#include "tessera/io/scattered_data_csv.h"

#include <gtest/gtest.h>

#include "tessera/core/error.h"

namespace tessera {
namespace {

// The message of the InvalidArgument that parsing `content` throws (empty if none).
std::string error_of(const std::string& content, const ScatteredDataCsvOptions& options = {}) {
  try {
    parse_scattered_data_csv(content, "data.csv", options);
  } catch (const InvalidArgument& error) {
    return error.what();
  }
  return "";
}

TEST(ScatteredDataCsv, ReadsPointsAndValuesWithoutHeader) {
  const ScatteredData data =
      parse_scattered_data_csv("# Franke\n0, 0, 1\n1,0,2\n\n 0 , 1 , 3 \n", "data.csv");
  ASSERT_EQ(data.points.cols(), 3);
  EXPECT_EQ(data.points.col(2), Eigen::Vector2d(0, 1));
  ASSERT_TRUE(data.has_values());
  EXPECT_EQ(data.values, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(data.lines, (std::vector<std::size_t>{2, 3, 5}));
}

TEST(ScatteredDataCsv, HeaderNamesTheColumnsInAnyOrder) {
  const std::string content = "id,Y,X,f,g\n1,0,0,5,6\n2,0,1,7,8\n3,1,0,9,10\n";
  const ScatteredData by_default = parse_scattered_data_csv(content, "data.csv");
  EXPECT_EQ(by_default.points.col(1), Eigen::Vector2d(1, 0));
  EXPECT_EQ(by_default.values, Eigen::Vector3d(1, 2, 3));  // first other column: id
  const ScatteredData named = parse_scattered_data_csv(content, "data.csv", {.value_column = "g"});
  EXPECT_EQ(named.values, Eigen::Vector3d(6, 8, 10));
  const ScatteredData no_values = parse_scattered_data_csv("x,y\n0,0\n1,0\n0,1\n", "data.csv");
  EXPECT_FALSE(no_values.has_values());
}

TEST(ScatteredDataCsv, MalformedFilesGiveMessagesNamingTheLine) {
  EXPECT_EQ(error_of("x,y,z\n0,0,1\n1,0\n0,1,1\n"),
            "CSV file 'data.csv', line 3: missing column 'z' (column 3)");
  EXPECT_EQ(error_of("0,0\n1,zero\n0,1\n"),
            "CSV file 'data.csv', line 2: column y is 'zero', not a finite number");
  EXPECT_EQ(error_of("0,0\n1,0\n"),
            "CSV file 'data.csv': 2 point(s); a triangulation needs at least 3");
  EXPECT_EQ(error_of("0,0\n1,1\n2,2\n3,3\n"),
            "CSV file 'data.csv': all 4 points lie on one line; a triangulation needs an area");
  EXPECT_EQ(error_of("0,0\n1,0\n0,1\n1,0.0\n"),
            "CSV file 'data.csv', line 4: the point (1, 0) is the same as on line 2");
  EXPECT_EQ(error_of("a,b\n0,0\n"),
            "CSV file 'data.csv', line 1: the header has no column named 'x'");
  EXPECT_EQ(error_of("x,y\n0,0\n1,0\n0,1\n", {.value_column = "f"}),
            "CSV file 'data.csv', line 1: the header has no column named 'f' (the value column "
            "asked for)");
  EXPECT_EQ(error_of("0,0,inf\n1,0,1\n0,1,1\n"),
            "CSV file 'data.csv', line 1: column value is 'inf', not a finite number");
}

TEST(ScatteredDataCsv, MissingFileIsNamed) {
  try {
    read_scattered_data_csv("/nonexistent/points.csv");
    ADD_FAILURE() << "no error for a missing file";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent/points.csv"), std::string::npos);
  }
}

}  // namespace
}  // namespace tessera
