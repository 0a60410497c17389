// SPDX-License-Identifier: MIT
// Method `atlas`: the failures of issue 10, each a regression test named after it. The atlas
// must complete with a valid mesh of the right topology at coarse tolerances too, where the
// radius the tolerance allows exceeds what M's curvature, its reach or the corrector allow;
// every mesh is also checked geometrically (no flipped triangle, no doubled patch).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "support/mesh_defects.h"
#include "support/test_support.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/methods/atlas/atlas.h"
#include "tessera/methods/atlas/atlas_triangulation.h"
#include "tessera/problems/catalogue.h"
#include "tessera/problems/problem_file.h"

namespace tessera {
namespace {

struct ReliabilityRun {
  ProblemSetup setup;
  CoveringResult result;
};

// The command line's defaults for the radius (2h) with the tolerance given.
ReliabilityRun run_atlas(ProblemSetup setup, double tolerance,
                         const Eigen::VectorXd* start = nullptr) {
  ReliabilityRun run;
  run.setup = std::move(setup);
  AtlasOptions options;
  options.step = 2.0 * run.setup.suggested_step;
  options.tolerance = tolerance;
  run.result = cover_by_atlas(*run.setup.problem, start ? *start : run.setup.start,
                              run.setup.domain, options);
  return run;
}

// Completed, valid, one component of the expected χ, and geometrically sound: no flipped
// triangle (with `interior_only`, none without a vertex on ∂S: the clipping at box corners is
// another method's code and still leaves some there, see issue 10) and no doubled patch.
void expect_complete_and_sound(const ReliabilityRun& run, const std::string& what,
                               bool interior_only = false) {
  const CoveringSummary& summary = run.result.summary;
  ASSERT_TRUE(summary.is_complete()) << what << ": " << summary.message;
  const MeshValidation validation = validate(run.result.mesh);
  ASSERT_TRUE(validation.is_valid()) << what << ": " << validation.report();
  EXPECT_EQ(validation.component_count, 1) << what;
  ASSERT_TRUE(run.setup.expected_euler_characteristic.has_value());
  EXPECT_EQ(validation.euler_characteristic, *run.setup.expected_euler_characteristic) << what;
  const TriangleMesh& mesh = run.result.mesh;
  const Domain& domain = run.setup.domain;
  const auto is_interior = [&](int t) {
    for (int v : mesh.triangle(t)) {
      if (!domain.is_unbounded() &&
          domain.boundary_distance(mesh.point(v)).signed_distance < 1e-9) {
        return false;
      }
    }
    return true;
  };
  EXPECT_EQ(testing::count_flipped_triangles(
                mesh, *run.setup.problem, [&](int t) { return !interior_only || is_interior(t); }),
            0)
      << what;
  if (!interior_only) {
    EXPECT_EQ(testing::count_overlapping_pairs(mesh), 0) << what;
  }
}

ProblemSetup thin_genus2() {
  return load_problem_file(testing::source_path("examples/problems/genus2_thin.tsr"));
}

TEST(AtlasReliability, CstrFromTheIssueStartAtTolerance0_01477DoesNotOverlapItself) {
  // Was: exit 1, a partial mesh with flipped triangles and doubled patches.
  Eigen::VectorXd start(4);
  start << 0.173424, 0.08, 0.115309, 4.30553;
  expect_complete_and_sound(run_atlas(make_catalogue_problem("cstr"), 0.01477, &start),
                            "cstr at 0.01477", /*interior_only=*/true);
}

TEST(AtlasReliability, CstrAtTolerance0_004HasNoDegenerateTriangle) {
  // Was: "degenerate triangle: 10", 49 flipped triangles and 176 overlapping pairs.
  expect_complete_and_sound(run_atlas(make_catalogue_problem("cstr"), 0.004), "cstr at 0.004",
                            /*interior_only=*/true);
}

TEST(AtlasReliability, ThinGenus2TubeCompletesAtCoarseTolerances) {
  // Half-thickness 0.07, largest curvature ≈ 57: every tolerance ≥ 0.006 used to fail (radii
  // measured at one scale and in one half of the disk missed the top of the tube).
  for (double tolerance : {0.006, 0.03}) {
    expect_complete_and_sound(run_atlas(thin_genus2(), tolerance),
                              "genus2_thin at " + std::to_string(tolerance));
  }
}

TEST(AtlasReliability, TroughCompletesAtCoarseTolerances) {
  // Its arch turns within ~0.03 of its flat part: charts of radius 0.06 from both sides used to
  // overlap across the gap without cutting each other (holes of 13–26 vertices).
  for (double tolerance : {0.01, 0.03}) {
    expect_complete_and_sound(run_atlas(make_catalogue_problem("trough"), tolerance),
                              "trough at " + std::to_string(tolerance));
  }
}

TEST(AtlasReliability, ThinTorusFillsStripsWhereNeighbouringPolygonsDisagree) {
  // A torus with R = 1, r = 0.07 (curvature 14): tangent planes of neighbouring charts differ by
  // about 20°, and the polygons of two rows of charts disagreed along strips of 12–52 charts,
  // once with an island triangle inside; holes of more than 12 charts were refused, so 21 of
  // the stress campaign's 25 runs failed ("a hole of 16 vertices … cannot be triangulated").
  struct Case {
    double step, tolerance;
    std::vector<double> start;  // empty: the file's start
  };
  const std::vector<Case> cases = {
      {0.035, 0.005, {}},  // a strip of 12 charts around an island triangle
      {0.016122049512421514, 0.0021275991980830872,  // the stress campaign's case 522: 52
       {1.0056139815490543, 0.10049439354202486, -0.064987244262022362}}};
  for (const Case& c : cases) {
    ReliabilityRun run;
    run.setup = load_problem_file(testing::source_path("tests/stress/problems/thin_torus.tsr"));
    Eigen::VectorXd start = run.setup.start;
    if (!c.start.empty()) {
      start = Eigen::Map<const Eigen::VectorXd>(c.start.data(), 3);
    }
    AtlasOptions options;
    options.step = c.step;
    options.tolerance = c.tolerance;
    run.result = cover_by_atlas(*run.setup.problem, start, run.setup.domain, options);
    expect_complete_and_sound(run, "thin torus at step " + std::to_string(c.step));
  }
}

TEST(AtlasReliability, Bratu2dBandCompletesAtCoarseSteps) {
  // bratu2d's lower sheet is a band 0.3 wide between ε = 0 and ε = 0.3. Charts of radius 0.6
  // spanned it and the atlas could not close one of them ("projection failed" after 16 000
  // charts, 21 s); the disks are now held to half the band's width there, and the summary
  // says how many.
  ReliabilityRun run;
  run.setup = make_catalogue_problem("bratu2d:N=10");
  AtlasOptions options;
  options.step = 0.6;
  options.tolerance = 0.3;
  run.result = cover_by_atlas(*run.setup.problem, run.setup.start, run.setup.domain, options);
  expect_complete_and_sound(run, "bratu2d:N=10 at step 0.6");
  // The counts are in every summary; the note only where they are a tenth of the charts or more
  // (issue 34), which tests/app/cli_test.cpp checks.
  EXPECT_GT(run.result.summary.radius_caps.band, 0);
}

TEST(AtlasReliability, Bratu2dChartsThatCannotReachTheirCornersAreShrunk) {
  // At steps of 0.7–1.0 on bratu2d a chart of the full radius near a fold or on the face ε = 0
  // could not be closed: its child either drifted beyond the disk (Gauss–Newton where the chord
  // failed) or, at the rim, landed on another sheet, and the same useless child came back until
  // the children bound stopped the run ("could not be closed": N = 10 at 0.8, a child 0.7503
  // from a chart of radius 0.7; N = 32 at 0.7, the same inner child 746 times). Such a chart
  // is now shrunk, as where pointOnDisk fails on its rim. (N = 32 is left to
  // bench/history/RESULTS-log.md section 10, tenth step: the geometric checks below cost 40 s
  // at n = 1026.)
  struct Case {
    int grid;
    double step;
  };
  // N = 20 at 0.8 also leaves a notch at the face λ = 0.5 whose closing edge is 1.29 long,
  // 4.6 boundary edges: notches are closed up to 5 (was 2) boundary edge lengths.
  for (const Case& c : {Case{10, 0.8}, Case{20, 0.8}}) {
    ReliabilityRun run;
    run.setup = make_catalogue_problem("bratu2d:N=" + std::to_string(c.grid));
    AtlasOptions options;
    options.step = c.step;
    options.tolerance = 0.3;
    run.result = cover_by_atlas(*run.setup.problem, run.setup.start, run.setup.domain, options);
    expect_complete_and_sound(
        run, "bratu2d:N=" + std::to_string(c.grid) + " at step " + std::to_string(c.step));
  }
}

TEST(AtlasReliability, CoarseRadiiAreCappedByTheCurvatureAndTheSummarySaysSo) {
  const ReliabilityRun run = run_atlas(thin_genus2(), 0.03);
  ASSERT_TRUE(run.result.summary.is_complete()) << run.result.summary.message;
  // sqrt(2ε/κ) at the top of the tube (κ ≈ 57) would be 0.032; the turning cap 0.5/κ ≈ 0.009.
  EXPECT_LT(run.result.summary.min_chart_radius, 0.012);
  EXPECT_GT(run.result.summary.radius_caps.curvature, 0);
}

TEST(AtlasReliability, DefectCountsFindAPlantedFlipAndADoubledPatch) {
  // The geometric checks above must be able to fail.
  const ReliabilityRun run = run_atlas(make_catalogue_problem("sphere"), 0.03);
  ASSERT_TRUE(run.result.summary.is_complete());
  const TriangleMesh& mesh = run.result.mesh;
  ASSERT_EQ(testing::count_flipped_triangles(mesh, *run.setup.problem), 0);
  ASSERT_EQ(testing::count_overlapping_pairs(mesh), 0);

  std::vector<Triangle> triangles = mesh.triangles();
  std::swap(triangles[0][1], triangles[0][2]);
  TriangleMesh flipped(mesh.ambient_dimension());
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    flipped.add_vertex(mesh.point(v));
  }
  flipped.set_triangles(triangles);
  EXPECT_EQ(testing::count_flipped_triangles(flipped, *run.setup.problem), 1);

