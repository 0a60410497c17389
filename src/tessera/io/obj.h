// SPDX-License-Identifier: MIT
// Wavefront OBJ reading and writing: three coordinates per vertex, triangles only.
#pragma once

#include <array>
#include <string>

#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

/// Writes "v" lines with three coordinates of each vertex and 1-based "f a b c" lines.
///
/// OBJ holds points of R^3 only, so a mesh in R^n is written as its projection onto the
/// coordinates `coordinates` (indices into 0..n-1, repeats allowed). For n < 3 an index >= n
/// writes 0, so that the default {0, 1, 2} puts a planar mesh into the plane z = 0.
/// Numbers use the shortest decimal form that reads back to the same double.
///
/// \throw InvalidArgument if an index is negative or (for n >= 3) >= n, if a triangle has an
///        index outside [0, vertex_count), or if the file cannot be written.
void write_obj(const std::string& path, const TriangleMesh& mesh,
               std::array<int, 3> coordinates = {0, 1, 2});

/// Reads "v" and "f" lines of an OBJ file into a mesh in R^3.
///
/// "v x y z" may carry more numbers (w, or colours), which are ignored. A face vertex may be
/// written a, a/t, a//n or a/t/n; only a is used. Indices are 1-based, a negative index counts
/// back from the last vertex defined so far (-1 is the last). A polygon with k > 3 vertices
/// becomes the fan (v0, v{i}, v{i+1}), i = 1..k-2, which keeps its orientation. Comments (#)
/// and all other statements (vt, vn, g, o, s, usemtl, mtllib, l, p, ...) are ignored.
///
/// \throw InvalidArgument naming the file and the line if it cannot be read, a number is
///        malformed, a face has fewer than 3 vertices, or an index is 0 or out of range.
TriangleMesh read_obj(const std::string& path);

}  // namespace tessera
