// SPDX-License-Identifier: MIT
// The cubic surface of method `bezier` as a JSON file (format: docs/bezier-patches.md).
#pragma once

#include <string>
#include <vector>

#include "tessera/geometry/bezier_patch.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

/// A triangle mesh with one cubic Bézier patch per triangle.
struct BezierSurfaceFile {
  TriangleMesh mesh;
  std::vector<CubicBezierPatch> patches;      ///< patches[t] over mesh.triangle(t)
  std::vector<std::string> coordinate_names;  ///< n names; empty: x0 … x{n−1} (x, y, z)
};

/// Writes `surface` as JSON: format name and version, dimension, coordinate names, the
/// multi-index order, vertices, triangles and 10 control points per triangle.
/// \throw InvalidArgument if the patch count or dimensions disagree with the mesh or the file
///        cannot be written (the message names the path).
void write_bezier_patches(const std::string& path, const BezierSurfaceFile& surface);

/// Reads a file written by write_bezier_patches.
/// \throw InvalidArgument naming the path and the field if the file is malformed.
BezierSurfaceFile read_bezier_patches(const std::string& path);

}  // namespace tessera
