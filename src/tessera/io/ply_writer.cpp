// SPDX-License-Identifier: MIT
// write_ply: the header, then all vertex records, then all face records.
#include "tessera/io/ply.h"

#include <algorithm>
#include <cctype>
#include <set>

#include "tessera/core/error.h"

#include "tessera/io/detail/file_buffer.h"
#include "tessera/io/detail/write_checks.h"

namespace tessera {

namespace {

constexpr std::string_view kPlyOutput = "PLY";

// A name other tools accept as a PLY property and as a field name (meshio makes NumPy record
// fields of them): a letter or '_', then letters, digits and '_'.
bool is_identifier(std::string_view name) {
  if (name.empty() || std::isdigit(static_cast<unsigned char>(name.front()))) {
    return false;
  }
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
}

// x, y, z for the first three coordinates: the only names meshio, ParaView and VTK take a
// position from (VTK's reader crashed on x0 ...). Coordinate k >= 3 keeps its given name when
// that is an identifier no other property uses, else becomes coordinate_k.
std::vector<std::string> property_names(const std::vector<std::string>& coordinate_names,
                                        const std::vector<VertexScalars>& scalars) {
  std::set<std::string> taken = {"x", "y", "z"};
  for (const auto& field : scalars) {
    TESSERA_CHECK(taken.count(field.name) == 0,
                  "PlyOptions::vertex_scalars: name '"
                      << field.name << "' is taken: PLY names the first three coordinates x, y, z");
    taken.insert(field.name);
  }
  std::vector<std::string> names;
  for (std::size_t k = 0; k < coordinate_names.size(); ++k) {
    if (k < 3) {
      names.emplace_back(1, "xyz"[k]);
      continue;
    }
    std::string name = coordinate_names[k];
    if (!is_identifier(name) || taken.count(name) > 0) {
      name = "coordinate_" + std::to_string(k);
      for (int suffix = 2; taken.count(name) > 0; ++suffix) {
        name = "coordinate_" + std::to_string(k) + "_" + std::to_string(suffix);
      }
    }
    taken.insert(name);
    names.push_back(std::move(name));
  }
  return names;
}

void write_header(io_detail::OutputFile& file, const TriangleMesh& mesh,
                  const std::vector<std::string>& coordinate_names,
                  const std::vector<std::string>& property_names, const PlyOptions& options) {
  file.text("ply\n");
  file.text(options.binary ? "format binary_little_endian 1.0\n" : "format ascii 1.0\n");
  // read_ply takes the dimension from this line: the first n vertex properties are the point.
  file.text("comment written by tessera: triangle mesh in R^");
  file.integer(mesh.ambient_dimension());
  file.character('\n');
  if (!options.coordinate_names.empty() && coordinate_names != property_names) {
    file.text("comment coordinate names:");
    for (const auto& name : coordinate_names) {
      file.character(' ');
      file.text(name);
    }
    file.character('\n');
  }
  for (const auto& comment : options.comments) {
    file.text("comment ");
    file.text(comment);
    file.character('\n');
  }
  file.text("element vertex ");
  file.integer(mesh.vertex_count());
  file.character('\n');
  for (const auto& name : property_names) {
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
  const auto names = property_names(coordinate_names, options.vertex_scalars);
  io_detail::check_triangle_indices(mesh, path);

  io_detail::OutputFile file(kPlyOutput, path);
  write_header(file, mesh, coordinate_names, names, options);
  if (options.binary) {
    write_binary_data(file, mesh, options);
  } else {
    write_ascii_data(file, mesh, options);
  }
  file.close();
}

}  // namespace tessera
