// SPDX-License-Identifier: MIT
#include "tessera/io/detail/polyline_mesh_formats.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>

#include "tessera/core/error.h"

namespace tessera::io_detail {
namespace {

[[noreturn]] void refuse(const std::string& path, const std::string& message) {
  refuse_polylines(path, message);
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

}  // namespace

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

namespace {

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

}  // namespace

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

namespace {

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

}  // namespace

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

}  // namespace tessera::io_detail
