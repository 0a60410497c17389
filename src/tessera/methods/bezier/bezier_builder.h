// SPDX-License-Identifier: MIT
// The state of method `bezier` while it runs: vertices with their tangent planes and steps, the
// triangles and their Bézier patches, the front of free edges, and the queue of edges to
// realise. Internal to the method (bezier_continuation.cpp has the algorithm, bezier_front.cpp
// the bookkeeping of the front and the final mesh).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <optional>
#include <queue>
#include <string>
#include <unordered_map>
#include <vector>

#include "tessera/core/corrector.h"
#include "tessera/core/domain.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/core/linearization.h"
#include "tessera/geometry/planar.h"
#include "tessera/methods/bezier/bezier_continuation.h"
#include "tessera/methods/common/point_grid.h"
#include "tessera/methods/start_point.h"

namespace tessera::detail {

using EdgeKey = std::uint64_t;

inline EdgeKey edge_key(int a, int b) {
  return (static_cast<EdgeKey>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

struct StopRun {
  CoveringTermination termination;
  std::string message;
};

struct VertexData {
  Eigen::VectorXd x;
  Eigen::MatrixXd T;   // n×2 orthonormal basis of T_x M
  double step = 0.0;   // s_j: the step with which the vertex was computed (section 5)
  double theta = 0.0;  // θ_j: first contraction of its Gauss–Newton iteration
  double step_limit = std::numeric_limits<double>::infinity();  // from the tolerance, if any
  // From the domain: where M ∩ S is a band narrower than the grown steps, max(step, width/2).
  double band_limit = std::numeric_limits<double>::infinity();
  std::vector<int> faces;  // domain half-spaces the vertex lies on
  bool in_grid = false;
};

// A computed point, before it is accepted as a vertex.
struct NewPoint {
  VertexData vertex;
  Linearization linearization;  // at vertex.x
};

// Why a step failed and by how much to reduce it.
struct StepFailure {
  std::string why;
  double factor = 0.5;
};

struct QueueEntry {
  double key;
  int a, b;
  bool operator>(const QueueEntry& other) const {
    return key > other.key || (key == other.key && edge_key(a, b) > edge_key(other.a, other.b));
  }
};

class BezierBuilder {
 public:
  BezierBuilder(const ImplicitProblem& problem, const Domain& domain, const BezierOptions& options)
      : problem_(problem),
        domain_(domain),
        options_(options),
        n_(problem.ambient_dimension()),
        max_step_(options.max_step > 0 ? options.max_step : 8.0 * options.step),
        min_step_(options.min_step_fraction * options.step),
        search_radius_(3.0 * max_step_),
        grid_(problem.ambient_dimension(), search_radius_) {
    corrector_.tolerance = options.corrector.tolerance;
    corrector_.max_iterations = options.corrector.max_iterations;
    corrector_.max_contraction = options.max_contraction;
  }

  void build_initial_triangle(const StartPoint& start);
  void run();

  int connections() const { return connections_; }
  int step_reductions() const { return step_reductions_; }
  // The final mesh and patches, with non-manifold vertices of a partial run removed.
  void extract(CoveringResult& result) const;
  int vertex_count() const { return static_cast<int>(vertices_.size()); }

 private:
  // -- the triangulation
  int add_vertex(VertexData vertex);
  void add_triangle(int i, int j, int k);
  bool has_edge(int a, int b) const { return edge_triangle_.count(edge_key(a, b)) > 0; }
  bool is_free(int a, int b) const { return has_edge(a, b) && !has_edge(b, a); }
  bool is_front_vertex(int v) const { return !front_out_[v].empty() || !front_in_[v].empty(); }
  bool is_boundary_edge(int a, int b) const;
  int third_vertex(int t, int a, int b) const;
  void update_front_membership(int v);
  void push_edges_of(int v);
  // Front angle at the ends of free edge a→b (radians, through the unfilled side).
  double wedge_angle(int v, int u, int c, int w) const;
  std::optional<int> previous_on_front(int a, int b, int c) const;
  std::optional<int> next_on_front(int a, int b, int c) const;
  double front_angle(int a, int b) const;

  // -- the algorithm
  bool realize(int a, int b, std::string& why);
  double predicted_step(int a, int b) const;
  std::optional<NewPoint> compute_point(const Eigen::VectorXd& prediction, double s,
                                        const Eigen::MatrixXd& reference, StepFailure& failure);
  bool project_onto_faces(Eigen::VectorXd& y, std::vector<int>& faces, double& theta) const;
  std::vector<int> faces_of(const Eigen::VectorXd& y) const;
  std::optional<double> worst_tangent_angle(int a, const NewPoint& point, int b) const;
  bool is_admissible(int a, int b, int c, int v, const Eigen::VectorXd& y) const;
  double new_edges_distance(int a, int b, int v) const;
  bool overlaps_mesh(int a, int b, int v, const Eigen::VectorXd& y) const;
  std::vector<int> front_vertices_near(const Eigen::VectorXd& x, double radius) const;

  const ImplicitProblem& problem_;
  const Domain& domain_;
  const BezierOptions& options_;
  const int n_;
  const double max_step_;
  const double min_step_;
  const double search_radius_;
  CorrectorOptions corrector_;

  std::vector<VertexData> vertices_;
  std::vector<Triangle> triangles_;
  std::vector<CubicBezierPatch> patches_;
  std::unordered_map<EdgeKey, int> edge_triangle_;  // directed edge → its triangle
  std::vector<std::vector<int>> vertex_triangles_;
  std::vector<std::vector<int>> front_out_, front_in_;  // free directed edges at each vertex
  std::unordered_map<EdgeKey, int> failures_;
  std::vector<std::pair<EdgeKey, std::string>> failure_messages_;  // first failure of each edge
  PointGrid grid_;  // front vertices only: the paper's "boundary vertices" (section 4)
  std::priority_queue<QueueEntry, std::vector<QueueEntry>, std::greater<>> queue_;
  int connections_ = 0;
  int step_reductions_ = 0;
  double longest_edge_ = 0.0;  // of the whole mesh, for the radius of the overlap search
  ProgressSchedule progress_schedule_;
};

/// Collapses the build's needles and swaps its caps away (bezier_shape_repair.cpp,
/// docs/algorithms/bezier.md "Shape repair"); notes what it did in result.summary.
void repair_shapes(const ImplicitProblem& problem, const BezierOptions& options,
                   CoveringResult& result);

}  // namespace tessera::detail
