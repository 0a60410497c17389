// SPDX-License-Identifier: MIT
// read_states_npy: NPY versions 1.0 – 3.0, 2-d arrays of floats (points) and integers
// (triangles), https://numpy.org/doc/stable/reference/generated/numpy.lib.format.html
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "tessera/io/detail/file_buffer.h"
#include "tessera/io/detail/mesh_parsers.h"
#include "tessera/io/npy.h"

namespace tessera {

namespace {

constexpr std::string_view kNumPyInput = "NumPy";

// What the header says about the data.
struct NpyHeader {
  bool is_big_endian = false;
  char kind = 0;  ///< 'f' float, 'i' signed, 'u' unsigned integer
  int item_size = 0;
  bool fortran_order = false;
  std::int64_t rows = 0;  ///< shape (rows, columns)
  std::int64_t columns = 0;
  std::size_t data_offset = 0;
  std::string descr;  ///< as written, for messages
};

// Reads the header dictionary, a Python literal such as
// {'descr': '<f8', 'fortran_order': False, 'shape': (3, 4), }
class HeaderParser {
 public:
  HeaderParser(std::string_view text, const std::string& path) : text_(text), path_(path) {}

  void parse(NpyHeader& header) {
    bool has_descr = false;
    bool has_order = false;
    bool has_shape = false;
    expect('{');
    while (true) {
      skip_spaces();
      if (peek() == '}') {
        ++position_;
        break;
      }
      const std::string key = string_literal();
      expect(':');
      if (key == "descr") {
        header.descr = string_literal();
        has_descr = true;
      } else if (key == "fortran_order") {
        header.fortran_order = boolean();
        has_order = true;
      } else if (key == "shape") {
        shape(header);
        has_shape = true;
      } else {
        fail("unexpected key '" + key + "' (an .npy header has descr, fortran_order and shape)");
      }
      skip_spaces();
      if (peek() == ',') {
        ++position_;
      } else if (peek() != '}') {
        fail("expected ',' or '}' in the header dictionary");
      }
    }
    if (!has_descr || !has_order || !has_shape) {
      fail("the header lacks '" +
           std::string(!has_descr   ? "descr"
                       : !has_order ? "fortran_order"
                                    : "shape") +
           "'");
    }
    skip_spaces();
    if (position_ != text_.size()) {
      fail("unexpected text after the header dictionary");
    }
    read_descr(header);
  }

 private:
  [[noreturn]] void fail(const std::string& message) const {
    io_detail::throw_file_error(kNumPyInput, path_, "header: " + message);
  }
  char peek() const { return position_ < text_.size() ? text_[position_] : '\0'; }
  void skip_spaces() {
    while (position_ < text_.size() && (text_[position_] == ' ' || text_[position_] == '\n')) {
      ++position_;
    }
  }
  void expect(char c) {
    skip_spaces();
    if (peek() != c) {
      fail(std::string("expected '") + c + "'");
    }
    ++position_;
  }
  std::string string_literal() {
    skip_spaces();
    const char quote = peek();
    if (quote != '\'' && quote != '"') {
      fail("expected a quoted string");
    }
    const std::size_t end = text_.find(quote, position_ + 1);
    if (end == std::string_view::npos) {
      fail("unterminated string");
    }
    std::string value(text_.substr(position_ + 1, end - position_ - 1));
    position_ = end + 1;
    return value;
  }
  bool boolean() {
    skip_spaces();
    for (const auto& [word, value] : {std::pair{"True", true}, std::pair{"False", false}}) {
      const std::string_view w(word);
      if (text_.substr(position_, w.size()) == w) {
        position_ += w.size();
        return value;
      }
    }
    fail("fortran_order must be True or False");
  }
  std::int64_t integer() {
    skip_spaces();
    std::int64_t value = 0;
    bool any = false;
    while (position_ < text_.size() && text_[position_] >= '0' && text_[position_] <= '9') {
      if (value > (std::numeric_limits<std::int64_t>::max() - 9) / 10) {
        fail("a dimension of the shape is too large");
      }
      value = 10 * value + (text_[position_] - '0');
      ++position_;
      any = true;
    }
    if (!any) {
      fail("expected a dimension (a non-negative integer) in the shape");
    }
    return value;
  }
  void shape(NpyHeader& header) {
    expect('(');
    std::vector<std::int64_t> dimensions;
    while (true) {
      skip_spaces();
      if (peek() == ')') {
        ++position_;
        break;
      }
      dimensions.push_back(integer());
      skip_spaces();
      if (peek() == ',') {
        ++position_;
      } else if (peek() != ')') {
        fail("expected ',' or ')' in the shape");
      }
    }
    if (dimensions.size() != 2) {
      fail("the shape has " + std::to_string(dimensions.size()) +
           " dimensions; a 2-d array (rows, columns) is expected");
    }
    header.rows = dimensions[0];
    header.columns = dimensions[1];
  }
  void read_descr(NpyHeader& header) {
    const std::string& d = header.descr;
    const bool valid_order =
        !d.empty() && (d[0] == '<' || d[0] == '>' || d[0] == '|' || d[0] == '=');
    const bool valid_kind = d.size() >= 3 && (d[1] == 'f' || d[1] == 'i' || d[1] == 'u');
    int size = 0;
    for (std::size_t k = 2; valid_kind && k < d.size() && size <= 8; ++k) {
      size = d[k] >= '0' && d[k] <= '9' ? 10 * size + (d[k] - '0') : 100;
    }
    const bool valid_size =
        valid_kind && (d[1] == 'f' ? (size == 4 || size == 8)
                                   : (size == 1 || size == 2 || size == 4 || size == 8));
    if (!valid_order || !valid_kind || !valid_size) {
      fail(
          "descr '" + d +
          "' is not supported (floats '<f8', '<f4' and integers '<i8' … '<u1', either byte order)");
    }
    header.is_big_endian = d[0] == '>' || (d[0] == '=' && std::endian::native == std::endian::big);
    header.kind = d[1];
    header.item_size = size;
  }