  // A copy of one triangle on new vertices, moved slightly along M's normal.
  TriangleMesh doubled(mesh.ambient_dimension());
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    doubled.add_vertex(mesh.point(v));
  }
  std::vector<Triangle> with_copy = mesh.triangles();
  Triangle copy;
  for (int i = 0; i < 3; ++i) {
    copy[i] = doubled.add_vertex(1.001 * Eigen::VectorXd(mesh.point(mesh.triangle(0)[i])));
  }
  with_copy.push_back(copy);
  doubled.set_triangles(with_copy);
  EXPECT_GE(testing::count_overlapping_pairs(doubled), 1);
}

// whitney_pleat at tolerance 0.01062 left a hole in S: four nearly cocircular charts whose
// polygons each chose another diagonal proposed no triangle all of them agreed on, and the
// hole filler walked from that hole, through a second one at a chart never completed (just
// beyond the margin outside S), along the whole outer boundary of the atlas; that walk was
// longer than any hole and dropped, the first hole with it. Here on a planar grid of charts
// whose outer ring is open: hole B is a square at the open ring, hole A a square of closed
// charts touching B at one corner. A must be filled, B (an open chart's) left alone.
TEST(AtlasTriangulation, FillsAHoleOfClosedChartsThatTouchesTheOpenBoundaryOfTheAtlas) {
  constexpr int kSide = 16;  // the outer ring has 60 charts: longer than any hole
  constexpr double kRadius = 0.8;
  constexpr double kDelta = 0.01;
  // Chart numbers decide where the filler's walks start and which way they turn: the first
  // walk starts on A at (2, 2), reaches the shared chart (1, 2) and turns into B, then runs
  // along the whole ring before it comes back, as the walk on whitney_pleat did.
  std::vector<std::array<int, 2>> position = {{2, 2}, {1, 1}, {1, 2}, {1, 3}, {2, 3}};
  for (int x = 0; x < kSide; ++x) {
    for (int y = 0; y < kSide; ++y) {
      if (std::find(position.begin(), position.end(), std::array<int, 2>{x, y}) == position.end()) {
        position.push_back({x, y});
      }
    }
  }
  std::vector<int> number(kSide * kSide);
  for (int c = 0; c < kSide * kSide; ++c) {
    number[position[c][0] * kSide + position[c][1]] = c;
  }
  auto index = [&](int x, int y) { return number[x * kSide + y]; };
  // Squares by their lower left corner: A at (1, 2), B at (0, 1); they share the chart (1, 2).
  auto is_hole = [](int x, int y) { return (x == 1 && y == 2) || (x == 0 && y == 1); };
  std::vector<ChartPolygon> polygons(kSide * kSide);
  std::vector<bool> closed(kSide * kSide, false);
  for (int x = 0; x < kSide; ++x) {
    for (int y = 0; y < kSide; ++y) {
      ChartPolygon& polygon = polygons[index(x, y)];
      polygon = ChartPolygon(1.2 * kRadius);
      for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy) {
          if ((dx == 0 && dy == 0) || x + dx < 0 || x + dx >= kSide || y + dy < 0 ||
              y + dy >= kSide) {
            continue;
          }
          const double length = std::hypot(dx, dy);
          double offset = 0.5 * length;
          if (dx != 0 && dy != 0) {
            // A diagonal neighbour: its bisector passes through the square's corner. Charts
            // agree on the diagonal (x, y)–(x+1, y+1) except in a hole, where every chart sees
            // its diagonal neighbour a little nearer, so neighbours disagree.
            const bool hole = is_hole(std::min(x, x + dx), std::min(y, y + dy));
            offset += (hole || dx == dy) ? -kDelta : kDelta;
          }
          polygon.cut(dx / length, dy / length, offset, index(x + dx, y + dy));
        }
      }
      closed[index(x, y)] =
          polygon.farthest_exterior_vertex(kRadius) < 0 &&
          std::none_of(polygon.vertices().begin(), polygon.vertices().end(),
                       [](const auto& v) { return v.edge_label == ChartPolygon::kNoNeighbour; });
    }
  }
  ASSERT_FALSE(closed[index(0, 1)]);
  ASSERT_TRUE(closed[index(1, 2)] && closed[index(2, 2)] && closed[index(1, 3)] &&
              closed[index(2, 3)]);
  AtlasCells cells;
  cells.ambient_dimension = 3;
  cells.chart_count = kSide * kSide;
  cells.center = [&](int c) {
    return Eigen::VectorXd(Eigen::Vector3d(position[c][0], position[c][1], 0));
  };
  cells.tangent = [](int) { return Eigen::MatrixXd(Eigen::MatrixXd::Identity(3, 2)); };
  cells.polygon = [&](int c) -> const ChartPolygon& { return polygons[c]; };
  cells.radius = [](int) { return kRadius; };
  cells.is_closed = [&](int c) { return closed[c]; };
  const AtlasTriangulation triangulation = triangulate_atlas(cells);
  EXPECT_TRUE(triangulation.message.empty()) << triangulation.message;
  // Triangles with all three vertices in a square, found by position (z = 0, integer x, y).
  auto triangles_in = [&](int x, int y) {
    int count = 0;
    for (const Triangle& t : triangulation.mesh.triangles()) {
      bool inside = true;
      for (int v : t) {
        const Eigen::VectorXd& p = triangulation.mesh.point(v);
        inside = inside && (p(0) == x || p(0) == x + 1) && (p(1) == y || p(1) == y + 1);
      }
      count += inside ? 1 : 0;
    }
    return count;
  };
  EXPECT_EQ(triangles_in(1, 2), 2);  // hole A, filled
  EXPECT_EQ(triangles_in(0, 1), 0);  // hole B, at the open ring: no triangle agreed on, none made
  EXPECT_EQ(triangles_in(5, 5), 2);  // an ordinary square
  EXPECT_EQ(triangulation.filled_holes, 1);
}

}  // namespace
}  // namespace tessera
