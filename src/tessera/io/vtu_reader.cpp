// SPDX-License-Identifier: MIT
// read_vtu: the XML UnstructuredGrid files (one Piece, ASCII data arrays) that write_vtu
// produces, read back with all n coordinates (from the PointData arrays) and the triangles.
//
// As read_vtk: counts are checked against the text that holds the values before anything is
// reserved, and every offset and index is checked before use.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/io/detail/file_buffer.h"
#include "tessera/io/detail/mesh_parsers.h"
#include "tessera/io/detail/ply_header.h"
#include "tessera/io/detail/vtk_cell_types.h"
#include "tessera/io/detail/vtk_points.h"
#include "tessera/io/detail/xml_document.h"
#include "tessera/io/vtk.h"

namespace tessera {

using io_detail::append_fan;
using io_detail::dimension_after;
using io_detail::PointArray;
using io_detail::XmlDocument;
using io_detail::XmlElement;

namespace {

constexpr std::string_view kVtu = "VTU";
using io_detail::kVtkPolygon;
using io_detail::kVtkQuad;
using io_detail::kVtkTriangle;

class VtuReader {
 public:
  VtuReader(const std::string& content, const std::string& path) : document_(kVtu, content, path) {}

  TriangleMesh read(std::vector<VertexScalars>* vertex_scalars) {
    const XmlElement& root = document_.root();
    if (root.name != "VTKFile") {
      fail(root, "the root element is '<" + root.name + ">', expected '<VTKFile>'");
    }
    const std::string* type = root.attribute("type");
    if (type == nullptr || *type != "UnstructuredGrid") {
      fail(root, "VTKFile type is '" + (type ? *type : std::string()) +
                     "'; tessera reads UnstructuredGrid (.vtu)");
    }
    const XmlElement& grid = only_child(root, "UnstructuredGrid");
    std::vector<std::size_t> pieces = children(grid, "Piece");
    if (pieces.size() != 1) {
      fail(grid, "the grid has " + std::to_string(pieces.size()) +
                     " pieces; tessera reads files with one Piece");
    }
    const XmlElement& piece = document_.element(pieces.front());
    const std::int64_t vertex_count = count_attribute(piece, "NumberOfPoints");
    const std::int64_t cell_count = count_attribute(piece, "NumberOfCells");

    std::vector<double> xyz;
    read_array(only_child(only_child(piece, "Points"), "DataArray"), vertex_count, 3, xyz);

    std::vector<PointArray> arrays;
    for (const std::size_t index : children(piece, "PointData")) {
      for (const std::size_t array_index : document_.element(index).children) {
        const XmlElement& array = document_.element(array_index);
        if (array.name != "DataArray") {
          continue;
        }
        PointArray point_array;
        const std::string* name = array.attribute("Name");
        point_array.name = name ? *name : std::string();
        point_array.components = components(array);
        read_array(array, vertex_count, point_array.components, point_array.values);
        arrays.push_back(std::move(point_array));
      }
    }

    const XmlElement& cells = only_child(piece, "Cells");
    std::vector<double> connectivity, offsets, types;
    read_array(named_array(cells, "connectivity"), -1, 1, connectivity);
    read_array(named_array(cells, "offsets"), cell_count, 1, offsets);
    read_array(named_array(cells, "types"), cell_count, 1, types);
    std::vector<Triangle> triangles;
    std::vector<std::int64_t> polygon;
    double begin = 0;
    for (std::size_t c = 0; c < offsets.size(); ++c) {
      const double end = offsets[c];
      if (!(end >= begin && end <= static_cast<double>(connectivity.size()) &&
            end == static_cast<double>(static_cast<std::int64_t>(end)))) {
        fail(cells, "cell " + std::to_string(c) + " has offset " + number(end) +
                        "; offsets must be integers, non-decreasing, at most the " +
                        std::to_string(connectivity.size()) + " connectivity entries");
      }
      const auto size = static_cast<std::int64_t>(end - begin);
      const double type = types[c];
      const bool is_fan = (type == kVtkTriangle && size == 3) || (type == kVtkQuad && size == 4) ||
                          (type == kVtkPolygon && size >= 3);
      if (!is_fan) {
        fail(cells, "cell " + std::to_string(c) + " has type " + number(type) + " and " +
                        std::to_string(size) +
                        " vertices; tessera reads triangles (5), quads (9) and polygons (7)");
      }
      polygon.clear();
      for (auto i = static_cast<std::size_t>(begin); i < static_cast<std::size_t>(end); ++i) {
        const double v = connectivity[i];
        if (!(v >= 0 && v < static_cast<double>(vertex_count) &&
              v == static_cast<double>(static_cast<std::int64_t>(v)))) {
          fail(cells, "cell " + std::to_string(c) + " has vertex index " + number(v) +
                          "; the file has " + std::to_string(vertex_count) + " points");
        }
        polygon.push_back(static_cast<std::int64_t>(v));
      }
      append_fan(polygon, triangles);
      begin = end;
    }
    if (begin != static_cast<double>(connectivity.size())) {
      fail(cells, "the offsets end at " + number(begin) + " but the connectivity has " +
                      std::to_string(connectivity.size()) + " entries");
    }

    int dimension = 0;
    for (const auto& comment : document_.comments()) {
      const std::string_view text = comment;
      const std::size_t first = text.find_first_not_of(' ');
      if (first != std::string_view::npos) {
        dimension = dimension_after(text.substr(first), "written by tessera: triangle mesh in R^");
      }
      if (dimension > 0) {
        break;
      }
    }
    return io_detail::assemble(
        dimension, xyz, arrays, std::move(triangles),
        [&](const std::string& message) { fail(piece, message); }, vertex_scalars);
  }

