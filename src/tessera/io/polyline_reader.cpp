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
#include "tessera/io/file_names.h"
#include "tessera/io/output_checks.h"

namespace tessera {

namespace {

[[noreturn]] void refuse(const std::string& path, const std::string& message) {
  throw InvalidArgument("polylines file '" + path + "': " + message);
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

// VTK_LINE, the segments of the curve files (vtkCellType.h).
constexpr int kVtkLine = 3;

// The point lists of polylines from VTK cells in file order: consecutive segments (VTK_LINE) that
// share a point are one polyline, as write_polylines writes them (one segment per pair of
// consecutive points; a closed polyline ends with the segment back to its first point, after
// which nothing more joins it); any other cell (a vertex, a VTK_POLY_LINE of earlier files) is a
// polyline of its own.
std::vector<std::vector<int>> join_segments(const std::vector<int>& types,
                                            const std::vector<std::vector<int>>& cells) {
  std::vector<std::vector<int>> lines;
  bool can_extend = false;  // the last polyline is made of segments and still open
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const auto& cell = cells[c];
    const bool is_segment = types[c] == kVtkLine && cell.size() == 2;
    if (is_segment && can_extend && lines.back().back() == cell[0]) {
      lines.back().push_back(cell[1]);
    } else {
      lines.push_back(cell);
    }
    can_extend =
        is_segment && !(lines.back().size() > 2 && lines.back().front() == lines.back().back());
  }
  return lines;
}

// The words of `text` from `at`, whitespace separated, as write_vtk/write_ply write them.
class Words {
 public:
  Words(const std::string& path, const std::string& text) : path_(path), in_(text) {}
  std::string next(const char* what) {
    std::string word;
    if (!(in_ >> word)) {
      refuse(path_, std::string("ends before ") + what);
    }
    return word;
  }
  double number(const char* what) {
    const std::string word = next(what);
    try {
      std::size_t used = 0;
      const double value = std::stod(word, &used);
      if (used == word.size()) {
        return value;
      }
    } catch (const std::exception&) {
    }
    refuse(path_, std::string("'") + word + "' is not a number (" + what + ")");
  }
  long integer(const char* what) {
    const double value = number(what);
    if (value != std::floor(value) || value < 0) {
      refuse(path_, std::string("'") + std::to_string(value) + "' is not a count or index (" + what + ")");
    }
    return static_cast<long>(value);
  }
  std::string line() {
    std::string text;
    std::getline(in_, text);
    return text;
  }
  void expect(const std::string& word, const char* where) {
    const std::string found = next(where);
    if (found != word) {
      refuse(path_, "expected '" + word + "' (" + where + "), found '" + found + "'");
    }
  }

