// SPDX-License-Identifier: MIT
// write_ply: the header, then all vertex records, then all face records.
#include "tessera/io/ply.h"

#include "tessera/io/detail/file_buffer.h"
#include "tessera/io/detail/write_checks.h"

namespace tessera {

namespace {

constexpr std::string_view kFormat = "PLY";

void write_header(io_detail::OutputFile& file, const TriangleMesh& mesh,
                  const std::vector<std::string>& coordinate_names, const PlyOptions& options) {
  file.text("ply\n");
  file.text(options.binary ? "format binary_little_endian 1.0\n" : "format ascii 1.0\n");
  file.text("comment written by tessera: triangle mesh in R^");
  file.integer(mesh.ambient_dimension());
  file.character('\n');
  for (const auto& comment : options.comments) {
    file.text("comment ");
    file.text(comment);
    file.character('\n');
  }
  file.text("element vertex ");
  file.integer(mesh.vertex_count());
  file.character('\n');
  for (const auto& name : coordinate_names) {
    file.text("property double ");
    file.text(name);
    file.character('\n');
  }
  for (const auto& field : options.vertex_scalars) {
    file.text("property double ");
    file.text(field.name);
    file.character('\n');
  }
  file.text("element face ");
  file.integer(mesh.triangle_count());
  file.text("\nproperty list uchar int vertex_indices\nend_header\n");
}

void write_binary_data(io_detail::OutputFile& file, const TriangleMesh& mesh,
                       const PlyOptions& options) {
  const int n = mesh.ambient_dimension();
  const double* coordinates = mesh.points().data();
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    for (int k = 0; k < n; ++k) {
      file.little_endian_double(coordinates[static_cast<std::ptrdiff_t>(v) * n + k]);
    }
    for (const auto& field : options.vertex_scalars) {
      file.little_endian_double(field.values[static_cast<std::size_t>(v)]);
    }
  }
  for (const auto& triangle : mesh.triangles()) {
    file.character(3);
    for (const int v : triangle) {
      file.little_endian_int32(v);
    }
  }
}

void write_ascii_data(io_detail::OutputFile& file, const TriangleMesh& mesh,
                      const PlyOptions& options) {
  const int n = mesh.ambient_dimension();
  const double* coordinates = mesh.points().data();
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    bool first = true;
    for (int k = 0; k < n; ++k) {
      if (!first) {
        file.character(' ');
      }
      first = false;
      file.real(coordinates[static_cast<std::ptrdiff_t>(v) * n + k]);
    }
    for (const auto& field : options.vertex_scalars) {
      if (!first) {
        file.character(' ');
      }
      first = false;
      file.real(field.values[static_cast<std::size_t>(v)]);
    }
    file.character('\n');
  }
  write_triangle_lines(file, mesh.triangles());
}

}  // namespace

void write_ply(const std::string& path, const TriangleMesh& mesh, const PlyOptions& options) {
  const auto coordinate_names = io_detail::checked_vertex_data_names(
      mesh, options.coordinate_names, options.vertex_scalars, "PlyOptions");
  io_detail::check_comments(options.comments, "PlyOptions");
  io_detail::check_triangle_indices(mesh, path);

  io_detail::OutputFile file(kFormat, path);
  write_header(file, mesh, coordinate_names, options);
  if (options.binary) {
    write_binary_data(file, mesh, options);
  } else {
    write_ascii_data(file, mesh, options);
  }
  file.close();
}

}  // namespace tessera
