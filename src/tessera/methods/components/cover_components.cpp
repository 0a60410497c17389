// SPDX-License-Identifier: MIT
#include "tessera/methods/components/cover_components.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include "tessera/core/counted_problem.h"
#include "tessera/core/domain.h"
#include "tessera/core/error.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/methods/components/component_coverage.h"
#include "tessera/methods/components/component_seeds.h"
#include "tessera/methods/start_point.h"

namespace tessera {
namespace {

// Adds one covering's counters to the run's; the first covering also gives the run's method,
// step and tolerance.
void add_work(CoveringSummary& total, const CoveringSummary& part, bool is_first) {
  if (is_first) {
    total.method = part.method;
    total.step = part.step;
    total.tolerance = part.tolerance;
    total.min_chart_radius = part.min_chart_radius;
    total.max_chart_radius = part.max_chart_radius;
  } else {
    total.min_chart_radius = std::min(total.min_chart_radius, part.min_chart_radius);
    total.max_chart_radius = std::max(total.max_chart_radius, part.max_chart_radius);
  }
  total.function_evaluations += part.function_evaluations;
  total.jacobian_evaluations += part.jacobian_evaluations;
  total.factorisations += part.factorisations;
  total.solves += part.solves;
  total.factorisation_seconds += part.factorisation_seconds;
  total.threads = part.threads;  // the same problem: the same for every part
  for (const PhaseWork& phase : part.work_by_phase) {
    auto same = std::find_if(total.work_by_phase.begin(), total.work_by_phase.end(),
                             [&](const PhaseWork& p) { return p.phase == phase.phase; });
    if (same == total.work_by_phase.end()) {
      total.work_by_phase.push_back(phase);
    } else {
      same->counts += phase.counts;
      same->wall_seconds += phase.wall_seconds;
    }
  }
  total.merges += part.merges;
  total.step_reductions += part.step_reductions;
  total.front_connections += part.front_connections;
  total.clipped_half_spaces = std::max(total.clipped_half_spaces, part.clipped_half_spaces);
  total.charts += part.charts;
  total.radius_caps.curvature += part.radius_caps.curvature;
  total.radius_caps.not_a_graph += part.radius_caps.not_a_graph;
  total.radius_caps.grading += part.radius_caps.grading;
  total.radius_caps.reach += part.radius_caps.reach;
  total.radius_caps.band += part.radius_caps.band;
  total.radius_caps.reduced_later += part.radius_caps.reduced_later;
  total.singular_crossings += part.singular_crossings;
  total.sheet_rejections += part.sheet_rejections;
  total.filled_holes += part.filled_holes;
  total.borrowed_factorisations += part.borrowed_factorisations;
  total.boundary_peak_bytes = std::max(total.boundary_peak_bytes, part.boundary_peak_bytes);
  total.resident_peak_bytes = std::max(total.resident_peak_bytes, part.resident_peak_bytes);
  total.resident_beyond_boundary_peak_bytes =
      std::max(total.resident_beyond_boundary_peak_bytes, part.resident_beyond_boundary_peak_bytes);
  total.refined_edges += part.refined_edges;
  total.max_sampled_distance = std::max(total.max_sampled_distance, part.max_sampled_distance);
  total.removed_triangles += part.removed_triangles;
  total.repaired_holes += part.repaired_holes;
}

// "start 2" or "seed 17" (from 1), as the summary names where a component came from.
std::string origin_name(bool is_start, int index) {
  return (is_start ? "start " : "seed ") + std::to_string(index + 1);
}

// The run being assembled: the mesh of the components so far, the summary, the coverage test.
class ComponentRun {
 public:
  ComponentRun(const ImplicitProblem& problem, const ComponentSearchOptions& options)
      : options_(options), coverage_(result_.mesh, metric_weights(problem), options.tolerance) {
    result_.mesh = TriangleMesh(problem.ambient_dimension());
  }

