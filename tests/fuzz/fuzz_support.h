// SPDX-License-Identifier: MIT
// Shared by the libFuzzer targets: the one answer a reader may give to bytes it cannot read.
//
// A reader's contract is "a mesh (or problem, or data set) that keeps the documented promises, or
// InvalidArgument naming what is wrong". Any other exception, a crash, a hang or a sanitizer
// report is a bug; these helpers turn the first two into an abort that libFuzzer reports with
// the input that caused it. A new reader is one file (see ply_fuzz.cpp):
//
//     extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
//       return tessera::fuzzing::fuzz_mesh_reader(data, size, ".vtu", tessera::read_vtu);
//     }
//
// plus a seed corpus in corpus/<target>/ (target = file name without _fuzz.cpp).
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <typeinfo>

#include "tessera/core/error.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera::fuzzing {

/// Prints `what` and aborts: libFuzzer then saves the input as crash-<hash>.
[[noreturn]] inline void fail(const std::string& what) {
  std::fprintf(stderr, "tessera fuzz target: %s\n", what.c_str());
  std::abort();
}

/// Runs `parse()`. InvalidArgument is the documented rejection of bad input; any other exception
/// is a bug.
template <class Parse>
void expect_only_invalid_argument(Parse&& parse) {
  try {
    parse();
  } catch (const InvalidArgument&) {
  } catch (const std::exception& error) {
    fail(std::string("threw ") + typeid(error).name() +
         " instead of InvalidArgument: " + error.what());
  } catch (...) {
    fail("threw something that is not a std::exception");
  }
}

/// Writes `data` to a scratch file of this process whose name ends in `extension` and returns its
/// path: the mesh readers take paths. /dev/shm keeps the file in memory where it exists.
inline std::string write_scratch_file(const std::uint8_t* data, std::size_t size,
                                      const std::string& extension) {
  static const std::string path = std::string(access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp") +
                                  "/tessera_fuzz_" + std::to_string(getpid()) + extension;
  static const int removed_at_exit = std::atexit([] { std::remove(path.c_str()); });
  (void)removed_at_exit;
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr || (size > 0 && std::fwrite(data, 1, size, file) != size) ||
      std::fclose(file) != 0) {
    fail("cannot write the scratch file " + path);
  }
  return path;
}

/// The promises every mesh reader makes about a mesh it returns: a dimension when there are
/// points, and every triangle's indices in [0, vertex_count).
inline void check_mesh(const TriangleMesh& mesh) {
  if (mesh.vertex_count() > 0 && mesh.ambient_dimension() < 1) {
    fail("a mesh with vertices but dimension " + std::to_string(mesh.ambient_dimension()));
  }
  for (const Triangle& triangle : mesh.triangles()) {
    for (const int vertex : triangle) {
      if (vertex < 0 || vertex >= mesh.vertex_count()) {
        fail("triangle index " + std::to_string(vertex) + " outside [0, " +
             std::to_string(mesh.vertex_count()) + ")");
      }
    }
  }
}

/// The body of a mesh reader's fuzz target: `data` as a file named *`extension`, read by
/// `read(path)`, which returns a TriangleMesh or throws InvalidArgument.
template <class Read>
int fuzz_mesh_reader(const std::uint8_t* data, std::size_t size, const std::string& extension,
                     Read&& read) {
  const std::string path = write_scratch_file(data, size, extension);
  expect_only_invalid_argument([&] { check_mesh(read(path)); });
  return 0;
}

}  // namespace tessera::fuzzing
