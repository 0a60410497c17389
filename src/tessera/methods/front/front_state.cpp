// SPDX-License-Identifier: MIT
#include "tessera/methods/front/front_state.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "tessera/core/describe.h"
#include "tessera/core/error.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/planar.h"

namespace tessera {
namespace {

// Rotates triangle t so that v comes first: (v, a, b) with a→b counterclockwise around v.
std::pair<int, int> opposite_edge(const Triangle& t, int v) {
  if (t[0] == v) {
    return {t[1], t[2]};
  }
  if (t[1] == v) {
    return {t[2], t[0]};
  }
  return {t[0], t[1]};
}

// The index of the chain with the most vertices (the fan that stays at v).
std::size_t largest_chain(const std::vector<FanChain>& chains) {
  std::size_t largest = 0;
  for (std::size_t i = 1; i < chains.size(); ++i) {
    if (chains[i].vertices.size() > chains[largest].vertices.size()) {
      largest = i;
    }
  }
  return largest;
}

}  // namespace

FrontState::FrontState(std::shared_ptr<const AmbientSpace> space, double grid_cell)
    : space_(std::move(space)),
      coordinates_(space_->local_rows()),
      grid_(space_, grid_cell) {}

int FrontState::add_vertex(const Eigen::Ref<const Eigen::VectorXd>& x, VertexType type) {
  const int v = static_cast<int>(types_.size());
  coordinates_.push_back(x);
  types_.push_back(type);
  incident_.emplace_back();
  grid_.insert(v, x);
  grid_.refit_if_due([this](int id) { return point(id); });
  ++live_vertices_;
  if (type == VertexType::Frontal) {
    queue_.push_back(v);
    ++frontal_vertices_;
  }
  return v;
}

int FrontState::add_triangle(int a, int b, int c) {
  const int t = static_cast<int>(triangles_.size());
  triangles_.push_back({a, b, c});
  ++live_triangles_;
  for (int v : {a, b, c}) {
    incident_[v].push_back(t);
  }
  return t;
}

void FrontState::set_type(int v, VertexType type) {
  type_log_.emplace_back(v, types_[v]);
  if (type == VertexType::Frontal && types_[v] != VertexType::Frontal) {
    queue_.push_back(v);
  }
  frontal_vertices_ +=
      (type == VertexType::Frontal ? 1 : 0) - (types_[v] == VertexType::Frontal ? 1 : 0);
  types_[v] = type;
}

FrontState::Checkpoint FrontState::checkpoint() {
  type_log_.clear();
  return {static_cast<int>(types_.size()), static_cast<int>(triangles_.size())};
}

std::vector<int> FrontState::roll_back(const Checkpoint& checkpoint) {
  for (int t = static_cast<int>(triangles_.size()) - 1; t >= checkpoint.triangles; --t) {
    if (triangles_[t][0] >= 0) {
      remove_triangle(t);
    }
  }
  triangles_.resize(checkpoint.triangles);
  // Types first (a vertex added since may be in the log), then the added vertices.
  // set_type logs again: walk a moved-out copy of the log, not the vector it appends to.
  const std::vector<std::pair<int, VertexType>> log = std::move(type_log_);
  type_log_.clear();
  std::vector<int> restored;
  for (auto it = log.rbegin(); it != log.rend(); ++it) {
    const auto [v, before] = *it;
    if (v < checkpoint.vertices) {
      set_type(v, before);
      restored.push_back(v);
    }
  }
  for (int v = static_cast<int>(types_.size()) - 1; v >= checkpoint.vertices; --v) {
    grid_.remove(v, point(v));
    frontal_vertices_ -= types_[v] == VertexType::Frontal ? 1 : 0;
    live_vertices_ -= types_[v] == VertexType::Removed ? 0 : 1;
  }
  coordinates_.resize(checkpoint.vertices);
  types_.resize(checkpoint.vertices);
  incident_.resize(checkpoint.vertices);
  std::erase_if(queue_, [&](int v) { return v >= checkpoint.vertices; });
  type_log_.clear();
  std::sort(restored.begin(), restored.end());
  restored.erase(std::unique(restored.begin(), restored.end()), restored.end());
  return restored;
}

std::optional<int> FrontState::pop_frontal() {
  while (!queue_.empty()) {
    const int v = queue_.front();
    queue_.pop_front();
    if (types_[v] == VertexType::Frontal) {
      return v;
    }
  }
  return std::nullopt;
}

std::vector<int> FrontState::vertices_near(const Eigen::Ref<const Eigen::VectorXd>& x,
                                           double radius) const {
  return grid_.near(x, radius, [this](int id) { return point(id); });
}

std::vector<double> FrontState::distances(const Eigen::Ref<const Eigen::VectorXd>& x,
                                          const std::vector<int>& vertices) const {
  std::vector<double> result(vertices.size());
  if (!space_->is_distributed()) {
    for (std::size_t k = 0; k < vertices.size(); ++k) {
      result[k] = (point(vertices[k]) - x).norm();
    }
    return result;
  }
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    result[k] = (point(vertices[k]) - x).squaredNorm();
  }
  if (!result.empty()) {
    space_->sum(result.data(), static_cast<int>(result.size()));
  }
  for (double& value : result) {
    value = std::sqrt(value);
  }
  return result;
}