 private:
  [[noreturn]] void fail(const XmlElement& element, const std::string& message) const {
    document_.fail(element.line, message);
  }

  static std::string number(double value) {
    char buffer[32];
    return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, value).ptr);
  }

  std::vector<std::size_t> children(const XmlElement& parent, std::string_view name) const {
    std::vector<std::size_t> found;
    for (const std::size_t index : parent.children) {
      if (document_.element(index).name == name) {
        found.push_back(index);
      }
    }
    return found;
  }

  const XmlElement& only_child(const XmlElement& parent, std::string_view name) const {
    const auto found = children(parent, name);
    if (found.size() != 1) {
      fail(parent, "'<" + parent.name + ">' has " + std::to_string(found.size()) + " '<" +
                       std::string(name) + ">' elements; expected one");
    }
    return document_.element(found.front());
  }

  const XmlElement& named_array(const XmlElement& parent, std::string_view name) const {
    for (const std::size_t index : parent.children) {
      const XmlElement& child = document_.element(index);
      const std::string* child_name = child.attribute("Name");
      if (child.name == "DataArray" && child_name != nullptr && *child_name == name) {
        return child;
      }
    }
    fail(parent, "'<" + parent.name + ">' has no DataArray named '" + std::string(name) + "'");
  }

  std::int64_t count_attribute(const XmlElement& element, std::string_view key) const {
    const std::string* text = element.attribute(key);
    std::int64_t value = -1;
    if (text == nullptr || !io_detail::parse_integer(*text, value) || value < 0 ||
        value > INT_MAX) {
      fail(element, "'<" + element.name + ">' needs " + std::string(key) +
                        " as an integer in [0, 2^31 - 1], found '" + (text ? *text : "") + "'");
    }
    return value;
  }

  int components(const XmlElement& array) const {
    const std::string* text = array.attribute("NumberOfComponents");
    std::int64_t value = 1;
    if (text != nullptr && (!io_detail::parse_integer(*text, value) || value < 1 || value > 1024)) {
      fail(array, "NumberOfComponents '" + *text + "' must be an integer in [1, 1024]");
    }
    return static_cast<int>(value);
  }

  // Reads an ASCII DataArray of `tuples` tuples (-1: any number) of `expected_components`.
  void read_array(const XmlElement& array, std::int64_t tuples, int expected_components,
                  std::vector<double>& values) const {
    const std::string* name_attribute = array.attribute("Name");
    const std::string name =
        "DataArray" + (name_attribute ? " '" + *name_attribute + "'" : std::string());
    const std::string* format = array.attribute("format");
    if (format == nullptr || *format != "ascii") {
      fail(array, name + " has format '" + (format ? *format : std::string()) +
                      "'; tessera reads ASCII data arrays (the .vtu files it writes); save "
                      "with ASCII data in ParaView, or use .ply");
    }
    if (components(array) != expected_components) {
      fail(array, name + " has " + std::to_string(components(array)) + " components, expected " +
                      std::to_string(expected_components));
    }
    const std::string* type = array.attribute("type");
    static constexpr std::string_view kTypes[] = {"Int8",    "UInt8",  "Int16", "UInt16",
                                                  "Int32",   "UInt32", "Int64", "UInt64",
                                                  "Float32", "Float64"};
    if (type == nullptr || std::find(std::begin(kTypes), std::end(kTypes),
                                     std::string_view(*type)) == std::end(kTypes)) {
      fail(array, name + " has type '" + (type ? *type : std::string()) + "'; expected one of " +
                      "Int8 ... UInt64, Float32, Float64");
    }
    const bool is_integer = type->front() != 'F';
    io_detail::TextCursor cursor(array.text, array.text_line);
    const std::int64_t expected = tuples < 0 ? -1 : tuples * expected_components;
    if (expected > static_cast<std::int64_t>(array.text.size() / 2 + 1)) {
      fail(array, name + " should hold " + std::to_string(expected) + " values but its " +
                      std::to_string(array.text.size()) + " characters cannot");
    }
    if (expected > 0) {
      values.reserve(static_cast<std::size_t>(expected));
    }
    for (std::string_view token = cursor.next_token(); !token.empty();
         token = cursor.next_token()) {
      double value = 0;
      std::int64_t integer = 0;
      const bool parsed = is_integer ? io_detail::parse_integer(token, integer)
                                     : io_detail::parse_real(token, value);
      if (!parsed) {
        document_.fail(cursor.line(),
                       "expected " + std::string(is_integer ? "an integer" : "a number") + " in " +
                           name + ", found " + io_detail::quoted_excerpt(token));
      }
      values.push_back(is_integer ? static_cast<double>(integer) : value);
      if (expected >= 0 && static_cast<std::int64_t>(values.size()) > expected) {
        document_.fail(cursor.line(), name + " has more than the " + std::to_string(expected) +
                                          " values expected");
      }
    }
    if (expected >= 0 && static_cast<std::int64_t>(values.size()) != expected) {
      fail(array, name + " has " + std::to_string(values.size()) + " values, expected " +
                      std::to_string(expected));
    }
    if (expected < 0 && values.size() % static_cast<std::size_t>(expected_components) != 0) {
      fail(array, name + " has " + std::to_string(values.size()) +
                      " values, not a multiple of its components");
    }
  }

  XmlDocument document_;
};

}  // namespace

TriangleMesh io_detail::parse_vtu(const std::string& content, const std::string& path,
                                  std::vector<VertexScalars>* vertex_scalars) {
  return VtuReader(content, path).read(vertex_scalars);
}

TriangleMesh read_vtu(const std::string& path) {
  return io_detail::parse_vtu(io_detail::read_file(kVtu, path), path);
}

}  // namespace tessera
