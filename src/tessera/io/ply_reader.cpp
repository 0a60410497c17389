// SPDX-License-Identifier: MIT
// read_ply: parse the header, decide which properties are coordinates and which list holds the
// faces, then read every element record in order from an ASCII or a binary source.
#include "tessera/io/ply.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <climits>
#include <cstdint>
#include <limits>

#include "tessera/io/detail/file_buffer.h"
#include "tessera/io/detail/mesh_parsers.h"
#include "tessera/io/detail/ply_header.h"

namespace tessera {

namespace {

constexpr std::string_view kPlyInput = "PLY";
// Far above any ambient dimension tessera meets; bounds what a comment can make us allocate.
constexpr std::int64_t kMaxDimension = 1 << 16;

using io_detail::PlyElement;
using io_detail::PlyEncoding;
using io_detail::PlyHeader;
using io_detail::PlyProperty;
using io_detail::PlyType;

// Which element and properties hold the mesh.
struct ReadPlan {
  int vertex_element = -1;
  std::vector<int> coordinate_of_property;  // per vertex property: coordinate index or -1
  int dimension = 0;
  int face_element = -1;
  int face_property = -1;
};

int find_property(const PlyElement& element, std::string_view name) {
  for (std::size_t p = 0; p < element.properties.size(); ++p) {
    if (element.properties[p].name == name) {
      return static_cast<int>(p);
    }
  }
  return -1;
}

std::string property_list(const PlyElement& element) {
  std::string names;
  for (const auto& property : element.properties) {
    names += (names.empty() ? "" : ", ") + property.name;
  }
  return names.empty() ? "(none)" : names;
}

// The n of "written by tessera: triangle mesh in R^n" among the comments, or 0.
int tessera_dimension(const std::vector<std::string>& comments) {
  constexpr std::string_view kMarker = "written by tessera: triangle mesh in R^";
  for (const auto& comment : comments) {
    if (comment.compare(0, kMarker.size(), kMarker) != 0) {
      continue;
    }
    const std::string_view digits = std::string_view(comment).substr(kMarker.size());
    std::int64_t n = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
    if (error == std::errc() && n >= 1 && n <= kMaxDimension) {
      return static_cast<int>(n);
    }
  }
  return 0;
}

// x0, x1, ... if x0 is present (earlier tessera versions, n != 3), else x, y, z followed by x3,
// x4, ... or by coordinate_3, coordinate_4, ...: each list stops at the first gap.
std::vector<int> detect_coordinates(const PlyElement& vertex) {
  std::vector<int> found;
  const bool indexed = find_property(vertex, "x0") >= 0;
  for (int k = 0;; ++k) {
    const std::string index = std::to_string(k);
    int p = find_property(vertex, indexed || k >= 3 ? "x" + index : std::string(1, "xyz"[k]));
    if (p < 0 && !indexed && k >= 3) {
      p = find_property(vertex, "coordinate_" + index);
    }
    if (p < 0) {
      return found;
    }
    found.push_back(p);
  }
}

ReadPlan make_plan(const PlyHeader& header, const std::vector<std::string>& requested,
                   const std::string& path) {
  ReadPlan plan;
  for (std::size_t e = 0; e < header.elements.size(); ++e) {
    if (header.elements[e].name == "vertex" && plan.vertex_element < 0) {
      plan.vertex_element = static_cast<int>(e);
    }
    if (header.elements[e].name == "face" && plan.face_element < 0) {
      plan.face_element = static_cast<int>(e);
    }
  }
  if (plan.vertex_element < 0) {
    io_detail::throw_file_error(kPlyInput, path, "the header declares no 'vertex' element");
  }
  const PlyElement& vertex = header.elements[static_cast<std::size_t>(plan.vertex_element)];
  if (vertex.count > INT_MAX) {
    io_detail::throw_file_error(kPlyInput, path,
                                "the header declares " + std::to_string(vertex.count) +
                                    " vertices; at most 2^31 - 1 are supported");
  }
  std::vector<int> coordinates;
  const int dimension = requested.empty() ? tessera_dimension(header.comments) : 0;
  if (dimension > 0) {
    // tessera writes the n coordinates first, whatever their names (x, y, z, then the names of
    // the problem; x0 ... before; any names given to write_ply).
    if (static_cast<std::size_t>(dimension) > vertex.properties.size()) {
      io_detail::throw_file_error(kPlyInput, path,
                                  "the comment says the mesh is in R^" + std::to_string(dimension) +
                                      " but the vertex has only " +
                                      std::to_string(vertex.properties.size()) +
                                      " properties: " + property_list(vertex));
    }
    for (int k = 0; k < dimension; ++k) {
      coordinates.push_back(k);
    }
  } else if (requested.empty()) {
    coordinates = detect_coordinates(vertex);
    if (coordinates.empty()) {
      io_detail::throw_file_error(
          kPlyInput, path,
          "no coordinate properties: expected x, y, z (then x3, x4, ...) or x0, x1, ...; the "
          "vertex properties are " +
              property_list(vertex));
    }
  } else {
    for (const auto& name : requested) {
      const int p = find_property(vertex, name);
      if (p < 0) {
        io_detail::throw_file_error(kPlyInput, path,
                                    "no vertex property '" + name +
                                        "' (a requested coordinate); the vertex properties are " +
                                        property_list(vertex));
      }
      coordinates.push_back(p);
    }
  }
  plan.coordinate_of_property.assign(vertex.properties.size(), -1);
  for (std::size_t k = 0; k < coordinates.size(); ++k) {
    const auto& property = vertex.properties[static_cast<std::size_t>(coordinates[k])];
    if (property.is_list) {
      io_detail::throw_file_error(
          kPlyInput, path,
          "vertex property '" + property.name + "' is a list; a coordinate must be a scalar");
    }
    plan.coordinate_of_property[static_cast<std::size_t>(coordinates[k])] = static_cast<int>(k);
  }
  plan.dimension = static_cast<int>(coordinates.size());

  if (plan.face_element >= 0) {
    const PlyElement& face = header.elements[static_cast<std::size_t>(plan.face_element)];
    plan.face_property = find_property(face, "vertex_indices");
    if (plan.face_property < 0) {
      plan.face_property = find_property(face, "vertex_index");
    }
    if (plan.face_property < 0) {
      io_detail::throw_file_error(kPlyInput, path,
                                  "element 'face' has no list property 'vertex_indices' (or "
                                  "'vertex_index'); its properties are " +
                                      property_list(face));
    }
    const auto& property = face.properties[static_cast<std::size_t>(plan.face_property)];
    if (!property.is_list || !io_detail::is_integer_type(property.type)) {
      io_detail::throw_file_error(
          kPlyInput, path, "face property '" + property.name + "' must be a list of integers");
    }
  }
  return plan;
}

// Rejects, before anything is allocated, a header that declares more records than the data can
// hold: every value takes at least `unit` bytes (binary: its size; ASCII: one character and a
// separator), so a truncated file or a corrupt count fails here with a clear message.
void check_data_size(const PlyHeader& header, std::size_t data_size, const std::string& path,
                     std::size_t last_line) {
  const bool ascii = header.encoding == PlyEncoding::Ascii;
  double needed = 0;  // double: counts up to 2^63 times sizes must not overflow
  for (const auto& element : header.elements) {
    std::size_t record = 0;
    for (const auto& property : element.properties) {
      record +=
          ascii ? 2
                : io_detail::ply_type_size(property.is_list ? property.count_type : property.type);
    }
    needed += static_cast<double>(element.count) * static_cast<double>(record);
    if (needed > static_cast<double>(data_size) + 1) {
      const std::string message = "unexpected end of file: the header declares " +
                                  std::to_string(element.count) + " '" + element.name +
                                  "' records, more than the " + std::to_string(data_size) +
                                  " bytes after the header can hold";
      if (ascii) {
        io_detail::throw_file_error(kPlyInput, path, last_line, message);
      }
      io_detail::throw_file_error(kPlyInput, path, message + " (truncated binary data)");
    }
  }
}

class AsciiSource {
 public:
  AsciiSource(std::string_view data, std::size_t first_line, const std::string& path)
      : cursor_(data, first_line), path_(path) {}