 private:
  const std::string& path_;
  std::istringstream in_;
};

std::string kind_from(const std::string& text) {
  const auto at = text.find("kind: ");
  if (at == std::string::npos) {
    return "";
  }
  const auto begin = at + 6;
  const auto end = text.find_first_of("; \n", begin);
  return text.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
}

// Legacy VTK as write_vtk writes it: POINTS, CELLS and CELL_TYPES (segments and vertices) of an
// UNSTRUCTURED_GRID, or LINES of the POLYDATA of earlier versions, then one SCALARS array per
// column and the marks (the int array).
PolylineFile read_vtk_polylines(const std::string& path, const std::string& text) {
  PolylineFile file;
  Words words(path, text);
  words.line();  // "# vtk DataFile Version 4.2"
  file.options.kind = kind_from(words.line());
  words.expect("ASCII", "the format");
  words.expect("DATASET", "the data set");
  const std::string dataset = words.next("the data set");
  if (dataset != "UNSTRUCTURED_GRID" && dataset != "POLYDATA") {
    refuse(path,
           "expected 'DATASET UNSTRUCTURED_GRID' (or 'POLYDATA', as tessera wrote "
           "curves before), found '" +
               dataset + "'");
  }
  const bool is_unstructured = dataset == "UNSTRUCTURED_GRID";
  words.expect("POINTS", "the points");
  const long count = words.integer("the point count");
  words.next("the point type");
  for (long i = 0; i < 3 * count; ++i) {
    words.number("a point");
  }
  words.expect(is_unstructured ? "CELLS" : "LINES", "the lines");
  const long cell_count = words.integer("the line count");
  words.integer("the lines' size");
  // Checked against the rest of the text before anything of that size is allocated: every cell
  // takes at least two characters.
  if (static_cast<double>(cell_count) > static_cast<double>(text.size()) / 2) {
    refuse(path, "claims " + std::to_string(cell_count) + " cells, more than the file can hold");
  }
  std::vector<std::vector<int>> cells(static_cast<std::size_t>(cell_count));
  for (auto& indices : cells) {
    const long size = words.integer("a line's length");
    for (long i = 0; i < size; ++i) {
      const long index = words.integer("a point index");
      if (index >= count) {
        refuse(path, "a line refers to point " + std::to_string(index) + " of " + std::to_string(count));
      }
      indices.push_back(static_cast<int>(index));
    }
  }
  std::vector<std::vector<int>> lines = cells;
  if (is_unstructured) {
    words.expect("CELL_TYPES", "the cell types");
    if (words.integer("the cell type count") != cell_count) {
      refuse(path, "CELL_TYPES does not match the " + std::to_string(cell_count) + " CELLS");
    }
    std::vector<int> types;
    for (long c = 0; c < cell_count; ++c) {
      types.push_back(static_cast<int>(words.integer("a cell type")));
    }
    lines = join_segments(types, cells);
  }
  words.expect("POINT_DATA", "the point data");
  words.integer("the point data's count");
  std::vector<std::vector<double>> columns;
  std::vector<int> marks(static_cast<std::size_t>(count), 0);
  for (;;) {
    std::string word;
    try {
      word = words.next("an array");
    } catch (const InvalidArgument&) {
      break;  // the end of the file
    }
    if (word != "SCALARS") {
      refuse(path, "expected SCALARS, found '" + word + "'");
    }
    const std::string name = words.next("an array's name");
    const std::string type = words.next("an array's type");
    words.next("an array's components");
    words.expect("LOOKUP_TABLE", "an array");
    words.next("the lookup table");
    std::vector<double> values;
    for (long i = 0; i < count; ++i) {
      values.push_back(words.number("an array's value"));
    }
    if (type == "int") {
      file.options.marker_name = name;
      for (long i = 0; i < count; ++i) {
        marks[static_cast<std::size_t>(i)] = values[static_cast<std::size_t>(i)] != 0.0;
      }
    } else {
      file.options.names.push_back(name);
      columns.push_back(std::move(values));
    }
  }
  Eigen::MatrixXd points(static_cast<Eigen::Index>(columns.size()), count);
  for (std::size_t c = 0; c < columns.size(); ++c) {
    for (long i = 0; i < count; ++i) {
      points(static_cast<Eigen::Index>(c), i) = columns[c][static_cast<std::size_t>(i)];
    }
  }
  file.polylines = assemble_polylines(points, marks, lines);
  return file;
}

// The values of every <DataArray> in the XML text, by name, in order.
std::vector<std::pair<std::string, std::vector<double>>> vtu_arrays(const std::string& path,
                                                                   const std::string& text,
                                                                   std::vector<std::string>& types) {
  std::vector<std::pair<std::string, std::vector<double>>> arrays;
  for (std::size_t at = text.find("<DataArray"); at != std::string::npos;
       at = text.find("<DataArray", at + 1)) {
    const std::size_t close = text.find('>', at);
    const std::size_t end = text.find("</DataArray>", close);
    if (close == std::string::npos || end == std::string::npos) {
      refuse(path, "a DataArray is not closed");
    }
    const std::string tag = text.substr(at, close - at);
    auto attribute = [&](const std::string& key) {
      const auto begin = tag.find(key + "=\"");
      if (begin == std::string::npos) {
        return std::string();
      }
      const auto from = begin + key.size() + 2;
      return tag.substr(from, tag.find('"', from) - from);
    };
    std::vector<double> values;
    Words words(path, text.substr(close + 1, end - close - 1));
    for (;;) {
      try {
        values.push_back(words.number("a DataArray's value"));
      } catch (const InvalidArgument& error) {
        if (std::string(error.what()).find("ends before") == std::string::npos) {
          throw;
        }
        break;
      }
    }
    arrays.emplace_back(attribute("Name"), std::move(values));
    types.push_back(attribute("type"));
  }
  return arrays;
}

// VTU as write_vtu writes it: the point data arrays (columns, then the Int32 marks), the points
// and VTK_POLY_LINE cells.
PolylineFile read_vtu_polylines(const std::string& path, const std::string& text) {
  PolylineFile file;
  const auto kind_at = text.find("<!-- kind: ");
  if (kind_at != std::string::npos) {
    file.options.kind = kind_from(text.substr(kind_at, 200));
  }
  const std::size_t point_data_end = text.find("</PointData>");
  if (point_data_end == std::string::npos) {
    refuse(path, "no <PointData> with the curves' columns");
  }
  std::vector<std::string> types;
  const auto arrays = vtu_arrays(path, text, types);
  std::vector<double> connectivity;
  std::vector<double> offsets;
  std::vector<double> cell_types;
  std::vector<const std::vector<double>*> columns;
  std::vector<int> marks;
  std::size_t point_arrays = 0;
  for (std::size_t at = text.find("<DataArray"); at != std::string::npos && at < point_data_end;
       at = text.find("<DataArray", at + 1)) {
    ++point_arrays;
  }
  for (std::size_t a = 0; a < arrays.size(); ++a) {
    const auto& [name, values] = arrays[a];
    if (a < point_arrays) {
      if (types[a] == "Int32") {
        file.options.marker_name = name;
        for (const double v : values) {
          marks.push_back(v != 0.0);
        }
      } else {
        file.options.names.push_back(name);
        columns.push_back(&values);
      }
    } else if (name == "connectivity") {
      connectivity = values;
    } else if (name == "offsets") {
      offsets = values;
    } else if (name == "types") {
      cell_types = values;
    }
  }
  const long count = columns.empty() ? 0 : static_cast<long>(columns.front()->size());
  marks.resize(static_cast<std::size_t>(count), 0);
  Eigen::MatrixXd points(static_cast<Eigen::Index>(columns.size()), count);
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (static_cast<long>(columns[c]->size()) != count) {
      refuse(path, "the point data arrays differ in length");
    }
    for (long i = 0; i < count; ++i) {
      points(static_cast<Eigen::Index>(c), i) = (*columns[c])[static_cast<std::size_t>(i)];
    }
  }
  std::vector<std::vector<int>> cells;
  std::size_t begin = 0;
  for (const double end : offsets) {
    std::vector<int> indices;
    for (std::size_t i = begin; i < static_cast<std::size_t>(end) && i < connectivity.size(); ++i) {
      const auto index = static_cast<long>(connectivity[i]);
      if (index < 0 || index >= count) {
        refuse(path, "a cell refers to point " + std::to_string(index) + " of " + std::to_string(count));
      }
      indices.push_back(static_cast<int>(index));
    }
    begin = static_cast<std::size_t>(end);
    cells.push_back(std::move(indices));
  }
  // Segments and vertices (this version), or one VTK_POLY_LINE per polyline (earlier ones).
  std::vector<int> cell_type(cells.size(), 0);
  for (std::size_t c = 0; c < cells.size() && c < cell_types.size(); ++c) {
    cell_type[c] = static_cast<int>(cell_types[c]);
  }
  file.polylines = assemble_polylines(points, marks, join_segments(cell_type, cells));
  return file;
}

// The count of an `element` line from `at` on: a non-negative integer that a file of `size`
// bytes can hold (every item takes at least two characters), checked before anything of that
// size is allocated.
long header_count(const std::string& path, const std::string& line, std::size_t at,
                  std::size_t size) {
  const std::string text = line.substr(at);
  long value = -1;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value < 0) {
    refuse(path, "'" + line + "': the count is not a non-negative integer");
  }
  if (static_cast<double>(value) > static_cast<double>(size) / 2) {
    refuse(path,
           "'" + line + "': more than the file of " + std::to_string(size) + " bytes can hold");
  }
  return value;
}

