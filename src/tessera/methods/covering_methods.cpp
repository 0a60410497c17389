// SPDX-License-Identifier: MIT
#include "tessera/methods/covering_methods.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "tessera/core/error.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/methods/atlas/atlas.h"
#include "tessera/methods/bezier/bezier_continuation.h"
#include "tessera/methods/front/advancing_front.h"

namespace tessera {
namespace {

// The settings every method shares; a 0 leaves the option's default.
void apply_shared_settings(const MethodSettings& settings, CoveringOptions& options) {
  if (settings.tolerance > 0) {
    options.tolerance = settings.tolerance;
  }
  options.max_vertices = settings.max_vertices;
  if (settings.max_start_distance > 0) {
    options.max_start_distance = settings.max_start_distance;
  }
  options.progress = settings.progress;
  options.stop_requested = settings.stop_requested;
  if (settings.check_seconds_after_stop >= 0) {
    options.check_seconds_after_stop = settings.check_seconds_after_stop;
  }
}

// Defaults tied to the problem's suggested step h, the one length scale every catalogue entry
// and problem file gives: charts up to 2h across flat parts, and a distance bound of h/50
// (on the unit sphere with h = 0.3: ε = 0.006, radius 0.11, about 700 vertices).
CoveringResult run_atlas(const ProblemSetup& setup, const MethodSettings& settings) {
  AtlasOptions options;
  options.step = settings.step > 0 ? settings.step : 2.0 * setup.suggested_step;
  options.tolerance = default_tolerance(setup);
  apply_shared_settings(settings, options);
  options.checkpoint = settings.atlas_checkpoint;
  options.chart_tolerance = settings.atlas_chart_tolerance;
  // A checkpointed run takes the disk rule under "auto": its fallback from the hexagonal
  // placement would otherwise start a second build that a resumed run cannot tell apart.
  const bool checkpointed = settings.atlas_checkpoint.save || settings.atlas_checkpoint.resume_from;
  const bool automatic = settings.atlas_placement == "auto" && !checkpointed;
  const bool hexagonal =
      settings.atlas_placement == "hexagonal" ||
      (automatic && !setup.problem->has_sparse_jacobian() && setup.domain.is_unbounded());
  options.placement = hexagonal ? AtlasPlacement::Hexagonal : AtlasPlacement::Disk;
  CoveringResult result = cover_by_atlas(*setup.problem, setup.start, setup.domain, options);
  const CoveringTermination ended = result.summary.termination;
  if (!automatic || !hexagonal || (ended != CoveringTermination::TriangulationFailed &&
                                   ended != CoveringTermination::ProjectionFailed)) {
    return result;
  }
  // The hexagonal placement's packing is tighter than the disk rule's, and at coarse settings
  // (charts a sixth of the sphere's radius) its polygons can leave a hole that cannot be
  // triangulated, where the disk rule's never have in the stress campaigns: chosen
  // automatically, it falls back to the disk rule, which keeps the run as robust as before.
  // The first attempt's work is counted, as a step of its own.
  const CoveringSummary first = result.summary;
  options.placement = AtlasPlacement::Disk;
  result = cover_by_atlas(*setup.problem, setup.start, setup.domain, options);
  CoveringSummary& summary = result.summary;
  summary.function_evaluations += first.function_evaluations;
  summary.jacobian_evaluations += first.jacobian_evaluations;
  summary.factorisations += first.factorisations;
  summary.factorisation_seconds += first.factorisation_seconds;
  summary.wall_seconds += first.wall_seconds;
  PhaseWork attempt{"hexagonal attempt",
                    {first.function_evaluations, first.jacobian_evaluations,
                     first.factorisations},
                    first.wall_seconds};
  summary.work_by_phase.insert(summary.work_by_phase.begin(), attempt);
  summary.notes.push_back("the hexagonal placement (--placement auto) ended early (" +
                          first.message + "); covered again with the disk placement");
  return result;
}

CoveringResult run_front(const ProblemSetup& setup, const MethodSettings& settings) {
  FrontOptions options;
  options.step = settings.step > 0 ? settings.step : setup.suggested_step;
  apply_shared_settings(settings, options);
  if (settings.front_min_gap_degrees > 0) {
    options.min_gap_angle = settings.front_min_gap_degrees * M_PI / 180.0;
  }
  if (settings.front_max_valence > 0) {
    options.max_valence = settings.front_max_valence;
  }
  options.order = settings.front_order == "fifo" ? FrontOrder::Fifo : FrontOrder::SmallestGapFirst;
  options.checkpoint = settings.front_checkpoint;
  return triangulate_by_front(*setup.problem, setup.start, setup.domain, options);
}

CoveringResult run_bezier(const ProblemSetup& setup, const MethodSettings& settings) {
  BezierOptions options;
  options.step = settings.step > 0 ? settings.step : setup.suggested_step;
  apply_shared_settings(settings, options);
  if (settings.bezier_max_step > 0) {
    options.max_step = std::max(settings.bezier_max_step, options.step);
  }
  if (settings.bezier_edge_length_factor > 0) {
    options.edge_length_factor = settings.bezier_edge_length_factor;
  }
  if (settings.bezier_min_tangent_cosine > 0) {
    options.min_tangent_cosine = settings.bezier_min_tangent_cosine;
  }
  return triangulate_by_bezier_continuation(*setup.problem, setup.start, setup.domain, options);
}

}  // namespace

double default_tolerance(const ProblemSetup& setup) { return 0.02 * setup.suggested_step; }

const std::vector<CoveringMethod>& covering_methods() {
  static const std::vector<CoveringMethod> methods = {
      {"atlas", "atlas of curvature-adapted charts, any topology (Henderson)", run_atlas},
      {"front", "advancing front with fixed step h (Brodzik & Rheinboldt, PITMAN)", run_front},
      {"bezier",
       "adaptive continuation with Gauss-Newton step control and cubic Bezier patches "
       "(Hohmann)",
       run_bezier},
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

CoveringResult cover(const ProblemSetup& setup, const CoveringMethod& method,
                     const MethodSettings& settings) {
  CoveringResult result = method.run(setup, settings);
  if (result.summary.is_complete() && setup.expected_euler_characteristic) {
    const MeshValidation validation = validate(result.mesh);
    if (validation.euler_characteristic != *setup.expected_euler_characteristic) {
      std::ostringstream message;
      message << "the mesh has Euler characteristic " << validation.euler_characteristic << " in "
              << validation.component_count << " component(s) with "
              << validation.boundary_loop_count << " boundary loop(s), but the surface has "
              << *setup.expected_euler_characteristic << ": a part of M is missing or was cut off";
      result.summary.termination = CoveringTermination::TriangulationFailed;
      result.summary.message = message.str();
    }
  }
  return result;
}

void refuse_options_of_other_methods(const MethodSettings& given, const std::string& method,
                                     bool keyword_names) {
  const auto spelled = [&](std::string options) {
    if (keyword_names) {  // "--max-step, --edge-length-factor" → "max_step, edge_length_factor"
      std::string keywords;
      for (std::size_t i = 0; i < options.size(); ++i) {
        if (options.compare(i, 2, "--") == 0) {
          ++i;
        } else {
          keywords += options[i] == '-' ? '_' : options[i];
        }
      }
      options = keywords;
    }
    return options;
  };
  const auto refuse_unless = [&](bool applies, const char* options, const char* owner) {
    TESSERA_CHECK(applies, spelled(options) << ": only for method '" << owner
                                            << "', not for method '" << method << "'");
  };
  refuse_unless(given.atlas_placement == "auto" || method == "atlas", "--placement", "atlas");
  refuse_unless(given.atlas_chart_tolerance == 0 || method == "atlas", "--chart-tolerance",
                "atlas");
  refuse_unless((given.front_order == "gap" && given.front_min_gap_degrees == 0 &&
                 given.front_max_valence == 0) ||
                    method == "front",
                "--order, --min-gap-angle, --max-valence", "front");
  refuse_unless((given.bezier_max_step == 0 && given.bezier_edge_length_factor == 0 &&
                 given.bezier_min_tangent_cosine == 0) ||
                    method == "bezier",
                "--max-step, --edge-length-factor, --min-tangent-cosine", "bezier");
}

}  // namespace tessera