  /// The component covering x on M, or −1.
  int covering_component(const Eigen::VectorXd& x) const { return coverage_.covering_component(x); }

  /// Whether the search may go on: no failure, no stop request, vertices left for a component.
  bool may_continue() {
    if (!result_.summary.is_complete()) {
      return false;
    }
    if (options_.stop_requested && options_.stop_requested()) {
      result_.summary.record_failure(
          CoveringTermination::Interrupted,
          "stopped on request after " + std::to_string(component_count()) + " component(s)");
      return false;
    }
    if (vertices_left() < 3) {
      result_.summary.record_failure(CoveringTermination::VertexLimit,
                                     "the vertex limit " + std::to_string(options_.max_vertices) +
                                         " was reached after " + std::to_string(component_count()) +
                                         " component(s); components not yet found "
                                         "are missing");
      return false;
    }
    return true;
  }

  int vertices_left() const { return options_.max_vertices - result_.mesh.vertex_count(); }
  int component_count() const { return static_cast<int>(result_.summary.components.size()); }

  /// Appends the covering `part`, started at `start` by `origin`, as the next component.
  /// \return its index, or −1 if it made no triangle (its start failed: passed over).
  int add(CoveringResult part, const Eigen::VectorXd& start, const std::string& origin) {
    const bool is_first = component_count() == 0 && !has_work_;
    add_work(result_.summary, part.summary, is_first);
    has_work_ = true;
    if (part.mesh.triangle_count() == 0) {
      if (part.summary.termination != CoveringTermination::StartFailed) {
        result_.summary.record_failure(
            part.summary.termination,
            "the covering from " + origin + " made no triangle: " + part.summary.message);
      }
      return -1;
    }
    ComponentRecord record;
    record.origin = origin;
    record.start = start;
    record.first_vertex = result_.mesh.vertex_count();
    record.vertex_count = part.mesh.vertex_count();
    record.first_triangle = result_.mesh.triangle_count();
    record.triangle_count = part.mesh.triangle_count();
    const MeshValidation validation = validate(part.mesh);
    record.euler_characteristic = validation.euler_characteristic;
    record.boundary_loop_count = validation.boundary_loop_count;
    record.genus = validation.genus;
    record.termination = part.summary.termination;
    record.message = part.summary.message;
    TriangleMesh& mesh = result_.mesh;
    mesh.reserve(mesh.vertex_count() + part.mesh.vertex_count(),
                 mesh.triangle_count() + part.mesh.triangle_count());
    for (int v = 0; v < part.mesh.vertex_count(); ++v) {
      mesh.add_vertex(part.mesh.point(v));
    }
    for (const Triangle& t : part.mesh.triangles()) {
      mesh.add_triangle(t[0] + record.first_vertex, t[1] + record.first_vertex,
                        t[2] + record.first_vertex);
    }
    result_.patches.insert(result_.patches.end(), part.patches.begin(), part.patches.end());
    if (is_first) {
      result_.patch_edge_length_factor = part.patch_edge_length_factor;
    }
    const int index = component_count();
    for (const std::string& note : part.summary.notes) {
      if (note == kStartComponentNote) {  // the search's own note says what it covered
        continue;
      }
      result_.summary.notes.push_back("component " + std::to_string(index + 1) + ": " + note);
    }
    if (!part.summary.is_complete()) {
      result_.summary.record_failure(
          part.summary.termination,
          "component " + std::to_string(index + 1) + " (" + origin + "): " + part.summary.message);
    }
    result_.summary.components.push_back(std::move(record));
    coverage_.add_component();
    return index;
  }

  CoveringResult& result() { return result_; }

