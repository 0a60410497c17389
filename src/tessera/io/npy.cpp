// SPDX-License-Identifier: MIT
// write_npy: NPY format 1.0, https://numpy.org/doc/stable/reference/generated/numpy.lib.format.html
#include "tessera/io/npy.h"

#include <bit>
#include <cstdint>

#include "tessera/core/error.h"
#include "tessera/io/detail/file_buffer.h"
#include "tessera/io/detail/write_checks.h"

namespace tessera {

namespace {

constexpr std::string_view kFormat = "NumPy";

// The preamble and header of a C-order 2-d array: magic, version 1.0, header length, dictionary.
// numpy.lib.format pads the header so that the data is aligned to 64 bytes (memory mapping).
void write_header(io_detail::OutputFile& file, std::string_view descr, std::int64_t rows,
                  std::int64_t columns) {
  std::string header = "{'descr': '" + std::string(descr) +
                       "', 'fortran_order': False, 'shape': (" + std::to_string(rows) + ", " +
                       std::to_string(columns) + "), }";
  constexpr std::size_t kPreamble = 10;  // magic (6), version (2), header length (2)
  const std::size_t unpadded = kPreamble + header.size() + 1;
  header.append((64 - unpadded % 64) % 64, ' ');
  header.push_back('\n');
  file.text("\x93NUMPY");
  file.character(1);
  file.character(0);
  const auto length = static_cast<std::uint16_t>(header.size());  // < 200 bytes
  file.character(static_cast<char>(length & 0xff));
  file.character(static_cast<char>(length >> 8));
  file.text(header);
}

}  // namespace

void write_npy(const std::string& path, const Eigen::Ref<const Eigen::MatrixXd>& points) {
  io_detail::OutputFile file(kFormat, path);
  write_header(file, "<f8", points.cols(), points.rows());
  for (Eigen::Index j = 0; j < points.cols(); ++j) {
    if constexpr (std::endian::native == std::endian::little) {
      // A column of a Ref<const MatrixXd> is contiguous: one copy per point.
      file.bytes(points.col(j).data(), static_cast<std::size_t>(points.rows()) * sizeof(double));
    } else {
      for (Eigen::Index i = 0; i < points.rows(); ++i) {
        file.little_endian_double(points(i, j));
      }
    }
  }
  file.close();
}

void write_npy(const std::string& path, const std::vector<Triangle>& triangles) {
  io_detail::OutputFile file(kFormat, path);
  write_header(file, "<i8", static_cast<std::int64_t>(triangles.size()), 3);
  for (const Triangle& triangle : triangles) {
    for (const int v : triangle) {
      file.little_endian_int64(v);
    }
  }
  file.close();
}

std::string triangles_npy_path(const std::string& states_path) {
  const std::string extension = ".npy";
  const bool has_extension =
      states_path.size() > extension.size() &&
      states_path.compare(states_path.size() - extension.size(), extension.size(), extension) == 0;
  return (has_extension ? states_path.substr(0, states_path.size() - extension.size())
                        : states_path) +
         ".triangles.npy";
}

void write_states_npy(const std::string& path, const TriangleMesh& mesh) {
  io_detail::check_triangle_indices(mesh, path);
  write_npy(triangles_npy_path(path), mesh.triangles());
  write_npy(path, mesh.points());
}

}  // namespace tessera
