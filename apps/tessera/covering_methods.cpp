// SPDX-License-Identifier: MIT
#include "covering_methods.h"

#include <algorithm>
#include <cmath>

#include "tessera/core/error.h"
#include "tessera/methods/atlas/atlas.h"
#include "tessera/methods/bezier/bezier_continuation.h"
#include "tessera/methods/front/advancing_front.h"

namespace tessera::app {
namespace {

// Defaults tied to the problem's suggested step h, the one length scale every catalogue entry
// and problem file gives: charts up to 2h across flat parts, and a distance bound of h/50
// (on the unit sphere with h = 0.3: ε = 0.006, radius 0.11, about 700 vertices).
CoveringResult run_atlas(const ProblemSetup& setup, const MethodSettings& settings) {
  AtlasOptions options;
  const double h = settings.step > 0 ? settings.step : 2.0 * setup.suggested_step;
  options.max_radius = h;
  options.tolerance = settings.tolerance > 0 ? settings.tolerance : 0.02 * setup.suggested_step;
  options.max_vertices = settings.max_vertices;
  options.placement =
      settings.atlas_placement == "hexagonal" ? AtlasPlacement::Hexagonal : AtlasPlacement::Disk;
  if (settings.max_start_distance > 0) {
    options.max_start_distance = settings.max_start_distance;
  }
  options.progress = settings.progress;
  return cover_by_atlas(*setup.problem, setup.start, setup.domain, options);
}

CoveringResult run_front(const ProblemSetup& setup, const MethodSettings& settings) {
  FrontOptions options;
  options.step = settings.step > 0 ? settings.step : setup.suggested_step;
  options.max_vertices = settings.max_vertices;
  if (settings.front_min_gap_degrees > 0) {
    options.min_gap_angle = settings.front_min_gap_degrees * M_PI / 180.0;
  }
  if (settings.front_max_valence > 0) {
    options.max_valence = settings.front_max_valence;
  }
  options.order =
      settings.front_order == "fifo" ? FrontOrder::Fifo : FrontOrder::SmallestGapFirst;
  if (settings.max_start_distance > 0) {
    options.max_start_distance_steps = settings.max_start_distance / options.step;
  }
  options.progress = settings.progress;
  return triangulate_by_front(*setup.problem, setup.start, setup.domain, options);
}

CoveringResult run_bezier(const ProblemSetup& setup, const MethodSettings& settings) {
  BezierOptions options;
  options.initial_step = settings.step > 0 ? settings.step : setup.suggested_step;
  if (settings.bezier_max_step > 0) {
    options.max_step = std::max(settings.bezier_max_step, options.initial_step);
  }
  options.tolerance = settings.tolerance;
  if (settings.bezier_edge_length_factor > 0) {
    options.edge_length_factor = settings.bezier_edge_length_factor;
  }
  if (settings.bezier_min_tangent_cosine > 0) {
    options.min_tangent_cosine = settings.bezier_min_tangent_cosine;
  }
  options.max_vertices = settings.max_vertices;
  options.max_start_distance = settings.max_start_distance;
  options.progress = settings.progress;
  BezierResult bezier =
      triangulate_by_bezier_continuation(*setup.problem, setup.start, setup.domain, options);
  bezier.summary.tolerance = options.tolerance;  // so that `compare` shows the bound asked for
  return {std::move(bezier.mesh), std::move(bezier.summary), std::move(bezier.patches)};
}

}  // namespace

const std::vector<CoveringMethod>& covering_methods() {
  static const std::vector<CoveringMethod> methods = {
      {"atlas", "atlas of curvature-adapted charts, any topology (Henderson)", true, run_atlas},
      {"front", "advancing front with fixed step h (Brodzik & Rheinboldt, PITMAN)", false,
       run_front},
      {"bezier",
       "adaptive continuation with Gauss-Newton step control and cubic Bezier patches "
       "(Hohmann)",
       true, run_bezier},
  };
  return methods;
}

std::vector<std::string> covering_method_names() {
  std::vector<std::string> names;
  for (const auto& method : covering_methods()) {
    names.push_back(method.name);
  }
  return names;
}

const CoveringMethod& find_covering_method(const std::string& name) {
  std::string known;
  for (const auto& method : covering_methods()) {
    if (method.name == name) {
      return method;
    }
    known += (known.empty() ? "" : ", ") + method.name;
  }
  throw InvalidArgument("--method '" + name + "' is not available; methods: " + known);
}

}  // namespace tessera::app
