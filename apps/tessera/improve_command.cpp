// SPDX-License-Identifier: MIT
#include "improve_command.h"

#include "cli_support.h"

#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "tessera/core/error.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/io/mesh_io.h"
#include "tessera/io/output_checks.h"
#include "tessera/io/text_file.h"
#include "tessera/methods/improvement/improve_mesh.h"
#include "tessera/methods/improvement/tangential_smoothing.h"
#include "tessera/problems/catalogue.h"
#include "tessera/report/improvement_report.h"
#include "tessera/report/problem_record.h"

namespace tessera::app {
namespace {

void print_line(const char* label, const MeshQuality& quality, const MeshValidation& validation) {
  std::printf(
      "%-7s min angle %.2f°, %.3f%% of angles below 30°, max distance to M: centroids %.4g, "
      "edge midpoints %.4g; chi %d, %s\n",
      label, quality.min_angle_degrees, 100.0 * quality.fraction_angles_below_30,
      quality.centroid_distance.max, quality.midpoint_distance.max, validation.euler_characteristic,
      validation.is_valid() ? "valid" : "NOT valid");
}

}  // namespace

int run_improve(const ImproveCommand& command) {
  check_mesh_output(command.output);
  check_output_folder(command.summary);
  check_replaces_same_kind("-o", command.output, TesseraFileKind::Mesh);
  check_replaces_same_kind("--summary", command.summary, TesseraFileKind::ImproveSummary);
  const ProblemSetup setup = resolve_problem(command.problem);
  TriangleMesh mesh = read_mesh(command.mesh);
  TESSERA_CHECK(mesh.ambient_dimension() == setup.problem->ambient_dimension(),
                command.mesh << " has points in R^" << mesh.ambient_dimension() << " but problem '"
                             << command.problem << "' lives in R^"
                             << setup.problem->ambient_dimension());
  ImprovementOptions options;
  options.max_sweeps = command.max_sweeps;
  options.criterion = command.criterion == "normal"     ? ImprovementCriterion::NormalAngle
                      : command.criterion == "distance" ? ImprovementCriterion::MidpointDistance
                                                        : ImprovementCriterion::MaxMinAngle;
  const MeshValidation validation_before = validate(mesh);
  const MeshQuality quality_before = measure_quality(mesh, *setup.problem);
  const MeshImprovement improvement = improve_mesh(mesh, *setup.problem, options, command.smooth);
  const ImprovementSummary& summary = improvement.swaps;
  const SmoothingSummary& smoothing = improvement.smoothing;
  const MeshValidation validation_after = validate(mesh);
  const MeshQuality quality_after = measure_quality(mesh, *setup.problem);

  MeshFileOptions file_options;
  file_options.comments = {"tessera improve " + command.mesh + " --problem " + command.problem +
                           " --criterion " + command.criterion};
  // What `tessera check FILE` takes for the problem when it is not given.
  for (auto& comment : problem_record_comments(command.problem)) {
    file_options.comments.push_back(std::move(comment));
  }
  write_mesh(command.output, mesh, file_options);

  std::printf("criterion %s: %d swaps in %d sweeps (%s), %d interior edges\n",
              command.criterion.c_str(), summary.swaps, summary.sweeps,
              summary.converged ? "converged" : "stopped at the sweep cap", summary.interior_edges);
  if (command.smooth > 0) {
    std::printf(
        "smoothing: %d vertex moves in %d passes (refused: %d fold, %d angle, %d projection)\n",
        smoothing.moves, smoothing.iterations, smoothing.rejected_fold, smoothing.rejected_angle,
        smoothing.rejected_projection);
  }
  print_line("before", quality_before, validation_before);
  print_line("after", quality_after, validation_after);
  if (!command.summary.empty()) {
    const nlohmann::json json = {{"mesh", command.mesh},
                                 {"problem", command.problem},
                                 {"criterion", command.criterion},
                                 {"swaps", summary.swaps},
                                 {"sweeps", summary.sweeps},
                                 {"converged", summary.converged},
                                 {"interior_edges", summary.interior_edges},
                                 {"smoothing_passes", smoothing.iterations},
                                 {"smoothing_moves", smoothing.moves},
                                 {"rejected_non_convex", summary.rejected_non_convex},
                                 {"rejected_existing_edge", summary.rejected_existing_edge},
                                 {"rejected_projection_failed", summary.rejected_projection_failed},
                                 {"before", improvement_quality_json(quality_before, validation_before)},
                                 {"after", improvement_quality_json(quality_after, validation_after)}};
    write_text_file(command.summary, json.dump(2) + "\n", "JSON summary");
  }
  std::cout << "wrote " << command.output
            << (command.summary.empty() ? "" : " and " + command.summary) << "\n";
  if (!validation_after.is_valid()) {
    std::cerr << "tessera: the improved mesh is not valid:\n" << validation_after.report();
    return 1;
  }
  return 0;
}

}  // namespace tessera::app
