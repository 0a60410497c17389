// SPDX-License-Identifier: MIT
// The compiled half of the Python package: problems, meshes whose arrays are views of the C++
// storage, and the commands of the CLI (mesh, check, improve, ddt) with the GIL released while
// C++ works. Keyword arguments, defaults, docstrings and the exceptions a user sees are in
// python/tessera/__init__.py; this module is its private implementation (tessera._tessera).
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cmath>
#include <complex>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "checkpoints.h"
#include "mesh_call.h"
#include "ddt.h"
#include "handles.h"
#include "interrupt_handler.h"
#include "progress.h"
#include "python_problem.h"
#include "tessera/core/error.h"
#include "tessera/core/parallel_for.h"
#include "tessera/geometry/bezier_surface.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/io/bezier_patches.h"
#include "tessera/io/mesh_io.h"
#include "tessera/io/npy.h"
#include "tessera/io/output_checks.h"
#include "tessera/io/view_mesh.h"
#include "tessera/methods/components/cover_components.h"
#include "tessera/methods/covering_methods.h"
#include "tessera/methods/improvement/improve_mesh.h"
#include "tessera/methods/stability/state_jacobian.h"
#include "tessera/picture/run_diagram.h"
#include "tessera/picture/picture.h"
#include "tessera/problems/catalogue.h"
#include "tessera/problems/problem_file.h"
#include "tessera/problems/start_and_box.h"
#include "tessera/problems/view.h"
#include "tessera/report/mesh_analyses.h"
#include "tessera/report/fold_output.h"
#include "tessera/report/improvement_report.h"
#include "tessera/report/level_output.h"
#include "tessera/report/mesh_report.h"
#include "tessera/report/method_comparison.h"
#include "tessera/report/stability_output.h"
#include "tessera/report/summary_json.h"

