// SPDX-License-Identifier: MIT
#include "tessera/io/mesh_io.h"

#include <cctype>
#include <filesystem>

#include "tessera/core/error.h"
#include "tessera/io/file_names.h"
#include "tessera/io/npy.h"

namespace tessera {

namespace {

}  // namespace

void write_mesh(const std::string& path, const TriangleMesh& mesh, const MeshFileOptions& options) {
  const std::string extension = lowercase_extension(path);
  if (extension == ".ply") {
    write_ply(path, mesh,
              {.binary = options.binary,
               .coordinate_names = options.coordinate_names,
               .vertex_scalars = options.vertex_scalars,
               .comments = options.comments});
  } else if (extension == ".obj") {
    write_obj(path, mesh, options.obj_coordinates);
  } else if (extension == ".vtk" || extension == ".vtu") {
    const VtkOptions vtk_options{.coordinate_names = options.coordinate_names,
                                 .vertex_scalars = options.vertex_scalars,
                                 .comments = options.comments};
    if (extension == ".vtk") {
      write_vtk(path, mesh, vtk_options);
    } else {
      write_vtu(path, mesh, vtk_options);
    }
  } else {
    TESSERA_CHECK(false, "cannot write '" << path << "': unknown extension '" << extension
                                          << "'; supported: .ply, .obj, .vtk, .vtu");
  }
}

TriangleMesh read_mesh(const std::string& path) {
  const std::string extension = lowercase_extension(path);
  if (extension == ".ply") {
    return read_ply(path);
  }
  if (extension == ".obj") {
    return read_obj(path);
  }
  if (extension == ".vtk") {
    return read_vtk(path);
  }
  if (extension == ".vtu") {
    return read_vtu(path);
  }
  if (extension == ".npy") {
    return read_states_npy(path);
  }
  TESSERA_CHECK(false, "cannot read '" << path << "': unknown extension '" << extension
                                       << "'; supported: .ply, .obj, .vtk, .vtu, .npy (states)");
  return {};
}

}  // namespace tessera