// ASCII PLY as write_ply writes it: the columns' names in a comment, vertices (x, y, z, the
// further columns, the marks), edges between consecutive points of a polyline.
PolylineFile read_ply_polylines(const std::string& path, const std::string& text) {
  PolylineFile file;
  std::istringstream in(text);
  std::string line;
  long count = -1;
  long edge_count = -1;
  int property_count = 0;
  bool in_vertex = false;
  while (std::getline(in, line) && line != "end_header") {
    if (line.rfind("comment kind: ", 0) == 0) {
      file.options.kind = line.substr(14);
    } else if (line.rfind("comment coordinate names:", 0) == 0) {
      std::istringstream names(line.substr(25));
      for (std::string name; names >> name;) {
        file.options.names.push_back(name);
      }
    } else if (line.rfind("element vertex ", 0) == 0) {
      count = header_count(path, line, 15, text.size());
      in_vertex = true;
    } else if (line.rfind("element edge ", 0) == 0) {
      edge_count = header_count(path, line, 13, text.size());
      in_vertex = false;
    } else if (line.rfind("property ", 0) == 0 && in_vertex) {
      ++property_count;
      file.options.marker_name = line.substr(line.rfind(' ') + 1);  // the last: the marks
    } else if (line.rfind("format ", 0) == 0 && line != "format ascii 1.0") {
      refuse(path, "not a polylines file of tessera (tessera writes curves as ASCII PLY, this is '" +
                       line + "': a mesh?)");
    }
  }
  if (count < 0 || edge_count < 0 || file.options.names.empty()) {
    refuse(path, "not a polylines file of tessera (a vertex and an edge element and a "
                 "'comment coordinate names:' line are needed)");
  }
  const int k = static_cast<int>(file.options.names.size());
  if (property_count != std::max(k, 3) + 1) {
    refuse(path, "its vertices have " + std::to_string(property_count) + " properties; " +
                     std::to_string(k) + " columns and the marks need " +
                     std::to_string(std::max(k, 3) + 1));
  }
  std::string rest((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Words words(path, rest);
  Eigen::MatrixXd points(k, count);
  std::vector<int> marks(static_cast<std::size_t>(count), 0);
  for (long i = 0; i < count; ++i) {
    for (int c = 0; c < std::max(k, 3); ++c) {
      const double value = words.number("a vertex");
      if (c < k) {
        points(c, i) = value;
      }
    }
    marks[static_cast<std::size_t>(i)] = words.number("a vertex's mark") != 0.0;
  }
  // Consecutive edges (a, b), (b, c), … form one polyline; one back to its start closes it.
  std::vector<std::vector<int>> lines;
  for (long e = 0; e < edge_count; ++e) {
    const long a = words.integer("an edge");
    const long b = words.integer("an edge");
    if (a >= count || b >= count) {
      refuse(path, "an edge refers to a vertex beyond the " + std::to_string(count));
    }
    if (lines.empty() || lines.back().back() != a || (lines.back().size() > 2 && lines.back().front() == lines.back().back())) {
      lines.push_back({static_cast<int>(a)});
    }
    lines.back().push_back(static_cast<int>(b));
  }
  file.polylines = assemble_polylines(points, marks, lines);
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
    return read_vtk_polylines(path, text);
  }
  return extension == ".vtu" ? read_vtu_polylines(path, text) : read_ply_polylines(path, text);
}

}  // namespace tessera
