// SPDX-License-Identifier: MIT
#include "cli_support.h"

#include <cctype>
#include <nlohmann/json.hpp>
#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "tessera/core/error.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_validation.h"

namespace tessera::app {

const CLI::Validator& finite_positive() {
  static const CLI::Validator validator(
      [](std::string& text) -> std::string {
        try {
          std::size_t used = 0;
          const double value = std::stod(text, &used);
          if (used == text.size() && std::isfinite(value) && value > 0) {
            return {};
          }
        } catch (const std::exception&) {
        }
        return "'" + text + "' is not a finite number > 0";
      },
      "POSITIVE", "finite positive number");
  return validator;
}

std::vector<double> parse_numbers(const std::string& text, const std::string& option) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    std::size_t used = 0;
    double value = 0;
    try {
      value = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    while (used < item.size() && std::isspace(static_cast<unsigned char>(item[used]))) {
      ++used;
    }
    if (item.empty() || used != item.size()) {
      throw InvalidArgument(option + ": '" + item +
                            "' is not a number (expected a "
                            "comma-separated list such as 0,0,1)");
    }
    values.push_back(value);
  }
  return values;
}

namespace {

// "--box name=lower:upper,…": bounds on named coordinates only, either side may be empty
// (unbounded). At large n a box needs 2n numbers; a continuation user bounds the parameters.
Domain named_bounds(const std::string& text, const ImplicitProblem& problem) {
  const int n = problem.ambient_dimension();
  const std::vector<std::string> names = problem.coordinate_names();
  Domain domain(n);
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    const auto equals = item.find('=');
    const auto colon = item.find(':', equals == std::string::npos ? 0 : equals);
    TESSERA_CHECK(equals != std::string::npos && colon != std::string::npos,
                  "--box item '" << item
                                 << "' is not name=lower:upper (e.g. lambda=5:20; either bound may "
                                    "be left empty)");
    const std::string name = item.substr(0, equals);
    const auto found = std::find(names.begin(), names.end(), name);
    TESSERA_CHECK(found != names.end(), "--box names coordinate '"
                                            << name << "', which problem '" << problem.name()
                                            << "' does not have");
    const int i = static_cast<int>(found - names.begin());
    // An empty side is unbounded; a given one is a single finite number.
    const auto parse_side = [&](const std::string& part) -> std::optional<double> {
      if (part.empty()) {
        return std::nullopt;
      }
      const auto values = parse_numbers(part, "--box");
      TESSERA_CHECK(values.size() == 1 && std::isfinite(values[0]),
                    "--box bound '" << part << "' of " << name << " is not one finite number");
      return values[0];
    };
    const std::optional<double> lower = parse_side(item.substr(equals + 1, colon - equals - 1));
    const std::optional<double> upper = parse_side(item.substr(colon + 1));
    TESSERA_CHECK(!lower || !upper || *lower <= *upper,
                  "--box is empty: lower bound " << *lower << " of " << name
                                                 << " exceeds upper bound " << *upper);
    const auto add = [&](double bound, bool is_lower) {
      Eigen::VectorXd normal = Eigen::VectorXd::Zero(n);
      Eigen::VectorXd point = Eigen::VectorXd::Zero(n);
      normal(i) = is_lower ? 1.0 : -1.0;
      point(i) = bound;
      std::ostringstream label;
      label << name << (is_lower ? " >= " : " <= ") << bound;
      domain.add_half_space(normal, point, label.str());
    };
    if (lower) {
      add(*lower, true);
    }
    if (upper) {
      add(*upper, false);
    }
  }
  return domain;
}

}  // namespace

void apply_start_and_box(ProblemSetup& setup, const std::string& start, const std::string& box) {
  const int n = setup.problem->ambient_dimension();
  if (!start.empty()) {
    const auto values = parse_numbers(start, "--start");
    TESSERA_CHECK(static_cast<int>(values.size()) == n,
                  "--start has " << values.size() << " values, problem '" << setup.problem->name()
                                 << "' has n = " << n << " coordinates");
    setup.start = Eigen::Map<const Eigen::VectorXd>(values.data(), n);
  }
  if (!box.empty() && box.find('=') != std::string::npos) {
    setup.domain.intersect_with(named_bounds(box, *setup.problem));
    setup.expected_euler_characteristic.reset();
    setup.exact_area.reset();
  } else if (!box.empty()) {
    const auto values = parse_numbers(box, "--box");
    TESSERA_CHECK(static_cast<int>(values.size()) == 2 * n,
                  "--box has " << values.size() << " values, expected " << 2 * n
                               << " (lower,upper for each of the " << n << " coordinates)");
    Eigen::VectorXd lower(n);
    Eigen::VectorXd upper(n);
    for (int i = 0; i < n; ++i) {
      lower(i) = values[2 * i];
      upper(i) = values[2 * i + 1];
    }
    setup.domain.intersect_with(Domain::box(lower, upper, setup.problem->coordinate_names()));
    // The catalogue's topology and area describe its own domain, not the user's box.
    setup.expected_euler_characteristic.reset();
    setup.exact_area.reset();
  }
}

