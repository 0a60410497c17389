// SPDX-License-Identifier: MIT
// read_vtk and read_vtu: the ASCII legacy and XML files that write_vtk and write_vtu produce,
// read back with all n coordinates (from the point-data arrays) and the triangles.
//
// Both readers take every count from the file as a claim to check, never as a size to allocate:
// arrays grow only with values actually present, and every index is checked before use, so a
// malformed or hostile file gives an InvalidArgument naming the file and the line.
#include <algorithm>
#include <bit>
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
#include "tessera/io/vtk.h"

namespace tessera {

namespace {

constexpr int kVtkTriangle = 5;
constexpr int kVtkPolygon = 7;
constexpr int kVtkQuad = 9;
// Far above any ambient dimension tessera meets; bounds what a comment can make us expect.
constexpr std::int64_t kMaxDimension = 1 << 16;

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

// The n of "... triangle mesh in R^n" at `text`'s start after `prefix`, or 0.
int dimension_after(std::string_view text, std::string_view prefix) {
  if (text.substr(0, prefix.size()) != prefix) {
    return 0;
  }
  text.remove_prefix(prefix.size());
  std::int64_t n = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), n);
  return error == std::errc() && n >= 1 && n <= kMaxDimension ? static_cast<int>(n) : 0;
}

// One named array of point data with one value per vertex (and component).
struct PointArray {
  std::string name;
  int components = 1;
  std::vector<double> values;  // vertex-major: values[v * components + c]
};

// Turns polygons (a first vertex and a fan) into triangles, keeping their orientation.
void append_fan(const std::vector<std::int64_t>& polygon, std::vector<Triangle>& triangles) {
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
    triangles.push_back({static_cast<int>(polygon[0]), static_cast<int>(polygon[i]),
                         static_cast<int>(polygon[i + 1])});
  }
}

// The mesh from the 3-column points, the point-data arrays and n (0: not known from the file).
// The first n arrays are the coordinates, as write_vtk / write_vtu put them; their first three
// must agree with the points bit for bit, which both writers guarantee.
template <class Fail>
TriangleMesh assemble(int dimension, const std::vector<double>& xyz,
                      const std::vector<PointArray>& arrays, std::vector<Triangle> triangles,
                      const Fail& fail) {
  const std::size_t vertex_count = xyz.size() / 3;
  bool from_arrays = true;
  if (dimension == 0) {
    // Not a tessera file, or one whose marker was lost: the point data may still start with the
    // coordinates x0, x1, ... that tessera used to name them; otherwise the points are in R^3
    // and the point data (whatever it holds) is not read.
    std::size_t k = 0;
    while (k < arrays.size() && arrays[k].name == "x" + std::to_string(k) &&
           arrays[k].components == 1) {
      ++k;
    }
    dimension = k >= 3 ? static_cast<int>(k) : 3;
    from_arrays = k >= 3;
  }
  const auto n = static_cast<std::size_t>(dimension);
  from_arrays = from_arrays && !(n <= 3 && arrays.size() < n);
  if (from_arrays && arrays.size() < n) {
    fail("the file is a mesh in R^" + std::to_string(n) + " but has only " +
         std::to_string(arrays.size()) +
         " point-data arrays; the coordinates beyond the "
         "third are point-data arrays");
  }
  Eigen::MatrixXd points(dimension, static_cast<Eigen::Index>(vertex_count));
  for (std::size_t k = 0; k < n; ++k) {
    if (!from_arrays) {
      for (std::size_t v = 0; v < vertex_count; ++v) {
        points(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(v)) = xyz[3 * v + k];
      }
      continue;
    }
    const PointArray& array = arrays[k];
    if (array.components != 1) {
      fail("point-data array '" + array.name + "' (coordinate " + std::to_string(k) + ") has " +
           std::to_string(array.components) + " components; a coordinate has one");
    }
    for (std::size_t v = 0; v < vertex_count; ++v) {
      const double value = array.values[v];
      if (k < 3 &&
          std::bit_cast<std::uint64_t>(value) != std::bit_cast<std::uint64_t>(xyz[3 * v + k])) {
        fail("point-data array '" + array.name + "' (coordinate " + std::to_string(k) +
             ") differs from the points at vertex " + std::to_string(v) +
             ": the file was changed after tessera wrote it");
      }
      points(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(v)) = value;
    }
  }
  return TriangleMesh(points, std::move(triangles));
}

