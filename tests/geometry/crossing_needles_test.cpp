// SPDX-License-Identifier: MIT
// validate() with a problem finds triangles that cross on M without sharing an edge, however thin:
// needles (smallest angle well below 1°) crossing at several sizes, crossing angles and places,
// on a plane, a sphere and a torus in R^4 (issue 33: two needles of a `bezier` mesh crossed on a
// genus-2 surface and the validation called the mesh valid).
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "tessera/core/domain.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/problems/catalogue.h"
#include "tessera/problems/examples.h"

namespace tessera {
namespace {

struct NeedleCase {
  double length;         // of the needle's long edges
  double apex_degrees;   // its smallest angle
  double cross_degrees;  // the angle between the two needles' axes
  double shift;          // where the second needle's axis crosses the first, as a fraction of
                         // its length from its middle (0: middle, 0.4: near its base, -0.4:
                         // near its apex)
};

std::string name_of(const NeedleCase& c) {
  std::ostringstream out;
  out << "length " << c.length << ", apex " << c.apex_degrees << "°, crossing at "
      << c.cross_degrees << "°, shift " << c.shift;
  return out.str();
}

// A needle in the tangent plane at the origin of the (u, v) chart: apex at −L/2 along the axis
// d, base at +L/2 with half-width L/2·tan(apex/2), shifted by `shift`·L along d.
std::vector<Eigen::Vector2d> needle(double length, double apex_degrees, double axis_degrees,
                                    double shift) {
  const double a = axis_degrees * std::numbers::pi / 180.0;
  const Eigen::Vector2d d(std::cos(a), std::sin(a));
  const Eigen::Vector2d normal(-d.y(), d.x());
  const double half_width = length * std::tan(apex_degrees * std::numbers::pi / 360.0);
  const Eigen::Vector2d offset = -shift * length * d;
  return {offset - 0.5 * length * d, offset + 0.5 * length * d - half_width * normal,
          offset + 0.5 * length * d + half_width * normal};
}

// Two needles crossing at the chart's origin, each its own component; `lift` puts a chart point
// onto M.
template <typename Lift>
TriangleMesh crossing_needles(const NeedleCase& c, int n, Lift lift) {
  std::vector<Eigen::Vector2d> corners = needle(c.length, c.apex_degrees, 0.0, 0.0);
  const std::vector<Eigen::Vector2d> second =
      needle(c.length, c.apex_degrees, c.cross_degrees, c.shift);
  corners.insert(corners.end(), second.begin(), second.end());
  Eigen::MatrixXd points(n, 6);
  for (int k = 0; k < 6; ++k) {
    points.col(k) = lift(corners[static_cast<std::size_t>(k)]);
  }
  return TriangleMesh(points, {{0, 1, 2}, {3, 4, 5}});
}

// The test on M resolves an overlap whose width exceeds the distortion of the chart it is
// judged in, (chord errors)·κ·(its reach), about κ²L²/4 · w/(2 sin θ) for needles of length L
// and width w crossing at θ (docs/validation.md): at κL = 0.3 (length 0.3 on the unit sphere,
// a coarser mesh than any method leaves after refinement) from θ ≈ 6°, at κL ≤ 0.09 from θ ≈ 1°.
std::vector<NeedleCase> needle_cases() {
  std::vector<NeedleCase> cases;
  for (double length : {0.3, 0.09, 0.01}) {
    for (double apex : {2.0, 0.5, 0.25, 0.1}) {
      for (double cross : {90.0, 30.0, length > 0.1 ? 10.0 : 3.0}) {
        for (double shift : {0.0, 0.4, -0.4}) {
          cases.push_back({length, apex, cross, shift});
        }
      }
    }
  }
  return cases;
}

void expect_crossing_found(const TriangleMesh& mesh, const ImplicitProblem& problem,
                           const NeedleCase& c) {
  ASSERT_TRUE(validate(mesh).is_valid()) << "two disjoint needles are combinatorially valid";
  const MeshValidation validation = validate(mesh, problem, Domain());
  EXPECT_EQ(validation.overlapping_pair_count, 1) << name_of(c) << "\n" << validation.report();
  EXPECT_EQ(validation.flipped_triangle_count, 0) << name_of(c) << "\n" << validation.report();
}

TEST(CrossingNeedles, AreFoundOnAPlane) {
  const Plane plane;
  for (const NeedleCase& c : needle_cases()) {
    expect_crossing_found(crossing_needles(c, 3,
                                           [](const Eigen::Vector2d& uv) {
                                             return Eigen::Vector3d(0.3 + uv.x(), -0.2 + uv.y(),
                                                                    0.0);
                                           }),
                          plane, c);
  }
}

TEST(CrossingNeedles, AreFoundOnASphere) {
  const Sphere sphere(1.0);
  // Chart at a point off the axes: the needles' vertices are the chart points pushed radially.
  const Eigen::Vector3d centre = Eigen::Vector3d(1, 2, 2).normalized();
  const Eigen::Vector3d e1 = centre.unitOrthogonal();
  const Eigen::Vector3d e2 = centre.cross(e1);
  for (const NeedleCase& c : needle_cases()) {
    expect_crossing_found(crossing_needles(c, 3,
                                           [&](const Eigen::Vector2d& uv) {
                                             return Eigen::Vector3d(
                                                 (centre + uv.x() * e1 + uv.y() * e2).normalized());
                                           }),
                          sphere, c);
  }
}

TEST(CrossingNeedles, AreFoundOnATorusInR4) {
  const ProblemSetup torus = make_catalogue_problem("flat_torus");
  for (const NeedleCase& c : needle_cases()) {
    expect_crossing_found(crossing_needles(c, 4,
                                           [](const Eigen::Vector2d& uv) {
                                             const double a = 0.4 + uv.x(), b = 1.1 + uv.y();
                                             return Eigen::Vector4d(std::cos(a), std::sin(a),
                                                                    std::cos(b), std::sin(b));
                                           }),
                          *torus.problem, c);
  }
}

}  // namespace
}  // namespace tessera