  bool real(PlyType /*type*/, double& value) {
    expected_ = "a number";
    token_ = cursor_.next_token();
    return io_detail::parse_real(token_, value);
  }
  bool integer(PlyType /*type*/, std::int64_t& value) {
    expected_ = "an integer";
    token_ = cursor_.next_token();
    return io_detail::parse_integer(token_, value);
  }
  bool skip(PlyType /*type*/) {
    expected_ = "a value";
    token_ = cursor_.next_token();
    return !token_.empty();
  }
  // At least one character and a separator per value.
  bool can_hold(std::int64_t count, PlyType /*type*/) const {
    return count <= static_cast<std::int64_t>(cursor_.remaining() / 2 + 1);
  }
  /// The last read failed while reading `what`.
  [[noreturn]] void fail(const std::string& what) const {
    if (token_.empty()) {
      truncated(what);
    }
    error("expected " + expected_ + " for " + what + ", found " +
          io_detail::quoted_excerpt(token_));
  }
  /// The data ends before `what`.
  [[noreturn]] void truncated(const std::string& what) const {
    error("unexpected end of file in " + what);
  }
  [[noreturn]] void error(const std::string& message) const {
    io_detail::throw_file_error(kPlyInput, path_, cursor_.line(), message);
  }

 private:
  io_detail::TextCursor cursor_;
  const std::string& path_;
  std::string_view token_;
  std::string expected_;
};

class BinarySource {
 public:
  BinarySource(std::string_view data, bool swap, const std::string& path)
      : data_(data), swap_(swap), path_(path) {}