// ---------------------------------------------------------------------------------------------
// Legacy VTK (ASCII, DATASET POLYDATA)

constexpr std::string_view kVtk = "VTK";

class LegacyReader {
 public:
  LegacyReader(std::string_view data, std::size_t first_line, const std::string& path)
      : cursor_(data, first_line), path_(path) {}

  [[noreturn]] void fail(const std::string& message) const {
    io_detail::throw_file_error(kVtk, path_, cursor_.line(), message);
  }

  std::string_view token() { return cursor_.next_token(); }

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
        "bit",          "char", "unsigned_char", "short", "unsigned_short", "int",
        "unsigned_int", "long", "unsigned_long", "float", "double",         "vtkIdType"};
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

TriangleMesh io_detail::parse_vtk(const std::string& content, const std::string& path) {
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
  if (!equals_ignoring_case(dataset, "DATASET") || !equals_ignoring_case(kind, "POLYDATA")) {
    reader.fail("expected 'DATASET POLYDATA', found " +
                io_detail::quoted_excerpt(std::string(dataset) + " " + std::string(kind)) +
                "; tessera writes and reads polygonal data");
  }

  std::optional<std::vector<double>> xyz;
  std::vector<Triangle> triangles;
  std::vector<PointArray> arrays;
  std::int64_t vertex_count = -1;
  std::int64_t cell_count = 0;
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
    } else if (equals_ignoring_case(keyword, "POLYGONS") ||
               equals_ignoring_case(keyword, "VERTICES") ||
               equals_ignoring_case(keyword, "LINES") ||
               equals_ignoring_case(keyword, "TRIANGLE_STRIPS")) {
      const std::string name(keyword);
      const bool is_polygons = equals_ignoring_case(keyword, "POLYGONS");
      if (!xyz) {
        reader.fail(name + " before POINTS");
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
          if (v < 0 || v >= vertex_count) {
            reader.fail(name + " cell " + std::to_string(c) + " has vertex index " +
                        std::to_string(v) + "; the file has " + std::to_string(vertex_count) +
                        " points");
          }
          polygon.push_back(v);
        }
        if (is_polygons) {
          append_fan(polygon, triangles);
        }
      }
      if (read != size) {
        reader.fail(name + " declares a list size of " + std::to_string(size) + " but its " +
                    std::to_string(cells) + " cells take " + std::to_string(read));
      }
      cell_count += cells;
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
                  "; tessera reads POINTS, POLYGONS, POINT_DATA and CELL_DATA");
    }
  }
  if (!xyz) {
    io_detail::throw_file_error(kVtk, path, "no POINTS section");
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
  return assemble(dimension, *xyz, arrays, std::move(triangles), [&](const std::string& message) {
    io_detail::throw_file_error(kVtk, path, message);
  });
}

// ---------------------------------------------------------------------------------------------
// XML VTK UnstructuredGrid (.vtu) with ASCII data arrays

namespace {

constexpr std::string_view kVtu = "VTU";
constexpr int kMaxDepth = 64;  // VTU nests 5 deep; bounds the work on hostile files

struct XmlElement {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;
  std::string_view text;  // character data directly inside (the first run of it)
  std::size_t text_line = 0;
  std::size_t line = 0;
  std::vector<std::size_t> children;  // indices into the document's elements