 private:
  const ComponentSearchOptions& options_;
  CoveringResult result_;
  ComponentCoverage coverage_;
  bool has_work_ = false;
};

}  // namespace

CoveringResult cover_components(const ImplicitProblem& problem, const Domain& domain,
                                const std::vector<Eigen::VectorXd>& starts,
                                const ComponentSearchOptions& options,
                                const CoverComponent& cover_component) {
  const auto clock_start = std::chrono::steady_clock::now();
  const int n = problem.ambient_dimension();
  TESSERA_CHECK(!problem.space()->is_distributed(),
                "several components (--components all, or more than one --start) are not yet "
                "available for a distributed problem (--backend petsc): cover one start's "
                "component per run");
  TESSERA_CHECK(!starts.empty() || options.every_component,
                "cover_components: no start given and no search asked for");
  TESSERA_CHECK(options.seed_count >= 1, "ComponentSearchOptions::seed_count = "
                                             << options.seed_count << " must be at least 1");
  for (const Eigen::VectorXd& start : starts) {
    TESSERA_CHECK(start.size() == n,
                  "start point has " << start.size() << " coordinates, the problem n = " << n);
  }
  SeededBox box;
  if (options.every_component) {
    box = seeded_box(domain);
    TESSERA_CHECK(!box.is_empty(),
                  "--components all searches a bounded region, but the domain "
                      << (domain.is_unbounded() ? "is all of R^" + std::to_string(n)
                                                : "(" + domain.describe() + ")")
                      << " bounds no coordinate on both sides: give a box, e.g. --box "
                         "-2,2,-2,2,-2,2, or bounds on the coordinates to search, e.g. --box "
                         "lambda=0:4");
  }
  // The projections of starts and seeds are counted as the run's phase "seeds".
  const CountedProblem counted(problem);
  ComponentRun run(problem, options);
  CoveringSummary& summary = run.result().summary;
  const auto try_point = [&](const Eigen::VectorXd& guess, double max_distance, bool is_start,
                             int index, StartRecord* record) {
    const std::string origin = origin_name(is_start, index);
    Eigen::VectorXd on_manifold;
    try {
      on_manifold = project_start_point(counted, guess, domain, max_distance).x;
    } catch (const ComputationFailed& failure) {
      if (record != nullptr) {
        record->message = failure.what();
      } else {
        ++summary.component_search->seeds_not_projected;
      }
      return;
    }
    if (record != nullptr) {
      record->on_manifold = on_manifold;
    }
    const int covered_by = run.covering_component(on_manifold);
    if (covered_by >= 0) {
      if (record != nullptr) {
        record->component = covered_by;
      } else {
        ++summary.component_search->seeds_on_covered;
      }
      return;
    }
    ComponentRequest request{on_manifold, is_start && index == 0, run.vertices_left()};
    const int component = run.add(cover_component(request), on_manifold, origin);
    if (record != nullptr) {
      record->component = component;
      record->started_component = component >= 0;
      if (component < 0) {
        record->message = "its covering made no triangle";
      }
    } else if (component >= 0) {
      ++summary.component_search->seeds_started;
    } else {
      ++summary.component_search->seeds_not_projected;
    }
  };
  for (int i = 0; i < static_cast<int>(starts.size()); ++i) {
    StartRecord record;
    record.guess = starts[static_cast<std::size_t>(i)];
    if (run.may_continue()) {
      try_point(record.guess, options.max_start_distance, true, i, &record);
    } else {
      record.message = "not tried: the run stopped before it";
    }
    summary.starts.push_back(std::move(record));
  }
  if (options.every_component) {
    ComponentSearchRecord search;
    search.seed_count = options.seed_count;
    search.seed_spacing = seed_spacing(box, options.seed_count, metric_weights(problem));
    const std::vector<std::string> names = problem.coordinate_names();
    for (int coordinate : box.coordinates) {
      search.seeded_coordinates.push_back(names.at(static_cast<std::size_t>(coordinate)));
    }
    summary.component_search = search;
    const Eigen::VectorXd reference =
        starts.empty() ? Eigen::VectorXd(Eigen::VectorXd::Zero(n)) : starts.front();
    const Eigen::MatrixXd seeds = halton_seeds(box, reference, options.seed_count);
    // A seed may land anywhere in the region: the limit is the seeded box's diagonal.
    const double max_distance = (box.upper - box.lower).norm();
    for (int j = 0; j < options.seed_count; ++j) {
      if (!run.may_continue()) {
        summary.component_search->seeds_not_tried = options.seed_count - j;
        break;
      }
      try_point(seeds.col(j), max_distance, false, j, nullptr);
    }
  }
  if (run.component_count() == 0 && summary.is_complete()) {
    std::string message = "no start or seed led to a component of M in the domain";
    for (std::size_t i = 0; i < summary.starts.size(); ++i) {
      if (!summary.starts[i].message.empty()) {
        message += "; start " + std::to_string(i + 1) + ": " + summary.starts[i].message;
      }
    }
    summary.record_failure(CoveringTermination::StartFailed, message);
  }
  if (options.every_component) {
    std::ostringstream note;
    note.precision(3);
    note << "searched the region with " << options.seed_count << " seeds (spacing "
         << summary.component_search->seed_spacing
         << "): a component smaller than the spacing, one that no seed's projection reaches, "
            "or one nearer to another than a quarter of the step may be missing";
    summary.notes.push_back(note.str());
  } else {
    summary.notes.push_back("covered the components of the " + std::to_string(starts.size()) +
                            " starts; other components, if any, need their own start points "
                            "(or --components all)");
  }
  const WorkCounts seeds = counted.counts();
  summary.function_evaluations += seeds.function_evaluations;
  summary.jacobian_evaluations += seeds.jacobian_evaluations;
  summary.factorisations += seeds.factorisations;
  summary.factorisation_seconds += counted.factorisation_seconds();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  double covering_seconds = 0.0;
  for (const PhaseWork& phase : summary.work_by_phase) {
    covering_seconds += phase.wall_seconds;
  }
  summary.work_by_phase.insert(
      summary.work_by_phase.begin(),
      PhaseWork{"seeds", seeds, std::max(0.0, seconds - covering_seconds)});
  summary.vertex_count = run.result().mesh.vertex_count();
  summary.triangle_count = run.result().mesh.triangle_count();
  summary.wall_seconds = seconds;
  return std::move(run.result());
}

CoveringResult cover_components(ProblemSetup& setup, const CoveringMethod& method,
                                const MethodSettings& settings,
                                const std::vector<Eigen::VectorXd>& starts,
                                ComponentSearchOptions options) {
  const double step = settings.step > 0 ? settings.step : 2.0 * setup.suggested_step;
  options.max_start_distance =
      settings.max_start_distance > 0 ? settings.max_start_distance : 10.0 * step;
  options.max_vertices = settings.max_vertices;
  if (!options.stop_requested) {
    options.stop_requested = settings.stop_requested;
  }
  if (options.tolerance <= 0) {
    options.tolerance = settings.tolerance;
  }
  // setup.start and the expected topology are the first start's; put back on every exit.
  struct Restore {
    ProblemSetup& setup;
    Eigen::VectorXd start;
    std::optional<int> euler;
    ~Restore() {
      setup.start = std::move(start);
      setup.expected_euler_characteristic = euler;
    }
  } restore{setup, setup.start, setup.expected_euler_characteristic};
  const std::vector<Eigen::VectorXd> given =
      starts.empty() ? std::vector<Eigen::VectorXd>{setup.start} : starts;
  MethodSettings component_settings = settings;
  CoveringResult result = cover_components(
      *setup.problem, setup.domain, given, options, [&](const ComponentRequest& request) {
        setup.start = request.start;
        setup.expected_euler_characteristic = request.is_first_start ? restore.euler : std::nullopt;
        component_settings.max_vertices = request.max_vertices;
        return cover(setup, method, component_settings);
      });
  result.summary.method = method.name;
  return result;
}

}  // namespace tessera