  bool real(PlyType type, double& value) {
    if (!has(io_detail::ply_type_size(type))) {
      return false;
    }
    switch (type) {
      case PlyType::Float32:
        value = load<float>();
        return true;
      case PlyType::Float64:
        value = load<double>();
        return true;
      case PlyType::UInt64:
        value = static_cast<double>(load<std::uint64_t>());
        return true;
      default:
        std::int64_t integer_value = 0;
        integer(type, integer_value);
        value = static_cast<double>(integer_value);
        return true;
    }
  }
  bool integer(PlyType type, std::int64_t& value) {
    if (!has(io_detail::ply_type_size(type))) {
      return false;
    }
    switch (type) {
      case PlyType::Int8:
        value = load<std::int8_t>();
        break;
      case PlyType::UInt8:
        value = load<std::uint8_t>();
        break;
      case PlyType::Int16:
        value = load<std::int16_t>();
        break;
      case PlyType::UInt16:
        value = load<std::uint16_t>();
        break;
      case PlyType::Int32:
        value = load<std::int32_t>();
        break;
      case PlyType::UInt32:
        value = load<std::uint32_t>();
        break;
      case PlyType::Int64:
        value = load<std::int64_t>();
        break;
      case PlyType::UInt64: {
        const std::uint64_t unsigned_value = load<std::uint64_t>();
        // Beyond int64 it is out of range anyway; -1 makes the range check say so.
        value =
            unsigned_value > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())
                ? -1
                : static_cast<std::int64_t>(unsigned_value);
        break;
      }
      default:
        return false;  // excluded by the header checks: counts and indices are integers
    }
    return true;
  }
  bool skip(PlyType type) {
    if (!has(io_detail::ply_type_size(type))) {
      return false;
    }
    position_ += io_detail::ply_type_size(type);
    return true;
  }
  bool can_hold(std::int64_t count, PlyType type) const {
    return count <=
           static_cast<std::int64_t>((data_.size() - position_) / io_detail::ply_type_size(type));
  }
  /// The last read failed while reading `what`: a binary read fails only at the end of data.
  [[noreturn]] void fail(const std::string& what) const { truncated(what); }
  [[noreturn]] void truncated(const std::string& what) const {
    error("unexpected end of file in " + what + " (truncated binary data)");
  }
  [[noreturn]] void error(const std::string& message) const {
    io_detail::throw_file_error(
        kPlyInput, path_, message + " (at byte " + std::to_string(position_) + " after the header)");
  }

 private:
  bool has(std::size_t size) const { return data_.size() - position_ >= size; }
  template <class T>
  T load() {
    T value;
    std::memcpy(&value, data_.data() + position_, sizeof(T));
    position_ += sizeof(T);
    return swap_ ? io_detail::byte_swapped(value) : value;
  }

