// SPDX-License-Identifier: MIT
#include "tessera/methods/common/boundary_notches.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <vector>

#include "tessera/core/ambient_space.h"
#include "tessera/core/error.h"
#include "tessera/core/face_projection.h"
#include "tessera/core/linearization.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/geometry/mesh_validation.h"

namespace tessera {
namespace {

// Ears below this smallest angle are not added: a notch that needs them is left to the report.
constexpr double kMinAngle = 10.0 * std::numbers::pi / 180.0;
// Twice the projected area of the new triangle must exceed this times its longest edge squared.
constexpr double kMinAreaRatio = 1e-6;
// Each pass adds one triangle; a notch takes one to a few.
constexpr int kMaxPasses = 64;

// The corners' coordinates in the tangent plane at `origin` (T: n×2), this rank's parts of them
// on a split mesh (summed by the caller).
std::array<Eigen::Vector2d, 3> plane_coordinates(const Eigen::MatrixXd& T,
                                                 const Eigen::VectorXd& origin,
                                                 const std::array<Eigen::VectorXd, 3>& corners) {
  std::array<Eigen::Vector2d, 3> y;
  for (int k = 0; k < 3; ++k) {
    y[k] = T.transpose() * (corners[k] - origin);
  }
  return y;
}

double signed_area(const std::array<Eigen::Vector2d, 3>& y) {
  const Eigen::Vector2d u = y[1] - y[0];
  const Eigen::Vector2d w = y[2] - y[0];
  return u(0) * w(1) - u(1) * w(0);
}

struct Candidate {
  double new_edge = 0.0;
  int a = -1;
  int v = -1;
  int b = -1;
  int along_av = -1;  // the triangle on the boundary edge a→v
};

}  // namespace

NotchClosing close_boundary_notches(const ImplicitProblem& problem, const Domain& domain,
                                    TriangleMesh& mesh, double max_edge) {
  NotchClosing closing;
  if (domain.is_unbounded() || mesh.triangle_count() == 0) {
    return closing;
  }
  // A split mesh (SPMD): the points are this rank's rows, and each pass sums its distances and
  // lengths over the ranks at once, so that every rank picks the same notch.
  const std::shared_ptr<const AmbientSpace> shared_space = problem.space();
  const AmbientSpace& space = *shared_space;
  const bool split = space.is_distributed();
  if (split) {
    check_mesh_of_problem(mesh, problem, "close_boundary_notches");
    TESSERA_CHECK(domain.is_distributed(), "close_boundary_notches: problem '"
                                               << problem.name()
                                               << "' is distributed; so must the domain be "
                                                  "(Domain::distributed)");
  }
  const int faces = static_cast<int>(domain.half_spaces().size());
  const double on_face_tolerance = 1e-6 * (1.0 + max_edge);
  Linearization linearization;
  std::vector<std::array<int, 3>> refused;  // (a, v, b) tried and taken back
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    const MeshTopology topology(mesh);
    // Each boundary vertex's distances to the faces (its boundary_distance is the smallest) and
    // the squared length of the edge between its loop neighbours: one reduction per pass.
    const auto stride = static_cast<std::size_t>(faces + 1);
    std::vector<double> parts;
    for (int l = 0; l < topology.boundary_loop_count(); ++l) {
      const auto loop = topology.boundary_loop(l);
      const auto size = static_cast<int>(loop.size());
      for (int i = 0; i < size && size >= 4; ++i) {
        const auto v = mesh.point(loop[i]);
        for (int k = 0; k < faces; ++k) {
          parts.push_back(domain.partial_signed_distance(k, v));
        }
        parts.push_back(split ? (mesh.point(loop[(i + size - 1) % size]) -
                                 mesh.point(loop[(i + 1) % size]))
                                    .squaredNorm()
                              : 0.0);
      }
    }
    if (split && !parts.empty()) {
      space.sum(parts.data(), static_cast<int>(parts.size()));
    }
    std::size_t position = 0;  // of the current vertex's row in parts
    std::vector<Candidate> candidates;
    for (int l = 0; l < topology.boundary_loop_count(); ++l) {
      const auto loop = topology.boundary_loop(l);
      const auto size = static_cast<int>(loop.size());
      if (size < 4) {
        continue;
      }
      for (int i = 0; i < size; ++i, position += stride) {
        const int a = loop[(i + size - 1) % size];
        const int v = loop[i];
        const int b = loop[(i + 1) % size];
        // As Domain::boundary_distance: the smallest signed distance.
        double boundary_distance = std::numeric_limits<double>::infinity();
        for (int k = 0; k < faces; ++k) {
          boundary_distance = std::min(boundary_distance, parts[position + k]);
        }
        if (boundary_distance <= on_face_tolerance || topology.find_edge(a, b) >= 0 ||
            std::find(refused.begin(), refused.end(), std::array<int, 3>{a, v, b}) !=
                refused.end()) {
          continue;
        }
        const int e = topology.find_edge(a, v);
        if (e < 0 || !topology.is_boundary_edge(e)) {
          continue;
        }
        const double new_edge = split ? std::sqrt(parts[position + faces])
                                      : (mesh.point(a) - mesh.point(b)).norm();
        if (new_edge <= max_edge) {
          candidates.push_back({new_edge, a, v, b, topology.edge_triangles(e)[0]});
        }
      }
    }
    if (candidates.empty()) {
      break;
    }
    // The shortest new edge first: the tightest notch, the best-shaped ear.
    const Candidate& c = *std::min_element(
        candidates.begin(), candidates.end(),
        [](const Candidate& p, const Candidate& q) { return p.new_edge < q.new_edge; });
    const Eigen::VectorXd a = mesh.point(c.a);
    const Eigen::VectorXd v = mesh.point(c.v);
    const Eigen::VectorXd b = mesh.point(c.b);
    std::array<double, 3> sides{};  // |ab|, |bv|, |va|
    if (split) {
      sides = {(a - b).squaredNorm(), (b - v).squaredNorm(), (v - a).squaredNorm()};
      space.sum(sides.data(), 3);
      sides = {std::sqrt(sides[0]), std::sqrt(sides[1]), std::sqrt(sides[2])};
    } else {
      sides = {(a - b).norm(), (b - v).norm(), (v - a).norm()};
    }
    const auto [ab, bv, va] = sides;
    bool accepted = min_angle_of_sides(ab, bv, va) >= kMinAngle && linearization.factor(problem, v);
    if (accepted) {
      const Eigen::MatrixXd& T = linearization.tangent_basis();
      const Triangle& along = mesh.triangle(c.along_av);
      // Both triangles' corners in the tangent plane at v (one reduction on a split mesh).
      std::array<std::array<Eigen::Vector2d, 3>, 2> y = {
          plane_coordinates(T, v,
                            {mesh.point(along[0]), mesh.point(along[1]), mesh.point(along[2])}),
          plane_coordinates(T, v, {a, b, v})};
      if (split) {
        std::array<double, 12> coordinates{};
        for (int j = 0; j < 6; ++j) {
          coordinates[2 * j] = y[j / 3][j % 3](0);
          coordinates[2 * j + 1] = y[j / 3][j % 3](1);
        }
        space.sum(coordinates.data(), 12);
        for (int j = 0; j < 6; ++j) {
          y[j / 3][j % 3] = {coordinates[2 * j], coordinates[2 * j + 1]};
        }
      }
      const double existing = signed_area(y[0]);
      const double added = signed_area(y[1]);
      const double longest = std::max({ab, bv, va});
      accepted = existing * added > 0 && std::abs(added) > kMinAreaRatio * longest * longest;
    }
    if (accepted) {
      mesh.add_triangle(c.a, c.b, c.v);
      const std::array<int, 3> changed{c.a, c.b, c.v};
      if (!validate_around(mesh, changed).is_valid_but_unreferenced()) {
        std::vector<Triangle> triangles = mesh.triangles();
        triangles.pop_back();
        mesh.set_triangles(std::move(triangles));
        accepted = false;
      }
    }
    if (!accepted) {
      refused.push_back({c.a, c.v, c.b});
      continue;
    }
    ++closing.added_triangles;
  }
  return closing;
}

}  // namespace tessera
