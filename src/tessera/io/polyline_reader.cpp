// SPDX-License-Identifier: MIT
// read_polylines: the polyline files write_polylines writes (polylines.cpp), read back, for
// `tessera render --curves` and `--diagram`.
#include "tessera/io/polylines.h"

#include <Eigen/Core>
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tessera/core/error.h"
#include "tessera/io/detail/file_buffer.h"
#include "tessera/io/detail/polyline_mesh_formats.h"
#include "tessera/io/file_names.h"
#include "tessera/io/output_checks.h"

namespace tessera {

namespace io_detail {

void refuse_polylines(const std::string& path, const std::string& message) {
  throw InvalidArgument("polylines file '" + path + "': " + message);
}

// Polylines from the points of a file (k×N, in file order) and its lines as index lists (a closed
// polyline repeats its first index, as line_indices writes it); points in no line are polylines
// of one point (special points).
std::vector<Polyline> assemble_polylines(const Eigen::MatrixXd& points, const std::vector<int>& marks,
                                         const std::vector<std::vector<int>>& lines) {
  std::vector<Polyline> polylines;
  std::vector<char> used(static_cast<std::size_t>(points.cols()), 0);
  for (const auto& indices : lines) {
    std::vector<int> order = indices;
    Polyline line;
    line.is_closed = order.size() > 2 && order.front() == order.back();
    if (line.is_closed) {
      order.pop_back();
    }
    line.points.resize(points.rows(), static_cast<Eigen::Index>(order.size()));
    for (std::size_t i = 0; i < order.size(); ++i) {
      line.points.col(static_cast<Eigen::Index>(i)) = points.col(order[i]);
      line.marked.push_back(marks[static_cast<std::size_t>(order[i])] != 0);
      used[static_cast<std::size_t>(order[i])] = 1;
    }
    polylines.push_back(std::move(line));
  }
  std::vector<Eigen::Index> firsts;
  for (const auto& indices : lines) {
    firsts.push_back(indices.empty() ? points.cols()
                                     : *std::min_element(indices.begin(), indices.end()));
  }
  for (Eigen::Index j = 0; j < points.cols(); ++j) {
    if (!used[static_cast<std::size_t>(j)]) {
      Polyline single;
      single.points = points.col(j);
      single.marked = {marks[static_cast<std::size_t>(j)] != 0};
      polylines.push_back(std::move(single));
      firsts.push_back(j);
    }
  }
  // In file order: write_polylines numbers the points polyline by polyline, so a polyline's
  // smallest index says where it was (a point on its own among them too, as PLY has no cell for
  // it).
  std::vector<std::size_t> order(polylines.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    order[i] = i;
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return firsts[a] < firsts[b]; });
  std::vector<Polyline> sorted;
  sorted.reserve(polylines.size());
  for (const std::size_t i : order) {
    sorted.push_back(std::move(polylines[i]));
  }
  return sorted;
}

}  // namespace io_detail

