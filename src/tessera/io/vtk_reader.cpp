// SPDX-License-Identifier: MIT
// read_vtk: the ASCII legacy files (DATASET UNSTRUCTURED_GRID) that write_vtk produces, and the
// DATASET POLYDATA files of earlier tessera versions, read back with all n coordinates (from the
// point-data arrays) and the triangles.
//
// Every count in the file is a claim to check, never a size to allocate: arrays grow only with
// values actually present, and every index is checked before use, so a malformed or hostile file
// gives an InvalidArgument naming the file and the line.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/io/detail/file_buffer.h"
#include "tessera/io/detail/mesh_parsers.h"
#include "tessera/io/detail/ply_header.h"
#include "tessera/io/detail/vtk_cell_types.h"
#include "tessera/io/detail/vtk_points.h"
#include "tessera/io/vtk.h"

namespace tessera {

using io_detail::append_fan;
using io_detail::dimension_after;
using io_detail::PointArray;

namespace {

bool equals_ignoring_case(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

bool starts_with_ignoring_case(std::string_view text, std::string_view prefix) {
  return text.size() >= prefix.size() &&
         equals_ignoring_case(text.substr(0, prefix.size()), prefix);
}

constexpr std::string_view kVtk = "VTK";

using io_detail::kVtkPolygon;
using io_detail::kVtkPolyLine;
using io_detail::kVtkQuad;
using io_detail::kVtkTriangle;
using io_detail::kVtkVertex;

class LegacyReader {
 public:
  LegacyReader(std::string_view data, std::size_t first_line, const std::string& path)
      : cursor_(data, first_line), path_(path) {}

  [[noreturn]] void fail(const std::string& message) const {
    io_detail::throw_file_error(kVtk, path_, cursor_.line(), message);
  }

  std::string_view token() { return cursor_.next_token(); }

  // The token after the next `skip` tokens, without consuming any.
  std::string_view peek_token(int skip) const {
    io_detail::TextCursor copy = cursor_;
    for (int i = 0; i < skip; ++i) {
      copy.next_token();
    }
    return copy.next_token();
  }

  std::string_view required_token(const std::string& what) {
    const std::string_view token = cursor_.next_token();
    if (token.empty()) {
      fail("unexpected end of file: expected " + what);
    }
    return token;
  }

  // A count that the rest of the file can hold with `per_item` values of one character and a
  // separator each, so that no claim of the header becomes an allocation.
  std::int64_t count(const std::string& what, std::int64_t per_item = 1) {
    const std::string_view token = required_token(what);
    std::int64_t value = -1;
    if (!io_detail::parse_integer(token, value) || value < 0 || value > INT_MAX) {
      fail("expected " + what + " (an integer in [0, 2^31 - 1]), found " +
           io_detail::quoted_excerpt(token));
    }
    if (static_cast<double>(value) * static_cast<double>(per_item) >
        static_cast<double>(cursor_.remaining()) / 2 + 1) {
      fail("unexpected end of file: " + what + " is " + std::to_string(value) +
           ", more than the rest of the file can hold");
    }
    return value;
  }

  double real(const std::string& what) {
    const std::string_view token = required_token(what);
    double value = 0;
    if (!io_detail::parse_real(token, value)) {
      fail("expected a number for " + what + ", found " + io_detail::quoted_excerpt(token));
    }
    return value;
  }

  // `describe` builds the name of the value only when it is needed for a message: cells are read
  // by the million.
  template <class Describe>
  std::int64_t integer_of(const Describe& describe) {
    const std::string_view token = cursor_.next_token();
    std::int64_t value = 0;
    if (token.empty()) {
      fail("unexpected end of file: expected " + describe());
    }
    if (!io_detail::parse_integer(token, value)) {
      fail("expected an integer for " + describe() + ", found " + io_detail::quoted_excerpt(token));
    }
    return value;
  }

  std::int64_t integer(const std::string& what) {
    const std::string_view token = required_token(what);
    std::int64_t value = 0;
    if (!io_detail::parse_integer(token, value)) {
      fail("expected an integer for " + what + ", found " + io_detail::quoted_excerpt(token));
    }
    return value;
  }

  void expect_data_type(std::string_view type) {
    static constexpr std::string_view kTypes[] = {
        "bit", "char", "unsigned_char", "short", "unsigned_short", "int", "unsigned_int", "long",
        "unsigned_long", "float", "double", "vtkIdType",
        // version 5.1 (the OFFSETS and CONNECTIVITY of meshio's files)
        "vtktypeint8", "vtktypeuint8", "vtktypeint16", "vtktypeuint16", "vtktypeint32",
        "vtktypeuint32", "vtktypeint64", "vtktypeuint64"};
    for (const auto known : kTypes) {
      if (equals_ignoring_case(type, known)) {
        return;
      }
    }
    fail("unknown data type " + io_detail::quoted_excerpt(type));
  }

 private:
  io_detail::TextCursor cursor_;
  const std::string& path_;
};

// Reads `count` values into `values` (growing with the data, not with the claim).
void read_values(LegacyReader& reader, std::int64_t count, const std::string& what,
                 std::vector<double>& values) {
  for (std::int64_t i = 0; i < count; ++i) {
    values.push_back(reader.real(what));
  }
}

// One attribute block (SCALARS, VECTORS, NORMALS, FIELD ...) of POINT_DATA or CELL_DATA with
// `tuples` tuples; keeps point-data arrays in `arrays` when `keep`.
void read_attribute(LegacyReader& reader, std::string_view keyword, std::int64_t tuples, bool keep,
                    std::vector<PointArray>& arrays) {
  if (equals_ignoring_case(keyword, "SCALARS")) {
    PointArray array;
    array.name = std::string(reader.required_token("the SCALARS name"));
    reader.expect_data_type(reader.required_token("the SCALARS data type"));
    // Optional component count, then optional LOOKUP_TABLE: both are recognised by what they are.
    std::string_view next = reader.required_token("the SCALARS values");
    std::int64_t components = 0;
    if (io_detail::parse_integer(next, components)) {
      if (components < 1 || components > 4) {
        reader.fail("SCALARS '" + array.name + "' has " + std::to_string(components) +
                    " components; the format allows 1 to 4");
      }
      array.components = static_cast<int>(components);
      next = reader.required_token("the SCALARS values");
    }
    if (!equals_ignoring_case(next, "LOOKUP_TABLE")) {
      reader.fail("expected LOOKUP_TABLE after SCALARS '" + array.name + "', found " +
                  io_detail::quoted_excerpt(next));
    }
    reader.required_token("the lookup table name");
    read_values(reader, tuples * array.components, "SCALARS '" + array.name + "'", array.values);
    if (keep) {
      arrays.push_back(std::move(array));
    }
    return;
  }
  if (equals_ignoring_case(keyword, "VECTORS") || equals_ignoring_case(keyword, "NORMALS")) {
    const std::string name(reader.required_token("the array name"));
    reader.expect_data_type(reader.required_token("the data type"));
    std::vector<double> ignored;
    read_values(reader, 3 * tuples, std::string(keyword) + " '" + name + "'", ignored);
    return;
  }
  if (equals_ignoring_case(keyword, "FIELD")) {
    reader.required_token("the FIELD name");
    const std::int64_t array_count = reader.count("the number of FIELD arrays", 4);
    for (std::int64_t a = 0; a < array_count; ++a) {
      PointArray array;
      array.name = std::string(reader.required_token("a FIELD array name"));
      const std::int64_t components = reader.integer("the component count of '" + array.name + "'");
      if (components < 1 || components > 1024) {
        reader.fail("FIELD array '" + array.name + "' has " + std::to_string(components) +
                    " components; expected 1 to 1024");
      }
      const std::int64_t array_tuples = reader.integer("the tuple count of '" + array.name + "'");
      if (array_tuples != tuples) {
        reader.fail("FIELD array '" + array.name + "' has " + std::to_string(array_tuples) +
                    " tuples; the data section has " + std::to_string(tuples));
      }
      reader.expect_data_type(reader.required_token("the data type of '" + array.name + "'"));
      array.components = static_cast<int>(components);
      read_values(reader, tuples * components, "FIELD array '" + array.name + "'", array.values);
      if (keep) {
        arrays.push_back(std::move(array));
      }
    }
    return;
  }
  reader.fail("unsupported attribute " + io_detail::quoted_excerpt(keyword) +
              "; tessera reads SCALARS, VECTORS, NORMALS and FIELD");
}

// The line of `content` that starts at `position`, without its line end; moves `position` to
// the start of the next line.
std::string_view header_line(const std::string& content, std::size_t& position) {
  std::size_t end = content.find('\n', position);
  end = end == std::string::npos ? content.size() : end;
  std::string_view line(content.data() + position, end - position);
  position = std::min(end + 1, content.size());
  if (!line.empty() && line.back() == '\r') {
    line.remove_suffix(1);
  }
  return line;
}

}  // namespace

TriangleMesh io_detail::parse_vtk(const std::string& content, const std::string& path,
                                  std::vector<VertexScalars>* vertex_scalars) {
  std::size_t position = 0;
  const std::string_view version = header_line(content, position);
  if (!starts_with_ignoring_case(version, "# vtk DataFile Version")) {
    io_detail::throw_file_error(kVtk, path, 1,
                                "not a legacy VTK file: the first line is " +
                                    io_detail::quoted_excerpt(version) +
                                    ", expected '# vtk DataFile Version ...'");
  }
  const std::string_view title = header_line(content, position);
  const std::string_view encoding = header_line(content, position);
  const auto encoding_tokens = io_detail::split_tokens(encoding);
  if (encoding_tokens.size() == 1 && equals_ignoring_case(encoding_tokens.front(), "BINARY")) {
    io_detail::throw_file_error(kVtk, path, 3,
                                "binary legacy VTK is not supported; tessera writes and reads "
                                "ASCII (convert with ParaView, or use .vtu or .ply)");
  }
  if (encoding_tokens.size() != 1 || !equals_ignoring_case(encoding_tokens.front(), "ASCII")) {
    io_detail::throw_file_error(
        kVtk, path, 3,
        "expected 'ASCII' on the third line, found " + io_detail::quoted_excerpt(encoding));
  }
  LegacyReader reader(std::string_view(content).substr(position), 4, path);
  const std::string_view dataset = reader.required_token("DATASET");
  const std::string_view kind = reader.required_token("the dataset type");
  const bool is_unstructured = equals_ignoring_case(kind, "UNSTRUCTURED_GRID");
  if (!equals_ignoring_case(dataset, "DATASET") ||
      !(is_unstructured || equals_ignoring_case(kind, "POLYDATA"))) {
    reader.fail("expected 'DATASET UNSTRUCTURED_GRID' or 'DATASET POLYDATA', found " +
                io_detail::quoted_excerpt(std::string(dataset) + " " + std::string(kind)) +
                "; tessera writes and reads surface meshes");
  }

  std::optional<std::vector<double>> xyz;
  std::vector<Triangle> triangles;
  std::vector<PointArray> arrays;
  std::int64_t vertex_count = -1;
  std::int64_t cell_count = 0;
  // The CELLS of an unstructured grid wait for their CELL_TYPES: cell c is
  // cell_vertices[cell_offsets[c] .. cell_offsets[c + 1]).
  std::optional<std::vector<std::int64_t>> cell_offsets;
  std::vector<std::int64_t> cell_vertices;
  bool has_cell_types = false;
  auto check_index = [&](std::int64_t v, const std::string& name, std::int64_t c) {
    if (v < 0 || v >= vertex_count) {
      reader.fail(name + " cell " + std::to_string(c) + " has vertex index " + std::to_string(v) +
                  "; the file has " + std::to_string(vertex_count) + " points");
    }
  };
  enum class Section { Geometry, PointData, CellData } section = Section::Geometry;
  for (std::string_view keyword = reader.token(); !keyword.empty(); keyword = reader.token()) {
    if (equals_ignoring_case(keyword, "POINTS")) {
      if (xyz) {
        reader.fail("a second POINTS section");
      }
      vertex_count = reader.count("the number of points", 3);
      reader.expect_data_type(reader.required_token("the POINTS data type"));
      xyz.emplace();
      xyz->reserve(static_cast<std::size_t>(3 * vertex_count));
      read_values(reader, 3 * vertex_count, "POINTS", *xyz);
    } else if (is_unstructured && equals_ignoring_case(keyword, "CELLS") &&
               equals_ignoring_case(reader.peek_token(2), "OFFSETS")) {
      // Version 5.1 (meshio's default): CELLS <offsets> <connectivity size>, OFFSETS, CONNECTIVITY.
      if (!xyz) {
        reader.fail("CELLS before POINTS");
      }
      if (cell_offsets) {
        reader.fail("a second CELLS section");
      }
      const std::int64_t offset_count = reader.count("the number of CELLS offsets");
      const std::int64_t size = reader.count("the size of the CELLS connectivity");
      reader.required_token("OFFSETS");
      reader.expect_data_type(reader.required_token("the OFFSETS data type"));
      cell_offsets.emplace();
      for (std::int64_t c = 0; c < offset_count; ++c) {
        const std::int64_t offset =
            reader.integer_of([&] { return "CELLS offset " + std::to_string(c); });
        const std::int64_t previous = c == 0 ? 0 : cell_offsets->back();
        if (offset < previous || offset > size || (c == 0 && offset != 0)) {
          reader.fail("CELLS offset " + std::to_string(c) + " is " + std::to_string(offset) +
                      "; offsets start at 0 and do not decrease up to the connectivity size " +
                      std::to_string(size));
        }
        cell_offsets->push_back(offset);
      }
      if (cell_offsets->empty()) {
        cell_offsets->push_back(0);
      }
      if (cell_offsets->back() != size) {
        reader.fail("the CELLS offsets end at " + std::to_string(cell_offsets->back()) +
                    " but the connectivity has " + std::to_string(size) + " entries");
      }
      const std::string_view connectivity = reader.required_token("CONNECTIVITY");
      if (!equals_ignoring_case(connectivity, "CONNECTIVITY")) {
        reader.fail("expected CONNECTIVITY after the CELLS offsets, found " +
                    io_detail::quoted_excerpt(connectivity));
      }
      reader.expect_data_type(reader.required_token("the CONNECTIVITY data type"));
      std::int64_t cell = 0;
      for (std::int64_t i = 0; i < size; ++i) {
        while ((*cell_offsets)[static_cast<std::size_t>(cell + 1)] <= i) {
          ++cell;
        }
        const std::int64_t v =
            reader.integer_of([&] { return "CELLS cell " + std::to_string(cell); });
        check_index(v, "CELLS", cell);
        cell_vertices.push_back(v);
      }
      cell_count += static_cast<std::int64_t>(cell_offsets->size()) - 1;
    } else if ((is_unstructured && equals_ignoring_case(keyword, "CELLS")) ||
               (!is_unstructured && (equals_ignoring_case(keyword, "POLYGONS") ||
                                     equals_ignoring_case(keyword, "VERTICES") ||
                                     equals_ignoring_case(keyword, "LINES") ||
                                     equals_ignoring_case(keyword, "TRIANGLE_STRIPS")))) {
      const std::string name(keyword);
      const bool is_polygons = equals_ignoring_case(keyword, "POLYGONS");
      const bool is_cells = equals_ignoring_case(keyword, "CELLS");
      if (!xyz) {
        reader.fail(name + " before POINTS");
      }
      if (is_cells && cell_offsets) {
        reader.fail("a second CELLS section");
      }
      if (is_cells) {
        cell_offsets.emplace(1, 0);
      }
      const std::int64_t cells = reader.count("the number of " + name + " cells", 2);
      const std::int64_t size = reader.count("the size of the " + name + " list");
      std::int64_t read = 0;
      std::vector<std::int64_t> polygon;
      for (std::int64_t c = 0; c < cells; ++c) {
        const std::int64_t k =
            reader.integer_of([&] { return name + " cell " + std::to_string(c) + " (its size)"; });
        read += 1 + std::max<std::int64_t>(k, 0);
        if (k < 1 || read > size) {
          reader.fail(
              name + " cell " + std::to_string(c) + " has size " + std::to_string(k) +
              (k < 1 ? "" : ", beyond the list size " + std::to_string(size) + " declared"));
        }
        if (is_polygons && k < 3) {
          reader.fail("polygon " + std::to_string(c) + " has " + std::to_string(k) +
                      " vertices; a polygon needs at least 3");
        }
        polygon.clear();
        for (std::int64_t i = 0; i < k; ++i) {
          const std::int64_t v =
              reader.integer_of([&] { return name + " cell " + std::to_string(c); });
          check_index(v, name, c);
          polygon.push_back(v);
        }
        if (is_polygons) {
          append_fan(polygon, triangles);
        }
        if (is_cells) {
          cell_vertices.insert(cell_vertices.end(), polygon.begin(), polygon.end());
          cell_offsets->push_back(static_cast<std::int64_t>(cell_vertices.size()));
        }
      }
      if (read != size) {
        reader.fail(name + " declares a list size of " + std::to_string(size) + " but its " +
                    std::to_string(cells) + " cells take " + std::to_string(read));
      }
      cell_count += cells;
    } else if (is_unstructured && equals_ignoring_case(keyword, "CELL_TYPES")) {
      if (!cell_offsets) {
        reader.fail("CELL_TYPES before CELLS");
      }
      if (has_cell_types) {
        reader.fail("a second CELL_TYPES section");
      }
      has_cell_types = true;
      const auto cells = static_cast<std::int64_t>(cell_offsets->size()) - 1;
      const std::int64_t count = reader.count("the number of CELL_TYPES");
      if (count != cells) {
        reader.fail("CELL_TYPES " + std::to_string(count) + " does not match the " +
                    std::to_string(cells) + " CELLS");
      }
      std::vector<std::int64_t> polygon;
      for (std::int64_t c = 0; c < cells; ++c) {
        const std::int64_t type =
            reader.integer_of([&] { return "the type of cell " + std::to_string(c); });
        const auto begin = cell_vertices.begin() + (*cell_offsets)[static_cast<std::size_t>(c)];
        const auto end = cell_vertices.begin() + (*cell_offsets)[static_cast<std::size_t>(c) + 1];
        const auto size = end - begin;
        if (type >= kVtkVertex && type <= kVtkPolyLine) {
          continue;  // vertices and lines: not part of the surface
        }
        const bool is_surface = (type == kVtkTriangle && size == 3) ||
                                (type == kVtkQuad && size == 4) ||
                                (type == kVtkPolygon && size >= 3);
        if (!is_surface) {
          reader.fail("cell " + std::to_string(c) + " has type " + std::to_string(type) + " and " +
                      std::to_string(size) +
                      " vertices; tessera reads triangles (5), quads (9) and polygons (7), and "
                      "skips vertices and lines (1 to 4)");
        }
        polygon.assign(begin, end);
        append_fan(polygon, triangles);
      }
    } else if (equals_ignoring_case(keyword, "POINT_DATA") ||
               equals_ignoring_case(keyword, "CELL_DATA")) {
      const bool is_point_data = equals_ignoring_case(keyword, "POINT_DATA");
      // Compared with the known counts below, so no check against the file size is needed.
      const std::int64_t count = reader.count(std::string(keyword) + " count", 0);
      const std::int64_t expected = is_point_data ? vertex_count : cell_count;
      if (count != expected) {
        reader.fail(std::string(keyword) + " " + std::to_string(count) + " does not match the " +
                    std::to_string(std::max<std::int64_t>(expected, 0)) +
                    (is_point_data ? " points" : " cells"));
      }
      section = is_point_data ? Section::PointData : Section::CellData;
    } else if (section != Section::Geometry) {
      const bool is_point_data = section == Section::PointData;
      read_attribute(reader, keyword, is_point_data ? vertex_count : cell_count, is_point_data,
                     arrays);
    } else {
      reader.fail("unsupported section " + io_detail::quoted_excerpt(keyword) +
                  (is_unstructured
                       ? "; tessera reads POINTS, CELLS, CELL_TYPES, POINT_DATA and CELL_DATA "
                         "of an unstructured grid"
                       : "; tessera reads POINTS, POLYGONS, POINT_DATA and CELL_DATA of polygonal "
                         "data"));
    }
  }
  if (!xyz) {
    io_detail::throw_file_error(kVtk, path, "no POINTS section");
  }
  if (cell_offsets && !has_cell_types) {
    io_detail::throw_file_error(kVtk, path, "CELLS without CELL_TYPES");
  }
  // write_vtk starts the title with "tessera triangle mesh in R^n"; earlier versions did so only
  // without comments, so "coordinates: a b c ..." (the comment of `tessera mesh`) counts too when
  // the point data starts with arrays of those names.
  int dimension = dimension_after(title, "tessera triangle mesh in R^");
  if (dimension == 0) {
    const std::size_t at = title.find("coordinates:");
    if (at != std::string_view::npos) {
      const auto names = io_detail::split_tokens(title.substr(at + 12));
      bool match = names.size() >= 3 && names.size() <= arrays.size();
      for (std::size_t k = 0; match && k < names.size(); ++k) {
        match = arrays[k].name == names[k];
      }
      dimension = match ? static_cast<int>(names.size()) : 0;
    }
  }
  return io_detail::assemble(
      dimension, *xyz, arrays, std::move(triangles),
      [&](const std::string& message) { io_detail::throw_file_error(kVtk, path, message); },
      vertex_scalars);
}

TriangleMesh read_vtk(const std::string& path) {
  return io_detail::parse_vtk(io_detail::read_file(kVtk, path), path);
}

}  // namespace tessera
