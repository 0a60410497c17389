// SPDX-License-Identifier: MIT
#include "tessera/io/detail/write_checks.h"

#include <set>

#include "tessera/core/error.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/io/detail/file_buffer.h"

namespace tessera::io_detail {

std::vector<std::string> checked_vertex_data_names(const TriangleMesh& mesh,
                                                   const std::vector<std::string>& requested,
                                                   const std::vector<VertexScalars>& scalars,
                                                   const std::string& options_name) {
  const int n = mesh.ambient_dimension();
  TESSERA_CHECK(requested.empty() || static_cast<int>(requested.size()) == n,
                options_name << "::coordinate_names has " << requested.size()
                             << " names; the mesh is in R^" << n << " and needs " << n
                             << " (or none, for the defaults)");
  std::vector<std::string> names = requested.empty() ? default_coordinate_names(n) : requested;
  std::set<std::string> seen;
  for (const auto& name : names) {
    TESSERA_CHECK(is_plain_name(name), options_name << "::coordinate_names: '" << name
                                                    << "' must be non-empty without whitespace");
    TESSERA_CHECK(seen.insert(name).second,
                  options_name << "::coordinate_names: '" << name << "' appears twice");
  }
  for (const auto& field : scalars) {
    TESSERA_CHECK(is_plain_name(field.name), options_name
                                                 << "::vertex_scalars: name '" << field.name
                                                 << "' must be non-empty without whitespace");
    TESSERA_CHECK(seen.insert(field.name).second,
                  options_name << "::vertex_scalars: name '" << field.name
                               << "' is already used by a coordinate or another field");
    TESSERA_CHECK(static_cast<int>(field.values.size()) == mesh.vertex_count(),
                  options_name << "::vertex_scalars '" << field.name << "' has "
                               << field.values.size() << " values; the mesh has "
                               << mesh.vertex_count() << " vertices");
  }
  return names;
}

void check_triangle_indices(const TriangleMesh& mesh, const std::string& path) {
  const int vertex_count = mesh.vertex_count();
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    for (const int v : mesh.triangle(t)) {
      TESSERA_CHECK(v >= 0 && v < vertex_count,
                    "cannot write '" << path << "': triangle " << t << " has vertex index " << v
                                     << "; the mesh has " << vertex_count << " vertices");
    }
  }
}

void check_comments(const std::vector<std::string>& comments, const std::string& options_name) {
  for (const auto& comment : comments) {
    TESSERA_CHECK(comment.find_first_of("\r\n") == std::string::npos,
                  options_name << "::comments: '" << comment << "' must be a single line");
  }
}

}  // namespace tessera::io_detail