Eigen::Matrix2Xd FrontState::split_tangent_coordinates(const Eigen::MatrixXd& U, int from,
                                                       const std::vector<int>& to) const {
  Eigen::Matrix2Xd result(2, static_cast<Eigen::Index>(to.size()));
  for (std::size_t j = 0; j < to.size(); ++j) {
    result.col(static_cast<Eigen::Index>(j)) = U.transpose() * (point(to[j]) - point(from));
  }
  if (result.size() > 0) {
    space_->sum(result.data(), static_cast<int>(result.size()));
  }
  return result;
}

bool FrontState::are_adjacent(int a, int b) const {
  for (int t : incident_[a]) {
    const Triangle& tri = triangles_[t];
    if (tri[0] == b || tri[1] == b || tri[2] == b) {
      return true;
    }
  }
  return false;
}

std::vector<int> FrontState::ring(int v, int depth) const {
  std::vector<int> result{v};
  std::vector<int> layer{v};
  for (int d = 0; d < depth; ++d) {
    std::vector<int> next;
    for (int u : layer) {
      for (int t : incident_[u]) {
        for (int w : triangles_[t]) {
          if (std::find(result.begin(), result.end(), w) == result.end()) {
            result.push_back(w);
            next.push_back(w);
          }
        }
      }
    }
    layer = std::move(next);
  }
  std::sort(result.begin(), result.end());
  return result;
}

int FrontState::edge_triangle_count(int a, int b) const {
  int count = 0;
  for (int t : incident_[a]) {
    const Triangle& tri = triangles_[t];
    count += (tri[0] == b || tri[1] == b || tri[2] == b) ? 1 : 0;
  }
  return count;
}

bool FrontState::has_directed_edge(int a, int b) const {
  for (int t : incident_[a]) {
    const Triangle& tri = triangles_[t];
    for (int i = 0; i < 3; ++i) {
      if (tri[i] == a && tri[(i + 1) % 3] == b) {
        return true;
      }
    }
  }
  return false;
}

std::vector<FanChain> FrontState::fan_chains(int v) const {
  // next[a] = b for each triangle (v, a, b); chains follow next from vertices that are no b.
  std::vector<std::pair<int, int>> edges;
  for (int t : incident_[v]) {
    edges.push_back(opposite_edge(triangles_[t], v));
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 1; i < edges.size(); ++i) {
    if (edges[i].first == edges[i - 1].first) {
      // Collective on split states: the two descriptions in a fixed order.
      const std::string at = describe_point(point(v), *space_);
      const std::string to = describe_point(point(edges[i].first), *space_);
      throw ComputationFailed("internal fold: vertex " + std::to_string(v) + " " + at +
                              " has two triangles on the same side of its edge to " + to);
    }
  }
  const auto next = [&](int a) -> int {
    auto it = std::lower_bound(edges.begin(), edges.end(),
                               std::make_pair(a, std::numeric_limits<int>::min()));
    return (it != edges.end() && it->first == a) ? it->second : -1;
  };
  std::vector<int> is_target;
  for (const auto& e : edges) {
    is_target.push_back(e.second);
  }
  std::sort(is_target.begin(), is_target.end());
  std::vector<char> used(edges.size(), 0);
  std::vector<FanChain> chains;
  const auto index_of = [&](int a) {
    return static_cast<std::size_t>(
        std::lower_bound(edges.begin(), edges.end(),
                         std::make_pair(a, std::numeric_limits<int>::min())) -
        edges.begin());
  };
  // Open chains first, from their starting vertices (sources that are no target).
  for (const auto& e : edges) {
    if (std::binary_search(is_target.begin(), is_target.end(), e.first)) {
      continue;
    }
    FanChain chain;
    int a = e.first;
    chain.vertices.push_back(a);
    while (true) {
      const int b = next(a);
      if (b < 0) {
        break;
      }
      used[index_of(a)] = 1;
      chain.vertices.push_back(b);
      a = b;
    }
    chains.push_back(std::move(chain));
  }
  // What is left forms closed cycles.
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (used[i]) {
      continue;
    }
    FanChain chain;
    chain.is_closed = true;
    int a = edges[i].first;
    while (!used[index_of(a)]) {
      used[index_of(a)] = 1;
      chain.vertices.push_back(a);
      a = next(a);
    }
    chains.push_back(std::move(chain));
  }
  return chains;
}

