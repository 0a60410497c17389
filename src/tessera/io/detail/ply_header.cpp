// SPDX-License-Identifier: MIT
#include "tessera/io/detail/ply_header.h"

#include "tessera/io/detail/file_buffer.h"

namespace tessera::io_detail {

namespace {

constexpr std::string_view kPlyHeader = "PLY";

struct PlyTypeName {
  std::string_view name;
  PlyType type;
};

// The names of the PLY specification, their sized aliases, and the 64-bit types meshio writes.
constexpr PlyTypeName kTypeNames[] = {
    {"char", PlyType::Int8},       {"int8", PlyType::Int8},      {"uchar", PlyType::UInt8},
    {"uint8", PlyType::UInt8},     {"short", PlyType::Int16},    {"int16", PlyType::Int16},
    {"ushort", PlyType::UInt16},   {"uint16", PlyType::UInt16},  {"int", PlyType::Int32},
    {"int32", PlyType::Int32},     {"uint", PlyType::UInt32},    {"uint32", PlyType::UInt32},
    {"int64", PlyType::Int64},     {"uint64", PlyType::UInt64},  {"float", PlyType::Float32},
    {"float32", PlyType::Float32}, {"double", PlyType::Float64}, {"float64", PlyType::Float64}};

bool parse_type(std::string_view name, PlyType& type) {
  for (const auto& entry : kTypeNames) {
    if (entry.name == name) {
      type = entry.type;
      return true;
    }
  }
  return false;
}

}  // namespace

std::size_t ply_type_size(PlyType type) {
  switch (type) {
    case PlyType::Int8:
    case PlyType::UInt8:
      return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
      return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
      return 4;
    case PlyType::Int64:
    case PlyType::UInt64:
    case PlyType::Float64:
      return 8;
  }
  return 8;
}

std::string quoted_excerpt(std::string_view line) {
  constexpr std::size_t kMaxLength = 60;  // binary garbage must not flood the message
  return "'" + std::string(line.substr(0, kMaxLength)) + (line.size() > kMaxLength ? "...'" : "'");
}

PlyHeader parse_ply_header(const std::string& content, const std::string& path) {
  PlyHeader header;
  bool has_format = false;
  std::size_t position = 0;
  std::size_t line_number = 0;
  while (true) {
    if (position >= content.size()) {
      throw_file_error(kPlyHeader, path, line_number, "the header has no 'end_header' line");
    }
    std::size_t end = content.find('\n', position);
    const bool is_last = end == std::string::npos;
    end = is_last ? content.size() : end;
    std::string_view line(content.data() + position, end - position);
    position = is_last ? end : end + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') {
      line.remove_suffix(1);
    }
    const auto tokens = split_tokens(line);
    auto fail = [&](const std::string& message) {
      throw_file_error(kPlyHeader, path, line_number, message);
    };
    if (line_number == 1) {
      if (tokens.size() != 1 || tokens[0] != "ply") {
        fail("not a PLY file: the first line is " + quoted_excerpt(line) + ", expected 'ply'");
      }
      continue;
    }
    if (!tokens.empty() && tokens[0] == "comment") {
      const std::size_t text = line.find("comment") + 7;
      const std::size_t first = line.find_first_not_of(" \t", text);
      header.comments.emplace_back(first == std::string_view::npos ? std::string_view()
                                                                   : line.substr(first));
      continue;
    }
    if (tokens.empty() || tokens[0] == "obj_info") {
      continue;
    }
    const std::string_view keyword = tokens[0];
    if (keyword == "end_header") {
      if (!has_format) {
        fail("the header has no 'format' line");
      }
      header.data_offset = position;
      header.data_line = line_number + 1;
      return header;
    }
    if (keyword == "format") {
      if (tokens.size() != 3) {
        fail("expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0', found " +
             quoted_excerpt(line));
      }
      if (tokens[1] == "ascii") {
        header.encoding = PlyEncoding::Ascii;
      } else if (tokens[1] == "binary_little_endian") {
        header.encoding = PlyEncoding::BinaryLittleEndian;
      } else if (tokens[1] == "binary_big_endian") {
        header.encoding = PlyEncoding::BinaryBigEndian;
      } else {
        fail("unknown format '" + std::string(tokens[1]) +
             "'; expected ascii, binary_little_endian or binary_big_endian");
      }
      has_format = true;
    } else if (keyword == "element") {
      std::int64_t count = -1;
      if (tokens.size() != 3 || !parse_integer(tokens[2], count) || count < 0) {
        fail("expected 'element <name> <count>' with count >= 0, found " + quoted_excerpt(line));
      }
      header.elements.push_back({std::string(tokens[1]), count, {}});
    } else if (keyword == "property") {
      if (header.elements.empty()) {
        fail("'property' before any 'element' line");
      }
      PlyProperty property;
      const bool is_list = tokens.size() >= 2 && tokens[1] == "list";
      if (is_list) {
        property.is_list = true;
        if (tokens.size() != 5 || !parse_type(tokens[2], property.count_type) ||
            !parse_type(tokens[3], property.type) || !is_integer_type(property.count_type)) {
          fail("expected 'property list <integer type> <type> <name>', found " +
               quoted_excerpt(line));
        }
        property.name = tokens[4];
      } else {
        if (tokens.size() != 3 || !parse_type(tokens[1], property.type)) {
          fail(
              "expected 'property <type> <name>' with type one of char, uchar, short, ushort, "
              "int, uint, float, double (or int8 ... float64), found " +
              quoted_excerpt(line));
        }
        property.name = tokens[2];
      }
      header.elements.back().properties.push_back(std::move(property));
    } else {
      fail("unknown header keyword " + quoted_excerpt(keyword));
    }
  }
}

}  // namespace tessera::io_detail
