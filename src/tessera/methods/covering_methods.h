// SPDX-License-Identifier: MIT
// The covering methods by name: `tessera mesh --method NAME`, `tessera compare` and the
// bindings go through this one list. Adding a method = one folder and one entry in
// covering_methods().
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "tessera/methods/atlas/atlas_checkpoint.h"
#include "tessera/methods/front/front_checkpoint.h"
#include "tessera/methods/covering_result.h"
#include "tessera/problems/problem_setup.h"

namespace tessera {

/// What the user asked for, in method-neutral terms plus each method's own knobs.
/// A value of 0 (or empty) means "the method's default".
struct MethodSettings {
  double step = 0.0;  ///< the method's length scale; 0: derived from the problem's suggestion
  /// Bound on the distance of every output triangle to M, for every method (refinement by
  /// bisection enforces it); 0: atlas step/50·…, see each method; front and bezier: no bound.
  double tolerance = 0.0;
  int max_vertices = 2'000'000;
  double max_start_distance = 0.0;  ///< in ambient units; 0: the method's default
  ProgressCallback progress;
  StopRequest stop_requested;  ///< see StopRequest; empty: the run is never interrupted
  /// CoveringOptions::check_seconds_after_stop; negative: its default (kCheckSecondsAfterStop).
  double check_seconds_after_stop = -1.0;
  // atlas
  /// "auto" (the default): "hexagonal" where DF is dense and the domain unbounded (small n: a
  /// factorisation costs a few evaluations of F, and the hexagonal atlas's smoothing
  /// projections are cheap; 30 % fewer vertices in the same time), "disk" where DF is sparse
  /// (each smoothing projection is a factorisation: 6× the factorisations and 1.3× the time at
  /// n = 52 already) or the domain bounded (the disk rule's row of charts snapped onto ∂S keeps
  /// the clipped boundary's angles: 18–20° against 9° on whitney_pleat and trough).
  std::string atlas_placement = "auto";  ///< with a checkpoint, "auto" is "disk"
  AtlasCheckpointing atlas_checkpoint;  ///< checkpoints and resuming (method atlas only)
  FrontCheckpointing front_checkpoint;  ///< checkpoints and resuming (method front only)
  double atlas_chart_tolerance = 0.0;   ///< AtlasOptions::chart_tolerance (0: the tolerance)
  // front
  double front_min_gap_degrees = 0.0;
  int front_max_valence = 0;
  std::string front_order = "gap";
  // bezier (0: the method's default)
  double bezier_max_step = 0.0;            ///< upper bound on the step; 0: 8 × initial step
  double bezier_edge_length_factor = 0.0;  ///< l_ij/‖y_j − y_i‖ of eq. 3.4 (paper 1.2)
  double bezier_min_tangent_cosine = 0.0;  ///< α_min (paper 0.8)
};

struct CoveringMethod {
  std::string name;     ///< e.g. "front"
  std::string summary;  ///< one line for --help and `tessera compare`
  /// Covers setup's manifold from setup.start in setup.domain (the method's own entry point,
  /// with options derived from the settings and the problem's suggested step).
  std::function<CoveringResult(const ProblemSetup&, const MethodSettings&)> run;
};

/// The distance bound of a run that asks for none (MethodSettings::tolerance 0) where one is
/// needed: the atlas's, which sizes its charts by it, and `tessera compare`'s for every method,
/// so that its rows are comparable. A fiftieth of the problem's suggested step.
double default_tolerance(const ProblemSetup& setup);

/// All methods, the default first.
const std::vector<CoveringMethod>& covering_methods();

/// The names, for CLI11's IsMember check.
std::vector<std::string> covering_method_names();

/// \throw InvalidArgument naming the unknown method and the known ones.
const CoveringMethod& find_covering_method(const std::string& name);

/// Runs `method` on `setup` and holds the result to what is known of M: a run that reports
/// Completed but whose mesh has another Euler characteristic than the one expected of the
/// component (setup.expected_euler_characteristic) is turned into TriangulationFailed, with the
/// counts in the message. This is what the command line and the bindings call.
CoveringResult cover(const ProblemSetup& setup, const CoveringMethod& method,
                     const MethodSettings& settings);

/// A method's own options given to another method would be ignored silently: refuses them
/// (InvalidArgument naming them), as the command line spells them (`--max-step`) or, with
/// `keyword_names`, as the bindings do (`max_step`).
void refuse_options_of_other_methods(const MethodSettings& given, const std::string& method,
                                     bool keyword_names);

}  // namespace tessera
