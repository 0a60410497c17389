// SPDX-License-Identifier: MIT
#include "tessera/geometry/mesh_quality.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>
#include <random>
#include <utility>
#include <vector>

#include "tessera/core/corrector.h"
#include "tessera/core/error.h"
#include "tessera/core/factorisation_cache.h"
#include "tessera/core/linearization.h"
#include "tessera/core/parallel_for.h"
#include "tessera/core/scaled_problem.h"
#include "tessera/geometry/mesh_topology.h"

namespace tessera {
namespace {

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
// double the memory of a large-n run at its end). Every measure of a triangle (a, b, c) comes
// from the inner products of its edges e0 = b − a, e1 = c − b, e2 = a − c: the angle at the
// start of e_r is atan2(|e_r ∧ e_(r+2)|, −e_r·e_(r+2)), the area ½|e0 ∧ e2|. For a split mesh
// (SPMD, each rank its rows of every vertex) these are sums over the ranks, reduced for a block
// of triangles at once; in one process the sum is the identity, so that one code path measures
// every backend's mesh (the PETSc backend's report measured its split meshes in x, not in the
// metric, until 2026-11-28: bratu2d's angles 0.6°…179° for the serial 6.5°…143°).
template <class PointOf>
MeshQuality shape_of(const TriangleMesh& mesh, const PointOf& point) {
  MeshQuality quality;
  const AmbientSpace& space = mesh.space();
  const int count = mesh.triangle_count();
  constexpr int kBlock = 4096;  // triangles per reduction: 192 KB of products
  std::vector<double> products(6 * static_cast<std::size_t>(std::min(count, kBlock)));
  double min_angle = std::numeric_limits<double>::infinity();
  double max_angle = 0.0;
  double min_edge = std::numeric_limits<double>::infinity();
  double max_edge = 0.0;
  long below = 0;
  for (int first = 0; first < count; first += kBlock) {
    const int size = std::min(kBlock, count - first);
    for (int k = 0; k < size; ++k) {
      const Triangle& t = mesh.triangle(first + k);
      using Point = decltype(point(0));  // a Map of the mesh's column, or a scaled copy
      const std::array<Point, 3> corners = {point(t[0]), point(t[1]), point(t[2])};
      double* e = products.data() + 6 * static_cast<std::size_t>(k);
      for (int r = 0; r < 3; ++r) {
        const auto edge = corners[(r + 1) % 3] - corners[r];            // e_r
        const auto next = corners[(r + 2) % 3] - corners[(r + 1) % 3];  // e_(r+1)
        e[r] = edge.squaredNorm();                                      // |e_r|²
        e[3 + r] = edge.dot(next);                                      // e_r · e_(r+1)
      }
    }
    space.sum(products.data(), 6 * size);
    for (int k = 0; k < size; ++k) {
      const double* e = products.data() + 6 * static_cast<std::size_t>(k);
      // The corner at the start of e_r: u = e_r, w = −e_(r+2), u·w = −e_(r+2)·e_r.
      const auto corner_dot = [e](int r) { return -e[3 + (r + 2) % 3]; };
      const auto wedge = [e, &corner_dot](int r) {  // |e_r ∧ e_(r+2)| by Lagrange's identity
        const double dot = corner_dot(r);
        return std::sqrt(std::max(0.0, e[r] * e[(r + 2) % 3] - dot * dot));
      };
      quality.area += 0.5 * wedge(0);
      for (int r = 0; r < 3; ++r) {
        const double angle = std::atan2(wedge(r), corner_dot(r)) * 180.0 / std::numbers::pi;
        min_angle = std::min(min_angle, angle);
        max_angle = std::max(max_angle, angle);
        below += angle < 30.0 ? 1 : 0;
        const double length = std::sqrt(e[r]);
        min_edge = std::min(min_edge, length);
        max_edge = std::max(max_edge, length);
      }
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

}  // namespace

MeshQuality measure_shape(const TriangleMesh& mesh) {
  return shape_of(mesh, [&mesh](int v) { return mesh.point(v); });
}

// The area equals
// sqrt(det G) / 2 for the Gram matrix G of two edge vectors, but det G = |u|^2 |v|^2 - (u.v)^2
// cancels catastrophically for thin triangles (its rounding error, ~1e-16 L^4, would give a
// collinear triangle an area of ~1e-8 L^2). Instead the apex is projected onto the longest
// edge u: area = |u| |w| / 2 with w = v - (u.v / u.u) u, whose error is a few ulp * L^2.
std::pair<double, double> triangle_area_and_longest_squared(const TriangleMesh& mesh,
                                                            const Triangle& tri) {
  const auto points = mesh.points();
  const AmbientSpace& space = mesh.space();
  std::array<double, 3> squared_length;  // edge k joins tri[k] and tri[(k + 1) % 3]
  for (int k = 0; k < 3; ++k) {
    squared_length[k] = (points.col(tri[(k + 1) % 3]) - points.col(tri[k])).squaredNorm();
  }
  space.sum(squared_length.data(), 3);  // over the ranks of a split mesh (else nothing)
  const int k = static_cast<int>(std::max_element(squared_length.begin(), squared_length.end()) -
                                 squared_length.begin());
  const double uu = squared_length[k];
  if (uu == 0.0) {
    return {0.0, 0.0};
  }
  const auto base = points.col(tri[k]);
  const auto u = points.col(tri[(k + 1) % 3]) - base;
  const auto v = points.col(tri[(k + 2) % 3]) - base;
  // (In one process Eigen's own reductions, as before the split: the same bits.)
  const double s = (space.is_distributed() ? space.dot(u, v) : u.dot(v)) / uu;
  const double ww =
      space.is_distributed() ? space.squared_norm(v - s * u) : (v - s * u).squaredNorm();
  return {0.5 * std::sqrt(uu * ww), uu};
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
  const Eigen::VectorXd start = x;
  if (project_gauss_newton(problem, x, options, workspace).is_success()) {
    return true;
  }
  // Steps of 1e-13·(1 + ‖x‖) can be below what rounding lets Gauss–Newton resolve: from a point
  // already on M (|F| 2e-10 on bratu2d:N=8, a midpoint of a nearly straight edge) the steps
  // stalled at rounding, |F| at 1.8e-14, and were read as divergence (θ = 0.98). Measured
  // again to the solver's own tolerance, which the mesh's vertices meet.
  x = start;
  options = CorrectorOptions();
  options.max_contraction = 0.9;
  return project_gauss_newton(problem, x, options, workspace).is_success();
}

namespace {

// M in the coordinates of its metric, y = W x, where lengths are the problem's own (the norm
// the covering methods use): the problem itself where its metric is Euclidean; in one process
// ScaledProblem; a distributed problem's own twin in y (metric_problem(): ScaledProblem cannot
// wrap a distributed problem). `weights`: this rank's rows of W, empty where W = I.
class InMetric {
 public:
  explicit InMetric(const ImplicitProblem& problem) : problem_(&problem) {
    const AmbientSpace& space = *problem.space();
    const ImplicitProblem* twin = problem.metric_problem();
    if (space.is_distributed() && twin == nullptr) {
      return;  // check_mesh_of_problem refuses it if it has a metric
    }
    const Eigen::VectorXd weights = metric_weights(problem);
    if (weights.size() == 0) {
      return;
    }
    weights_ = weights.segment(space.first_row(), space.local_rows());
    if (space.is_distributed()) {
      problem_ = twin;
    } else {
      scaled_.emplace(problem, weights);
      problem_ = &*scaled_;
    }
  }
  InMetric(const InMetric&) = delete;
  InMetric& operator=(const InMetric&) = delete;

  const ImplicitProblem& problem() const { return *problem_; }
  const Eigen::VectorXd& weights() const { return weights_; }

 private:
  std::optional<ScaledProblem> scaled_;
  const ImplicitProblem* problem_;
  Eigen::VectorXd weights_;
};

// f(point) with point(v) the image of vertex v in the metric's coordinates: one code path for
// every problem and backend, instantiated for the mesh's own columns (W = I) and for scaled
// copies of them.
template <class Measure>
MeshQuality in_metric(const TriangleMesh& mesh, const InMetric& metric, const Measure& measure) {
  if (metric.weights().size() == 0) {
    return measure([&mesh](int v) { return mesh.point(v); });
  }
  const Eigen::VectorXd& weights = metric.weights();
  return measure([&](int v) -> Eigen::VectorXd { return weights.cwiseProduct(mesh.point(v)); });
}

template <class PointOf>
MeshQuality quality_of(const TriangleMesh& mesh, const PointOf& point,
                       const ImplicitProblem& problem, const QualityOptions& options);

}  // namespace

MeshQuality measure_quality(const TriangleMesh& mesh, const ImplicitProblem& problem,
                            const QualityOptions& options) {
  TESSERA_CHECK(options.max_samples >= 0,
                "QualityOptions::max_samples = " << options.max_samples << " must be >= 0");
  const InMetric metric(problem);
  check_mesh_of_problem(mesh, metric.problem(), "measure_quality");
  return in_metric(mesh, metric, [&](const auto& point) {
    return quality_of(mesh, point, metric.problem(), options);
  });
}

MeshQuality measure_shape(const TriangleMesh& mesh, const ImplicitProblem& problem) {
  const InMetric metric(problem);
  check_mesh_of_problem(mesh, metric.problem(), "measure_shape");
  return in_metric(mesh, metric, [&](const auto& point) { return shape_of(mesh, point); });
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
  // A split mesh's samples are measured the same way, every step reduced over the ranks (they
  // were projected by Gauss–Newton until 2026-11-28: three or four factorisations by MUMPS per
  // sample, and other feet than the serial report's).
  const bool is_sparse = problem.has_sparse_jacobian();
  FactorisationCache corners(32, std::size_t{512} << 20);
  CorrectorOptions chord;
  chord.tolerance = 1e-13;
  chord.residual_tolerance = 1e-11;
  chord.max_contraction = 0.9;
  chord.max_iterations = 60;
  Eigen::MatrixXd tangent;
  // Dense problems measure every point on its own (a projection from scratch), so the points
  // are measured on threads and recorded after, in the serial order: the same statistics,
  // to the bit, whatever the thread count. Sparse problems share the corners' factorisations
  // in that order, on one thread (threads_for).
  const int threads = threads_for(problem);
  // The distance from x to M, NaN where the projection failed; `own` is the workspace of a
  // dense problem's point (sparse ones use the shared `workspace` and `corners`).
  const auto distance_of = [&](const Eigen::VectorXd& x, int corner, Linearization& own) -> double {
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
          Eigen::VectorXd z = y + tangent * space.tangent_coordinates(tangent, x - y);
          if (!project_chord(problem, *at_corner, z, chord).is_success() ||
              space.distance(z, x) >= space.distance(y, x)) {
            break;
          }
          y = z;
        }
        return space.distance(y, x);
      }
      y = x;
    }
    if (!project_onto_manifold(problem, y, is_sparse ? workspace : own)) {
      return std::numeric_limits<double>::quiet_NaN();
    }
    return space.distance(y, x);
  };
  const auto record = [&](double value, Statistic& statistic) {
    if (std::isnan(value)) {
      ++quality.failed_projections;
    } else {
      accumulate(statistic, value);
    }
  };
  const auto distance = [&](const Eigen::VectorXd& x, int corner, Statistic& statistic) {
    record(distance_of(x, corner, workspace), statistic);
  };
  {
    std::vector<double> residual(static_cast<std::size_t>(mesh.vertex_count()));
    parallel_for(mesh.vertex_count(), threads, [&](int v) {
      Eigen::VectorXd own_F(F.size());
      problem.evaluate(point(v), own_F);
      residual[static_cast<std::size_t>(v)] = space.norm(own_F);
    });
    for (const double r : residual) {
      accumulate(quality.vertex_residual, r);
    }
  }
  quality.vertex_residual.population = mesh.vertex_count();
  const MeshTopology topology(mesh);
  const auto& edges = topology.edges();
  const std::vector<int> vertices = sample_indices(mesh.vertex_count(), options.max_samples);
  const std::vector<int> triangles = sample_indices(mesh.triangle_count(), options.max_samples);
  const std::vector<int> midpoints =
      sample_indices(static_cast<int>(edges.size()), options.max_samples);
  quality.vertex_distance.population = mesh.vertex_count();
  quality.centroid_distance.population = mesh.triangle_count();
  quality.midpoint_distance.population = static_cast<int>(edges.size());
  const auto started = std::chrono::steady_clock::now();
  const auto has_time = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() <
           options.max_seconds;
  };
  // Every point, without a time budget, of a sparse problem: by corner, a vertex and then the
  // triangles and edges whose first corner it is, all from the vertex's factorisation: one
  // factorisation per vertex instead of one per point (in index order the corners of the
  // three kinds drift apart and leave the cache; on the PETSc backend a factorisation is
  // collective). Otherwise the three kinds in turn, so that a spent time budget leaves a
  // uniform sample of each.
  const bool by_corner =
      is_sparse && options.max_samples == 0 && !std::isfinite(options.max_seconds);
  std::vector<int> first_triangle;  // triangles and edges by first corner (CSR)
  std::vector<int> triangles_at;
  std::vector<int> first_edge;
  std::vector<int> edges_at;
  if (by_corner) {
    const auto group = [&mesh](int count, const auto& first_corner, std::vector<int>& first,
                               std::vector<int>& members) {
      first.assign(static_cast<std::size_t>(mesh.vertex_count()) + 1, 0);
      for (int k = 0; k < count; ++k) {
        ++first[static_cast<std::size_t>(first_corner(k)) + 1];
      }
      for (std::size_t v = 1; v < first.size(); ++v) {
        first[v] += first[v - 1];
      }
      members.resize(static_cast<std::size_t>(count));
      std::vector<int> next(first.begin(), first.end() - 1);
      for (int k = 0; k < count; ++k) {
        members[static_cast<std::size_t>(next[static_cast<std::size_t>(first_corner(k))]++)] = k;
      }
    };
    group(
        mesh.triangle_count(), [&mesh](int t) { return mesh.triangle(t)[0]; }, first_triangle,
        triangles_at);
    group(
        static_cast<int>(edges.size()), [&edges](int e) { return edges[e][0]; }, first_edge,
        edges_at);
  }
  const std::size_t rounds =
      by_corner ? vertices.size() : std::max({vertices.size(), triangles.size(), midpoints.size()});
  const auto centroid = [&](int t) {
    const Triangle& tri = mesh.triangle(t);
    distance((point(tri[0]) + point(tri[1]) + point(tri[2])) / 3.0, tri[0],
             quality.centroid_distance);
  };
  const auto midpoint = [&](int e) {
    const auto& edge = edges[static_cast<std::size_t>(e)];
    distance(0.5 * (point(edge[0]) + point(edge[1])), edge[0], quality.midpoint_distance);
  };
  if (threads > 1) {
    // Rounds in blocks: each block's points on threads, then recorded in order; the stop
    // request and the time budget are polled between blocks, on this thread. The first block
    // is the samples the budget always leaves.
    // (Few blocks: each ends at a barrier, which costs a time slice on a loaded machine.)
    const std::size_t later_blocks = 4096 * static_cast<std::size_t>(threads);
    constexpr double kNotSampled = -1.0;          // distances are >= 0; NaN: the projection failed
    std::vector<std::array<double, 3>> measured;  // per round: vertex, centroid, midpoint
    for (std::size_t first = 0, block = kMinDistanceSamples; first < rounds;
         first += block, block = later_blocks) {
      bool stop = (first >= static_cast<std::size_t>(kMinDistanceSamples) && !has_time()) ||
                  (options.stop_requested && options.stop_requested());
      if (options.decide_together) {
        stop = options.decide_together(stop);
      }
      if (stop) {
        break;
      }
      const std::size_t size = std::min(block, rounds - first);
      measured.assign(size, {kNotSampled, kNotSampled, kNotSampled});
      parallel_for(static_cast<int>(size), threads, [&](int k) {
        const std::size_t i = first + static_cast<std::size_t>(k);
        std::array<double, 3>& out = measured[static_cast<std::size_t>(k)];
        Linearization own;
        if (i < vertices.size()) {
          out[0] = distance_of(point(vertices[i]), -1, own);
        }
        if (i < triangles.size()) {
          const Triangle& tri = mesh.triangle(triangles[i]);
          out[1] = distance_of((point(tri[0]) + point(tri[1]) + point(tri[2])) / 3.0, -1, own);
        }
        if (i < midpoints.size()) {
          const auto& edge = edges[static_cast<std::size_t>(midpoints[i])];
          out[2] = distance_of(0.5 * (point(edge[0]) + point(edge[1])), -1, own);
        }
      });
      for (const std::array<double, 3>& out : measured) {
        Statistic* statistics[3] = {&quality.vertex_distance, &quality.centroid_distance,
                                    &quality.midpoint_distance};
        for (int kind = 0; kind < 3; ++kind) {
          if (!(out[kind] == kNotSampled)) {
            record(out[kind], *statistics[kind]);
          }
        }
      }
    }
    return quality;
  }
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
    if (by_corner) {
      for (int k = first_triangle[i]; k < first_triangle[i + 1]; ++k) {
        centroid(triangles_at[static_cast<std::size_t>(k)]);
      }
      for (int k = first_edge[i]; k < first_edge[i + 1]; ++k) {
        midpoint(edges_at[static_cast<std::size_t>(k)]);
      }
      continue;
    }
    if (i < triangles.size()) {
      centroid(triangles[i]);
    }
    if (i < midpoints.size()) {
      midpoint(midpoints[i]);
    }
  }
  return quality;
}

}  // namespace
}  // namespace tessera