double FrontState::fan_signed_area(int v, const FanChain& chain, const Eigen::MatrixXd& U) const {
  double area = 0.0;
  if (chain.vertices.size() < 2) {
    return area;
  }
  if (space_->is_distributed()) {  // the chain's coordinates in one reduction
    const Eigen::Matrix2Xd y = split_tangent_coordinates(U, v, chain.vertices);
    for (Eigen::Index i = 0; i + 1 < y.cols(); ++i) {
      area += 0.5 * cross(y.col(i), y.col(i + 1));
    }
    return area;
  }
  const Eigen::VectorXd center = point(v);
  // Each vertex of the chain projected once (O(n) each): b becomes the next a.
  Eigen::Vector2d a = U.transpose() * (point(chain.vertices[0]) - center);
  for (std::size_t i = 0; i + 1 < chain.vertices.size(); ++i) {
    const Eigen::Vector2d b = U.transpose() * (point(chain.vertices[i + 1]) - center);
    area += 0.5 * cross(a, b);
    a = b;
  }
  return area;
}

double FrontState::fan_angle(int v, const FanChain& chain, const Eigen::MatrixXd& U) const {
  double total = 0.0;
  if (chain.vertices.size() < 2) {
    return total;
  }
  if (space_->is_distributed()) {
    const Eigen::Matrix2Xd y = split_tangent_coordinates(U, v, chain.vertices);
    for (Eigen::Index i = 0; i + 1 < y.cols(); ++i) {
      total += std::atan2(cross(y.col(i), y.col(i + 1)), y.col(i).dot(y.col(i + 1)));
    }
    return total;
  }
  const Eigen::VectorXd center = point(v);
  Eigen::Vector2d a = U.transpose() * (point(chain.vertices[0]) - center);
  for (std::size_t i = 0; i + 1 < chain.vertices.size(); ++i) {
    const Eigen::Vector2d b = U.transpose() * (point(chain.vertices[i + 1]) - center);
    total += std::atan2(cross(a, b), a.dot(b));
    a = b;
  }
  return total;
}