// From this n on, the report's distances to M are measured at kReportSamples vertices,
// centroids and edge midpoints each (the largest of 300 uniform samples exceeds the 99th
// percentile with probability 95 %); below it at every one.
constexpr int kSampledReportDimension = 500;
constexpr int kReportSamples = 300;
constexpr double kMinReportSeconds = 10.0;
constexpr double kReportTimeFraction = 0.1;

MeshReport make_report(const TriangleMesh& mesh, const ProblemSetup& setup,
                       const std::string& problem_argument, const MeshValidation* known,
                       int samples, bool measure_distances, double run_seconds,
                       const std::function<bool()>& stop_requested,
                       const std::function<bool(bool)>& decide_together) {
  MeshReport report;
  report.problem = problem_argument;  // as the user spelled it, e.g. "torus:R=2"
  report.ambient_dimension = setup.problem->ambient_dimension();
  // The geometric checks (orientation along M, overlaps on M, vertices in S) need the problem,
  // which every caller of make_report has.
  const bool is_known = known != nullptr && known->vertex_count == mesh.vertex_count() &&
                        known->triangle_count == mesh.triangle_count();
  report.validation = is_known ? *known : validate(mesh, *setup.problem, setup.domain);
  // Distances are Gauss–Newton projections, a few factorisations each: at large n they are
  // measured on a uniform sample (the report says how many) instead of at every point.
  QualityOptions quality;
  quality.max_samples = samples >= 0                                         ? samples
                        : report.ambient_dimension >= kSampledReportDimension ? kReportSamples
                                                                              : 0;
  if (samples < 0) {
    // The report is a check of the run, not a second run (bratu2d:N=316: 900 samples took
    // longer than the covering): a tenth of its time, at least kMinReportSeconds.
    quality.max_seconds = std::max(kMinReportSeconds, kReportTimeFraction * run_seconds);
  }
  quality.stop_requested = stop_requested;
  quality.decide_together = decide_together;
  if (measure_distances) {
    report.quality = measure_quality(mesh, *setup.problem, quality);
  } else {
    report.quality = measure_shape(mesh);
    report.quality.vertex_residual.population = mesh.vertex_count();
    report.quality.vertex_distance.population = mesh.vertex_count();
    report.quality.centroid_distance.population = mesh.triangle_count();
    report.quality.midpoint_distance.population = report.validation.edge_count;
  }
  report.expected_euler_characteristic = setup.expected_euler_characteristic;
  report.exact_area = setup.exact_area;
  return report;
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
  refuse_unless(given.atlas_placement == "disk" || method == "atlas", "--placement", "atlas");
  refuse_unless((given.front_order == "gap" && given.front_min_gap_degrees == 0 &&
                 given.front_max_valence == 0) ||
                    method == "front",
                "--order, --min-gap-angle, --max-valence", "front");
  refuse_unless((given.bezier_max_step == 0 && given.bezier_edge_length_factor == 0 &&
                 given.bezier_min_tangent_cosine == 0) ||
                    method == "bezier",
                "--max-step, --edge-length-factor, --min-tangent-cosine", "bezier");
}

nlohmann::json improvement_quality_json(const MeshQuality& quality,
                                        const MeshValidation& validation) {
  return {{"min_angle_degrees", quality.min_angle_degrees},
          {"max_angle_degrees", quality.max_angle_degrees},
          {"fraction_angles_below_30", quality.fraction_angles_below_30},
          {"max_centroid_distance", quality.centroid_distance.max},
          {"max_midpoint_distance", quality.midpoint_distance.max},
          {"failed_projections", quality.failed_projections},
          {"area", quality.area},
          {"is_valid", validation.is_valid()},
          {"euler_characteristic", validation.euler_characteristic},
          {"boundary_edge_count", validation.boundary_edge_count}};
}

}  // namespace tessera::app
