// SPDX-License-Identifier: MIT
// Scattered data in the plane from CSV files: columns x, y and optionally a value.
#include "tessera/io/scattered_data_csv.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <string_view>
#include <utility>

#include "tessera/io/detail/file_buffer.h"

namespace tessera {
namespace {

constexpr std::string_view kCsv = "CSV";

std::string_view trim(std::string_view text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) {
    text.remove_prefix(1);
  }
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) {
    text.remove_suffix(1);
  }
  return text;
}

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  for (;;) {
    const auto comma = line.find(',');
    fields.push_back(trim(line.substr(0, comma)));
    if (comma == std::string_view::npos) {
      return fields;
    }
    line.remove_prefix(comma + 1);
  }
}

std::optional<double> parse_number(std::string_view field) {
  if (!field.empty() && field.front() == '+') {
    field.remove_prefix(1);
  }
  double value = 0.0;
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (error != std::errc() || end != field.data() + field.size() || field.empty()) {
    return std::nullopt;
  }
  return value;
}

// Shortest decimal form that reads back to the same double.
std::string format_number(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string lower(std::string_view text) {
  std::string result(text);
  for (char& c : result) {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return result;
}

struct Columns {
  int x = 0;
  int y = 1;
  int value = -1;                  // -1: no values
  std::vector<std::string> names;  // empty without a header
};

Columns columns_from_header(const std::vector<std::string_view>& fields, const std::string& path,
                            std::size_t line, const ScatteredDataCsvOptions& options) {
  Columns columns;
  columns.x = columns.y = -1;
  for (int i = 0; i < static_cast<int>(fields.size()); ++i) {
    columns.names.emplace_back(fields[i]);
    const std::string name = lower(fields[i]);
    if (name == "x" && columns.x < 0) {
      columns.x = i;
    } else if (name == "y" && columns.y < 0) {
      columns.y = i;
    }
  }
  if (columns.x < 0 || columns.y < 0) {
    io_detail::throw_file_error(
        kCsv, path, line,
        std::string("the header has no column named '") + (columns.x < 0 ? "x" : "y") + "'");
  }
  if (!options.value_column.empty()) {
    const auto found = std::find(columns.names.begin(), columns.names.end(), options.value_column);
    if (found == columns.names.end()) {
      io_detail::throw_file_error(kCsv, path, line,
                                  "the header has no column named '" + options.value_column +
                                      "' (the value column asked for)");
    }
    columns.value = static_cast<int>(found - columns.names.begin());
  } else {
    for (int i = 0; i < static_cast<int>(fields.size()); ++i) {
      if (i != columns.x && i != columns.y) {
        columns.value = i;
        break;
      }
    }
  }
  return columns;
}

std::string column_name(const Columns& columns, int index) {
  if (!columns.names.empty()) {
    return "'" + columns.names[index] + "'";
  }
  return index == columns.x ? "x" : index == columns.y ? "y" : "value";
}

}  // namespace

ScatteredData parse_scattered_data_csv(const std::string& content, const std::string& path,
                                       const ScatteredDataCsvOptions& options) {
  std::optional<Columns> columns;
  std::vector<double> xs;
  std::vector<double> ys;
  std::vector<double> values;
  ScatteredData data;
  std::size_t line_number = 0;
  std::size_t position = 0;
  while (position < content.size()) {
    const auto end = std::min(content.find('\n', position), content.size());
    std::string_view line(content.data() + position, end - position);
    position = end + 1;
    ++line_number;
    line = trim(line);
    if (line.empty() || line.front() == '#') {
      continue;
    }
    const std::vector<std::string_view> fields = split_fields(line);
    if (!columns) {
      if (!parse_number(fields.front())) {
        columns = columns_from_header(fields, path, line_number, options);
        continue;
      }
      if (!options.value_column.empty()) {
        io_detail::throw_file_error(kCsv, path, line_number,
                                    "the value column '" + options.value_column +
                                        "' was asked for by name, but the file has no header");
      }
      columns = Columns{0, 1, fields.size() >= 3 ? 2 : -1, {}};
    }
    const auto number = [&](int index) {
      if (index >= static_cast<int>(fields.size()) || fields[index].empty()) {
        io_detail::throw_file_error(kCsv, path, line_number,
                                    "missing column " + column_name(*columns, index) + " (column " +
                                        std::to_string(index + 1) + ")");
      }
      const std::optional<double> value = parse_number(fields[index]);
      if (!value || !std::isfinite(*value)) {
        io_detail::throw_file_error(kCsv, path, line_number,
                                    "column " + column_name(*columns, index) + " is '" +
                                        std::string(fields[index]) + "', not a finite number");
      }
      return *value;
    };
    xs.push_back(number(columns->x));
    ys.push_back(number(columns->y));
    if (columns->value >= 0) {
      values.push_back(number(columns->value));
    }
    data.lines.push_back(line_number);
  }

  const auto n = static_cast<int>(xs.size());
  if (n < 3) {
    io_detail::throw_file_error(kCsv, path,
                                std::to_string(n) + " point(s); a triangulation needs at least 3");
  }
  data.points.resize(2, n);
  for (int i = 0; i < n; ++i) {
    data.points.col(i) = Eigen::Vector2d(xs[i], ys[i]);
  }
  if (!values.empty()) {
    data.values = Eigen::Map<const Eigen::VectorXd>(values.data(), n);
  }

  std::map<std::pair<double, double>, int> seen;
  for (int i = 0; i < n; ++i) {
    const auto [where, inserted] = seen.emplace(std::pair{xs[i], ys[i]}, i);
    if (!inserted) {
      io_detail::throw_file_error(kCsv, path, data.lines[i],
                                  "the point (" + format_number(xs[i]) + ", " +
                                      format_number(ys[i]) + ") is the same as on line " +
                                      std::to_string(data.lines[where->second]));
    }
  }

  // All on one line: every point is within a relative 1e-12 of the line through point 0 and
  // the point farthest from it.
  int far = 0;
  for (int i = 1; i < n; ++i) {
    if ((data.points.col(i) - data.points.col(0)).squaredNorm() >
        (data.points.col(far) - data.points.col(0)).squaredNorm()) {
      far = i;
    }
  }
  const Eigen::Vector2d origin = data.points.col(0);
  const Eigen::Vector2d direction = data.points.col(far) - origin;
  bool is_collinear = true;
  for (int i = 0; i < n && is_collinear; ++i) {
    const Eigen::Vector2d v = data.points.col(i) - origin;
    const double cross = direction.x() * v.y() - direction.y() * v.x();
    is_collinear = std::abs(cross) <= 1e-12 * direction.squaredNorm();
  }
  if (is_collinear) {
    io_detail::throw_file_error(
        kCsv, path,
        "all " + std::to_string(n) + " points lie on one line; a triangulation needs an area");
  }
  return data;
}

ScatteredData read_scattered_data_csv(const std::string& path,
                                      const ScatteredDataCsvOptions& options) {
  return parse_scattered_data_csv(io_detail::read_file(kCsv, path), path, options);
}

}  // namespace tessera
