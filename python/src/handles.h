// SPDX-License-Identifier: MIT
// What the Python objects tessera.Problem and tessera.Mesh hold on the C++ side.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "python_problem.h"
#include "tessera/core/domain.h"
#include "tessera/geometry/bezier_patch.h"
#include "tessera/geometry/triangle_mesh.h"
#include "tessera/io/vertex_data.h"
#include "tessera/methods/stability/vertex_stability.h"
#include "tessera/problems/problem_setup.h"
#include "tessera/problems/view.h"

namespace tessera::python {

// A problem ready to be meshed any number of times: what a ProblemSetup holds, with the problem
// shared so that each run builds its own setup (start and box may differ per run).
struct ProblemHandle {
  std::shared_ptr<const ImplicitProblem> problem;
  Eigen::VectorXd start;
  Domain domain;
  double suggested_step = 0.1;
  std::string description;
  std::optional<int> expected_euler_characteristic;
  std::optional<double> exact_area;
  std::optional<View> view;
  std::string argument;  ///< as the user spelled it ("torus:R=2", a path): reports name it so

  static std::shared_ptr<ProblemHandle> from_setup(ProblemSetup setup, std::string argument) {
    auto handle = std::make_shared<ProblemHandle>();
    handle->problem = std::shared_ptr<const ImplicitProblem>(std::move(setup.problem));
    handle->start = std::move(setup.start);
    handle->domain = std::move(setup.domain);
    handle->suggested_step = setup.suggested_step;
    handle->description = std::move(setup.description);
    handle->expected_euler_characteristic = setup.expected_euler_characteristic;
    handle->exact_area = setup.exact_area;
    handle->view = std::move(setup.view);
    handle->argument = std::move(argument);
    return handle;
  }

  ProblemSetup setup() const {
    ProblemSetup setup;
    setup.problem = std::make_unique<SharedProblem>(problem);
    setup.start = start;
    setup.domain = domain;
    setup.suggested_step = suggested_step;
    setup.description = description;
    setup.expected_euler_characteristic = expected_euler_characteristic;
    setup.exact_area = exact_area;
    setup.view = view;
    return setup;
  }
};

// A mesh and what was learnt making it. Never changed after it is made, so that the NumPy views
// of its arrays stay valid for as long as they (and with them this object) live.
struct MeshHandle {
  TriangleMesh mesh;
  std::shared_ptr<ProblemHandle> problem;  ///< null for a mesh made from arrays
  std::vector<CubicBezierPatch> patches;
  std::string summary_json;  ///< the report (docs/summary-json.md), or improve's / ddt's summary
  std::string termination = "completed";
  std::string failure;       ///< empty, or the CLI's message for a run that did not succeed
  bool interrupted = false;  ///< Ctrl-C arrived during the run
  int interrupt_count = 0;   ///< how many times (the second and later are handed to Python)
  std::string comment;       ///< first comment line of the files written
  std::string note;          ///< what the user should know although the run succeeded
  std::vector<VertexScalars> vertex_scalars;  ///< ddt: the data values; mesh: the stability
  /// mesh(stability=True): one per vertex; empty otherwise.
  std::vector<VertexStability> stability;
};

}  // namespace tessera::python
