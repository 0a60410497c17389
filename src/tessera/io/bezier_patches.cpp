// SPDX-License-Identifier: MIT
#include "tessera/io/bezier_patches.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tessera/core/error.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/io/text_file.h"

namespace tessera {
namespace {

constexpr const char* kFormat = "tessera-bezier-patches";
constexpr int kVersion = 1;

nlohmann::json column(const Eigen::Ref<const Eigen::VectorXd>& x) {
  nlohmann::json values = nlohmann::json::array();
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    values.push_back(x(i));
  }
  return values;
}

Eigen::VectorXd vector_from(const nlohmann::json& values, int n, const std::string& where) {
  TESSERA_CHECK(values.is_array() && static_cast<int>(values.size()) == n,
                where << " must be an array of " << n << " numbers");
  Eigen::VectorXd x(n);
  for (int i = 0; i < n; ++i) {
    TESSERA_CHECK(values[i].is_number(), where << "[" << i << "] is not a number");
    x(i) = values[i].get<double>();
  }
  return x;
}

}  // namespace

void write_bezier_patches(const std::string& path, const BezierSurfaceFile& surface) {
  const TriangleMesh& mesh = surface.mesh;
  const int n = mesh.ambient_dimension();
  TESSERA_CHECK(static_cast<int>(surface.patches.size()) == mesh.triangle_count(),
                "write_bezier_patches: " << surface.patches.size() << " patches for "
                                         << mesh.triangle_count() << " triangles");
  TESSERA_CHECK(
      surface.coordinate_names.empty() || static_cast<int>(surface.coordinate_names.size()) == n,
      "write_bezier_patches: " << surface.coordinate_names.size()
                               << " coordinate names for n = " << n);
  nlohmann::json file;
  file["format"] = kFormat;
  file["version"] = kVersion;
  file["dimension"] = n;
  file["coordinate_names"] =
      surface.coordinate_names.empty() ? default_coordinate_names(n) : surface.coordinate_names;
  file["multi_indices"] = CubicBezierPatch::multi_indices();
  nlohmann::json vertices = nlohmann::json::array();
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    vertices.push_back(column(mesh.point(v)));
  }
  file["vertices"] = std::move(vertices);
  nlohmann::json triangles = nlohmann::json::array();
  nlohmann::json control_points = nlohmann::json::array();
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const CubicBezierPatch& patch = surface.patches[t];
    TESSERA_CHECK(patch.ambient_dimension() == n,
                  "write_bezier_patches: patch " << t << " is in R^" << patch.ambient_dimension());
    triangles.push_back(mesh.triangle(t));
    nlohmann::json points = nlohmann::json::array();
    for (int c = 0; c < 10; ++c) {
      points.push_back(column(patch.control_points().col(c)));
    }
    control_points.push_back(std::move(points));
  }
  file["triangles"] = std::move(triangles);
  file["control_points"] = std::move(control_points);
  // nlohmann::json writes doubles in their shortest round-trip form: the patches read back exactly.
  write_text_file(path, file.dump() + "\n", "Bezier patches");
}

