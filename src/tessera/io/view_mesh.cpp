// SPDX-License-Identifier: MIT
#include "tessera/io/view_mesh.h"

#include <algorithm>

#include "tessera/core/error.h"
#include "tessera/io/detail/root_writes.h"

namespace tessera {

TriangleMesh mesh_in_view(const TriangleMesh& mesh, const View& view) {
  // A split mesh holds some rows of each point; its space knows n.
  const AmbientSpace& space = mesh.space();
  TESSERA_CHECK(view.ambient_dimension() == space.dimension(),
                "the view '" << view.specification() << "' takes points of R^"
                             << view.ambient_dimension() << ", the mesh is in R^"
                             << space.dimension());
  TESSERA_CHECK(view.size() >= 2, "the view '"
                                      << view.specification() << "' has " << view.size()
                                      << " functional; a mesh needs at least two to place its "
                                         "vertices (three for a surface in space)");
  const Eigen::MatrixXd values = view.evaluate_columns(mesh.points(), space);
  if (view.size() >= 3) {
    return TriangleMesh(values, mesh.triangles());
  }
  Eigen::MatrixXd padded = Eigen::MatrixXd::Zero(3, values.cols());
  padded.topRows(values.rows()) = values;
  return TriangleMesh(padded, mesh.triangles());
}

std::vector<std::string> coordinate_names_in_view(const View& view) {
  std::vector<std::string> names = view.names();
  if (names.size() == 2) {
    std::string zero = "zero";
    for (int suffix = 2; std::find(names.begin(), names.end(), zero) != names.end(); ++suffix) {
      zero = "zero_" + std::to_string(suffix);
    }
    names.push_back(zero);
  }
  return names;
}

void write_mesh_in_view(const std::string& path, const TriangleMesh& mesh, const View& view,
                        MeshFileOptions options) {
  const TriangleMesh shown = mesh_in_view(mesh, view);
  options.coordinate_names = coordinate_names_in_view(view);
  options.obj_coordinates = {0, 1, 2};
  // An expression may hold "--" (x--y): the VTU writer makes it fit an XML comment.
  options.comments.push_back("view: " + view.specification());
  if (!mesh.space().is_distributed()) {
    write_mesh(path, shown, options);
    return;
  }
  io_detail::write_on_root(mesh.space(), "mesh", path, [&] { write_mesh(path, shown, options); });
}

}  // namespace tessera
