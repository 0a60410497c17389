// SPDX-License-Identifier: MIT
// Scattered data in the plane from CSV files: columns x, y and optionally a value.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace tessera {

/// Points of the plane with optional values, as read from a file.
struct ScatteredData {
  Eigen::Matrix2Xd points;         ///< 2×N, one point per column, in file order
  Eigen::VectorXd values;          ///< N values, or empty if the file has no value column
  std::vector<std::size_t> lines;  ///< line of the file each point came from (from 1)
  bool has_values() const { return values.size() > 0; }
};

struct ScatteredDataCsvOptions {
  /// Column holding the values, by its header name; empty: the third column if there is one.
  /// A named column needs a header line.
  std::string value_column;
};

/// Reads comma-separated points, one per line.
///
/// The first line that is not blank and not a comment (#) is a header if its first field is
/// not a number: then it names the columns, which must include x and y (any case), and the
/// columns may come in any order. Without a header the columns are x, y[, value]. Spaces
/// around fields are ignored; further columns are ignored.
///
/// \throw InvalidArgument naming the file and line for: a missing column, text where a number
///        is expected (or a number that is not finite), two equal points (both lines named);
///        naming the file for fewer than three points or all points on one line (within a
///        relative 1e-12 of the data's extent), or a file that cannot be read.
ScatteredData read_scattered_data_csv(const std::string& path,
                                      const ScatteredDataCsvOptions& options = {});
/// Same, from the text of a file; `path` is used in messages only.
ScatteredData parse_scattered_data_csv(const std::string& content, const std::string& path,
                                       const ScatteredDataCsvOptions& options = {});

}  // namespace tessera
