// SPDX-License-Identifier: MIT
#include "tessera/io/polylines.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "tessera/core/error.h"
#include "tessera/io/file_names.h"
#include "tessera/io/detail/file_buffer.h"
#include "tessera/io/text_file.h"

namespace tessera {

namespace {

int point_total(const std::vector<Polyline>& polylines) {
  int total = 0;
  for (const Polyline& line : polylines) {
    total += static_cast<int>(line.points.cols());
  }
  return total;
}

bool is_marked(const Polyline& line, int i) {
  return !line.marked.empty() && line.marked[static_cast<std::size_t>(i)];
}

// The point indices of each polyline in the file's numbering; a closed one repeats its first.
std::vector<std::vector<int>> line_indices(const std::vector<Polyline>& polylines) {
  std::vector<std::vector<int>> lines;
  int offset = 0;
  for (const Polyline& line : polylines) {
    const int m = static_cast<int>(line.points.cols());
    std::vector<int> indices;
    for (int i = 0; i < m; ++i) {
      indices.push_back(offset + i);
    }
    if (line.is_closed && m > 2) {
      indices.push_back(offset);
    }
    lines.push_back(std::move(indices));
    offset += m;
  }
  return lines;
}

// Calls f(line, i) for every point in file order.
template <class Function>
void for_each_point(const std::vector<Polyline>& polylines, Function f) {
  for (const Polyline& line : polylines) {
    for (int i = 0; i < line.points.cols(); ++i) {
      f(line, i);
    }
  }
}

void write_values(io_detail::OutputFile& file, const std::vector<Polyline>& polylines,
                  int coordinate) {
  for_each_point(polylines, [&](const Polyline& line, int i) {
    file.real(line.points(coordinate, i));
    file.character('\n');
  });
}

void write_xyz(io_detail::OutputFile& file, const Polyline& line, int i, char separator) {
  const int k = static_cast<int>(line.points.rows());
  for (int c = 0; c < 3; ++c) {
    if (c > 0) {
      file.character(separator);
    }
    file.real(c < k ? line.points(c, i) : 0.0);
  }
}

void write_vtk(const std::string& path, const std::vector<Polyline>& polylines,
               const PolylineFileOptions& options) {
  io_detail::OutputFile file("VTK", path);
  std::string title = "tessera polylines";
  if (!options.kind.empty()) {
    title += "; kind: " + options.kind;
  }
  for (const auto& comment : options.comments) {
    title += "; " + comment;
  }
  title = title.substr(0, 255);  // the legacy format's limit
  file.text("# vtk DataFile Version 3.0\n");
  file.text(title);
  file.text("\nASCII\nDATASET POLYDATA\nPOINTS ");
  const int total = point_total(polylines);
  file.integer(total);
  file.text(" double\n");
  for_each_point(polylines, [&](const Polyline& line, int i) {
    write_xyz(file, line, i, ' ');
    file.character('\n');
  });
  const auto lines = line_indices(polylines);
  long size = 0;
  for (const auto& indices : lines) {
    size += static_cast<long>(indices.size()) + 1;
  }
  file.text("LINES ");
  file.integer(static_cast<std::int64_t>(lines.size()));
  file.character(' ');
  file.integer(size);
  file.character('\n');
  for (const auto& indices : lines) {
    file.integer(static_cast<std::int64_t>(indices.size()));
    for (const int index : indices) {
      file.character(' ');
      file.integer(index);
    }
    file.character('\n');
  }
  file.text("POINT_DATA ");
  file.integer(total);
  file.character('\n');
  for (std::size_t c = 0; c < options.names.size(); ++c) {
    file.text("SCALARS " + options.names[c] + " double 1\nLOOKUP_TABLE default\n");
    write_values(file, polylines, static_cast<int>(c));
  }
  file.text("SCALARS " + options.marker_name + " int 1\nLOOKUP_TABLE default\n");
  for_each_point(polylines, [&](const Polyline& line, int i) {
    file.integer(is_marked(line, i) ? 1 : 0);
    file.character('\n');
  });
  file.close();
}

void write_vtu(const std::string& path, const std::vector<Polyline>& polylines,
               const PolylineFileOptions& options) {
  constexpr int kVtkPolyLine = 4;
  io_detail::OutputFile file("VTU", path);
  const auto lines = line_indices(polylines);
  file.text("<?xml version=\"1.0\"?>\n");
  if (!options.kind.empty()) {
    file.text("<!-- kind: " + options.kind + " -->\n");
  }
  for (const auto& comment : options.comments) {
    file.text("<!-- " + xml_comment_text(comment) + " -->\n");
  }
  file.text("<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
            "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"");
  file.integer(point_total(polylines));
  file.text("\" NumberOfCells=\"");
  file.integer(static_cast<std::int64_t>(lines.size()));
  file.text("\">\n      <PointData>\n");
  for (std::size_t c = 0; c < options.names.size(); ++c) {
    file.text("        <DataArray type=\"Float64\" Name=\"" + xml_escaped(options.names[c]) +
              "\" format=\"ascii\">\n");
    write_values(file, polylines, static_cast<int>(c));
    file.text("        </DataArray>\n");
  }
  file.text("        <DataArray type=\"Int32\" Name=\"" + xml_escaped(options.marker_name) +
            "\" format=\"ascii\">\n");
  for_each_point(polylines, [&](const Polyline& line, int i) {
    file.integer(is_marked(line, i) ? 1 : 0);
    file.character('\n');
  });
  file.text("        </DataArray>\n      </PointData>\n      <Points>\n"
            "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
  for_each_point(polylines, [&](const Polyline& line, int i) {
    write_xyz(file, line, i, ' ');
    file.character('\n');
  });
  file.text("        </DataArray>\n      </Points>\n      <Cells>\n"
            "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
  for (const auto& indices : lines) {
    for (const int index : indices) {
      file.integer(index);
      file.character(' ');
    }
    file.character('\n');
  }
  file.text("        </DataArray>\n"
            "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
  std::int64_t offset = 0;
  for (const auto& indices : lines) {
    offset += static_cast<std::int64_t>(indices.size());
    file.integer(offset);
    file.character('\n');
  }
  file.text("        </DataArray>\n"
            "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
  for (std::size_t l = 0; l < lines.size(); ++l) {
    file.integer(kVtkPolyLine);
    file.character('\n');
  }
  file.text("        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n"
            "</VTKFile>\n");
  file.close();
}

void write_ply(const std::string& path, const std::vector<Polyline>& polylines,
               const PolylineFileOptions& options) {
  io_detail::OutputFile file("PLY", path);
  const auto lines = line_indices(polylines);
  long edge_count = 0;
  for (const auto& indices : lines) {
    edge_count += std::max<long>(0, static_cast<long>(indices.size()) - 1);
  }
  file.text("ply\nformat ascii 1.0\n");
  if (!options.kind.empty()) {
    file.text("comment kind: " + options.kind + "\n");
  }
  for (const auto& comment : options.comments) {
    file.text("comment " + comment + "\n");
  }
  std::string names;
  for (const auto& name : options.names) {
    names += " " + name;
  }
  file.text("comment coordinate names:" + names + "\n");
  file.text("element vertex ");
  file.integer(point_total(polylines));
  file.text("\nproperty double x\nproperty double y\nproperty double z\n");
  for (std::size_t c = 3; c < options.names.size(); ++c) {
    file.text("property double " + options.names[c] + "\n");
  }
  file.text("property uchar " + options.marker_name + "\nelement edge ");
  file.integer(edge_count);
  file.text("\nproperty int vertex1\nproperty int vertex2\nend_header\n");
  for_each_point(polylines, [&](const Polyline& line, int i) {
    write_xyz(file, line, i, ' ');
    for (int c = 3; c < line.points.rows(); ++c) {
      file.character(' ');
      file.real(line.points(c, i));
    }
    file.text(is_marked(line, i) ? " 1\n" : " 0\n");
  });
  for (const auto& indices : lines) {
    for (std::size_t i = 1; i < indices.size(); ++i) {
      file.integer(indices[i - 1]);
      file.character(' ');
      file.integer(indices[i]);
      file.character('\n');
    }
  }
  file.close();
}

void write_json(const std::string& path, const std::vector<Polyline>& polylines,
                const PolylineFileOptions& options) {
  nlohmann::json document;
  document["columns"] = options.names;
  document["marker"] = options.marker_name;
  if (!options.kind.empty()) {
    document["kind"] = options.kind;
  }
  document["comments"] = options.comments;
  document["polylines"] = nlohmann::json::array();
  for (const Polyline& line : polylines) {
    nlohmann::json points = nlohmann::json::array();
    nlohmann::json marked = nlohmann::json::array();
    for (int i = 0; i < line.points.cols(); ++i) {
      points.push_back(std::vector<double>(line.points.col(i).data(),
                                           line.points.col(i).data() + line.points.rows()));
      if (is_marked(line, i)) {
        marked.push_back(i);
      }
    }
    document["polylines"].push_back(
        {{"closed", line.is_closed}, {"points", std::move(points)}, {"marked", std::move(marked)}});
  }
  io_detail::write_whole_file("JSON", path, document.dump(1) + "\n");
}

void write_csv(const std::string& path, const std::vector<Polyline>& polylines,
               const PolylineFileOptions& options) {
  io_detail::OutputFile file("CSV", path);
  for (const auto& comment : options.comments) {
    file.text("# " + comment + "\n");
  }
  if (!options.kind.empty()) {
    file.text("# kind: " + options.kind + "\n");
  }
  file.text("curve,point");
  for (const auto& name : options.names) {
    file.text("," + name);
  }
  file.text("," + options.marker_name + "\n");
  int curve = 0;
  for (const Polyline& line : polylines) {
    for (int i = 0; i < line.points.cols(); ++i) {
      file.integer(curve);
      file.character(',');
      file.integer(i);
      for (int c = 0; c < line.points.rows(); ++c) {
        file.character(',');
        file.real(line.points(c, i));
      }
      file.text(is_marked(line, i) ? ",1\n" : ",0\n");
    }
    ++curve;
  }
  file.close();
}

bool is_name(const std::string& name) {
  if (name.empty()) {
    return false;
  }
  for (const char c : name) {
    if (std::isspace(static_cast<unsigned char>(c)) || c == ',' || c == '"') {
      return false;
    }
  }
  return true;
}

// Letters, digits and '_': a kind goes into comments of every format (an XML comment may not
// hold "--").
bool is_word(const std::string& text) {
  return !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
}

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
  }
  PolylineFile file;
  if (!document.is_object() || !document.contains("polylines")) {
    refuse(path,
           "expected an object with \"polylines\" (the JSON of `tessera mesh "
           "--folds-output`), found " +
               (document.is_object() ? std::string("an object without it")
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
      if (!point.is_array() ||
          !std::all_of(point.begin(), point.end(), [](const auto& x) { return x.is_number(); })) {
        refuse(path, at + " must be an array of numbers");
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
        const double value = point[static_cast<std::size_t>(c)].get<double>();
        if (!std::isfinite(value)) {
          refuse(path, at + " has a coordinate that is not finite");
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
      if (used == 0 || used != field.size() || !std::isfinite(value)) {
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
  for (Eigen::Index j = 0; j < points.cols(); ++j) {
    if (!used[static_cast<std::size_t>(j)]) {
      Polyline single;
      single.points = points.col(j);
      single.marked = {marks[static_cast<std::size_t>(j)] != 0};
      polylines.push_back(std::move(single));
    }
  }
  return polylines;
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

// Legacy VTK as write_vtk writes it: POINTS, LINES, then one SCALARS array per column and the
// marks (the int array).
PolylineFile read_vtk_polylines(const std::string& path, const std::string& text) {
  PolylineFile file;
  Words words(path, text);
  words.line();  // "# vtk DataFile Version 3.0"
  file.options.kind = kind_from(words.line());
  words.expect("ASCII", "the format");
  words.expect("DATASET", "the data set");
  words.expect("POLYDATA", "the data set");
  words.expect("POINTS", "the points");
  const long count = words.integer("the point count");
  words.next("the point type");
  for (long i = 0; i < 3 * count; ++i) {
    words.number("a point");
  }
  words.expect("LINES", "the lines");
  const long line_count = words.integer("the line count");
  words.integer("the lines' size");
  std::vector<std::vector<int>> lines(static_cast<std::size_t>(line_count));
  for (auto& indices : lines) {
    const long size = words.integer("a line's length");
    for (long i = 0; i < size; ++i) {
      const long index = words.integer("a point index");
      if (index >= count) {
        refuse(path, "a line refers to point " + std::to_string(index) + " of " + std::to_string(count));
      }
      indices.push_back(static_cast<int>(index));
    }
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
  std::vector<std::vector<int>> lines;
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
    lines.push_back(std::move(indices));
  }
  file.polylines = assemble_polylines(points, marks, lines);
  return file;
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
      count = std::stol(line.substr(15));
      in_vertex = true;
    } else if (line.rfind("element edge ", 0) == 0) {
      edge_count = std::stol(line.substr(13));
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

bool is_polyline_file(const std::string& path) {
  static const std::set<std::string> known = {".vtk", ".vtu", ".ply", ".json", ".csv"};
  return known.count(lowercase_extension(path)) != 0;
}

void write_polylines(const std::string& path, const std::vector<Polyline>& polylines,
                     const PolylineFileOptions& options) {
  const int k = static_cast<int>(options.names.size());
  TESSERA_CHECK(k >= 2, "polylines '" << path << "': need at least two coordinate names, got "
                                      << k);
  std::set<std::string> seen{options.marker_name};
  TESSERA_CHECK(is_name(options.marker_name),
                "polylines '" << path << "': bad marker name '" << options.marker_name << "'");
  TESSERA_CHECK(options.kind.empty() || is_word(options.kind),
                "polylines '" << path << "': bad kind '" << options.kind
                              << "' (a word such as fold, hopf, neutral_saddle, level)");
  for (const auto& name : options.names) {
    TESSERA_CHECK(is_name(name), "polylines '" << path << "': bad coordinate name '" << name
                                               << "' (empty, or with a space, comma or quote)");
    TESSERA_CHECK(seen.insert(name).second,
                  "polylines '" << path << "': the name '" << name << "' occurs twice");
  }
  for (const Polyline& line : polylines) {
    TESSERA_CHECK(line.points.rows() == k, "polylines '" << path << "': a polyline has points in R^"
                                                         << line.points.rows() << ", the names R^"
                                                         << k);
    TESSERA_CHECK(line.marked.empty() || line.marked.size() == static_cast<std::size_t>(line.points.cols()),
                  "polylines '" << path << "': " << line.marked.size() << " marks for "
                                << line.points.cols() << " points");
  }
  const std::string extension = lowercase_extension(path);
  if (extension == ".vtk") {
    write_vtk(path, polylines, options);
  } else if (extension == ".vtu") {
    write_vtu(path, polylines, options);
  } else if (extension == ".ply") {
    write_ply(path, polylines, options);
  } else if (extension == ".json") {
    write_json(path, polylines, options);
  } else if (extension == ".csv") {
    write_csv(path, polylines, options);
  } else {
    TESSERA_CHECK(false, "cannot write polylines to '" << path << "': unknown extension '"
                                                        << extension
                                                        << "' (use .vtk, .vtu, .ply, .json or .csv)");
  }
}

}  // namespace tessera