  const std::string* attribute(std::string_view key) const {
    for (const auto& [name, value] : attributes) {
      if (name == key) {
        return &value;
      }
    }
    return nullptr;
  }
};

// A small XML reader for what VTK writes: elements, attributes, character data, comments, the
// declaration. No DTD, no CDATA, no namespaces; entities: the five predefined and &#...;.
class XmlDocument {
 public:
  XmlDocument(const std::string& content, const std::string& path) : text_(content), path_(path) {
    parse();
  }
  const XmlElement& root() const { return elements_.front(); }
  const XmlElement& element(std::size_t index) const { return elements_[index]; }
  const std::vector<std::string>& comments() const { return comments_; }
  [[noreturn]] void fail(std::size_t line, const std::string& message) const {
    io_detail::throw_file_error(kVtu, path_, line, message);
  }

 private:
  [[noreturn]] void fail(const std::string& message) const { fail(line_, message); }

  void advance(std::size_t count) {
    const std::size_t end = std::min(position_ + count, text_.size());
    line_ += static_cast<std::size_t>(
        std::count(text_.begin() + static_cast<std::ptrdiff_t>(position_),
                   text_.begin() + static_cast<std::ptrdiff_t>(end), '\n'));
    position_ = end;
  }
  bool at(std::string_view prefix) const {
    return text_.substr(position_, prefix.size()) == prefix;
  }
  // Moves past the next `terminator`; false if there is none.
  bool skip_past(std::string_view terminator) {
    const std::size_t end = text_.find(terminator, position_);
    if (end == std::string_view::npos) {
      return false;
    }
    advance(end + terminator.size() - position_);
    return true;
  }
  void skip_space() {
    while (position_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[position_]))) {
      advance(1);
    }
  }
  std::string name() {
    const std::size_t begin = position_;
    while (position_ < text_.size()) {
      const char c = text_[position_];
      if (std::isspace(static_cast<unsigned char>(c)) || c == '=' || c == '>' || c == '/' ||
          c == '<' || c == '"' || c == '\'') {
        break;
      }
      ++position_;
    }
    if (position_ == begin) {
      fail("expected a name, found " + io_detail::quoted_excerpt(text_.substr(position_, 20)));
    }
    return std::string(text_.substr(begin, position_ - begin));
  }
  std::string unescaped(std::string_view value) const {
    std::string out;
    for (std::size_t i = 0; i < value.size(); ++i) {
      if (value[i] != '&') {
        out += value[i];
        continue;
      }
      const std::size_t end = value.find(';', i);
      if (end == std::string_view::npos) {
        fail("an '&' without ';' in an attribute value");
      }
      const std::string_view entity = value.substr(i + 1, end - i - 1);
      static constexpr std::pair<std::string_view, char> kEntities[] = {
          {"amp", '&'}, {"lt", '<'}, {"gt", '>'}, {"quot", '"'}, {"apos", '\''}};
      bool known = false;
      for (const auto& [entity_name, character] : kEntities) {
        if (entity == entity_name) {
          out += character;
          known = true;
        }
      }
      if (!known && entity.size() >= 2 && entity[0] == '#') {
        const bool hex = entity[1] == 'x' || entity[1] == 'X';
        const std::string_view digits = entity.substr(hex ? 2 : 1);
        unsigned code = 0;
        const auto [ptr, error] =
            std::from_chars(digits.data(), digits.data() + digits.size(), code, hex ? 16 : 10);
        if (error == std::errc() && ptr == digits.data() + digits.size() && code > 0 &&
            code < 128) {
          out += static_cast<char>(code);
          known = true;
        }
      }
      if (!known) {
        fail("unsupported entity " + io_detail::quoted_excerpt(value.substr(i, end - i + 1)) +
             " in an attribute value");
      }
      i = end;
    }
    return out;
  }

  void parse() {
    std::vector<std::size_t> open;  // indices of the elements not yet closed
    while (true) {
      const std::size_t text_begin = position_;
      const std::size_t text_line = line_;
      const std::size_t next = text_.find('<', position_);
      const std::size_t text_end = next == std::string_view::npos ? text_.size() : next;
      if (!open.empty()) {
        XmlElement& parent = elements_[open.back()];
        if (parent.text.empty() && text_end > text_begin) {
          parent.text = text_.substr(text_begin, text_end - text_begin);
          parent.text_line = text_line;
        }
      } else if (text_.substr(text_begin, text_end - text_begin).find_first_not_of(" \t\r\n") !=
                 std::string_view::npos) {
        fail("text outside the root element");
      }
      advance(text_end - position_);
      if (position_ >= text_.size()) {
        break;
      }
      if (at("<?")) {
        if (!skip_past("?>")) {
          fail("unterminated '<?'");
        }
      } else if (at("<!--")) {
        advance(4);  // "<!-->" is not a whole comment: its "-->" starts inside "<!--"
        const std::size_t begin = position_;
        if (!skip_past("-->")) {
          fail("unterminated comment");
        }
        comments_.emplace_back(text_.substr(begin, position_ - 3 - begin));
      } else if (at("<!")) {
        fail("DTD and CDATA sections are not supported");
      } else if (at("</")) {
        advance(2);
        const std::string closing = name();
        skip_space();
        if (!at(">")) {
          fail("expected '>' after '</" + closing + "'");
        }
        advance(1);
        if (open.empty() || elements_[open.back()].name != closing) {
          fail("closing tag '</" + closing + ">' does not match " +
               (open.empty() ? std::string("any open element")
                             : "'<" + elements_[open.back()].name + ">'"));
        }
        open.pop_back();
        if (open.empty()) {
          break;
        }
      } else {
        start_element(open);
        if (open.empty()) {
          break;  // an empty root element
        }
      }
    }
    if (elements_.empty()) {
      fail("no root element");
    }
    if (!open.empty()) {
      fail("unexpected end of file: '<" + elements_[open.back()].name + ">' is not closed");
    }
  }

  void start_element(std::vector<std::size_t>& open) {
    if (!elements_.empty() && open.empty()) {
      fail("a second root element");
    }
    if (open.size() >= static_cast<std::size_t>(kMaxDepth)) {
      fail("elements nested deeper than " + std::to_string(kMaxDepth));
    }
    advance(1);
    XmlElement element;
    element.line = line_;
    element.name = name();
    while (true) {
      skip_space();
      if (position_ >= text_.size()) {
        fail("unexpected end of file in '<" + element.name + "'");
      }
      if (at("/>") || at(">")) {
        break;
      }
      std::string key = name();
      skip_space();
      if (!at("=")) {
        fail("expected '=' after attribute '" + key + "'");
      }
      advance(1);
      skip_space();
      if (!at("\"") && !at("'")) {
        fail("expected a quoted value for attribute '" + key + "'");
      }
      const char quote = text_[position_];
      const std::size_t end = text_.find(quote, position_ + 1);
      if (end == std::string_view::npos) {
        fail("unterminated value of attribute '" + key + "'");
      }
      std::string value = unescaped(text_.substr(position_ + 1, end - position_ - 1));
      advance(end + 1 - position_);
      element.attributes.emplace_back(std::move(key), std::move(value));
    }
    const bool is_empty = at("/>");
    advance(is_empty ? 2 : 1);
    const std::size_t index = elements_.size();
    if (!open.empty()) {
      elements_[open.back()].children.push_back(index);
    }
    elements_.push_back(std::move(element));
    if (!is_empty) {
      open.push_back(index);
    }
  }

  std::string_view text_;
  const std::string& path_;
  std::size_t position_ = 0;
  std::size_t line_ = 1;
  std::vector<XmlElement> elements_;
  std::vector<std::string> comments_;
};

class VtuReader {
 public:
  VtuReader(const std::string& content, const std::string& path) : document_(content, path) {}

  TriangleMesh read() {
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
    return assemble(dimension, xyz, arrays, std::move(triangles),
                    [&](const std::string& message) { fail(piece, message); });
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

TriangleMesh io_detail::parse_vtu(const std::string& content, const std::string& path) {
  return VtuReader(content, path).read();
}

TriangleMesh read_vtk(const std::string& path) {
  return io_detail::parse_vtk(io_detail::read_file(kVtk, path), path);
}

TriangleMesh read_vtu(const std::string& path) {
  return io_detail::parse_vtu(io_detail::read_file(kVtu, path), path);
}

}  // namespace tessera
