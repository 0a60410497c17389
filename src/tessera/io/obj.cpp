// SPDX-License-Identifier: MIT
#include "tessera/io/obj.h"

#include <limits>

#include "tessera/core/error.h"
#include "tessera/io/detail/file_buffer.h"
#include "tessera/io/detail/write_checks.h"

namespace tessera {

namespace {

constexpr std::string_view kObj = "OBJ";

}  // namespace

void write_obj(const std::string& path, const TriangleMesh& mesh, std::array<int, 3> coordinates) {
  const int n = mesh.ambient_dimension();
  for (const int c : coordinates) {
    TESSERA_CHECK(c >= 0 && (c < n || n < 3), "write_obj: coordinate index "
                                                  << c << " must be in [0, " << n
                                                  << ") for a mesh in R^" << n);
  }
  io_detail::check_triangle_indices(mesh, path);

  io_detail::OutputFile file(kObj, path);
  file.text("# written by tessera: triangle mesh in R^");
  file.integer(n);
  file.text(", coordinates ");
  file.integer(coordinates[0]);
  file.text(", ");
  file.integer(coordinates[1]);
  file.text(", ");
  file.integer(coordinates[2]);
  file.text("\n# ");
  file.integer(mesh.vertex_count());
  file.text(" vertices, ");
  file.integer(mesh.triangle_count());
  file.text(" triangles\n");
  const double* points = mesh.points().data();
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    file.character('v');
    for (const int c : coordinates) {
      file.character(' ');
      file.real(c < n ? points[static_cast<std::ptrdiff_t>(v) * n + c] : 0.0);
    }
    file.character('\n');
  }
  for (const auto& triangle : mesh.triangles()) {
    file.character('f');
    for (const int v : triangle) {
      file.character(' ');
      file.integer(static_cast<std::int64_t>(v) + 1);
    }
    file.character('\n');
  }
  file.close();
}

TriangleMesh read_obj(const std::string& path) {
  const std::string content = io_detail::read_file(kObj, path);
  std::vector<double> coordinates;
  std::vector<Triangle> triangles;
  std::vector<std::size_t> triangle_lines;  // for the range check after the last vertex
  std::vector<std::int64_t> polygon;
  std::size_t position = 0;
  std::size_t line_number = 0;
  while (position < content.size()) {
    std::size_t end = content.find('\n', position);
    end = end == std::string::npos ? content.size() : end;
    std::string_view line(content.data() + position, end - position);
    position = end + 1;
    ++line_number;
    line = line.substr(0, line.find('#'));
    const auto tokens = io_detail::split_tokens(line);
    auto fail = [&](const std::string& message) {
      io_detail::throw_file_error(kObj, path, line_number, message);
    };
    if (tokens.empty()) {
      continue;
    }
    if (tokens[0] == "v") {
      if (tokens.size() < 4) {
        fail("a vertex needs 3 coordinates, found " + std::to_string(tokens.size() - 1));
      }
      for (std::size_t k = 1; k <= 3; ++k) {
        double value = 0;
        if (!io_detail::parse_real(tokens[k], value)) {
          fail("expected a number, found '" + std::string(tokens[k]) + "'");
        }
        coordinates.push_back(value);
      }
    } else if (tokens[0] == "f") {
      if (tokens.size() < 4) {
        fail("a face needs at least 3 vertices, found " + std::to_string(tokens.size() - 1));
      }
      const auto defined = static_cast<std::int64_t>(coordinates.size() / 3);
      polygon.clear();
      for (std::size_t i = 1; i < tokens.size(); ++i) {
        const std::string_view reference = tokens[i].substr(0, tokens[i].find('/'));
        std::int64_t index = 0;
        if (!io_detail::parse_integer(reference, index) || index == 0) {
          fail("expected a vertex index (1-based, or negative to count back), found '" +
               std::string(tokens[i]) + "'");
        }
        index = index > 0 ? index - 1 : defined + index;
        if (index < 0 || index > std::numeric_limits<int>::max()) {
          fail("vertex index '" + std::string(tokens[i]) + "' is out of range; " +
               std::to_string(defined) + " vertices are defined before this line");
        }
        polygon.push_back(index);
      }
      for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
        triangles.push_back({static_cast<int>(polygon[0]), static_cast<int>(polygon[i]),
                             static_cast<int>(polygon[i + 1])});
        triangle_lines.push_back(line_number);
      }
    }
  }
  const auto vertex_count = static_cast<std::int64_t>(coordinates.size() / 3);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (const int v : triangles[t]) {
      if (v >= vertex_count) {
        io_detail::throw_file_error(kObj, path, triangle_lines[t],
                                    // 64 bits: v may be INT_MAX (found by obj_fuzz).
                                    "vertex index " + std::to_string(std::int64_t{v} + 1) +
                                        " is out of range; the file has " +
                                        std::to_string(vertex_count) + " vertices");
      }
    }
  }
  const Eigen::Map<const Eigen::MatrixXd> points(coordinates.data(), 3,
                                                 static_cast<Eigen::Index>(vertex_count));
  return TriangleMesh(points, std::move(triangles));
}

}  // namespace tessera
