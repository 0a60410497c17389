// SPDX-License-Identifier: MIT
// The largest sampled distance to M of each triangle a pass of refine_to_tolerance checks: the
// samples measured from their anchor's factorisation (on threads for dense problems), then
// judged in the pass's order.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <utility>
#include <vector>

#include "tessera/core/corrector.h"
#include "tessera/core/domain.h"
#include "tessera/core/factorisation_cache.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/core/linearization.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera::detail {

/// The key of the edge {a, b}, the same for (a, b) and (b, a).
std::uint64_t unordered_edge_key(int a, int b);

/// The faces of the domain both endpoints of an edge lie on (the edge runs along their
/// intersection). `distance_a`, `distance_b`: every face's signed distance of the endpoints.
std::vector<int> shared_faces(const Eigen::Ref<const Eigen::VectorXd>& distance_a,
                              const Eigen::Ref<const Eigen::VectorXd>& distance_b,
                              double tolerance);

/// A boundary edge that cuts a corner of the domain: one end on face a only, the other on face b
/// only. M ∩ S reaches beyond it to the corner point M ∩ a ∩ b (isolated: M is a surface), so
/// the gap is measured there and the edge is split at that point ({a, b}); empty otherwise.
std::vector<int> corner_faces(const Eigen::Ref<const Eigen::VectorXd>& distance_a,
                              const Eigen::Ref<const Eigen::VectorXd>& distance_b,
                              double tolerance);

/// A triangle (a, b, c)'s Gram numbers: |b − a|², |c − a|², (b − a)·(c − a), and |c − b|² (for
/// its third edge's length to the bit), indexed by triangle.
using Gram = std::array<double, 4>;

/// How the samples are measured (refine_to_tolerance's options, derived once).
struct SampleSettings {
  double threshold = 0.0;    ///< tolerance · sample_safety: a triangle beyond it is split
  double accuracy = 0.0;     ///< the distances are measured to this (a bound from above)
  double clear_below = 0.0;  ///< a chord bound below this passes after two steps
  double face_tolerance = 0.0;
  CorrectorOptions chord;         ///< the chord iterations' (the refinement's corrector)
  CorrectorOptions gauss_newton;  ///< the same, keeping its factorisation
  CorrectorOptions patient;       ///< Gauss–Newton where it contracts slowly (θ up to 0.9)
};

/// The factorisations a run of samples shares: the chord's, frozen at an anchor, the last
/// corners factored, and Gauss–Newton's workspace. A dense problem's anchor group gets a state
/// of its own, so that its distances depend on the group alone and the groups run on threads;
/// a sparse problem's samples share one, in the pass's order, with the bisection's projections
/// (one factorisation, ~50 MB at n = 10⁵, serves the most points that way).
struct SampleState {
  Linearization frozen;
  int frozen_at = -1;  ///< the vertex `frozen` is linearised at
  bool frozen_ok = false;
  FactorisationCache corners{6, std::size_t{256} << 20};
  /// The anchors' own factorisations, where worth sharing: later anchors borrow them.
  FactorisationLenders lenders{4, std::size_t{256} << 20};
  /// Whether the factorisations are worth sharing (worth_sharing): −1 until the first is made.
  /// Where they are not, each is made in place, as before sharing (a sparse factorisation's
  /// border follows the last one's basis), so that such runs keep their meshes and counts.
  int sharing = -1;
  Linearization workspace;
  /// Makes `frozen` a linearisation at vertex v unless it is one there already: one that
  /// borrows the nearest kept factorisation where that is near enough (FactorisationLenders,
  /// with the mesh's local `edge_length`; 0: never), else v's own (freeze_own_at).
  void freeze_at(const ImplicitProblem& problem, const TriangleMesh& mesh, int v,
                 double edge_length = 0.0);
  /// Factors `frozen` at vertex v, and keeps the factorisation as a lender.
  void freeze_own_at(const ImplicitProblem& problem, const TriangleMesh& mesh, int v);
};

/// Gauss–Newton from x, and where it contracts too slowly for the method's corrector (θ above its
/// max_contraction, typically 1/2) once more with θ up to 0.9: a midpoint far from a strongly
/// curved M (cstr, an edge 0.2 long) is often first overshot.
bool project_patiently(const ImplicitProblem& problem, Eigen::VectorXd& x,
                       const SampleSettings& settings, Linearization& workspace);

/// What one pass's samples found, per pair of the pass (in its order).
struct PassSamples {
  std::vector<double> worst;      ///< the triangle's largest sampled distance (+∞: unmeasured)
  std::vector<int> worst_edge;    ///< the boundary edge whose gap is the worst sample, else −1
  std::vector<int> worst_sample;  ///< 0 centroid, 1 + e midpoint of edge e, 4 circumcentre,
                                  ///< 5 the model between them (at the centroid)
  bool interrupted = false;       ///< a stop request ended the pass before it was measured
};

/// Measures the triangles' distances to M, pass after pass, remembering what does not change
/// (vertices never move): an edge's midpoint is measured once for both its triangles, a
/// boundary edge's gap beyond ∂S once.
class TriangleSampler {
 public:
  /// \param shared  the state of a sparse problem's samples (and of the bisection's projections)
  /// \param is_stop_requested  polled on the calling thread only: between triangles on one
  ///        thread, between blocks of anchor groups on several.
  TriangleSampler(const ImplicitProblem& problem, const Domain& domain, const TriangleMesh& mesh,
                  const SampleSettings& settings, SampleState& shared,
                  std::function<bool()> is_stop_requested);

  /// Samples the triangles of `pairs` ((anchor, triangle), grouped by anchor: each
  /// anchor's pairs next to each other). `gram`: the Gram
  /// numbers of these triangles; `triangles_at_edge`: every edge's triangles (empty for an
  /// unbounded domain: no gaps). The same results whatever the thread count.
  /// `may_stop`: whether a stop request may end the pass (PassSamples::interrupted).
  PassSamples sample(const std::vector<std::pair<int, int>>& pairs, const std::vector<Gram>& gram,
                     const std::unordered_map<std::uint64_t, int>& triangles_at_edge,
                     bool may_stop);

  /// The point of triangle t where `worst_sample` lies (PassSamples), for messages.
  Eigen::VectorXd sample_point(int t, int worst_sample, const std::vector<Gram>& gram) const;

 private:
  // The samples of one triangle, measured in phase 1 (on any thread).
  struct Measured {
    std::array<double, 5> distance{};  // centroid, the midpoints it measures, circumcentre last
    int count = 0;
    bool has_circumcentre = false;
    std::array<double, 3> gap{};  // of the boundary edges it measures
  };
  // Which samples a triangle measures for the others (bit e: edge e).
  struct Claims {
    std::uint8_t midpoints = 0;
    std::uint8_t gaps = 0;
  };
  void measure(int anchor, int t, Claims claims, const std::vector<Gram>& gram, SampleState& state,
               Measured& out) const;
  double distance_without_anchor(const Eigen::VectorXd& point, const Triangle& tri,
                                 SampleState& state) const;
  double gap(int u, int v, SampleState& state) const;
  bool has_circumcentre(const Gram& g, double& beta, double& gamma) const;

  const ImplicitProblem& problem_;
  const Domain& domain_;
  const TriangleMesh& mesh_;
  const SampleSettings& settings_;
  SampleState& shared_;
  std::function<bool()> is_stop_requested_;
  std::unordered_map<std::uint64_t, double> midpoint_distance_;
  std::unordered_map<std::uint64_t, double> boundary_gap_;
};

}  // namespace tessera::detail