  std::string_view text_;
  const std::string& path_;
  std::size_t position_ = 0;
};

NpyHeader parse_header(std::string_view content, const std::string& path) {
  constexpr std::string_view kMagic = "\x93NUMPY";
  if (content.size() < 10 || content.substr(0, kMagic.size()) != kMagic) {
    io_detail::throw_file_error(kNumPyInput, path,
                                "not an .npy file (it does not begin with \\x93NUMPY)");
  }
  const int major = static_cast<unsigned char>(content[6]);
  const int minor = static_cast<unsigned char>(content[7]);
  if (major < 1 || major > 3 || minor != 0) {
    io_detail::throw_file_error(kNumPyInput, path,
                                "format version " + std::to_string(major) + "." +
                                    std::to_string(minor) + " (1.0, 2.0 and 3.0 are read)");
  }
  const std::size_t preamble = major == 1 ? 10 : 12;
  if (content.size() < preamble) {
    io_detail::throw_file_error(kNumPyInput, path, "truncated in the preamble");
  }
  std::size_t header_length = 0;
  for (std::size_t k = preamble - 1; k >= 8; --k) {
    header_length = 256 * header_length + static_cast<unsigned char>(content[k]);
  }
  if (header_length > content.size() - preamble) {
    io_detail::throw_file_error(
        kNumPyInput, path,
        "the header of " + std::to_string(header_length) + " bytes is longer than the file");
  }
  NpyHeader header;
  HeaderParser(content.substr(preamble, header_length), path).parse(header);
  header.data_offset = preamble + header_length;
  // rows·columns·size must be the data's size; checked without overflow before any allocation.
  const std::size_t data_size = content.size() - header.data_offset;
  const auto item_size = static_cast<std::uint64_t>(header.item_size);
  const auto rows = static_cast<std::uint64_t>(header.rows);
  const auto columns = static_cast<std::uint64_t>(header.columns);
  const bool fits =
      columns == 0 || rows <= std::numeric_limits<std::uint64_t>::max() / item_size / columns;
  if (!fits || rows * columns * item_size != data_size) {
    io_detail::throw_file_error(
        kNumPyInput, path,
        "the shape (" + std::to_string(header.rows) + ", " + std::to_string(header.columns) +
            ") of '" + header.descr + "' needs " +
            (fits ? std::to_string(rows * columns * item_size) + " bytes" : "more bytes") +
            " of data, the file has " + std::to_string(data_size));
  }
  return header;
}

// Element (row, column) of the data as unsigned bits in this machine's byte order.
std::uint64_t element_bits(std::string_view content, const NpyHeader& header, std::int64_t row,
                           std::int64_t column) {
  const std::int64_t index =
      header.fortran_order ? row + column * header.rows : row * header.columns + column;
  const char* at = content.data() + header.data_offset +
                   static_cast<std::size_t>(index) * static_cast<std::size_t>(header.item_size);
  unsigned char bytes[8];
  std::memcpy(bytes, at, static_cast<std::size_t>(header.item_size));
  std::uint64_t bits = 0;
  for (int k = 0; k < header.item_size; ++k) {
    const int from = header.is_big_endian ? k : header.item_size - 1 - k;
    bits = (bits << 8) | bytes[from];
  }
  return bits;
}

}  // namespace

namespace io_detail {

Eigen::MatrixXd parse_npy_points(std::string_view content, const std::string& path) {
  const NpyHeader header = parse_header(content, path);
  if (header.kind != 'f') {
    throw_file_error(kNumPyInput, path,
                     "the states are of type '" + header.descr +
                         "'; floating-point numbers ('<f8' or '<f4') are expected");
  }
  if (header.columns < 1 || header.columns > std::numeric_limits<int>::max() ||
      header.rows > std::numeric_limits<int>::max()) {
    throw_file_error(kNumPyInput, path,
                     "the states have shape (" + std::to_string(header.rows) + ", " +
                         std::to_string(header.columns) +
                         "); expected (vertices, n) with n >= 1 and fewer than 2^31 of each");
  }
  Eigen::MatrixXd points(header.columns, header.rows);
  for (std::int64_t v = 0; v < header.rows; ++v) {
    for (std::int64_t i = 0; i < header.columns; ++i) {
      const std::uint64_t bits = element_bits(content, header, v, i);
      points(i, v) =
          header.item_size == 8
              ? std::bit_cast<double>(bits)
              : static_cast<double>(std::bit_cast<float>(static_cast<std::uint32_t>(bits)));
    }
  }
  return points;
}

std::vector<Triangle> parse_npy_triangles(std::string_view content, const std::string& path,
                                          int vertex_count) {
  const NpyHeader header = parse_header(content, path);
  if (header.kind == 'f') {
    throw_file_error(kNumPyInput, path,
                     "the triangles are of type '" + header.descr +
                         "'; integers ('<i8', '<i4', …) are expected");
  }
  if (header.columns != 3 || header.rows > std::numeric_limits<int>::max()) {
    throw_file_error(kNumPyInput, path,
                     "the triangles have shape (" + std::to_string(header.rows) + ", " +
                         std::to_string(header.columns) + "); expected (triangles, 3)");
  }
  std::vector<Triangle> triangles(static_cast<std::size_t>(header.rows));
  const int unused_bits = 64 - 8 * header.item_size;
  for (std::int64_t t = 0; t < header.rows; ++t) {
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t bits = element_bits(content, header, t, k);
      // Sign-extend a signed integer narrower than 64 bits.
      const std::int64_t value = header.kind == 'i'
                                     ? static_cast<std::int64_t>(bits << unused_bits) >> unused_bits
                                     : static_cast<std::int64_t>(bits);
      if (value < 0 || value >= vertex_count || (header.kind == 'u' && bits > INT32_MAX)) {
        throw_file_error(kNumPyInput, path,
                         "triangle " + std::to_string(t) + " has vertex index " +
                             (header.kind == 'u' ? std::to_string(bits) : std::to_string(value)) +
                             "; the states have " + std::to_string(vertex_count) + " vertices");
      }
      triangles[static_cast<std::size_t>(t)][static_cast<std::size_t>(k)] = static_cast<int>(value);
    }
  }
  return triangles;
}

}  // namespace io_detail

TriangleMesh read_states_npy(const std::string& path) {
  const Eigen::MatrixXd points =
      io_detail::parse_npy_points(io_detail::read_file(kNumPyInput, path), path);
  const std::string triangles_path = triangles_npy_path(path);
  std::error_code error;
  if (!std::filesystem::exists(triangles_path, error)) {
    io_detail::throw_file_error(kNumPyInput, path,
                                "its triangles belong in '" + triangles_path +
                                    "' (written beside it by tessera mesh --states), which does "
                                    "not exist");
  }
  std::vector<Triangle> triangles =
      io_detail::parse_npy_triangles(io_detail::read_file(kNumPyInput, triangles_path), triangles_path,
                                     static_cast<int>(points.cols()));
  return TriangleMesh(points, std::move(triangles));
}

}  // namespace tessera
