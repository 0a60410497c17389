// SPDX-License-Identifier: MIT
// Several components of M in one run (`tessera mesh --components all`, `--start` given more
// than once): every start, and with the search every seed spread over the region, is projected
// onto M; one that lands where no component covered so far reaches starts a covering of its
// own, by the run skeleton of the chosen method. The result is one mesh of several components.
// docs/components.md.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <limits>
#include <vector>

#include "tessera/methods/covering_methods.h"
#include "tessera/methods/covering_result.h"

namespace tessera {

class Domain;
class ImplicitProblem;

struct ComponentSearchOptions {
  /// Search the region for every component (seeds over it) after the starts; false: the
  /// components of the starts only.
  bool every_component = false;
  /// Seeds of the search, the points of a Halton sequence in the region's box (their mean
  /// spacing, (volume/seeds)^(1/d), is reported: components smaller than it may be missed).
  /// 512: a spacing of an eighth of the box's side in R^3.
  int seed_count = 512;
  /// How far the starts given may be from M (ambient units, in the problem's coordinates);
  /// +∞: no limit. The seeds may move across the seeded box: a seed lands on M wherever
  /// Gauss–Newton takes it.
  double max_start_distance = std::numeric_limits<double>::infinity();
  /// The vertex budget of all components together; each covering gets what is left.
  int max_vertices = 2'000'000;
  /// The run's distance bound (0: none), in the metric: points this close to a triangle more
  /// than the coverage reach count as covered (ComponentCoverage).
  double tolerance = 0.0;
  StopRequest stop_requested;  ///< polled before every start and seed
};

/// One covering asked of the caller: cover M from `start` (on M, inside the domain) with at
/// most `max_vertices` vertices.
struct ComponentRequest {
  Eigen::VectorXd start;
  /// True for the first start given: the component a run of one start would cover, whose
  /// topology the problem may declare (ProblemSetup::expected_euler_characteristic).
  bool is_first_start = false;
  int max_vertices = 0;
};
using CoverComponent = std::function<CoveringResult(const ComponentRequest&)>;

/// Covers the components of M ∩ `domain` that `starts` lie on and, with
/// options.every_component, those that seeds over the region land on.
///
/// Starts first, in order, then the seeds: each is projected onto M (Gauss–Newton, as the run
/// skeleton's start); one whose projection fails or leaves the domain is passed over (a start
/// with its reason in summary.starts); one that lands within reach of a component covered
/// before is passed over (ComponentCoverage); the others start a component,
/// `cover_component(request)`. The search stops at the first covering that does not complete
/// (its termination and message, "component K (seed J): …", become the run's), at the vertex
/// limit and at a stop request.
///
/// \return one mesh: the components' meshes one after the other (vertex indices disjoint,
///         each component valid as its covering left it), their cubic patches likewise, and a
///         summary that adds up the coverings' work (plus a phase "seeds" for the projections)
///         and lists each component (summary.components), what became of each start
///         (summary.starts) and the search (summary.component_search). StartFailed and an empty
///         mesh if no start or seed led to a component.
/// \throw InvalidArgument for a distributed problem (not available), no starts without the
///        search, a search in a domain that bounds no coordinate on both sides, starts of the
///        wrong size, or seed_count < 1.
CoveringResult cover_components(const ImplicitProblem& problem, const Domain& domain,
                                const std::vector<Eigen::VectorXd>& starts,
                                const ComponentSearchOptions& options,
                                const CoverComponent& cover_component);

/// The same for a ProblemSetup and a method of the registry: each component by
/// tessera::cover(setup with that start, method, settings), the expected topology of setup
/// held to the first start's component only (setup.start and expected_euler_characteristic
/// change during the call and are restored). `starts` empty: setup.start alone. The starts'
/// distance limit is settings.max_start_distance, else ten steps (settings.step, else twice
/// the problem's suggested step, the atlas's default step).
CoveringResult cover_components(ProblemSetup& setup, const CoveringMethod& method,
                                const MethodSettings& settings,
                                const std::vector<Eigen::VectorXd>& starts,
                                ComponentSearchOptions options);

}  // namespace tessera
