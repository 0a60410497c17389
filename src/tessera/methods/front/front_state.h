// SPDX-License-Identifier: MIT
// The growing mesh of the advancing front: vertices with their types, triangles, vertex–triangle
// incidence (the paper's xnod, sim and nod arrays), the queue of frontal vertices and a
// proximity grid. Internal to the front method.
#pragma once

#include <Eigen/Core>
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "tessera/core/ambient_space.h"
#include "tessera/core/point_storage.h"
#include "tessera/geometry/triangle_mesh.h"
#include "tessera/methods/common/point_grid.h"

namespace tessera {

class BinaryReader;
class BinaryWriter;

/// Node types of the paper's Table 4.1 (−1 frontal, 0/1 interior, 2 exterior).
enum class VertexType { Frontal, Interior, Exterior, Removed };

/// The triangles around a vertex v in counterclockwise order: triangle i is
/// (v, vertices[i], vertices[i+1]). Open chains start and end at the two open edges.
struct FanChain {
  std::vector<int> vertices;
  bool is_closed = false;  ///< a full neighbourhood: vertices.front() follows vertices.back()
};

/// On split states (SPMD, docs/cluster.md) every point is this rank's rows of an n-vector and
/// every measure of the points below (tangent coordinates, distances, angles) is reduced over
/// the ranks, so that every rank takes the same decisions; those calls are then collective.
class FrontState {
 public:
  /// Points are rows of `space` (R^n itself in one process).
  FrontState(std::shared_ptr<const AmbientSpace> space, double grid_cell);
  /// In R^n in one process.
  FrontState(int ambient_dimension, double grid_cell)
      : FrontState(std::make_shared<const AmbientSpace>(ambient_dimension), grid_cell) {}

  int add_vertex(const Eigen::Ref<const Eigen::VectorXd>& x, VertexType type);
  int add_triangle(int a, int b, int c);

  Eigen::Map<const Eigen::VectorXd> point(int v) const { return coordinates_.column(v); }
  /// Every vertex's point as the columns of one matrix (removed vertices included).
  Eigen::Map<const Eigen::MatrixXd> points() const { return coordinates_.matrix(); }
  VertexType type(int v) const { return types_[v]; }
  void set_type(int v, VertexType type);

  /// Next vertex of the FIFO queue that is still frontal; nullopt when the front is empty.
  std::optional<int> pop_frontal();
  /// The number of frontal vertices (the length of the front).
  int front_size() const { return frontal_vertices_; }
  int live_vertex_count() const { return live_vertices_; }
  int live_triangle_count() const { return live_triangles_; }

  std::vector<int> vertices_near(const Eigen::Ref<const Eigen::VectorXd>& x, double radius) const;
  /// ‖x_v − x‖ for each v of `vertices` (on split states in one reduction).
  std::vector<double> distances(const Eigen::Ref<const Eigen::VectorXd>& x,
                                const std::vector<int>& vertices) const;
  bool are_adjacent(int a, int b) const;
  int valence(int v) const { return static_cast<int>(incident_[v].size()); }
  /// Vertices within `depth` edges of v (v included), sorted.
  std::vector<int> ring(int v, int depth) const;

  /// The fans of triangles around v (one chain for a manifold vertex).
  /// \throw ComputationFailed if the triangles around v do not form chains (an internal fold).
  std::vector<FanChain> fan_chains(int v) const;
  /// Σ over the chain's triangles of the signed area of their projections onto U (n×2).
  double fan_signed_area(int v, const FanChain& chain, const Eigen::MatrixXd& U) const;
  /// Σ of the signed angles at v of the chain's triangles projected onto U, in radians.
  double fan_angle(int v, const FanChain& chain, const Eigen::MatrixXd& U) const;