namespace {

using io_detail::assemble_polylines;

[[noreturn]] void refuse(const std::string& path, const std::string& message) {
  io_detail::refuse_polylines(path, message);
}

// The JSON type of `value` in words, for messages.
std::string type_of(const nlohmann::json& value) { return std::string(value.type_name()); }

PolylineFile read_json(const std::string& path, const std::string& text) {
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& error) {
    // error.what() is nlohmann's wording ("[json.exception.parse_error.101] ..."); the byte is
    // what a user needs to find the fault.
    refuse(path, "not valid JSON (the syntax breaks at byte " + std::to_string(error.byte) +
                     "); expected the JSON polylines of `tessera mesh --folds-output`");
  } catch (const nlohmann::json::exception&) {
    // out_of_range.406, "number overflow parsing '1e999'": not a double.
    refuse(path,
           "a number is out of the range of a double (such as 1e999); the coordinates "
           "must be finite");
  }
  PolylineFile file;
  if (!document.is_object() || !document.contains("polylines")) {
    // Another file of tessera (a summary, where the docs once named the curves the same) is
    // named for what it is.
    const TesseraFileKind kind = tessera_file_kind(path);
    refuse(path,
           "expected an object with \"polylines\" (the JSON of `tessera mesh "
           "--folds-output`, --hopf-output or --level-output), found " +
               (kind != TesseraFileKind::None ? describe(kind)
                : document.is_object()        ? std::string("an object without it")
                                              : "a JSON " + type_of(document)));
  }
  auto text_field = [&](const char* key, std::string& out) {
    if (!document.contains(key)) {
      return;
    }
    if (!document[key].is_string()) {
      refuse(path,
             std::string("\"") + key + "\" must be a string, found a " + type_of(document[key]));
    }
    out = document[key].get<std::string>();
  };
  text_field("marker", file.options.marker_name);
  text_field("kind", file.options.kind);
  if (document.contains("columns")) {
    const auto& columns = document["columns"];
    if (!columns.is_array() ||
        !std::all_of(columns.begin(), columns.end(), [](const auto& c) { return c.is_string(); })) {
      refuse(path, "\"columns\" must be an array of names");
    }
    for (const auto& column : columns) {
      file.options.names.push_back(column.get<std::string>());
    }
  }
  if (document.contains("comments") && document["comments"].is_array()) {
    for (const auto& comment : document["comments"]) {
      if (comment.is_string()) {
        file.options.comments.push_back(comment.get<std::string>());
      }
    }
  }
  const auto& polylines = document["polylines"];
  if (!polylines.is_array()) {
    refuse(path, "\"polylines\" must be an array, found a " + type_of(polylines));
  }
  int k = file.options.names.empty() ? -1 : static_cast<int>(file.options.names.size());
  for (std::size_t l = 0; l < polylines.size(); ++l) {
    const auto& item = polylines[l];
    const std::string where = "polyline " + std::to_string(l);
    if (!item.is_object() || !item.contains("points") || !item["points"].is_array()) {
      refuse(path, where + " must be an object with \"points\", an array of points");
    }
    const auto& points = item["points"];
    Polyline line;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const auto& point = points[i];
      const std::string at = where + ", point " + std::to_string(i);
      // null: a value that was not computed (NaN when written, e.g. the first Lyapunov
      // coefficient l1 at a Bogdanov-Takens point, where it is not defined).
      if (!point.is_array() || !std::all_of(point.begin(), point.end(), [](const auto& x) {
            return x.is_number() || x.is_null();
          })) {
        refuse(path, at + " must be an array of numbers (or null for a value not computed)");
      }
      if (k < 0) {
        k = static_cast<int>(point.size());
      }
      if (static_cast<int>(point.size()) != k || k < 2) {
        refuse(path, at + " has " + std::to_string(point.size()) + " coordinates, expected " +
                         (k < 2 ? std::string("at least 2") : std::to_string(k)) +
                         (file.options.names.empty() ? "" : " (the \"columns\")"));
      }
      if (line.points.cols() == 0) {
        line.points.resize(k, static_cast<Eigen::Index>(points.size()));
      }
      for (int c = 0; c < k; ++c) {
        const auto& entry = point[static_cast<std::size_t>(c)];
        const double value =
            entry.is_null() ? std::numeric_limits<double>::quiet_NaN() : entry.get<double>();
        if (std::isinf(value)) {
          refuse(path, at + " has a coordinate that is infinite");
        }
        line.points(c, static_cast<Eigen::Index>(i)) = value;
      }
    }
    line.marked.assign(points.size(), false);
    if (item.contains("marked")) {
      const auto& marked = item["marked"];
      if (!marked.is_array()) {
        refuse(path, where + ": \"marked\" must be an array of point indices");
      }
      for (const auto& index : marked) {
        if (!index.is_number_unsigned() || index.get<std::size_t>() >= points.size()) {
          refuse(path, where + ": \"marked\" holds " + index.dump() + ", not an index of its " +
                           std::to_string(points.size()) + " points");
        }
        line.marked[index.get<std::size_t>()] = true;
      }
    }
    if (item.contains("closed")) {
      if (!item["closed"].is_boolean()) {
        refuse(path, where + ": \"closed\" must be true or false");
      }
      line.is_closed = item["closed"].get<bool>();
    }
    file.polylines.push_back(std::move(line));
  }
  return file;
}