namespace tessera::python {
namespace {

static_assert(sizeof(Triangle) == 3 * sizeof(int), "triangles are viewed as a (T, 3) int array");

// The (N, n) view of the n×N column-major points: C-contiguous, strides (8n, 8), no copy.
py::array vertices_view(const py::object& owner) {
  const MeshHandle& handle = owner.cast<const MeshHandle&>();
  const auto& mesh = handle.mesh;
  const py::ssize_t n = mesh.ambient_dimension();
  const py::ssize_t N = mesh.vertex_count();
  const double* data = N == 0 ? nullptr : mesh.points().data();
  py::array view(py::dtype::of<double>(), {N, n},
                 {static_cast<py::ssize_t>(sizeof(double)) * n,
                  static_cast<py::ssize_t>(sizeof(double))},
                 data, owner);
  view.attr("flags").attr("writeable") = false;
  return view;
}

py::array triangles_view(const py::object& owner) {
  const MeshHandle& handle = owner.cast<const MeshHandle&>();
  const auto& triangles = handle.mesh.triangles();
  const py::ssize_t T = static_cast<py::ssize_t>(triangles.size());
  const int* data = T == 0 ? nullptr : triangles.front().data();
  py::array view(py::dtype::of<int>(), {T, py::ssize_t{3}},
                 {static_cast<py::ssize_t>(sizeof(Triangle)),
                  static_cast<py::ssize_t>(sizeof(int))},
                 data, owner);
  view.attr("flags").attr("writeable") = false;
  return view;
}

void write_mesh_file(const MeshHandle& handle, const std::string& path, bool ascii,
                     const std::string& view_specification) {
  TESSERA_CHECK(handle.mesh.triangle_count() > 0,
                "write " << path << ": the mesh is empty (the run made no triangle)");
  if (std::filesystem::path(path).extension() == ".npy") {
    // `tessera mesh --states`: every coordinate, and the triangles beside.
    check_output_folder(path);
    write_states_npy(path, handle.mesh);
    return;
  }
  check_mesh_output(path);
  MeshFileOptions options;
  options.binary = !ascii;
  options.vertex_scalars = handle.vertex_scalars;
  if (!handle.comment.empty()) {
    options.comments = {handle.comment};
  }
  if (handle.problem == nullptr) {
    TESSERA_CHECK(view_specification.empty(),
                  "write " << path << ": a view needs the problem; this mesh has none");
    write_mesh(path, handle.mesh, options);
    return;
  }
  const ImplicitProblem& problem = *handle.problem->problem;
  const View view = choose_view(view_specification, *handle.problem);
  if (view.is_all_coordinates()) {
    // As `tessera mesh`: PLY keeps the standard names (x, y, z, x3, …), the problem's own go
    // into a comment, and into the arrays of VTK files.
    std::string names;
    for (const auto& name : problem.coordinate_names()) {
      names += " " + name;
    }
    if (std::filesystem::path(path).extension() != ".ply") {
      options.coordinate_names = problem.coordinate_names();
    }
    options.comments.push_back("coordinates:" + names);
    write_mesh(path, handle.mesh, options);
  } else {
    options.comments.push_back("a view of the states in R^" +
                               std::to_string(problem.ambient_dimension()) + ": " +
                               describe_coordinates(problem));
    write_mesh_in_view(path, handle.mesh, view, options);
  }
}

void check_dimensions(const MeshHandle& mesh, const ProblemHandle& problem) {
  const int n = problem.problem->ambient_dimension();
  TESSERA_CHECK(mesh.mesh.ambient_dimension() == n,
                "the mesh is in R^" << mesh.mesh.ambient_dimension() << " but problem '"
                                    << problem.argument << "' is in R^" << n);
}

// `tessera check`: the report, and whether the mesh passes (with the CLI's reasons).
py::tuple check_mesh(const MeshHandle& mesh, const std::shared_ptr<ProblemHandle>& problem,
                     int samples) {
  check_dimensions(mesh, *problem);
  std::string json;
  std::vector<std::string> failures;
  {
    py::gil_scoped_release release;
    const ProblemSetup setup = problem->setup();
    ReportOptions report_options;
    report_options.samples = samples;
    const MeshReport report =
        make_report(mesh.mesh, setup, problem->argument, nullptr, report_options);
    json = to_json(report);
    if (!report.validation.is_valid()) {
      failures.push_back("the mesh is not valid:\n" + report.validation.report());
    }
    if (setup.expected_euler_characteristic &&
        report.validation.euler_characteristic != *setup.expected_euler_characteristic) {
      failures.push_back("Euler characteristic " +
                         std::to_string(report.validation.euler_characteristic) +
                         ", but the surface of '" + problem->argument + "' has " +
                         std::to_string(*setup.expected_euler_characteristic));
    }
    if (report.quality.vertex_distance.max > 1e-6 || report.quality.failed_projections > 0) {
      std::ostringstream message;
      message << "vertices are not on M (max distance " << report.quality.vertex_distance.max
              << ", " << report.quality.failed_projections << " points could not be projected)";
      failures.push_back(message.str());
    }
  }
  return py::make_tuple(json, failures);
}


// `tessera improve`: a new mesh (the given one is not changed; its arrays may be viewed), with
// the CLI's --summary JSON as its summary.
std::shared_ptr<MeshHandle> improve(const MeshHandle& given,
                                    const std::shared_ptr<ProblemHandle>& problem,
                                    const std::string& criterion, int max_sweeps, int smooth) {
  check_dimensions(given, *problem);
  auto handle = std::make_shared<MeshHandle>();
  handle->problem = problem;
  handle->mesh = given.mesh;
  handle->comment = "tessera improve --problem " + problem->argument + " --criterion " + criterion;
  {
    py::gil_scoped_release release;
    const ImplicitProblem& f = *problem->problem;
    ImprovementOptions options;
    options.max_sweeps = max_sweeps;
    options.criterion = criterion == "normal"     ? ImprovementCriterion::NormalAngle
                        : criterion == "distance" ? ImprovementCriterion::MidpointDistance
                                                  : ImprovementCriterion::MaxMinAngle;
    const MeshValidation validation_before = validate(handle->mesh);
    const MeshQuality quality_before = measure_quality(handle->mesh, f);
    const MeshImprovement improvement = improve_mesh(handle->mesh, f, options, smooth);
    const MeshValidation validation_after = validate(handle->mesh);
    const MeshQuality quality_after = measure_quality(handle->mesh, f);
    const ImprovementSummary& swaps = improvement.swaps;
    const nlohmann::json json = {
        {"problem", problem->argument},
        {"criterion", criterion},
        {"swaps", swaps.swaps},
        {"sweeps", swaps.sweeps},
        {"converged", swaps.converged},
        {"interior_edges", swaps.interior_edges},
        {"smoothing_passes", improvement.smoothing.iterations},
        {"smoothing_moves", improvement.smoothing.moves},
        {"rejected_non_convex", swaps.rejected_non_convex},
        {"rejected_existing_edge", swaps.rejected_existing_edge},
        {"rejected_projection_failed", swaps.rejected_projection_failed},
        {"before", improvement_quality_json(quality_before, validation_before)},
        {"after", improvement_quality_json(quality_after, validation_after)}};
    handle->summary_json = json.dump(2);
    if (!validation_after.is_valid()) {
      handle->failure = "the improved mesh is not valid:\n" + validation_after.report();
    }
  }
  return handle;
}

// `tessera ddt` (ddt.cpp): the triangulation as a mesh in R^3 (x, y, value), as the CLI writes it,
// with the value also as a vertex scalar.
std::shared_ptr<MeshHandle> ddt(const Eigen::Matrix2Xd& points,
                                std::optional<Eigen::VectorXd> values,
                                const std::string& function_name, const std::string& criterion,
                                const std::string& norm, const std::string& test, int grid,
                                unsigned sweep_order_seed) {
  auto handle = std::make_shared<MeshHandle>();
  handle->comment = "tessera ddt, criterion " + criterion;
  DataDependentTriangulation result;
  {
    py::gil_scoped_release release;
    result = triangulate_data(points, values, {function_name, criterion, norm, test, grid,
                                               sweep_order_seed});
  }
  handle->summary_json = std::move(result.summary_json);
  handle->vertex_scalars.push_back({"value", std::move(result.values)});
  handle->mesh = std::move(result.mesh);
  return handle;
}

// `tessera ddt --all-criteria`: one mesh per row of the table, in the table's order.
std::vector<std::shared_ptr<MeshHandle>> ddt_all_criteria(
    const Eigen::Matrix2Xd& points, std::optional<Eigen::VectorXd> values,
    const std::string& function_name, const std::string& test, int grid, int orders,
    int compare_report) {
  std::vector<DataDependentTriangulation> results;
  {
    py::gil_scoped_release release;
    results = triangulate_all_criteria(points, values, {function_name, "", "", test, grid, 0},
                                       {orders, compare_report});
  }
  std::vector<std::shared_ptr<MeshHandle>> handles;
  for (auto& result : results) {
    auto handle = std::make_shared<MeshHandle>();
    handle->summary_json = std::move(result.summary_json);
    handle->comment = "tessera ddt --all-criteria, criterion " +
                      nlohmann::json::parse(handle->summary_json)["criterion"].get<std::string>();
    handle->vertex_scalars.push_back({"value", std::move(result.values)});
    handle->mesh = std::move(result.mesh);
    handles.push_back(std::move(handle));
  }
  return handles;
}

// `tessera compare`: every method on the problem, the table as JSON (one object per method),
// and how many times Ctrl-C came (the first stops the method running; the rest then stop at
// their first poll, so their rows say "interrupted").
py::tuple compare_methods(const std::shared_ptr<ProblemHandle>& problem,
                          const MeshRequest& request, bool handle_interrupt) {
  MethodSettings settings = request.settings;
  const std::string start = request.start.empty() ? "" : join_numbers(request.start);
  const std::string box = box_text(request);
  {
    // Checks --start and --box before any computation.
    ProblemSetup setup = problem->setup();
    apply_start_and_box(setup, start, box);
  }
  const InterruptHandler interrupt(handle_interrupt);
  settings.stop_requested = [&interrupt] { return interrupt.is_requested(); };
  nlohmann::json json;
  {
    py::gil_scoped_release release;
    const CompareReport report = tessera::compare_methods(
        [&] {
          ProblemSetup setup = problem->setup();
          apply_start_and_box(setup, start, box);
          return setup;
        },
        settings);
    nlohmann::json rows = nlohmann::json::array();
    for (const CompareRow& row : report.rows) {
      rows.push_back({{"method", row.method},
                      {"vertex_count", row.vertex_count},
                      {"triangle_count", row.triangle_count},
                      {"wall_seconds", row.run.wall_seconds},
                      {"max_distance", row.max_distance},
                      {"tolerance", row.run.tolerance},
                      {"min_angle_degrees", row.min_angle_degrees},
                      {"euler_characteristic", row.euler_characteristic},
                      {"valid", row.valid},
                      {"termination", to_string(row.run.termination)},
                      {"completed", row.run.is_complete()},
                      {"message", row.run.message},
                      {"passes", row.passes()}});
    }
    json = {{"problem", problem->argument},
            {"tolerance", report.tolerance},
            {"methods", rows},
            {"expected_euler_characteristic",
             report.expected_euler_characteristic
                 ? nlohmann::json(*report.expected_euler_characteristic)
                 : nlohmann::json(nullptr)},
            {"passes", report.passes()}};
  }
  return py::make_tuple(json.dump(2), interrupt.count());
}

std::shared_ptr<MeshHandle> mesh_from_arrays(
    const py::array_t<double, py::array::c_style | py::array::forcecast>& vertices,
    const py::array_t<long long, py::array::c_style | py::array::forcecast>& triangles) {
  TESSERA_CHECK(vertices.ndim() == 2 && vertices.shape(1) >= 2,
                "Mesh: vertices must be an (N, n) array with n >= 2, got " << vertices.ndim()
                                                                           << " dimensions");
  TESSERA_CHECK(triangles.ndim() == 2 && triangles.shape(1) == 3,
                "Mesh: triangles must be a (T, 3) array of vertex indices");
  const auto N = vertices.shape(0);
  const auto n = vertices.shape(1);
  std::vector<Triangle> copied(static_cast<std::size_t>(triangles.shape(0)));
  const long long* index = triangles.data();
  for (std::size_t t = 0; t < copied.size(); ++t) {
    for (int k = 0; k < 3; ++k, ++index) {
      TESSERA_CHECK(*index >= 0 && *index < N, "Mesh: triangle " << t << " has vertex index "
                                                                 << *index << ", not in [0, "
                                                                 << N - 1 << "]");
      copied[t][static_cast<std::size_t>(k)] = static_cast<int>(*index);
    }
  }
  auto handle = std::make_shared<MeshHandle>();
  // (N, n) row-major is the n×N column-major layout of TriangleMesh: one copy, no transpose.
  handle->mesh = TriangleMesh(
      Eigen::Map<const Eigen::MatrixXd>(vertices.data(), static_cast<Eigen::Index>(n),
                                        static_cast<Eigen::Index>(N)),
      std::move(copied));
  handle->summary_json = "{}";
  return handle;
}

// One value per vertex of mesh(stability=True), e.g. the unstable counts; empty without.
template <typename Value, typename Get>
py::array_t<Value> stability_array(const MeshHandle& mesh, Get get) {
  py::array_t<Value> values(static_cast<py::ssize_t>(mesh.stability.size()));
  Value* out = values.mutable_data();
  for (const VertexStability& s : mesh.stability) {
    *out++ = get(s);
  }
  return values;
}

// The computed eigenvalues of every vertex, by decreasing real part (complex arrays).
py::list eigenvalue_arrays(const MeshHandle& mesh) {
  py::list arrays;
  for (const VertexStability& s : mesh.stability) {
    py::array_t<std::complex<double>> values(static_cast<py::ssize_t>(s.eigenvalues.size()));
    std::copy(s.eigenvalues.begin(), s.eigenvalues.end(), values.mutable_data());
    arrays.append(values);
  }
  return arrays;
}

std::vector<CoordinateBlock> to_blocks(const py::list& blocks) {
  std::vector<CoordinateBlock> result;
  for (const auto& item : blocks) {
    const auto tuple = item.cast<py::tuple>();
    CoordinateBlock block;
    block.name = tuple[0].cast<std::string>();
    block.first = tuple[1].cast<int>();
    block.size = tuple[2].cast<int>();
    block.weight = tuple.size() > 3 ? tuple[3].cast<double>() : 1.0;
    result.push_back(block);
  }
  return result;
}

}  // namespace

PYBIND11_MODULE(_tessera, module) {
  module.doc() = "tessera's compiled core; use the package `tessera`, not this module.";
  py::register_exception<ComputationFailed>(module, "ComputationFailedError",
                                            PyExc_RuntimeError);

  py::class_<ProblemHandle, std::shared_ptr<ProblemHandle>>(module, "Problem")
      .def_static("resolve",
                  [](const std::string& argument) {
                    return ProblemHandle::from_setup(resolve_problem(argument), argument);
                  })
      .def_static("from_file",
                  [](const std::string& path, const std::map<std::string, double>& parameters) {
                    return ProblemHandle::from_setup(load_problem_file(path, parameters), path);
                  })
      .def_static("from_text",
                  [](const std::string& text, const std::string& source_name,
                     const std::map<std::string, double>& parameters) {
                    return ProblemHandle::from_setup(
                        parse_problem(text, source_name, parameters), source_name);
                  })
      .def_static(
          "from_python",
          [](int n, py::object F, py::object J, bool sparse, const std::string& name,
             std::vector<std::string> coordinate_names, const py::list& blocks,
             const Eigen::VectorXd& start, const std::vector<double>& box, double step,
             std::optional<int> euler_characteristic, std::optional<double> area,
             std::optional<Dynamics> dynamics) {
            auto problem = std::make_shared<PythonProblem>(n, std::move(F), std::move(J), sparse,
                                                           name, std::move(coordinate_names),
                                                           to_blocks(blocks), std::move(dynamics));
            metric_weights(*problem);  // checks the blocks
            TESSERA_CHECK(start.size() == n,
                          "Problem: start has " << start.size() << " values, n = " << n);
            TESSERA_CHECK(std::isfinite(step) && step > 0,
                          "Problem: step = " << step << " must be a finite number > 0");
            auto handle = std::make_shared<ProblemHandle>();
            handle->problem = problem;
            handle->start = start;
            handle->domain = Domain(n);
            handle->suggested_step = step;
            handle->description = name + ", defined in Python";
            handle->expected_euler_characteristic = euler_characteristic;
            handle->exact_area = area;
            handle->argument = name;
            if (!box.empty()) {
              ProblemSetup setup = handle->setup();
              apply_start_and_box(setup, "", join_numbers(box));
              handle->domain = setup.domain;
            }
            return handle;
          })
      .def_property_readonly("n",
                             [](const ProblemHandle& p) { return p.problem->ambient_dimension(); })
      .def_property_readonly("name", [](const ProblemHandle& p) { return p.problem->name(); })
      .def_property_readonly("argument", [](const ProblemHandle& p) { return p.argument; })
      .def_property_readonly("coordinate_names",
                             [](const ProblemHandle& p) { return p.problem->coordinate_names(); })
      .def_property_readonly("start", [](const ProblemHandle& p) { return p.start; })
      .def_property_readonly("suggested_step",
                             [](const ProblemHandle& p) { return p.suggested_step; })
      .def_property_readonly("description", [](const ProblemHandle& p) { return p.description; })
      .def_property_readonly("expected_euler_characteristic",
                             [](const ProblemHandle& p) { return p.expected_euler_characteristic; })
      .def_property_readonly("exact_area", [](const ProblemHandle& p) { return p.exact_area; })
      .def_property_readonly(
          "has_sparse_jacobian",
          [](const ProblemHandle& p) { return p.problem->has_sparse_jacobian(); })
      .def_property_readonly("dynamics",
                             [](const ProblemHandle& p) { return p.problem->dynamics(); })
      .def("F",
           [](const ProblemHandle& p, const Eigen::VectorXd& x) {
             const int n = p.problem->ambient_dimension();
             TESSERA_CHECK(x.size() == n, "F: x has " << x.size() << " values, n = " << n);
             Eigen::VectorXd F(n - 2);
             p.problem->evaluate(x, F);
             return F;
           })
      .def("J", [](const ProblemHandle& p, const Eigen::VectorXd& x) {
        const int n = p.problem->ambient_dimension();
        TESSERA_CHECK(x.size() == n, "J: x has " << x.size() << " values, n = " << n);
        Eigen::MatrixXd J(n - 2, n);
        p.problem->jacobian(x, J);
        return J;
      });

  // core/dynamics.h as it is; tessera.Dynamics (python/tessera/__init__.py) names the
  // parameters and checks each field before it reaches this.
  py::class_<Dynamics>(module, "Dynamics")
      .def(py::init<>())
      .def_readwrite("parameters", &Dynamics::parameters)
      .def_readwrite("sign", &Dynamics::sign)
      .def_readwrite("mass_diagonal", &Dynamics::mass_diagonal)
      .def_readwrite("mass_matrix", &Dynamics::mass_matrix);

  py::class_<MeshHandle, std::shared_ptr<MeshHandle>>(module, "Mesh")
      .def_static("from_arrays", &mesh_from_arrays)
      .def_property_readonly("vertices", &vertices_view)
      .def_property_readonly("triangles", &triangles_view)
      .def_property_readonly("summary_json", [](const MeshHandle& m) { return m.summary_json; })
      .def_property_readonly("termination", [](const MeshHandle& m) { return m.termination; })
      .def_property_readonly("failure", [](const MeshHandle& m) { return m.failure; })
      .def_property_readonly("note", [](const MeshHandle& m) { return m.note; })
      .def_property_readonly("has_stability",
                             [](const MeshHandle& m) { return !m.stability.empty(); })
      .def_property_readonly("unstable_count",
                             [](const MeshHandle& m) {
                               return stability_array<int>(
                                   m, [](const VertexStability& s) { return s.unstable_count; });
                             })
      .def_property_readonly("leading_real_part",
                             [](const MeshHandle& m) {
                               return stability_array<double>(
                                   m, [](const VertexStability& s) { return s.leading_real_part; });
                             })
      .def_property_readonly("stability_certain",
                             [](const MeshHandle& m) {
                               return stability_array<bool>(
                                   m, [](const VertexStability& s) { return s.is_certain; });
                             })
      .def_property_readonly("eigenvalues", &eigenvalue_arrays)
      .def_property_readonly("interrupted", [](const MeshHandle& m) { return m.interrupted; })
      .def_property_readonly("interrupt_count",
                             [](const MeshHandle& m) { return m.interrupt_count; })
      .def_property_readonly("problem", [](const MeshHandle& m) { return m.problem; })
      .def_property_readonly("has_patches", [](const MeshHandle& m) { return !m.patches.empty(); })
      .def("write", &write_mesh_file, py::arg("path"), py::arg("ascii"), py::arg("view"))
      .def("write_patches",
           [](const MeshHandle& m, const std::string& path) {
             TESSERA_CHECK(!m.patches.empty(),
                           "write_patches: only a mesh of method 'bezier' (not refined, not "
                           "improved) has Bezier patches");
             check_output_folder(path);
             write_bezier_patches(path, {m.mesh, m.patches, m.problem->problem->coordinate_names()});
           })
      .def_static("read", [](const std::string& path) {
        auto handle = std::make_shared<MeshHandle>();
        handle->mesh = read_mesh(path);
        handle->summary_json = "{}";
        return handle;
      });

  py::class_<MeshRequest>(module, "MeshRequest")
      .def(py::init<>())
      .def_readwrite("method", &MeshRequest::method)
      .def_readwrite("start", &MeshRequest::start)
      .def_readwrite("more_starts", &MeshRequest::more_starts)
      .def_readwrite("components", &MeshRequest::components)
      .def_readwrite("component_seeds", &MeshRequest::component_seeds)
      .def_readwrite("box", &MeshRequest::box)
      .def_readwrite("named_box", &MeshRequest::named_box)
      .def_readwrite("improve", &MeshRequest::improve)
      .def_readwrite("refine", &MeshRequest::refine)
      .def_readwrite("report_samples", &MeshRequest::report_samples)
      .def_readwrite("threads", &MeshRequest::threads)
      .def_readwrite("view", &MeshRequest::view)
      .def_readwrite("folds", &MeshRequest::folds)
      .def_readwrite("stability", &MeshRequest::stability)
      .def_readwrite("eigenvalues", &MeshRequest::eigenvalues)
      .def_readwrite("hopf", &MeshRequest::hopf)
      .def_readwrite("level", &MeshRequest::level)
      .def_readwrite("diagram", &MeshRequest::diagram)
      .def_readwrite("wants_patches", &MeshRequest::wants_patches)
      .def_property(
          "step", [](const MeshRequest& r) { return r.settings.step; },
          [](MeshRequest& r, double v) { r.settings.step = v; })
      .def_property(
          "tolerance", [](const MeshRequest& r) { return r.settings.tolerance; },
          [](MeshRequest& r, double v) { r.settings.tolerance = v; })
      .def_property(
          "max_vertices", [](const MeshRequest& r) { return r.settings.max_vertices; },
          [](MeshRequest& r, int v) { r.settings.max_vertices = v; })
      .def_property(
          "max_start_distance", [](const MeshRequest& r) { return r.settings.max_start_distance; },
          [](MeshRequest& r, double v) { r.settings.max_start_distance = v; })
      .def_property(
          "placement", [](const MeshRequest& r) { return r.settings.atlas_placement; },
          [](MeshRequest& r, const std::string& v) { r.settings.atlas_placement = v; })
      .def_property(
          "min_gap_angle", [](const MeshRequest& r) { return r.settings.front_min_gap_degrees; },
          [](MeshRequest& r, double v) { r.settings.front_min_gap_degrees = v; })
      .def_property(
          "max_valence", [](const MeshRequest& r) { return r.settings.front_max_valence; },
          [](MeshRequest& r, int v) { r.settings.front_max_valence = v; })
      .def_property(
          "order", [](const MeshRequest& r) { return r.settings.front_order; },
          [](MeshRequest& r, const std::string& v) { r.settings.front_order = v; })
      .def_property(
          "max_step", [](const MeshRequest& r) { return r.settings.bezier_max_step; },
          [](MeshRequest& r, double v) { r.settings.bezier_max_step = v; })
      .def_property(
          "edge_length_factor",
          [](const MeshRequest& r) { return r.settings.bezier_edge_length_factor; },
          [](MeshRequest& r, double v) { r.settings.bezier_edge_length_factor = v; })
      .def_property(
          "min_tangent_cosine",
          [](const MeshRequest& r) { return r.settings.bezier_min_tangent_cosine; },
          [](MeshRequest& r, double v) { r.settings.bezier_min_tangent_cosine = v; })
      .def_property(
          "chart_tolerance", [](const MeshRequest& r) { return r.settings.atlas_chart_tolerance; },
          [](MeshRequest& r, double v) { r.settings.atlas_chart_tolerance = v; })
      .def_property(
          "checkpoint", [](const MeshRequest& r) { return r.checkpoint.path; },
          [](MeshRequest& r, const std::string& v) { r.checkpoint.path = v; })
      .def_property(
          "checkpoint_every", [](const MeshRequest& r) { return r.checkpoint.every; },
          [](MeshRequest& r, double v) { r.checkpoint.every = v; })
      .def_property(
          "checkpoint_record", [](const MeshRequest& r) { return r.checkpoint.record; },
          [](MeshRequest& r, const std::string& v) { r.checkpoint.record = v; })
      .def_property(
          "resume_state", [](const MeshRequest& r) { return py::bytes(r.checkpoint.resume_state); },
          [](MeshRequest& r, const py::bytes& v) { r.checkpoint.resume_state = std::string(v); })
      .def_property(
          "extend", [](const MeshRequest& r) { return r.checkpoint.extend; },
          [](MeshRequest& r, bool v) { r.checkpoint.extend = v; });
  register_checkpoint_functions(module);

  module.def("mesh", &mesh_problem, py::arg("problem"), py::arg("request"), py::arg("progress"),
             py::arg("handle_interrupt"));
  module.def("check", &check_mesh);
  module.def("improve", &improve);
  module.def("ddt", &ddt);
  module.def("ddt_all_criteria", &ddt_all_criteria);
  module.def("compare", &compare_methods, py::arg("problem"), py::arg("request"),
             py::arg("handle_interrupt"));
  module.def("method_names", &covering_method_names);
  module.def("default_coordinate_names", &default_coordinate_names);
  // Raises `error` with a KeyboardInterrupt pending (the second Ctrl-C of a run): Python raises
  // it at its next check, in the code that handles `error`. Raised from C so that no check
  // between setting the interrupt and raising `error` can overtake it.
  module.def("raise_with_pending_interrupt", [](const py::object& error) {
    PyErr_SetInterrupt();
    PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(error.ptr())), error.ptr());
    throw py::error_already_set();
  });
  module.def("catalogue", [] {
    py::list entries;
    for (const auto& entry : catalogue()) {
      py::dict parameters;
      for (const auto& parameter : entry.parameters) {
        parameters[py::str(parameter.name)] = parameter.default_value;
      }
      entries.append(py::dict(py::arg("name") = entry.name, py::arg("summary") = entry.summary,
                              py::arg("parameters") = parameters));
    }
    return entries;
  });
}

}  // namespace tessera::python
