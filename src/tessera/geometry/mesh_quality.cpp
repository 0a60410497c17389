// SPDX-License-Identifier: MIT
#include "tessera/geometry/mesh_quality.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <random>
#include <utility>
#include <vector>

#include "tessera/core/corrector.h"
#include "tessera/core/error.h"
#include "tessera/core/factorisation_cache.h"
#include "tessera/core/linearization.h"
#include "tessera/core/scaled_problem.h"
#include "tessera/geometry/mesh_topology.h"

namespace tessera {
namespace {

double triangle_area(const Eigen::Ref<const Eigen::VectorXd>& a,
                     const Eigen::Ref<const Eigen::VectorXd>& b,
                     const Eigen::Ref<const Eigen::VectorXd>& c) {
  // Gram determinant: valid in any dimension.
  const auto u = b - a;
  const auto v = c - a;
  const double uu = u.squaredNorm();
  const double vv = v.squaredNorm();
  const double uv = u.dot(v);
  return 0.5 * std::sqrt(std::max(0.0, uu * vv - uv * uv));
}

void accumulate(Statistic& statistic, double value) {
  statistic.max = std::max(statistic.max, value);
  statistic.mean += (value - statistic.mean) / ++statistic.count;
}

// 0 … population − 1, or a uniform sample of `limit` of them (limit > 0) drawn with a fixed
// seed, so that reports are reproducible.
std::vector<int> sample_indices(int population, int limit) {
  std::vector<int> indices(population);
  std::iota(indices.begin(), indices.end(), 0);
  if (limit <= 0 || population <= limit) {
    return indices;
  }
  std::mt19937_64 generator(20261123);
  for (int i = 0; i < limit; ++i) {  // partial Fisher–Yates
    std::uniform_int_distribution<int> pick(i, population - 1);
    std::swap(indices[i], indices[pick(generator)]);
  }
  indices.resize(limit);
  return indices;  // in random order: every prefix is a uniform sample
}

}  // namespace

double corner_angle(const Eigen::Ref<const Eigen::VectorXd>& apex,
                    const Eigen::Ref<const Eigen::VectorXd>& p,
                    const Eigen::Ref<const Eigen::VectorXd>& q) {
  // u = p − apex, w = q − apex as expressions: no n-vector is allocated (this runs for every
  // angle that edge swaps, clipping and refinement compare, in R^n).
  const auto u = p - apex;
  const auto w = q - apex;
  // |u ∧ w|² = |u|²|w|² − (u·w)² (Lagrange's identity, valid in R^n).
  const double dot = u.dot(w);
  const double wedge = std::sqrt(std::max(0.0, u.squaredNorm() * w.squaredNorm() - dot * dot));
  return std::atan2(wedge, dot);
}

double min_angle(const TriangleMesh& mesh, const Triangle& t) {
  const auto p = mesh.point(t[0]);
  const auto q = mesh.point(t[1]);
  const auto r = mesh.point(t[2]);
  return min_angle_of_sides((q - p).norm(), (r - q).norm(), (p - r).norm());
}

double min_angle_of_sides(double a, double b, double c) {
  // Sorted a ≥ b ≥ c, the smallest angle is C, opposite c. Kahan ("Miscalculating area and
  // angles of a needle-like triangle", 2014): C = 2·atan(√(((a − b) + c)·μ / ((a + (b + c))·
  // ((a − c) + b)))) with μ = c − (a − b), every subtraction exact or benign.
  if (a < b) {
    std::swap(a, b);
  }
  if (b < c) {
    std::swap(b, c);
  }
  if (a < b) {
    std::swap(a, b);
  }
  const double mu = c - (a - b);
  const double denominator = (a + (b + c)) * ((a - c) + b);
  if (!(mu > 0) || !(denominator > 0)) {
    return 0.0;  // a degenerate (or, by rounding, impossible) triangle
  }
  return 2.0 * std::atan(std::sqrt(((a - b) + c) * mu / denominator));
}

namespace {

// The shape measures of the mesh whose vertex v is at point(v): the mesh's own points, or
// their images in a problem's metric (computed on the fly: a scaled copy of the mesh would
// double the memory of a large-n run at its end).
// A split mesh (SPMD, each rank its rows of every vertex): every measure of a triangle comes from
// its Gram matrix (|u|², |v|², u·v for u = b − a, v = c − a), summed over the ranks at once.
MeshQuality shape_of_split(const TriangleMesh& mesh) {
  MeshQuality quality;
  const int count = mesh.triangle_count();
  std::vector<double> gram(3 * static_cast<std::size_t>(count));
  for (int t = 0; t < count; ++t) {
    const Triangle& tri = mesh.triangle(t);
    const auto u = mesh.point(tri[1]) - mesh.point(tri[0]);
    const auto v = mesh.point(tri[2]) - mesh.point(tri[0]);
    gram[3 * static_cast<std::size_t>(t)] = u.squaredNorm();
    gram[3 * static_cast<std::size_t>(t) + 1] = v.squaredNorm();
    gram[3 * static_cast<std::size_t>(t) + 2] = u.dot(v);
  }
  if (count > 0) {
    mesh.space().sum(gram.data(), 3 * count);
  }
  double min_angle = std::numeric_limits<double>::infinity();
  double max_angle = 0.0;
  double min_edge = std::numeric_limits<double>::infinity();
  double max_edge = 0.0;
  long below = 0;
  for (int t = 0; t < count; ++t) {
    const double uu = gram[3 * static_cast<std::size_t>(t)];
    const double vv = gram[3 * static_cast<std::size_t>(t) + 1];
    const double uv = gram[3 * static_cast<std::size_t>(t) + 2];
    const double wedge = std::sqrt(std::max(0.0, uu * vv - uv * uv));  // twice the area
    quality.area += 0.5 * wedge;
    // Corners a: u, v; b: a − b = −u, c − b = v − u; c: a − c = −v, b − c = u − v.
    const std::array<double, 3> dots = {uv, uu - uv, vv - uv};
    for (double dot : dots) {
      const double angle = std::atan2(wedge, dot) * 180.0 / std::numbers::pi;
      min_angle = std::min(min_angle, angle);
      max_angle = std::max(max_angle, angle);
      below += angle < 30.0 ? 1 : 0;
    }
    for (double squared : {uu, vv, std::max(0.0, uu + vv - 2.0 * uv)}) {
      min_edge = std::min(min_edge, std::sqrt(squared));
      max_edge = std::max(max_edge, std::sqrt(squared));
    }
  }
  if (count > 0) {
    quality.min_angle_degrees = min_angle;
    quality.max_angle_degrees = max_angle;
    quality.fraction_angles_below_30 = static_cast<double>(below) / (3.0 * count);
    quality.min_edge_length = min_edge;
    quality.max_edge_length = max_edge;
  }
  return quality;
}

template <class PointOf>
MeshQuality shape_of(const TriangleMesh& mesh, const PointOf& point) {
  if (mesh.space().is_distributed()) {
    return shape_of_split(mesh);  // (point is the mesh's own: split meshes have no metric)
  }
  MeshQuality quality;
  double min_angle = std::numeric_limits<double>::infinity();
  double max_angle = 0.0;
  double min_edge = std::numeric_limits<double>::infinity();
  double max_edge = 0.0;
  long below = 0;
  for (const Triangle& t : mesh.triangles()) {
    using Point = decltype(point(0));  // a Map of the mesh's column, or a scaled copy
    const std::array<Point, 3> corners = {point(t[0]), point(t[1]), point(t[2])};
    const auto p = [&](int r) -> const Point& { return corners[r % 3]; };
    quality.area += triangle_area(p(0), p(1), p(2));
    for (int r = 0; r < 3; ++r) {
      const double angle = corner_angle(p(r), p(r + 1), p(r + 2)) * 180.0 / std::numbers::pi;
      min_angle = std::min(min_angle, angle);
      max_angle = std::max(max_angle, angle);
      below += angle < 30.0 ? 1 : 0;
      const double length = (p(r + 1) - p(r)).norm();
      min_edge = std::min(min_edge, length);
      max_edge = std::max(max_edge, length);
    }
  }
  if (mesh.triangle_count() > 0) {
    quality.min_angle_degrees = min_angle;
    quality.max_angle_degrees = max_angle;
    quality.fraction_angles_below_30 = static_cast<double>(below) / (3.0 * mesh.triangle_count());
    quality.min_edge_length = min_edge;
    quality.max_edge_length = max_edge;
  }
  return quality;
}

}  // namespace

MeshQuality measure_shape(const TriangleMesh& mesh) {
  return shape_of(mesh, [&mesh](int v) { return mesh.point(v); });
}

double surface_area(const TriangleMesh& mesh) { return measure_shape(mesh).area; }

void check_mesh_of_problem(const TriangleMesh& mesh, const ImplicitProblem& problem,
                           const char* caller) {
  TESSERA_CHECK(mesh.space().dimension() == problem.ambient_dimension(),
                caller << ": the mesh is in R^" << mesh.space().dimension() << " but problem '"
                       << problem.name() << "' is in R^" << problem.ambient_dimension());
  if (!problem.space()->is_distributed()) {
    return;
  }
  TESSERA_CHECK(mesh.space().is_distributed() &&
                    mesh.space().local_rows() == problem.space()->local_rows() &&
                    mesh.space().first_row() == problem.space()->first_row(),
                caller << ": problem '" << problem.name()
                       << "' is distributed; the mesh must hold this rank's rows of its points "
                          "(TriangleMesh::set_space)");
  TESSERA_CHECK(metric_weights(problem).size() == 0,
                caller << ": the distributed problem '" << problem.name()
                       << "' has a metric; work in the metric's coordinates "
                          "(petsc::ScaledPetscProblem)");
}

bool project_onto_manifold(const ImplicitProblem& problem, Eigen::Ref<Eigen::VectorXd> x,
                           Linearization& workspace) {
  CorrectorOptions options;
  options.tolerance = 1e-13;  // distances down to ~1e-12 must be resolved
  options.residual_tolerance = 1e-11;
  options.max_contraction = 0.9;
  return project_gauss_newton(problem, x, options, workspace).is_success();
}

namespace {

template <class PointOf>
MeshQuality quality_of(const TriangleMesh& mesh, const PointOf& point,
                       const ImplicitProblem& problem, const QualityOptions& options);

}  // namespace

MeshQuality measure_quality(const TriangleMesh& mesh, const ImplicitProblem& problem,
                            const QualityOptions& options) {
  TESSERA_CHECK(options.max_samples >= 0,
                "QualityOptions::max_samples = " << options.max_samples << " must be >= 0");
  if (const ImplicitProblem* scaled = problem.metric_problem();
      scaled != nullptr && problem.space()->is_distributed()) {
    // In the metric's coordinates y = W x, as in one process below, by the problem's own twin
    // there (a distributed problem cannot be wrapped in ScaledProblem).
    check_mesh_of_problem(mesh, *scaled, "measure_quality");
    const AmbientSpace& space = *problem.space();
    const Eigen::VectorXd weights =
        metric_weights(problem).segment(space.first_row(), space.local_rows());
    return quality_of(
        mesh, [&](int v) -> Eigen::VectorXd { return weights.cwiseProduct(mesh.point(v)); },
        *scaled, options);
  }
  check_mesh_of_problem(mesh, problem, "measure_quality");
  if (problem.space()->is_distributed()) {
    return quality_of(mesh, [&mesh](int v) { return mesh.point(v); }, problem, options);
  }
  const Eigen::VectorXd weights = metric_weights(problem);
  if (weights.size() > 0) {
    // In the metric's coordinates y = W x, where lengths are the problem's own.
    const ScaledProblem scaled(problem, weights);
    return quality_of(
        mesh, [&](int v) -> Eigen::VectorXd { return weights.cwiseProduct(mesh.point(v)); },
        scaled, options);
  }
  return quality_of(mesh, [&mesh](int v) { return mesh.point(v); }, problem, options);
}

namespace {

template <class PointOf>
MeshQuality quality_of(const TriangleMesh& mesh, const PointOf& point,
                       const ImplicitProblem& problem, const QualityOptions& options) {
  MeshQuality quality = shape_of(mesh, point);
  // A split mesh reduces through its space (in one process these are Eigen's own reductions).
  const AmbientSpace& space = *problem.space();
  Eigen::VectorXd F(space.local_equations());
  Linearization workspace;
  // Sparse problems: the chord from the factorisation at a corner of the sample's triangle or
  // edge (kept for the samples around it), converged like P: a few solves per sample instead
  // of Gauss–Newton's three or four factorisations (the report of bvp at ε = 10⁻⁴ took 300 s,
  // longer than the covering). The chord's offset is normal to the corner's tangent plane, so
  // it measures the distance to the same order as P; where it does not converge, P does.
  // (A split mesh's corner chord has no tangent_basis_near to correct its foot with, so its
  // samples are projected by Gauss–Newton, normal to M at the foot, as the serial estimate is
  // after its correction.)
  const bool is_sparse = problem.has_sparse_jacobian() && !space.is_distributed();
  FactorisationCache corners(32, std::size_t{512} << 20);
  CorrectorOptions chord;
  chord.tolerance = 1e-13;
  chord.residual_tolerance = 1e-11;
  chord.max_contraction = 0.9;
  chord.max_iterations = 60;
  Eigen::MatrixXd tangent;
  const auto distance = [&](const Eigen::VectorXd& x, int corner, Statistic& statistic) {
    Eigen::VectorXd y = x;
    if (is_sparse && corner >= 0) {
      const Linearization* at_corner = corners.find(corner);
      if (at_corner == nullptr) {
        at_corner = corners.factor(corner, problem, point(corner));
      }
      if (at_corner != nullptr && at_corner->is_factored() &&
          project_chord(problem, *at_corner, y, chord).is_success()) {
        // The chord's foot y is normal to M at the corner, not at y: on a coarse mesh
        // (κh ≈ 1) that overstates the distance by 15 %. Two steps towards the foot normal
        // at y: x's offset moved into the tangent plane at y (from the corner's
        // factorisation, no new one) and projected back; kept while it comes nearer.
        for (int step = 0; step < 2; ++step) {
          if (!tangent_basis_near(problem, *at_corner, y, tangent, 1e-6, 8)) {
            break;
          }
          Eigen::VectorXd z = y + tangent * (tangent.transpose() * (x - y));
          if (!project_chord(problem, *at_corner, z, chord).is_success() ||
              (z - x).norm() >= (y - x).norm()) {
            break;
          }
          y = z;
        }
        accumulate(statistic, (y - x).norm());
        return;
      }
      y = x;
    }
    if (!project_onto_manifold(problem, y, workspace)) {
      ++quality.failed_projections;
      return;
    }
    accumulate(statistic, space.distance(y, x));
  };
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    problem.evaluate(point(v), F);
    accumulate(quality.vertex_residual, space.norm(F));
  }
  quality.vertex_residual.population = mesh.vertex_count();
  const MeshTopology topology(mesh);
  const auto& edges = topology.edges();
  const std::vector<int> vertices = sample_indices(mesh.vertex_count(), options.max_samples);
  const std::vector<int> triangles = sample_indices(mesh.triangle_count(), options.max_samples);
  const std::vector<int> midpoints = sample_indices(static_cast<int>(edges.size()), options.max_samples);
  quality.vertex_distance.population = mesh.vertex_count();
  quality.centroid_distance.population = mesh.triangle_count();
  quality.midpoint_distance.population = static_cast<int>(edges.size());
  // The three kinds in turn, so that a spent time budget leaves a uniform sample of each.
  const auto started = std::chrono::steady_clock::now();
  const auto has_time = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() <
           options.max_seconds;
  };
  const std::size_t rounds = std::max({vertices.size(), triangles.size(), midpoints.size()});
  for (std::size_t i = 0; i < rounds; ++i) {
    bool stop = (i >= static_cast<std::size_t>(kMinDistanceSamples) && !has_time()) ||
                (options.stop_requested && options.stop_requested());
    if (options.decide_together) {
      stop = options.decide_together(stop);
    }
    if (stop) {
      break;
    }
    if (i < vertices.size()) {
      // The vertex's own factorisation: the chord from it lands in a step or two.
      distance(point(vertices[i]), is_sparse ? vertices[i] : -1, quality.vertex_distance);
    }
    if (i < triangles.size()) {
      const Triangle& tri = mesh.triangle(triangles[i]);
      distance((point(tri[0]) + point(tri[1]) + point(tri[2])) / 3.0, tri[0],
               quality.centroid_distance);
    }
    if (i < midpoints.size()) {
      const auto& edge = edges[midpoints[i]];
      distance(0.5 * (point(edge[0]) + point(edge[1])), edge[0], quality.midpoint_distance);
    }
  }
  return quality;
}

}  // namespace
}  // namespace tessera
