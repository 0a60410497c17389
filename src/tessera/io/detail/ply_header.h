// SPDX-License-Identifier: MIT
// Internal to the io layer: the header of a PLY file (encoding, elements, their properties).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace tessera::io_detail {

/// The scalar types of PLY (char ... double, their sized aliases int8 ... float64, and the
/// 64-bit integers meshio writes).
enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float32, Float64 };

/// Bytes of one value of `type` in binary PLY.
std::size_t ply_type_size(PlyType type);
inline bool is_integer_type(PlyType type) {
  return type != PlyType::Float32 && type != PlyType::Float64;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float64;  ///< of the value, or of the items of a list
  bool is_list = false;
  PlyType count_type = PlyType::UInt8;  ///< of the list length (an integer type)
};

struct PlyElement {
  std::string name;
  std::int64_t count = 0;  ///< number of records, >= 0
  std::vector<PlyProperty> properties;
};

enum class PlyEncoding { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyHeader {
  PlyEncoding encoding = PlyEncoding::Ascii;
  std::vector<PlyElement> elements;   ///< in file order, which is the order of the data
  std::vector<std::string> comments;  ///< text after "comment ", in file order
  std::size_t data_offset = 0;        ///< first byte after the "end_header" line
  std::size_t data_line = 0;          ///< line number (from 1) of that byte
};

/// Parses the header at the start of `content`, the whole file `path` (named in errors).
/// Accepts "\r\n" line ends and blank lines; skips comment and obj_info lines.
/// \throw InvalidArgument naming the file and the line if the header is malformed.
PlyHeader parse_ply_header(const std::string& content, const std::string& path);

/// `text` in single quotes, cut to a length that keeps binary garbage out of messages.
std::string quoted_excerpt(std::string_view text);

}  // namespace tessera::io_detail