bool FrontState::triangle_fits(const Triangle& t, const Eigen::MatrixXd& U) const {
  // Sectors that share an edge touch exactly; the tolerance only absorbs rounding.
  constexpr double kTolerance = 1e-9;
  // The direction from a corner to each of its neighbours, computed once per corner: each
  // neighbour is in two of the corner's triangles, and a projection costs O(n).
  std::vector<std::pair<int, double>> known;
  int known_from = -1;
  // Split states: every direction the test may ask for, reduced at once, per corner.
  std::array<std::vector<std::pair<int, double>>, 3> split_known;
  if (space_->is_distributed()) {
    std::vector<int> from;
    std::vector<int> to;
    for (int r = 0; r < 3; ++r) {
      const int v = t[r];
      for (int w : {t[(r + 1) % 3], t[(r + 2) % 3]}) {
        from.push_back(v);
        to.push_back(w);
      }
      for (int existing : incident_[v]) {
        const auto [p, q] = opposite_edge(triangles_[existing], v);
        for (int w : {p, q}) {
          from.push_back(v);
          to.push_back(w);
        }
      }
    }
    Eigen::Matrix2Xd y(2, static_cast<Eigen::Index>(to.size()));
    for (std::size_t j = 0; j < to.size(); ++j) {
      y.col(static_cast<Eigen::Index>(j)) = U.transpose() * (point(to[j]) - point(from[j]));
    }
    space_->sum(y.data(), static_cast<int>(y.size()));
    for (std::size_t j = 0; j < to.size(); ++j) {
      const int r = from[j] == t[0] ? 0 : from[j] == t[1] ? 1 : 2;
      const auto column = y.col(static_cast<Eigen::Index>(j));
      split_known[r].emplace_back(to[j], std::atan2(column(1), column(0)));
    }
  }
  const auto direction = [&](int from, int to) {
    if (space_->is_distributed()) {
      const int r = from == t[0] ? 0 : from == t[1] ? 1 : 2;
      for (const auto& [vertex, angle] : split_known[r]) {
        if (vertex == to) {
          return angle;
        }
      }
      TESSERA_ASSERT(false);  // every direction asked for was reduced above
      return std::numeric_limits<double>::quiet_NaN();
    }
    if (from != known_from) {
      known.clear();
      known_from = from;
    }
    for (const auto& [vertex, angle] : known) {
      if (vertex == to) {
        return angle;
      }
    }
    const Eigen::Vector2d y = U.transpose() * (point(to) - point(from));
    known.emplace_back(to, std::atan2(y(1), y(0)));
    return known.back().second;
  };
  const auto ccw = [](double from, double to) {
    const double two_pi = 2 * std::numbers::pi;
    double angle = std::fmod(to - from, two_pi);
    return angle < 0 ? angle + two_pi : angle;
  };
  for (int r = 0; r < 3; ++r) {
    const int v = t[r];
    const double start = direction(v, t[(r + 1) % 3]);
    const double width = ccw(start, direction(v, t[(r + 2) % 3]));
    if (width <= 0 || width >= std::numbers::pi) {
      return false;  // not positively oriented in U
    }
    for (int existing : incident_[v]) {
      const auto [p, q] = opposite_edge(triangles_[existing], v);
      const double other_start = ccw(start, direction(v, p));
      const double other_width = ccw(direction(v, p), direction(v, q));
      if (other_width >= std::numbers::pi) {
        continue;  // folded in this frame: too far away to judge
      }
      const bool disjoint = other_start >= width - kTolerance &&
                            other_start + other_width <= 2 * std::numbers::pi + kTolerance;
      if (!disjoint) {
        return false;
      }
    }
  }
  return true;
}

bool FrontState::can_add_edge(int a, int b) const {
  return !has_directed_edge(a, b) && edge_triangle_count(a, b) <= 1;
}

bool FrontState::can_identify(int a, int b) const {
  // For every common neighbour w the two edges (a, w) and (b, w) become one: each must have a
  // single triangle and the two must traverse the merged edge in opposite directions.
  std::vector<int> neighbours_a;
  for (int t : incident_[a]) {
    for (int u : triangles_[t]) {
      if (u != a) {
        neighbours_a.push_back(u);
      }
    }
  }
  std::sort(neighbours_a.begin(), neighbours_a.end());
  neighbours_a.erase(std::unique(neighbours_a.begin(), neighbours_a.end()), neighbours_a.end());
  for (int t : incident_[b]) {
    for (int w : triangles_[t]) {
      if (w == b || !std::binary_search(neighbours_a.begin(), neighbours_a.end(), w)) {
        continue;
      }
      if (edge_triangle_count(a, w) != 1 || edge_triangle_count(b, w) != 1) {
        return false;
      }
      const bool a_to_w = has_directed_edge(a, w);
      const bool b_to_w = has_directed_edge(b, w);
      if (a_to_w == b_to_w) {
        return false;
      }
    }
  }
  return true;
}

void FrontState::identify(int a, int b, const Eigen::Ref<const Eigen::VectorXd>& position,
                          std::optional<VertexType> type) {
  for (int t : incident_[b]) {
    for (int& u : triangles_[t]) {
      if (u == b) {
        u = a;
      }
    }
    incident_[a].push_back(t);
  }
  incident_[b].clear();
  grid_.remove(b, point(b));
  grid_.remove(a, point(a));
  coordinates_.column(a) = position;
  grid_.insert(a, position);
  const bool either_frontal = types_[a] == VertexType::Frontal || types_[b] == VertexType::Frontal;
  set_type(b, VertexType::Removed);
  --live_vertices_;
  if (type) {
    set_type(a, *type);
  } else if (either_frontal || types_[a] == VertexType::Exterior) {
    set_type(a, VertexType::Frontal);
  }
}

