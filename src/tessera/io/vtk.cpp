// SPDX-License-Identifier: MIT
#include "tessera/io/vtk.h"

#include <algorithm>

#include "tessera/core/error.h"
#include "tessera/io/detail/file_buffer.h"
#include "tessera/io/detail/vtk_cell_types.h"
#include "tessera/io/detail/write_checks.h"
#include "tessera/io/text_file.h"

namespace tessera {

namespace {

using io_detail::kVtkTriangle;

// Point j's first three coordinates, 0 for those beyond n.
void write_point_xyz(io_detail::OutputFile& file, const TriangleMesh& mesh, int vertex) {
  const int n = mesh.ambient_dimension();
  const double* point = mesh.points().data() + static_cast<std::ptrdiff_t>(vertex) * n;
  for (int k = 0; k < 3; ++k) {
    if (k > 0) {
      file.character(' ');
    }
    file.real(k < n ? point[k] : 0.0);
  }
}

// One value per line would make files of 10^6 vertices long to scroll; nine per line is what
// VTK's own writers do.
constexpr int kValuesPerLine = 9;

void write_coordinate(io_detail::OutputFile& file, const TriangleMesh& mesh, int coordinate) {
  const int n = mesh.ambient_dimension();
  const double* points = mesh.points().data();
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    file.real(points[static_cast<std::ptrdiff_t>(v) * n + coordinate]);
    file.character((v + 1) % kValuesPerLine == 0 ? '\n' : ' ');
  }
}

void write_values(io_detail::OutputFile& file, const std::vector<double>& values) {
  for (std::size_t v = 0; v < values.size(); ++v) {
    file.real(values[v]);
    file.character((v + 1) % kValuesPerLine == 0 ? '\n' : ' ');
  }
}

void write_legacy_scalars_header(io_detail::OutputFile& file, const std::string& name) {
  file.text("SCALARS ");
  file.text(name);
  file.text(" double 1\nLOOKUP_TABLE default\n");
}

void begin_vtu_array(io_detail::OutputFile& file, std::string_view type, const std::string& name,
                     int components) {
  file.text("        <DataArray type=\"");
  file.text(type);
  file.text("\"");
  if (!name.empty()) {
    file.text(" Name=\"");
    file.text(xml_escaped(name));
    file.text("\"");
  }
  if (components > 1) {
    file.text(" NumberOfComponents=\"");
    file.integer(components);
    file.text("\"");
  }
  file.text(" format=\"ascii\">\n");
}

void end_vtu_array(io_detail::OutputFile& file) { file.text("\n        </DataArray>\n"); }

}  // namespace

void write_vtk(const std::string& path, const TriangleMesh& mesh, const VtkOptions& options) {
  const auto names = io_detail::checked_vertex_data_names(mesh, options.coordinate_names,
                                                          options.vertex_scalars, "VtkOptions");
  io_detail::check_comments(options.comments, "VtkOptions");
  io_detail::check_triangle_indices(mesh, path);

  // read_vtk takes n from the start of the title, which the cut below never reaches.
  std::string title = "tessera triangle mesh in R^" + std::to_string(mesh.ambient_dimension());
  for (const auto& comment : options.comments) {
    title += "; " + comment;
  }
  constexpr std::size_t kMaxTitleLength = 255;  // the legacy format reads at most 256 characters
  title.resize(std::min(title.size(), kMaxTitleLength));

  io_detail::OutputFile file("VTK", path);
  file.text("# vtk DataFile Version 4.2\n");
  file.text(title);
  // UNSTRUCTURED_GRID rather than POLYDATA: meshio reads only unstructured grids from legacy
  // files, and VTK and ParaView read both alike.
  file.text("\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS ");
  file.integer(mesh.vertex_count());
  file.text(" double\n");
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    write_point_xyz(file, mesh, v);
    file.character('\n');
  }
  file.text("CELLS ");
  file.integer(mesh.triangle_count());
  file.character(' ');
  file.integer(4 * static_cast<std::int64_t>(mesh.triangle_count()));
  file.character('\n');
  write_triangle_lines(file, mesh.triangles());
  file.text("CELL_TYPES ");
  file.integer(mesh.triangle_count());
  file.character('\n');
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    file.integer(kVtkTriangle);
    file.character((t + 1) % 30 == 0 ? '\n' : ' ');
  }
  file.character('\n');
  file.text("POINT_DATA ");
  file.integer(mesh.vertex_count());
  file.character('\n');
  for (int k = 0; k < mesh.ambient_dimension(); ++k) {
    write_legacy_scalars_header(file, names[static_cast<std::size_t>(k)]);
    write_coordinate(file, mesh, k);
    file.character('\n');
  }
  for (const auto& field : options.vertex_scalars) {
    write_legacy_scalars_header(file, field.name);
    write_values(file, field.values);
    file.character('\n');
  }
  file.close();
}

void write_vtu(const std::string& path, const TriangleMesh& mesh, const VtkOptions& options) {
  const auto names = io_detail::checked_vertex_data_names(mesh, options.coordinate_names,
                                                          options.vertex_scalars, "VtkOptions");
  io_detail::check_comments(options.comments, "VtkOptions");
  io_detail::check_triangle_indices(mesh, path);

  io_detail::OutputFile file("VTU", path);
  file.text("<?xml version=\"1.0\"?>\n");
  file.text("<!-- written by tessera: triangle mesh in R^");
  file.integer(mesh.ambient_dimension());
  file.text(" -->\n");
  for (const auto& comment : options.comments) {
    file.text("<!-- ");
    file.text(xml_comment_text(comment));  // "--" may not occur in an XML comment
    file.text(" -->\n");
  }
  file.text(
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"");
  file.integer(mesh.vertex_count());
  file.text("\" NumberOfCells=\"");
  file.integer(mesh.triangle_count());
  file.text("\">\n      <PointData>\n");
  for (int k = 0; k < mesh.ambient_dimension(); ++k) {
    begin_vtu_array(file, "Float64", names[static_cast<std::size_t>(k)], 1);
    write_coordinate(file, mesh, k);
    end_vtu_array(file);
  }
  for (const auto& field : options.vertex_scalars) {
    begin_vtu_array(file, "Float64", field.name, 1);
    write_values(file, field.values);
    end_vtu_array(file);
  }
  file.text("      </PointData>\n      <Points>\n");
  begin_vtu_array(file, "Float64", "Points", 3);
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    write_point_xyz(file, mesh, v);
    file.character('\n');
  }
  end_vtu_array(file);
  file.text("      </Points>\n      <Cells>\n");
  begin_vtu_array(file, "Int64", "connectivity", 1);
  for (const auto& triangle : mesh.triangles()) {
    for (const int v : triangle) {
      file.integer(v);
      file.character(' ');
    }
    file.character('\n');
  }
  end_vtu_array(file);
  begin_vtu_array(file, "Int64", "offsets", 1);
  for (std::int64_t t = 1; t <= mesh.triangle_count(); ++t) {
    file.integer(3 * t);
    file.character(t % kValuesPerLine == 0 ? '\n' : ' ');
  }
  end_vtu_array(file);
  begin_vtu_array(file, "UInt8", "types", 1);
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    file.integer(kVtkTriangle);
    file.character((t + 1) % 30 == 0 ? '\n' : ' ');
  }
  end_vtu_array(file);
  file.text("      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
  file.close();
}

}  // namespace tessera