  std::string_view data_;
  std::size_t position_ = 0;
  bool swap_;
  const std::string& path_;
};

// `scalars` (or null): per vertex property, where its values go (null: not kept).
template <class Source>
void read_records(Source& source, const PlyHeader& header, const ReadPlan& plan,
                  Eigen::MatrixXd& points, std::vector<Triangle>& triangles,
                  const std::vector<std::vector<double>*>* scalars) {
  const std::int64_t vertex_count = points.cols();
  std::vector<std::int64_t> polygon;
  for (std::size_t e = 0; e < header.elements.size(); ++e) {
    const PlyElement& element = header.elements[e];
    const bool is_vertex = static_cast<int>(e) == plan.vertex_element;
    const bool is_face = static_cast<int>(e) == plan.face_element;
    // An element without properties has no data whatever its count; counting through its
    // records would take forever for a count near 2^63 (found by tests/fuzz/ply_fuzz).
    if (element.properties.empty()) {
      continue;
    }
    for (std::int64_t r = 0; r < element.count; ++r) {
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const PlyProperty& property = element.properties[p];
        auto what = [&] {
          return element.name + " " + std::to_string(r) + " of " + std::to_string(element.count) +
                 ", property '" + property.name + "'";
        };
        if (!property.is_list) {
          double value = 0;
          if (!source.real(property.type, value)) {
            source.fail(what());
          }
          if (is_vertex && plan.coordinate_of_property[p] >= 0) {
            points(plan.coordinate_of_property[p], static_cast<Eigen::Index>(r)) = value;
          } else if (is_vertex && scalars != nullptr && (*scalars)[p] != nullptr) {
            (*scalars)[p]->push_back(value);
          }
          continue;
        }
        std::int64_t count = 0;
        if (!source.integer(property.count_type, count)) {
          source.fail(what() + " (list length)");
        }
        if (count < 0) {
          source.error(what() + ": negative list length " + std::to_string(count));
        }
        if (!source.can_hold(count, property.type)) {
          source.truncated(what());
        }
        const bool is_polygon = is_face && static_cast<int>(p) == plan.face_property;
        if (!is_polygon) {
          for (std::int64_t i = 0; i < count; ++i) {
            if (!source.skip(property.type)) {
              source.fail(what());
            }
          }
          continue;
        }
        if (count < 3) {
          source.error("face " + std::to_string(r) + " has " + std::to_string(count) +
                       " vertices; a face needs at least 3");
        }
        polygon.resize(static_cast<std::size_t>(count));
        for (auto& index : polygon) {
          if (!source.integer(property.type, index)) {
            source.fail(what());
          }
          if (index < 0 || index >= vertex_count) {
            source.error("face " + std::to_string(r) + " has vertex index " +
                         std::to_string(index) + "; the file has " + std::to_string(vertex_count) +
                         " vertices");
          }
        }
        for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
          triangles.push_back({static_cast<int>(polygon[0]), static_cast<int>(polygon[i]),
                               static_cast<int>(polygon[i + 1])});
        }
      }
    }
  }
}

}  // namespace

TriangleMesh read_ply(const std::string& path, const std::vector<std::string>& coordinate_names) {
  return io_detail::parse_ply(io_detail::read_file(kPlyInput, path), path, coordinate_names);
}

TriangleMesh io_detail::parse_ply(const std::string& content, const std::string& path,
                                  const std::vector<std::string>& coordinate_names,
                                  std::vector<VertexScalars>* vertex_scalars) {
  const PlyHeader header = io_detail::parse_ply_header(content, path);
  const ReadPlan plan = make_plan(header, coordinate_names, path);
  const std::string_view data = std::string_view(content).substr(header.data_offset);
  const std::size_t last_line =
      header.data_line + static_cast<std::size_t>(std::count(data.begin(), data.end(), '\n'));
  check_data_size(header, data.size(), path, last_line);

  const auto& vertex = header.elements[static_cast<std::size_t>(plan.vertex_element)];
  Eigen::MatrixXd points(plan.dimension, static_cast<Eigen::Index>(vertex.count));
  std::vector<Triangle> triangles;
  if (plan.face_element >= 0) {
    triangles.reserve(static_cast<std::size_t>(
        header.elements[static_cast<std::size_t>(plan.face_element)].count));
  }
  // The scalar vertex properties that are not coordinates, when asked for; they grow with the
  // values read, not with the count claimed.
  std::vector<std::vector<double>*> scalar_of_property;
  if (vertex_scalars != nullptr) {
    vertex_scalars->clear();
    for (std::size_t p = 0; p < vertex.properties.size(); ++p) {
      if (!vertex.properties[p].is_list && plan.coordinate_of_property[p] < 0) {
        vertex_scalars->push_back({vertex.properties[p].name, {}});
      }
    }
    std::size_t next = 0;
    scalar_of_property.assign(vertex.properties.size(), nullptr);
    for (std::size_t p = 0; p < vertex.properties.size(); ++p) {
      if (!vertex.properties[p].is_list && plan.coordinate_of_property[p] < 0) {
        scalar_of_property[p] = &(*vertex_scalars)[next++].values;
      }
    }
  }
  const auto* scalars = vertex_scalars != nullptr ? &scalar_of_property : nullptr;
  if (header.encoding == PlyEncoding::Ascii) {
    AsciiSource source(data, header.data_line, path);
    read_records(source, header, plan, points, triangles, scalars);
  } else {
    const bool file_is_little = header.encoding == PlyEncoding::BinaryLittleEndian;
    const bool host_is_little = std::endian::native == std::endian::little;
    BinarySource source(data, file_is_little != host_is_little, path);
    read_records(source, header, plan, points, triangles, scalars);
  }
  return TriangleMesh(points, std::move(triangles));
}

}  // namespace tessera