void FrontState::remove_triangle(int t) {
  for (int v : triangles_[t]) {
    auto& list = incident_[v];
    list.erase(std::remove(list.begin(), list.end(), t), list.end());
  }
  triangles_[t] = {-1, -1, -1};
  --live_triangles_;
}

std::vector<int> FrontState::chain_triangles(int v, const FanChain& chain) const {
  std::vector<int> found;
  const auto& vertices = chain.vertices;
  const std::size_t count = chain.is_closed ? vertices.size() : vertices.size() - 1;
  for (std::size_t j = 0; j < count; ++j) {
    const int a = vertices[j];
    const int b = vertices[(j + 1) % vertices.size()];
    for (int t : incident_[v]) {
      const auto edge = opposite_edge(triangles_[t], v);
      if (edge.first == a && edge.second == b) {
        found.push_back(t);
      }
    }
  }
  return found;
}

int FrontState::drop_pinched_fans() {
  int removed = 0;
  for (int v = 0; v < static_cast<int>(types_.size()); ++v) {
    if (types_[v] == VertexType::Removed || incident_[v].empty()) {
      continue;
    }
    const auto chains = fan_chains(v);
    if (chains.size() <= 1) {
      continue;
    }
    const std::size_t largest = largest_chain(chains);
    std::vector<int> doomed;
    for (std::size_t i = 0; i < chains.size(); ++i) {
      if (i != largest) {
        const std::vector<int> fan = chain_triangles(v, chains[i]);
        doomed.insert(doomed.end(), fan.begin(), fan.end());
      }
    }
    for (int t : doomed) {
      remove_triangle(t);
      ++removed;
    }
  }
  return removed;
}

int FrontState::split_pinched_exterior_vertices() {
  int added = 0;
  const int vertex_count = static_cast<int>(types_.size());
  for (int v = 0; v < vertex_count; ++v) {
    if (types_[v] != VertexType::Exterior || incident_[v].empty()) {
      continue;
    }
    std::vector<FanChain> chains;
    try {
      chains = fan_chains(v);
    } catch (const ComputationFailed&) {
      continue;  // not chains at all (a fold): left for clipping and validation to judge
    }
    if (chains.size() <= 1) {
      continue;
    }
    const std::size_t largest = largest_chain(chains);
    for (std::size_t i = 0; i < chains.size(); ++i) {
      if (i == largest) {
        continue;
      }
      const Eigen::VectorXd x = point(v);  // a copy: add_vertex may move the storage
      const int copy = add_vertex(x, VertexType::Exterior);
      for (int t : chain_triangles(v, chains[i])) {
        for (int& corner : triangles_[t]) {
          if (corner == v) {
            corner = copy;
          }
        }
        auto& list = incident_[v];
        list.erase(std::remove(list.begin(), list.end(), t), list.end());
        incident_[copy].push_back(t);
      }
      ++added;
    }
  }
  return added;
}

TriangleMesh FrontState::take_mesh() {
  std::vector<int> new_index(types_.size(), -1);
  for (const Triangle& t : triangles_) {
    if (t[0] < 0) {
      continue;  // removed
    }
    for (int v : t) {
      if (new_index[v] < 0) {
        new_index[v] = 0;
      }
    }
  }
  int kept = 0;
  for (std::size_t v = 0; v < types_.size(); ++v) {
    if (new_index[v] == 0 && types_[v] != VertexType::Removed) {
      coordinates_.move_column(static_cast<int>(v), kept);
      new_index[v] = kept++;
    } else {
      new_index[v] = -1;
    }
  }
  coordinates_.resize(kept);
  std::vector<Triangle> triangles;
  for (const Triangle& t : triangles_) {
    if (t[0] >= 0) {
      triangles.push_back({new_index[t[0]], new_index[t[1]], new_index[t[2]]});
    }
  }
  TriangleMesh mesh(std::move(coordinates_), std::move(triangles));
  if (space_->is_distributed()) {
    mesh.set_space(space_);
  }
  return mesh;
}

}  // namespace tessera
