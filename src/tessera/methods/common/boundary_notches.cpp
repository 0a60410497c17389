// SPDX-License-Identifier: MIT
#include "tessera/methods/common/boundary_notches.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

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

double signed_area(const Eigen::MatrixXd& T, const Eigen::VectorXd& origin,
                   const std::array<Eigen::VectorXd, 3>& corners) {
  std::array<Eigen::Vector2d, 3> y;
  for (int k = 0; k < 3; ++k) {
    y[k] = T.transpose() * (corners[k] - origin);
  }
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
  const double on_face_tolerance = 1e-6 * (1.0 + max_edge);
  Linearization linearization;
  std::vector<std::array<int, 3>> refused;  // (a, v, b) tried and taken back
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    const MeshTopology topology(mesh);
    std::vector<Candidate> candidates;
    for (int l = 0; l < topology.boundary_loop_count(); ++l) {
      const auto loop = topology.boundary_loop(l);
      const auto size = static_cast<int>(loop.size());
      if (size < 4) {
        continue;
      }
      for (int i = 0; i < size; ++i) {
        const int a = loop[(i + size - 1) % size];
        const int v = loop[i];
        const int b = loop[(i + 1) % size];
        if (domain.boundary_distance(mesh.point(v)).signed_distance <= on_face_tolerance ||
            topology.find_edge(a, b) >= 0 ||
            std::find(refused.begin(), refused.end(), std::array<int, 3>{a, v, b}) !=
                refused.end()) {
          continue;
        }
        const int e = topology.find_edge(a, v);
        if (e < 0 || !topology.is_boundary_edge(e)) {
          continue;
        }
        const double new_edge = (mesh.point(a) - mesh.point(b)).norm();
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
    const double ab = (a - b).norm();
    const double bv = (b - v).norm();
    const double va = (v - a).norm();
    bool accepted = min_angle_of_sides(ab, bv, va) >= kMinAngle && linearization.factor(problem, v);
    if (accepted) {
      const Eigen::MatrixXd& T = linearization.tangent_basis();
      const Triangle& along = mesh.triangle(c.along_av);
      const double existing =
          signed_area(T, v, {mesh.point(along[0]), mesh.point(along[1]), mesh.point(along[2])});
      const double added = signed_area(T, v, {a, b, v});
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
