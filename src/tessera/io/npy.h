// SPDX-License-Identifier: MIT
// NumPy .npy files: the vertices (the states, points of R^n) and the triangles of a mesh as arrays
// that Python reads with numpy.load, at any n; and the same files read back.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "tessera/geometry/triangle_mesh.h"

namespace tessera {

/// Writes N points of R^n as a NumPy array file of shape (N, n): row j is point j, bit for bit.
///
/// The format is NPY version 1.0 (numpy.lib.format): the magic "\x93NUMPY", version 1.0, a 16-bit
/// little-endian header length, the header dictionary {'descr': '<f8', 'fortran_order': False,
/// 'shape': (N, n), } padded with spaces and ended by '\n' so that the data starts at a multiple
/// of 64 bytes, then the N·n little-endian doubles in C order. An n×N matrix of points (columns,
/// as TriangleMesh::points()) has the memory of a C-order (N, n) array, so the data is the
/// matrix's memory as it is. Python: `X = numpy.load(path)` (or `numpy.load(path,
/// mmap_mode="r")` to map a large file instead of reading it). The file is replaced atomically
/// (io_detail::OutputFile): a failed write leaves the previous file.
///
/// \param points  n×N, one point per column.
/// \throw InvalidArgument naming the file if it cannot be written.
void write_npy(const std::string& path, const Eigen::Ref<const Eigen::MatrixXd>& points);

/// Writes T triangles as a NumPy array file of shape (T, 3), dtype '<i8' (little-endian 64-bit
/// integers), C order: row t holds the vertex indices of triangle t (from 0, in the triangle's
/// orientation). Same format and atomic replacement as write_npy for points.
/// \throw InvalidArgument naming the file if it cannot be written.
void write_npy(const std::string& path, const std::vector<Triangle>& triangles);

/// Where write_states_npy puts the triangles: "S.triangles.npy" for a path "S.npy", else the
/// path with ".triangles.npy" appended.
std::string triangles_npy_path(const std::string& states_path);

/// Writes a mesh as two NumPy files: its vertices (the states, shape (V, n), '<f8') to `path`
/// and its triangles (shape (T, 3), '<i8') to triangles_npy_path(path).
///
/// Each file is replaced atomically; the pair is not: a run killed between the two leaves the
/// new states beside the previous triangles (the triangles are written first, so a completed
/// states file always has its triangles).
///
/// A split mesh (mesh.space().is_distributed(), docs/cluster.md) is written collectively, as
/// write_split_states_npy does: the same bytes as one process writes for the whole mesh.
///
/// \throw InvalidArgument if a triangle has an index outside [0, V) (nothing is written), or
///        naming the file that cannot be written.
void write_states_npy(const std::string& path, const TriangleMesh& mesh);

/// The n-vectors gathered to rank 0 at a time by write_split_states_npy: 4 MB (at least one
/// vertex), so that rank 0 never holds more than this of the states.
constexpr std::size_t kStatesGatherBytes = std::size_t{4} << 20;

/// write_states_npy of a split mesh, streaming: rank 0 writes the header, then gathers the
/// ranks' rows of `gather_bytes` of vertices at a time (AmbientSpace::gather_to_root) and
/// writes them, so that it never holds every vertex's n-vector. Collective: every rank calls
/// it; only rank 0 touches files, and if it fails every rank throws (rank 0 its own error).
/// The bytes are those write_states_npy writes for the whole mesh in one process. In one
/// process it is write_states_npy.
/// \throw InvalidArgument as write_states_npy.
void write_split_states_npy(const std::string& path, const TriangleMesh& mesh,
                            std::size_t gather_bytes = kStatesGatherBytes);

/// Reads what write_states_npy writes, as a mesh in R^n: the points from `path` and the
/// triangles from triangles_npy_path(path), both written by tessera or by NumPy (numpy.save).
///
/// The points must be a 2-d array (V, n), n ≥ 1, of floating-point numbers ('f4' or 'f8'); the
/// triangles a 2-d array (T, 3) of integers ('i1' … 'i8', 'u1' … 'u8') in [0, V). Either byte
/// order, C or Fortran order, format versions 1.0, 2.0 and 3.0 are read. The whole files are read
/// into memory (the points twice over for a moment: as bytes and as the mesh).
///
/// \throw InvalidArgument "NumPy file '<path>': <what is wrong>" if a file is missing, is not an
///        .npy file, has another shape or type, is truncated or longer than its shape, or a
///        triangle index is outside [0, V). Sizes are checked against the file before anything
///        is allocated.
TriangleMesh read_states_npy(const std::string& path);

}  // namespace tessera