BezierSurfaceFile read_bezier_patches(const std::string& path) {
  std::ifstream in(path);
  TESSERA_CHECK(in.good(), "cannot open '" << path << "'");
  const std::string where = "Bezier patches '" + path + "'";
  nlohmann::json file;
  try {
    in >> file;
  } catch (const nlohmann::json::parse_error& error) {
    // error.what() is nlohmann's wording ("[json.exception.parse_error.101] ..."): the byte is
    // what a user needs.
    TESSERA_CHECK(false, where << ": not valid JSON (the syntax breaks at byte " << error.byte
                               << "); expected the file of `tessera mesh --patches`");
  } catch (const nlohmann::json::exception&) {
    TESSERA_CHECK(false, where << ": a number is out of the range of a double");
  }
  TESSERA_CHECK(file.is_object(),
                where << ": expected a JSON object (the file of `tessera mesh --patches`), found "
                      << file.type_name());
  // Every field is checked before it is converted: nlohmann's own messages
  // ("[json.exception.type_error.302] type must be array, but is null") never reach a user.
  const auto field = [&](const char* key) -> const nlohmann::json& {
    TESSERA_CHECK(file.contains(key), where << ": the field '" << key
                                            << "' is missing; is it the file of `tessera mesh "
                                               "--patches`?");
    return file.at(key);
  };
  TESSERA_CHECK(field("format").is_string() && field("format").get<std::string>() == kFormat,
                where << ": the field 'format' is " << field("format").dump() << ", not \""
                      << kFormat << "\"");
  TESSERA_CHECK(field("version").is_number_integer() && field("version").get<int>() == kVersion,
                where << ": version " << field("version").dump() << " is not supported (this "
                      << "tessera reads version " << kVersion << ")");
  TESSERA_CHECK(field("dimension").is_number_integer() && field("dimension").get<int>() >= 3 &&
                    field("dimension").get<int>() <= (1 << 24),
                where << ": the field 'dimension' is " << field("dimension").dump()
                      << "; expected an integer n >= 3");
  const int n = field("dimension").get<int>();
  TESSERA_CHECK(field("multi_indices") == nlohmann::json(CubicBezierPatch::multi_indices()),
                where << ": the field 'multi_indices' is not tessera's order");
  const auto& names = field("coordinate_names");
  TESSERA_CHECK(
      names.is_array() && static_cast<int>(names.size()) == n &&
          std::all_of(names.begin(), names.end(),
                      [](const nlohmann::json& name) { return name.is_string(); }),
      where << ": the field 'coordinate_names' must be an array of " << n << " names (strings)");
  BezierSurfaceFile surface;
  surface.coordinate_names = names.get<std::vector<std::string>>();
  surface.mesh = TriangleMesh(n);
  const auto& vertices = field("vertices");
  TESSERA_CHECK(vertices.is_array(), where << ": the field 'vertices' must be an array");
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    surface.mesh.add_vertex(
        vector_from(vertices[v], n, where + ": vertices[" + std::to_string(v) + "]"));
  }
  const auto& triangles = field("triangles");
  const auto& control_points = field("control_points");
  TESSERA_CHECK(triangles.is_array() && control_points.is_array() &&
                    triangles.size() == control_points.size(),
                where << ": 'triangles' and 'control_points' must be arrays of equal size");
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& triangle = triangles[t];
    TESSERA_CHECK(triangle.is_array() && triangle.size() == 3 &&
                      std::all_of(triangle.begin(), triangle.end(),
                                  [](const nlohmann::json& v) { return v.is_number_integer(); }),
                  where << ": triangles[" << t << "] must be an array of 3 vertex indices, found "
                        << triangle.dump());
    std::array<int, 3> tri{};
    for (int i = 0; i < 3; ++i) {
      const auto v = triangle[static_cast<std::size_t>(i)].get<std::int64_t>();
      TESSERA_CHECK(v >= 0 && v < surface.mesh.vertex_count(),
                    where << ": triangles[" << t << "] has vertex " << v << " out of range");
      tri[static_cast<std::size_t>(i)] = static_cast<int>(v);
    }
    surface.mesh.add_triangle(tri[0], tri[1], tri[2]);
    TESSERA_CHECK(control_points[t].is_array() && control_points[t].size() == 10,
                  where << ": control_points[" << t << "] must hold 10 points");
    Eigen::MatrixXd b(n, 10);
    for (int c = 0; c < 10; ++c) {
      b.col(c) = vector_from(
          control_points[t][static_cast<std::size_t>(c)], n,
          where + ": control_points[" + std::to_string(t) + "][" + std::to_string(c) + "]");
    }
    surface.patches.emplace_back(std::move(b));
  }
  return surface;
}

}  // namespace tessera