PolylineFile read_csv(const std::string& path, const std::string& text) {
  PolylineFile file;
  std::stringstream stream(text);
  std::string line_text;
  bool has_header = false;
  int columns = 0;
  std::string current;
  int line_number = 0;
  auto fail = [&](const std::string& message) {
    refuse(path, "line " + std::to_string(line_number) + ": " + message);
  };
  while (std::getline(stream, line_text)) {
    ++line_number;
    if (!line_text.empty() && line_text.back() == '\r') {
      line_text.pop_back();  // a file written on Windows
    }
    if (line_text.empty()) {
      continue;
    }
    if (line_text[0] == '#') {
      const std::string comment =
          line_text.substr(line_text.find_first_not_of("# ") == std::string::npos
                               ? line_text.size()
                               : line_text.find_first_not_of("# "));
      if (comment.rfind("kind:", 0) == 0) {
        std::stringstream words(comment.substr(5));
        words >> file.options.kind;
      } else if (!has_header) {
        file.options.comments.push_back(comment);
      }
      continue;
    }
    std::vector<std::string> fields;
    std::stringstream row(line_text);
    for (std::string field; std::getline(row, field, ',');) {
      fields.push_back(field);
    }
    if (!has_header) {
      if (fields.size() < 5 || fields[0] != "curve" || fields[1] != "point") {
        fail("expected the header curve,point,<columns>,<marks> (at least two columns)");
      }
      columns = static_cast<int>(fields.size()) - 3;
      file.options.names.assign(fields.begin() + 2, fields.end() - 1);
      file.options.marker_name = fields.back();
      has_header = true;
      continue;
    }
    if (static_cast<int>(fields.size()) != columns + 3) {
      fail(std::to_string(fields.size()) + " fields, the header has " +
           std::to_string(columns + 3));
    }
    if (file.polylines.empty() || fields[0] != current) {
      file.polylines.emplace_back();
      file.polylines.back().points.resize(columns, 0);
      current = fields[0];
    }
    Polyline& line = file.polylines.back();
    const auto m = line.points.cols();
    line.points.conservativeResize(Eigen::NoChange, m + 1);
    for (int c = 0; c < columns; ++c) {
      const std::string& field = fields[static_cast<std::size_t>(2 + c)];
      double value = 0;
      std::size_t used = 0;
      try {
        value = std::stod(field, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      // nan: a value that was not computed (l1 at a Bogdanov-Takens point); inf is refused.
      if (used == 0 || used != field.size() || std::isinf(value)) {
        fail("not a finite number in column " + file.options.names[static_cast<std::size_t>(c)] +
             ": '" + field + "'");
      }
      line.points(c, m) = value;
    }
    line.marked.push_back(fields.back() == "1");
  }
  if (!has_header) {
    refuse(path, "no header line curve,point,<columns>,<marks>");
  }
  return file;
}


}  // namespace

PolylineFile read_polylines(const std::string& path) {
  const std::string extension = lowercase_extension(path);
  if (!is_polyline_file(path)) {
    refuse(path, "polylines are read from .json, .csv, .vtk, .vtu or .ply (as `tessera mesh "
                 "--folds/--hopf/--level` write them), not '" +
                     extension + "'");
  }
  const std::string text = io_detail::read_file("polylines", path);
  if (extension == ".json") {
    return read_json(path, text);
  }
  if (extension == ".csv") {
    return read_csv(path, text);
  }
  if (extension == ".vtk") {
    return io_detail::read_vtk_polylines(path, text);
  }
  return extension == ".vtu" ? io_detail::read_vtu_polylines(path, text)
                             : io_detail::read_ply_polylines(path, text);
}

}  // namespace tessera
