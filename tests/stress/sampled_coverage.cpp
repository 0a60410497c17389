// SPDX-License-Identifier: MIT
#include "stress/sampled_coverage.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "tessera/core/describe.h"
#include "tessera/core/linearization.h"
#include "tessera/geometry/mesh_quality.h"

namespace tessera::testing {
namespace {

// Triangles by the cells of a uniform grid over the three coordinates of largest extent (for
// n > 3: cstr's B spans 11 where x1 spans 1; hashing x1..x3 put whole rows of B in one cell)
// that their box, enlarged by a quarter of their longest edge (more than their chord error),
// overlaps: a point of M that a triangle's normal projection covers lies in one of them.
class TriangleGrid {
 public:
  TriangleGrid(const TriangleMesh& mesh, double cell) : cell_(cell) {
    const int dims = std::min(3, mesh.ambient_dimension());
    const Eigen::VectorXd extent =
        mesh.points().rowwise().maxCoeff() - mesh.points().rowwise().minCoeff();
    std::vector<int> order(static_cast<std::size_t>(mesh.ambient_dimension()));
    for (std::size_t i = 0; i < order.size(); ++i) {
      order[i] = static_cast<int>(i);
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return extent[a] > extent[b]; });
    for (int d = 0; d < dims; ++d) {
      axis_[d] = order[static_cast<std::size_t>(d)];
    }
    for (int t = 0; t < mesh.triangle_count(); ++t) {
      const Triangle& tri = mesh.triangle(t);
      double longest = 0.0;
      for (int k = 0; k < 3; ++k) {
        longest = std::max(longest, (mesh.point(tri[(k + 1) % 3]) - mesh.point(tri[k])).norm());
      }
      std::array<long, 3> low{0, 0, 0}, high{0, 0, 0};
      for (int d = 0; d < dims; ++d) {
        const int a = axis_[d];
        const double lo =
            std::min({mesh.point(tri[0])[a], mesh.point(tri[1])[a], mesh.point(tri[2])[a]}) -
            0.25 * longest;
        const double hi =
            std::max({mesh.point(tri[0])[a], mesh.point(tri[1])[a], mesh.point(tri[2])[a]}) +
            0.25 * longest;
        low[d] = std::lround(std::floor(lo / cell_));
        high[d] = std::lround(std::floor(hi / cell_));
      }
      for (long i = low[0]; i <= high[0]; ++i) {
        for (long j = low[1]; j <= high[1]; ++j) {
          for (long k = low[2]; k <= high[2]; ++k) {
            cells_[key(i, j, k)].push_back(t);
          }
        }
      }
    }
    dims_ = dims;
  }

  const std::vector<int>& near(const Eigen::VectorXd& x) const {
    std::array<long, 3> c{0, 0, 0};
    for (int d = 0; d < dims_; ++d) {
      c[d] = std::lround(std::floor(x[axis_[d]] / cell_));
    }
    const auto it = cells_.find(key(c[0], c[1], c[2]));
    return it == cells_.end() ? empty_ : it->second;
  }

