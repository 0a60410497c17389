// SPDX-License-Identifier: MIT
#include "tessera/report/component_report.h"

#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "tessera/problems/view.h"

namespace tessera {
namespace {

nlohmann::json point_json(const Eigen::VectorXd& x) {
  return std::vector<double>(x.data(), x.data() + x.size());
}

// "(1, 0, 0.5)" for n ≤ kLargeAmbientDimension, else "" (the report stays short at large n).
std::string point_text(const Eigen::VectorXd& x) {
  if (x.size() == 0 || x.size() > kLargeAmbientDimension) {
    return "";
  }
  std::ostringstream out;
  out.precision(4);
  out << " at (";
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    out << (i ? ", " : "") << x(i);
  }
  out << ")";
  return out.str();
}

}  // namespace

void add_components_json(const CoveringSummary& summary, int ambient_dimension,
                         nlohmann::json& run) {
  if (summary.components.empty() && summary.starts.empty() && !summary.component_search) {
    return;
  }
  const bool lists_points = ambient_dimension <= kLargeAmbientDimension;
  nlohmann::json components = nlohmann::json::array();
  for (std::size_t k = 0; k < summary.components.size(); ++k) {
    const ComponentRecord& c = summary.components[k];
    nlohmann::json entry = {{"component", k + 1},
                            {"origin", c.origin},
                            {"vertices", c.vertex_count},
                            {"triangles", c.triangle_count},
                            {"first_vertex", c.first_vertex},
                            {"first_triangle", c.first_triangle},
                            {"euler_characteristic", c.euler_characteristic},
                            {"boundary_loops", c.boundary_loop_count},
                            {"closed", c.boundary_loop_count == 0},
                            {"genus", c.genus},
                            {"termination", to_string(c.termination)},
                            {"message", c.message}};
    if (lists_points) {
      entry["start"] = point_json(c.start);
    }
    components.push_back(entry);
  }
  run["components"] = components;
  nlohmann::json starts = nlohmann::json::array();
  for (std::size_t i = 0; i < summary.starts.size(); ++i) {
    const StartRecord& s = summary.starts[i];
    nlohmann::json entry = {
        {"start", i + 1},
        {"component", s.component >= 0 ? nlohmann::json(s.component + 1) : nlohmann::json(nullptr)},
        {"started_component", s.started_component},
        {"message", s.message}};
    if (lists_points) {
      entry["point"] = point_json(s.guess);
      entry["on_manifold"] =
          s.on_manifold.size() > 0 ? point_json(s.on_manifold) : nlohmann::json(nullptr);
    }
    starts.push_back(entry);
  }
  run["starts"] = starts;
  if (summary.component_search) {
    const ComponentSearchRecord& search = *summary.component_search;
    run["component_search"] = {{"seeds", search.seed_count},
                               {"seed_spacing", search.seed_spacing},
                               {"seeded_coordinates", search.seeded_coordinates},
                               {"seeds_started", search.seeds_started},
                               {"seeds_on_covered", search.seeds_on_covered},
                               {"seeds_not_projected", search.seeds_not_projected},
                               {"seeds_not_tried", search.seeds_not_tried}};
  }
}

std::string components_text(const CoveringSummary& summary, int ambient_dimension) {
  if (summary.components.empty() && summary.starts.empty() && !summary.component_search) {
    return "";
  }
  std::ostringstream out;
  out.precision(3);
  out << "components     " << summary.components.size();
  if (summary.component_search) {
    const ComponentSearchRecord& search = *summary.component_search;
    out << " (" << search.seed_count << " seeds over ";
    for (std::size_t i = 0; i < search.seeded_coordinates.size(); ++i) {
      out << (i ? ", " : "") << search.seeded_coordinates[i];
    }
    out << ", spacing " << search.seed_spacing << ": " << search.seeds_started << " started one, "
        << search.seeds_on_covered << " landed on one covered, " << search.seeds_not_projected
        << " not projected into the region";
    if (search.seeds_not_tried > 0) {
      out << ", " << search.seeds_not_tried << " not tried";
    }
    out << ")";
  }
  out << "\n";
  for (std::size_t k = 0; k < summary.components.size(); ++k) {
    const ComponentRecord& c = summary.components[k];
    out << "  " << k + 1 << std::string(k + 1 < 10 ? 12 : 11, ' ') << c.origin
        << (ambient_dimension <= kLargeAmbientDimension ? point_text(c.start) : "") << ": "
        << c.vertex_count << " vertices, " << c.triangle_count << " triangles, χ "
        << c.euler_characteristic;
    if (c.boundary_loop_count == 0) {
      out << ", closed";
      if (c.genus >= 0) {
        out << ", genus " << c.genus;
      }
    } else {
      out << ", " << c.boundary_loop_count << " boundary loop(s)";
    }
    if (c.termination != CoveringTermination::Completed) {
      out << ", " << to_string(c.termination);
    }
    out << "\n";
  }
  if (!summary.starts.empty()) {
    out << "starts         ";
    for (std::size_t i = 0; i < summary.starts.size(); ++i) {
      const StartRecord& s = summary.starts[i];
      out << (i ? "; " : "") << "start " << i + 1;
      if (s.component < 0) {
        out << " → none (" << s.message << ")";
      } else {
        out << " → component " << s.component + 1
            << (s.started_component ? "" : " (already covered)");
      }
    }
    out << "\n";
  }
  return out.str();
}

}  // namespace tessera
