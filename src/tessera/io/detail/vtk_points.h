// SPDX-License-Identifier: MIT
// Internal to the io layer: what read_vtk and read_vtu share, turning the points, the point-data
// arrays and the cells of a VTK file into a mesh in R^n.
#pragma once

#include <bit>
#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/geometry/triangle_mesh.h"
#include "tessera/io/vertex_data.h"

namespace tessera::io_detail {

// Far above any ambient dimension tessera meets; bounds what a comment can make us expect.
inline constexpr std::int64_t kMaxVtkDimension = 1 << 16;

/// The n of "... triangle mesh in R^n" at `text`'s start after `prefix`, or 0.
inline int dimension_after(std::string_view text, std::string_view prefix) {
  if (text.substr(0, prefix.size()) != prefix) {
    return 0;
  }
  text.remove_prefix(prefix.size());
  std::int64_t n = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), n);
  return error == std::errc() && n >= 1 && n <= kMaxVtkDimension ? static_cast<int>(n) : 0;
}

/// One named array of point data with one value per vertex (and component).
struct PointArray {
  std::string name;
  int components = 1;
  std::vector<double> values;  // vertex-major: values[v * components + c]
};

/// Turns polygons (a first vertex and a fan) into triangles, keeping their orientation.
inline void append_fan(const std::vector<std::int64_t>& polygon, std::vector<Triangle>& triangles) {
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
    triangles.push_back({static_cast<int>(polygon[0]), static_cast<int>(polygon[i]),
                         static_cast<int>(polygon[i + 1])});
  }
}

/// The mesh from the 3-column points, the point-data arrays and n (0: not known from the file).
/// The first n arrays are the coordinates, as write_vtk / write_vtu put them; their first three
/// must agree with the points bit for bit, which both writers guarantee. The one-component
/// arrays after the coordinates (all of them when the coordinates come from the points) go to
/// `vertex_scalars` when it is not null.
template <class Fail>
TriangleMesh assemble(int dimension, const std::vector<double>& xyz,
                      const std::vector<PointArray>& arrays, std::vector<Triangle> triangles,
                      const Fail& fail, std::vector<VertexScalars>* vertex_scalars = nullptr) {
  const std::size_t vertex_count = xyz.size() / 3;
  bool from_arrays = true;
  if (dimension == 0) {
    // Not a tessera file, or one whose marker was lost: the point data may still start with the
    // coordinates x0, x1, ... that tessera used to name them; otherwise the points are in R^3
    // and the point data (whatever it holds) is not read.
    std::size_t k = 0;
    while (k < arrays.size() && arrays[k].name == "x" + std::to_string(k) &&
           arrays[k].components == 1) {
      ++k;
    }
    dimension = k >= 3 ? static_cast<int>(k) : 3;
    from_arrays = k >= 3;
  }
  const auto n = static_cast<std::size_t>(dimension);
  from_arrays = from_arrays && !(n <= 3 && arrays.size() < n);
  if (from_arrays && arrays.size() < n) {
    fail("the file is a mesh in R^" + std::to_string(n) + " but has only " +
         std::to_string(arrays.size()) +
         " point-data arrays; the coordinates beyond the "
         "third are point-data arrays");
  }
  Eigen::MatrixXd points(dimension, static_cast<Eigen::Index>(vertex_count));
  for (std::size_t k = 0; k < n; ++k) {
    if (!from_arrays) {
      for (std::size_t v = 0; v < vertex_count; ++v) {
        points(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(v)) = xyz[3 * v + k];
      }
      continue;
    }
    const PointArray& array = arrays[k];
    if (array.components != 1) {
      fail("point-data array '" + array.name + "' (coordinate " + std::to_string(k) + ") has " +
           std::to_string(array.components) + " components; a coordinate has one");
    }
    for (std::size_t v = 0; v < vertex_count; ++v) {
      const double value = array.values[v];
      if (k < 3 &&
          std::bit_cast<std::uint64_t>(value) != std::bit_cast<std::uint64_t>(xyz[3 * v + k])) {
        fail("point-data array '" + array.name + "' (coordinate " + std::to_string(k) +
             ") differs from the points at vertex " + std::to_string(v) +
             ": the file was changed after tessera wrote it");
      }
      points(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(v)) = value;
    }
  }
  if (vertex_scalars != nullptr) {
    vertex_scalars->clear();
    for (std::size_t a = from_arrays ? n : 0; a < arrays.size(); ++a) {
      if (arrays[a].components == 1 && arrays[a].values.size() == vertex_count) {
        vertex_scalars->push_back({arrays[a].name, arrays[a].values});
      }
    }
  }
  return TriangleMesh(points, std::move(triangles));
}

}  // namespace tessera::io_detail