 private:
  static std::uint64_t key(long i, long j, long k) {
    const auto part = [](long v) { return static_cast<std::uint64_t>(v + (1L << 20)) & 0x1fffff; };
    return part(i) << 42 | part(j) << 21 | part(k);
  }
  double cell_;
  int dims_ = 3;
  std::array<int, 3> axis_{0, 1, 2};  // the coordinates hashed
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
  std::vector<int> empty_;
};

// Where the normal space of M at m (tangent basis T) meets the plane of triangle t, in its
// barycentric coordinates, and that point; false if the plane stands across M there.
bool normal_meets(const TriangleMesh& mesh, int t, const Eigen::VectorXd& m,
                  const Eigen::MatrixXd& T, Eigen::Vector3d& barycentric, Eigen::VectorXd& q) {
  const Triangle& tri = mesh.triangle(t);
  const Eigen::VectorXd a = mesh.point(tri[0]);
  Eigen::MatrixXd E(a.size(), 2);
  E.col(0) = mesh.point(tri[1]) - a;
  E.col(1) = mesh.point(tri[2]) - a;
  const Eigen::Matrix2d TE = T.transpose() * E;
  if (std::abs(TE.determinant()) <= 1e-12 * E.col(0).squaredNorm() * E.col(1).squaredNorm()) {
    return false;
  }
  const Eigen::Vector2d w = TE.inverse() * (T.transpose() * (m - a));
  barycentric = {1.0 - w.x() - w.y(), w.x(), w.y()};
  q = a + E * w;
  return true;
}

double segment_distance(const Eigen::VectorXd& x, const Eigen::VectorXd& a,
                        const Eigen::VectorXd& b) {
  const Eigen::VectorXd d = b - a;
  const double s = std::clamp((x - a).dot(d) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
  return (a + s * d - x).norm();
}

// The distance from x to triangle t in R^n.
double triangle_distance(const TriangleMesh& mesh, int t, const Eigen::VectorXd& x) {
  const Triangle& tri = mesh.triangle(t);
  const Eigen::VectorXd a = mesh.point(tri[0]);
  Eigen::MatrixXd E(a.size(), 2);
  E.col(0) = mesh.point(tri[1]) - a;
  E.col(1) = mesh.point(tri[2]) - a;
  const Eigen::Matrix2d gram = E.transpose() * E;
  if (std::abs(gram.determinant()) > 1e-14 * gram.trace() * gram.trace()) {
    const Eigen::Vector2d w = gram.inverse() * (E.transpose() * (x - a));
    if (w.x() >= 0 && w.y() >= 0 && w.x() + w.y() <= 1) {
      return (a + E * w - x).norm();
    }
  }
  return std::min({segment_distance(x, a, mesh.point(tri[1])),
                   segment_distance(x, mesh.point(tri[1]), mesh.point(tri[2])),
                   segment_distance(x, mesh.point(tri[2]), a)});
}

// Is P(q) the point m again (the same sheet of M), and not a sheet |q − m| away?
bool same_sheet(const ImplicitProblem& problem, const Eigen::VectorXd& m, const Eigen::VectorXd& q,
                Linearization& workspace) {
  Eigen::VectorXd back = q;
  if (!project_onto_manifold(problem, back, workspace)) {
    return false;
  }
  return (back - m).norm() <= 0.25 * (q - m).norm() + 1e-9 * (1.0 + m.lpNorm<Eigen::Infinity>());
}

}  // namespace

SampledCoverage sample_coverage(const TriangleMesh& mesh, const ImplicitProblem& problem,
                                const Domain& domain, double gap, int random_points,
                                std::uint64_t seed, const ExactDistance& exact_distance) {
  SampledCoverage found;
  const int count = mesh.triangle_count();
  if (count == 0) {
    return found;
  }
  std::vector<double> edges;
  double longest = 0.0;
  for (int t = 0; t < count; ++t) {
    const Triangle& tri = mesh.triangle(t);
    for (int k = 0; k < 3; ++k) {
      const Eigen::VectorXd u = mesh.point(tri[(k + 1) % 3]) - mesh.point(tri[k]);
      const Eigen::VectorXd w = mesh.point(tri[(k + 2) % 3]) - mesh.point(tri[k]);
      const double cross =
          std::sqrt(std::max(0.0, u.squaredNorm() * w.squaredNorm() - u.dot(w) * u.dot(w)));
      found.min_angle_degrees =
          std::min(found.min_angle_degrees, std::atan2(cross, u.dot(w)) * 180.0 / std::numbers::pi);
      edges.push_back(u.norm());
      longest = std::max(longest, u.norm());
    }
  }
  std::nth_element(edges.begin(), edges.begin() + edges.size() / 2, edges.end());
  const TriangleGrid grid(mesh, 2.0 * edges[edges.size() / 2]);
  Linearization workspace;
  Linearization back;
  // 1. Ten points of every triangle: their distance to M, and (the seven inside it) whether
  //    another triangle lies over the same point of M.
  const std::array<Eigen::Vector3d, 10> points = {
      Eigen::Vector3d(1, 1, 1) / 3,     Eigen::Vector3d(0.8, 0.1, 0.1),
      Eigen::Vector3d(0.1, 0.8, 0.1),   Eigen::Vector3d(0.1, 0.1, 0.8),
      Eigen::Vector3d(0.5, 0.25, 0.25), Eigen::Vector3d(0.25, 0.5, 0.25),
      Eigen::Vector3d(0.25, 0.25, 0.5), Eigen::Vector3d(0.5, 0.5, 0),
      Eigen::Vector3d(0, 0.5, 0.5),     Eigen::Vector3d(0.5, 0, 0.5)};
  Eigen::Vector3d barycentric;
  Eigen::VectorXd q;
  for (int t = 0; t < count; ++t) {
    const Triangle& tri = mesh.triangle(t);
    for (std::size_t j = 0; j < points.size(); ++j) {
      const Eigen::VectorXd x = points[j][0] * mesh.point(tri[0]) +
                                points[j][1] * mesh.point(tri[1]) +
                                points[j][2] * mesh.point(tri[2]);
      Eigen::VectorXd m = x;
      if (!project_onto_manifold(problem, m, workspace) || !workspace.is_factored()) {
        continue;
      }
      found.max_distance =
          std::max(found.max_distance, exact_distance ? exact_distance(x) : (m - x).norm());
      if (j >= 7) {
        continue;  // on an edge: both its triangles cover it
      }
      const Eigen::MatrixXd T = workspace.tangent_basis();
      for (int s : grid.near(m)) {
        // Next to an edge that t and s share, the normal projections of two flat triangles
        // overlap in a sliver where M curves across the edge (a chord's artefact of about
        // κ·h·(chord error), seen at barycentric 1e-3 on the thin torus at a coarse
        // tolerance); a fold over that edge reaches far into s. Elsewhere any inside counts.
        int shared = 0;
        for (int v : mesh.triangle(s)) {
          shared += (v == tri[0] || v == tri[1] || v == tri[2]) ? 1 : 0;
        }
        const double inside = shared == 2 ? 0.05 : 1e-6;
        if (s == t || !normal_meets(mesh, s, m, T, barycentric, q) ||
            barycentric.minCoeff() <= inside || !same_sheet(problem, m, q, back)) {
          continue;
        }
        if (found.doubly_covered++ == 0) {
          std::ostringstream out;
          out.precision(4);
          out << "M at " << describe_point(m) << " lies under triangle " << t << " and inside "
              << "triangle " << s << " (smallest barycentric " << barycentric.minCoeff() << ")";
          found.example = out.str();
        }
        break;
      }
    }
  }
  // 2. Random points of M ∩ S near the mesh: covered by a triangle, or within `gap` of one.
  if (gap > 0 && random_points > 0) {
    Eigen::VectorXd low = mesh.points().rowwise().minCoeff();
    Eigen::VectorXd high = mesh.points().rowwise().maxCoeff();
    const Eigen::VectorXd margin = Eigen::VectorXd::Constant(low.size(), longest);
    low -= margin;
    high += margin;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int i = 0; i < random_points; ++i) {
      Eigen::VectorXd m(low.size());
      for (int d = 0; d < m.size(); ++d) {
        m[d] = low[d] + unit(rng) * (high[d] - low[d]);
      }
      if (!project_onto_manifold(problem, m, workspace) || !workspace.is_factored() ||
          !domain.contains(m, 1e-9 * (1.0 + m.lpNorm<Eigen::Infinity>()))) {
        continue;
      }
      const std::vector<int>& near = grid.near(m);
      double nearest = std::numeric_limits<double>::infinity();
      for (int s : near) {
        nearest = std::min(nearest, triangle_distance(mesh, s, m));
      }
      if (!(nearest <= 3.0 * longest)) {
        continue;  // far from the mesh: another part of M, not judged
      }
      ++found.random_samples;
      if (nearest <= gap) {
        continue;
      }
      const Eigen::MatrixXd T = workspace.tangent_basis();
      bool covered = false;
      for (int s : near) {
        covered = covered || (normal_meets(mesh, s, m, T, barycentric, q) &&
                              barycentric.minCoeff() >= -1e-6 && same_sheet(problem, m, q, back));
      }
      if (covered) {
        continue;
      }
      ++found.uncovered;
      if (nearest > found.uncovered_distance) {
        found.uncovered_distance = nearest;
        if (found.doubly_covered == 0) {
          std::ostringstream out;
          out.precision(4);
          out << "M at " << describe_point(m) << " is " << nearest
              << " from the mesh and under no triangle";
          found.example = out.str();
        }
      }
    }
  }
  return found;
}

}  // namespace tessera::testing
