// SPDX-License-Identifier: MIT
// write_npy: NPY format 1.0, https://numpy.org/doc/stable/reference/generated/numpy.lib.format.html
#include "tessera/io/npy.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <exception>
#include <optional>
#include <vector>

#include "tessera/core/error.h"
#include "tessera/io/detail/file_buffer.h"
#include "tessera/io/detail/root_writes.h"
#include "tessera/io/detail/write_checks.h"

namespace tessera {

namespace {

constexpr std::string_view kNumPy = "NumPy";

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
  io_detail::OutputFile file(kNumPy, path);
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
  io_detail::OutputFile file(kNumPy, path);
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
  if (mesh.space().is_distributed()) {
    write_split_states_npy(path, mesh);
    return;
  }
  io_detail::check_triangle_indices(mesh, path);
  write_npy(triangles_npy_path(path), mesh.triangles());
  write_npy(path, mesh.points());
}

void write_split_states_npy(const std::string& path, const TriangleMesh& mesh,
                            std::size_t gather_bytes) {
  const AmbientSpace& space = mesh.space();
  if (!space.is_distributed()) {
    write_states_npy(path, mesh);
    return;
  }
  io_detail::check_triangle_indices(mesh, path);  // every rank the same triangles, the same verdict
  const bool is_root = space.is_root();
  const std::int64_t n = space.dimension();
  const int vertex_count = mesh.vertex_count();
  // As write_states_npy: the triangles first, so that a complete states file has its triangles.
  std::exception_ptr error;
  std::optional<io_detail::OutputFile> file;
  if (is_root) {
    try {
      write_npy(triangles_npy_path(path), mesh.triangles());
      file.emplace(kNumPy, path);
      write_header(*file, "<f8", vertex_count, n);
    } catch (...) {
      error = std::current_exception();
      file.reset();
    }
  }
  const auto bytes_per_vertex = static_cast<std::size_t>(n) * sizeof(double);
  const int block = static_cast<int>(std::clamp<std::size_t>(
      gather_bytes / bytes_per_vertex, 1, static_cast<std::size_t>(std::max(1, vertex_count))));
  std::vector<double> whole(is_root ? static_cast<std::size_t>(n) * block : 0);
  const auto local = mesh.points();  // local rows × V, column-major
  for (int begin = 0; begin < vertex_count; begin += block) {
    // Stop early, and together, once the root cannot write.
    if (io_detail::any_rank_failed(space, error != nullptr)) {
      break;
    }
    const int count = std::min(block, vertex_count - begin);
    space.gather_to_root(local.data() + static_cast<std::ptrdiff_t>(begin) * local.rows(), count,
                         whole.data());
    if (!is_root) {
      continue;
    }
    try {
      if constexpr (std::endian::native == std::endian::little) {
        file->bytes(whole.data(), static_cast<std::size_t>(count) * bytes_per_vertex);
      } else {
        for (std::size_t i = 0; i < static_cast<std::size_t>(count * n); ++i) {
          file->little_endian_double(whole[i]);
        }
      }
    } catch (...) {
      error = std::current_exception();
      file.reset();
    }
  }
  if (file) {
    try {
      file->close();
    } catch (...) {
      error = std::current_exception();
    }
  }
  io_detail::throw_if_root_failed(space, error, kNumPy, path);
}

}  // namespace tessera
