// SPDX-License-Identifier: MIT
// Output paths: what kind of tessera file a path holds, and the refusal to replace one of another
// kind (issue 34: `--patches torus.json` silently replaced the summary `torus.json` of an earlier
// run, and the docs' later `json.load(...)["states"]` ended in a KeyError).
#include "tessera/io/output_checks.h"

#include <gtest/gtest.h>

#include "io/io_test_support.h"
#include "tessera/io/bezier_patches.h"
#include "tessera/io/mesh_io.h"
#include "tessera/io/polylines.h"

namespace tessera {
namespace {

using namespace io_test;

std::vector<Polyline> one_curve() {
  Polyline line;
  line.points = Eigen::MatrixXd::Random(3, 4);
  return {line};
}

TEST(OutputChecks, TellsTheKindOfEveryFileTesseraWrites) {
  const auto mesh = random_mesh(3, 20, 20);
  for (const std::string extension : {".ply", ".vtk", ".vtu"}) {
    SCOPED_TRACE(extension);
    write_mesh(test_path("kind_mesh" + extension), mesh);
    EXPECT_EQ(tessera_file_kind(test_path("kind_mesh" + extension)), TesseraFileKind::Mesh);
    write_polylines(test_path("kind_curves" + extension), one_curve(),
                    {.names = {"a", "b", "c"}, .kind = "fold"});
    EXPECT_EQ(tessera_file_kind(test_path("kind_curves" + extension)), TesseraFileKind::Curves);
  }
  write_mesh(test_path("kind_ascii.ply"), mesh, {.binary = false});
  EXPECT_EQ(tessera_file_kind(test_path("kind_ascii.ply")), TesseraFileKind::Mesh);
  write_polylines(test_path("kind_curves.json"), one_curve(), {.names = {"a", "b", "c"}});
  EXPECT_EQ(tessera_file_kind(test_path("kind_curves.json")), TesseraFileKind::Curves);

  write_text(test_path("kind_summary.json"),
             R"({"ambient_dimension": 3, "problem": "torus", "topology": {"euler": 0}})");
  EXPECT_EQ(tessera_file_kind(test_path("kind_summary.json")), TesseraFileKind::MeshSummary);
  write_text(test_path("kind_improve.json"),
             R"({"before": {}, "criterion": "angle", "mesh": "m.ply", "problem": "sphere",
                 "swaps": 3})");
  EXPECT_EQ(tessera_file_kind(test_path("kind_improve.json")), TesseraFileKind::ImproveSummary);

  BezierSurfaceFile patches;
  patches.mesh = TriangleMesh(3);
  patches.coordinate_names = {"x", "y", "z"};
  write_bezier_patches(test_path("kind_patches.json"), patches);
  EXPECT_EQ(tessera_file_kind(test_path("kind_patches.json")), TesseraFileKind::BezierPatches);

  // Not tessera's, or no file: free to write.
  write_text(test_path("kind_other.json"), R"({"name": "mine"})");
  write_text(test_path("kind_broken.json"), "{\"problem\": ");
  write_text(test_path("kind_other.ply"), "ply\nformat ascii 1.0\nelement vertex 0\nend_header\n");
  for (const std::string name :
       {"kind_other.json", "kind_broken.json", "kind_other.ply", "kind_no_such_file.json"}) {
    EXPECT_EQ(tessera_file_kind(test_path(name)), TesseraFileKind::None) << name;
  }
}

TEST(OutputChecks, RefusesToReplaceATesseraFileOfAnotherKindOnly) {
  const std::string summary = test_path("torus.json");
  write_text(summary, R"({"ambient_dimension": 3, "problem": "torus"})");
  // The same kind again (an earlier run's summary): replaced as usual.
  EXPECT_NO_THROW(check_replaces_same_kind("--summary", summary, TesseraFileKind::MeshSummary));
  // Another kind: refused, saying what the file holds and a name that would not collide.
  expect_invalid_argument(
      [&] { check_replaces_same_kind("--patches", summary, TesseraFileKind::BezierPatches); },
      {"--patches " + summary, "holds the JSON summary of a `tessera mesh` run",
       "would replace with Bezier patches", test_path("torus.patches.json")});
  const std::string mesh = test_path("replace_mesh.ply");
  write_mesh(mesh, random_mesh(3, 10, 10));
  expect_invalid_argument(
      [&] { check_replaces_same_kind("--folds-output", mesh, TesseraFileKind::Curves); },
      {"holds a mesh of tessera", "replace_mesh.curves.ply"});
  // Files of other tools, and no file, are no concern of this check.
  write_text(test_path("mine.json"), R"({"name": "mine"})");
  EXPECT_NO_THROW(check_replaces_same_kind("--patches", test_path("mine.json"),
                                           TesseraFileKind::BezierPatches));
  EXPECT_NO_THROW(check_replaces_same_kind("--patches", "", TesseraFileKind::BezierPatches));
}

}  // namespace
}  // namespace tessera
