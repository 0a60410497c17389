// SPDX-License-Identifier: MIT
// The covering methods the command line offers, by name: `tessera mesh --method NAME` and
// `tessera compare` go through this one list. Adding a method = one entry in covering_methods().
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "tessera/methods/covering_result.h"
#include "tessera/problems/problem_setup.h"

namespace tessera::app {

/// What the user asked for, in method-neutral terms plus each method's own knobs.
/// A value of 0 (or empty) means "the method's default".
struct MethodSettings {
  double step = 0.0;       ///< edge length h; 0: the problem's suggested step
  double tolerance = 0.0;  ///< bound on the distance of the mesh to M (adaptive methods)
  int max_vertices = 2'000'000;
  double max_start_distance = 0.0;  ///< in ambient units; 0: the method's default
  ProgressCallback progress;
  // atlas
  std::string atlas_placement = "disk";
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
  bool uses_tolerance = false;  ///< --tolerance applies (adaptive step); else it is refused
  /// Covers setup's manifold from setup.start in setup.domain.
  std::function<CoveringResult(const ProblemSetup&, const MethodSettings&)> run;
};

/// All methods, the default first.
const std::vector<CoveringMethod>& covering_methods();

/// The names, for CLI11's IsMember check.
std::vector<std::string> covering_method_names();

/// \throw InvalidArgument naming the unknown method and the known ones.
const CoveringMethod& find_covering_method(const std::string& name);

}  // namespace tessera::app
