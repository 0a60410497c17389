// SPDX-License-Identifier: MIT
// Regression tests for what the fuzz targets (tests/fuzz, docs/testing.md) found in the mesh and
// data readers: each test holds the input, reduced, that made a reader crash, hang or throw
// something other than InvalidArgument.
#include <gtest/gtest.h>

#include "io/io_test_support.h"
#include "tessera/io/obj.h"
#include "tessera/io/ply.h"

namespace tessera {
namespace {

using io_test::test_path;
using io_test::write_text;

// ply_fuzz: an element with no properties and a count near 2^63 made read_ply count through its
// empty records (a hang). Such an element has no data and is skipped.
TEST(PlyReaderFuzzFinding, ElementWithoutPropertiesAndHugeCountIsSkipped) {
  const std::string path = test_path("element_without_properties.ply");
  write_text(path,
             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
             "property float z\nelement junk 9000000000000000000\nelement face 1\n"
             "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const TriangleMesh mesh = read_ply(path);
  EXPECT_EQ(mesh.vertex_count(), 3);
  ASSERT_EQ(mesh.triangle_count(), 1);
  EXPECT_EQ(mesh.triangle(0), (Triangle{0, 1, 2}));
}

// obj_fuzz: the 1-based index 2147483648 (2^31) passed the index check as the 0-based INT_MAX,
// and the message that it is out of range overflowed int computing INT_MAX + 1.
TEST(ObjReaderFuzzFinding, IndexTwoToThe31IsOutOfRangeWithoutOverflow) {
  const std::string path = test_path("index_2_to_the_31.obj");
  write_text(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2147483648 3\n");
  io_test::expect_invalid_argument(
      [&] { read_obj(path); }, {"line 4", "vertex index 2147483648 is out of range", "3 vertices"});
}

}  // namespace
}  // namespace tessera