  /// True if the new triangle t = (a, b, c), positively oriented in the tangent frame U (n×2),
  /// does not overlap any existing triangle at any of its corners: at each corner, its angular
  /// sector in U must be disjoint from the sectors of the triangles already there.
  bool triangle_fits(const Triangle& t, const Eigen::MatrixXd& U) const;
  /// True if a triangle may use the directed edge a→b (no triangle uses it yet, and the
  /// undirected edge has at most one triangle).
  bool can_add_edge(int a, int b) const;
  /// True if identifying b with a keeps every edge manifold and consistently oriented.
  bool can_identify(int a, int b) const;
  /// Replaces b by a everywhere and moves a to `position` (the paper's Equate).
  void identify(int a, int b, const Eigen::Ref<const Eigen::VectorXd>& position,
                std::optional<VertexType> type);

  /// The front loop through v: v, then repeatedly the first vertex of the open chain, until it
  /// returns to v. Empty if longer than max_length or if a vertex on it is not a simple chain.
  std::vector<int> front_loop(int v, int max_length) const;
  /// Fills the hole bounded by `loop` (as returned by front_loop) with the triangulation of
  /// largest minimum angle whose triangles are positively oriented in the tangent frame U.
  /// Fails (returns false, changes nothing) if no triangulation has all angles ≥ min_angle.
  bool triangulate_hole(const std::vector<int>& loop, const Eigen::MatrixXd& U, double min_angle);

  /// Makes a partial mesh valid after a stopped run: where a vertex has several fans (the front
  /// was connected to a part of itself that was not yet glued), only its largest fan is kept.
  /// Only removes triangles, so no overlap can appear. Returns the number removed.
  int drop_pinched_fans();
  /// Where an exterior vertex has several fans (parts of the front connected to it that were
  /// never glued, since exterior vertices are not processed), each fan but the largest gets a
  /// copy of the vertex: the touch lies outside S and clipping removes both copies, whereas
  /// the pinch made every face's clipping fail its validation. Returns the copies made.
  int split_pinched_exterior_vertices();

  /// What the state was when a step began, to undo the step: its vertices and triangles, and
  /// the vertex types changed since (logged until the next checkpoint).
  struct Checkpoint {
    int vertices = 0;
    int triangles = 0;
  };
  Checkpoint checkpoint();
  /// Undoes everything since `checkpoint` was taken: triangles added are removed, vertices
  /// added are forgotten, types changed are restored. \pre no vertices were identified since
  /// (identify is not undone). Returns the vertices whose type was restored.
  std::vector<int> roll_back(const Checkpoint& checkpoint);
  /// Puts a frontal vertex at the back of the FIFO queue again.
  void requeue(int v) { queue_.push_back(v); }

  /// Writes the whole state (front_checkpoint.h): what decides every later step.
  void write_state(BinaryWriter& out) const;
  /// Reads what write_state wrote into a state made empty. \throw InvalidArgument naming a
  /// corrupt field (an index out of range, counts that disagree).
  void read_state(BinaryReader& in);

  /// The live part as a compact TriangleMesh (unreferenced vertices dropped). The points are
  /// handed over, compacted in place, not copied: the state has none afterwards.
  TriangleMesh take_mesh();

 private:
  int edge_triangle_count(int a, int b) const;
  /// The triangles of v's fan `chain` (as returned by fan_chains(v)).
  std::vector<int> chain_triangles(int v, const FanChain& chain) const;
  bool has_directed_edge(int a, int b) const;
  /// Column j: Uᵀ(x_{to[j]} − x_from), for split states summed over the ranks in one call.
  Eigen::Matrix2Xd split_tangent_coordinates(const Eigen::MatrixXd& U, int from,
                                             const std::vector<int>& to) const;

  std::shared_ptr<const AmbientSpace> space_;
  PointStorage coordinates_;
  std::vector<VertexType> types_;
  std::vector<std::vector<int>> incident_;  // vertex → triangles
  std::vector<Triangle> triangles_;
  std::deque<int> queue_;
  PointGrid grid_;
  int live_vertices_ = 0;
  int live_triangles_ = 0;
  int frontal_vertices_ = 0;
  std::vector<std::pair<int, VertexType>> type_log_;  // (vertex, type before) since checkpoint
  void remove_triangle(int t);
};

}  // namespace tessera
