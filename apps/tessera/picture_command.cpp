// SPDX-License-Identifier: MIT
#include "picture_command.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "cli_support.h"
#include "tessera/core/error.h"
#include "tessera/core/scaled_problem.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/io/file_names.h"
#include "tessera/io/mesh_io.h"
#include "tessera/io/output_checks.h"
#include "tessera/io/view_mesh.h"
#include "tessera/picture/bifurcation_diagram.h"
#include "tessera/problems/catalogue.h"
#include "tessera/problems/view.h"

namespace tessera::app {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The smallest angle of each triangle, in degrees, in the mesh's own coordinates: the measure
// of `tessera check` and the summary (atan2, accurate for slivers where acos is not).
Eigen::VectorXd minimum_angles(const TriangleMesh& mesh) {
  Eigen::VectorXd angles(mesh.triangle_count());
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    angles(t) = min_angle(mesh, mesh.triangle(t)) * 180.0 / kPi;
  }
  return angles;
}

Eigen::VectorXd areas(const TriangleMesh& mesh) {
  Eigen::VectorXd area(mesh.triangle_count());
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle& tri = mesh.triangle(t);
    const Eigen::VectorXd a = mesh.point(tri[1]) - mesh.point(tri[0]);
    const Eigen::VectorXd b = mesh.point(tri[2]) - mesh.point(tri[0]);
    area(t) = 0.5 * std::sqrt(std::max(0.0, a.squaredNorm() * b.squaredNorm() - std::pow(a.dot(b), 2)));
  }
  return area;
}

// Discrete Gaussian curvature of the drawn surface: the angle deficit 2π − Σθ at each interior
// vertex over a third of the area of its triangles (Meyer et al.'s barycentric cell), averaged
// over each triangle's corners; boundary vertices have no deficit and count 0.
Eigen::VectorXd gaussian_curvature(const TriangleMesh& mesh) {
  const MeshTopology topology(mesh);
  const int vertex_count = mesh.vertex_count();
  Eigen::VectorXd angle_sum = Eigen::VectorXd::Zero(vertex_count);
  Eigen::VectorXd area_sum = Eigen::VectorXd::Zero(vertex_count);
  const Eigen::VectorXd area = areas(mesh);
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle& tri = mesh.triangle(t);
    for (int k = 0; k < 3; ++k) {
      const int v = tri[static_cast<std::size_t>(k)];
      const Eigen::VectorXd a = mesh.point(tri[static_cast<std::size_t>((k + 1) % 3)]) - mesh.point(v);
      const Eigen::VectorXd b = mesh.point(tri[static_cast<std::size_t>((k + 2) % 3)]) - mesh.point(v);
      angle_sum(v) += std::acos(std::clamp(a.dot(b) / std::max(a.norm() * b.norm(), 1e-300), -1.0, 1.0));
      area_sum(v) += area(t) / 3.0;
    }
  }
  std::vector<char> on_boundary(static_cast<std::size_t>(vertex_count), 0);
  for (const int e : topology.boundary_edges()) {
    on_boundary[static_cast<std::size_t>(topology.edge(e)[0])] = 1;
    on_boundary[static_cast<std::size_t>(topology.edge(e)[1])] = 1;
  }
  Eigen::VectorXd curvature(mesh.triangle_count());
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    double sum = 0.0;
    for (const int v : mesh.triangle(t)) {
      if (!on_boundary[static_cast<std::size_t>(v)] && area_sum(v) > 0) {
        sum += (2 * kPi - angle_sum(v)) / area_sum(v);
      }
    }
    curvature(t) = sum / 3.0;
  }
  return curvature;
}

// Distance of each triangle's centroid to M, as the summary's centroid_distance measures it
// (measure_quality): ‖c − P(c)‖ with P = project_onto_manifold, in the problem's metric (for
// coordinate blocks of weight ≠ 1, in y = W x). NaN (drawn grey) where P does not converge.
Eigen::VectorXd centroid_distances(const TriangleMesh& mesh, const ImplicitProblem& problem) {
  const Eigen::VectorXd weights = metric_weights(problem);
  std::optional<ScaledProblem> scaled;
  if (weights.size() > 0) {
    scaled.emplace(problem, weights);
  }
  const ImplicitProblem& measured = scaled ? static_cast<const ImplicitProblem&>(*scaled) : problem;
  Eigen::VectorXd distance(mesh.triangle_count());
  Linearization workspace;
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const Triangle& tri = mesh.triangle(t);
    Eigen::VectorXd centroid = (mesh.point(tri[0]) + mesh.point(tri[1]) + mesh.point(tri[2])) / 3.0;
    if (scaled) {
      centroid = scaled->to_scaled(centroid);
    }
    Eigen::VectorXd y = centroid;
    distance(t) =
        project_onto_manifold(measured, y, workspace) ? (y - centroid).norm() : std::nan("");
  }
  return distance;
}

const VertexScalars* find_scalars(const std::vector<VertexScalars>& data, const std::string& name) {
  const auto found = std::find_if(data.begin(), data.end(),
                                  [&](const VertexScalars& s) { return s.name == name; });
  return found == data.end() ? nullptr : &*found;
}

// "Da,B" → {"Da", "B"}.
std::pair<std::string, std::string> parse_parameter_pair(const std::string& text) {
  const auto comma = text.find(',');
  const bool is_pair = comma != std::string::npos && comma > 0 && comma + 1 < text.size() &&
                       text.find(',', comma + 1) == std::string::npos;
  TESSERA_CHECK(is_pair,
                "--diagram " << text << ": expected two column names P1,P2, e.g. --diagram Da,B");
  return {text.substr(0, comma), text.substr(comma + 1)};
}

std::pair<int, int> parse_size(const std::string& size) {
  const auto x = size.find('x');
  TESSERA_CHECK(x != std::string::npos, "--size " << size << ": expected WIDTHxHEIGHT, e.g. 800x600");
  try {
    std::size_t used = 0;
    const int width = std::stoi(size.substr(0, x), &used);
    TESSERA_CHECK(used == x, "");
    const int height = std::stoi(size.substr(x + 1), &used);
    TESSERA_CHECK(used == size.size() - x - 1, "");
    return {width, height};
  } catch (const std::exception&) {
    throw InvalidArgument("--size " + size + ": expected WIDTHxHEIGHT in pixels, e.g. 800x600");
  }
}

}  // namespace

std::vector<std::string> picture_quantities() {
  return {"height", "none", "min-angle", "area", "curvature", "distance", "stability"};
}

void write_mesh_picture(const std::string& path, const TriangleMesh& mesh,
                        const TriangleMesh& mesh_in_view, const std::vector<std::string>& names,
                        const std::vector<Polyline>& curves, const std::string& colour,
                        PictureOptions options, const ProblemSetup* setup, bool draw_boundary) {
  PolylineFile folds;
  folds.polylines = curves;
  folds.options.kind = "fold";
  write_mesh_picture(path, mesh, mesh_in_view, names, {folds}, {}, colour, options, setup,
                     draw_boundary);
}

void write_mesh_picture(const std::string& path, const TriangleMesh& mesh,
                        const TriangleMesh& mesh_in_view, const std::vector<std::string>& names,
                        const std::vector<PolylineFile>& curve_files,
                        const std::vector<VertexScalars>& vertex_data, const std::string& colour,
                        PictureOptions options, const ProblemSetup* setup, bool draw_boundary) {
  const int k = mesh_in_view.ambient_dimension();
  TESSERA_CHECK(k >= 2, "a picture needs at least two coordinates, the mesh has " << k);
  PictureScene scene;
  scene.positions.setZero(3, mesh_in_view.vertex_count());
  scene.positions.topRows(std::min(k, 3)) = mesh_in_view.points().topRows(std::min(k, 3));
  scene.triangles = mesh_in_view.triangles();
  for (int c = 0; c < 3 && c < static_cast<int>(names.size()); ++c) {
    scene.axis_names[static_cast<std::size_t>(c)] = names[static_cast<std::size_t>(c)];
  }
  // A flat picture (the third coordinate constant: a 2-D view, a planar triangulation) is seen
  // from above, as a map.
  const bool is_flat = scene.positions.cols() > 0 &&
                       scene.positions.row(2).maxCoeff() == scene.positions.row(2).minCoeff();
  if (is_flat &&
      (options.choose_view || (options.elevation_degrees == PictureOptions{}.elevation_degrees &&
                               options.azimuth_degrees == PictureOptions{}.azimuth_degrees))) {
    options.azimuth_degrees = -90.0;
    options.elevation_degrees = 90.0;
    options.choose_view = false;
  }
  const auto column = std::find(names.begin(), names.end(), colour);
  const VertexScalars* scalars = find_scalars(vertex_data, colour);
  for (const auto& data : vertex_data) {
    TESSERA_CHECK(data.values.size() == static_cast<std::size_t>(mesh.vertex_count()),
                  "vertex data '" << data.name << "' has " << data.values.size()
                                  << " values, the mesh " << mesh.vertex_count() << " vertices");
  }
  // Coordinates and vertex data are values at the vertices: interpolated across the triangles.
  if (colour == "height" && is_flat) {
    // A flat picture has no height to show.
  } else if (colour == "height") {
    scene.vertex_values = mesh_in_view.points().row(std::min(k, 3) - 1).transpose();
    scene.value_label = names.size() >= 3 ? names[2] : "height";
  } else if (column != names.end() && column - names.begin() < k) {
    scene.vertex_values =
        mesh_in_view.points().row(static_cast<Eigen::Index>(column - names.begin())).transpose();
    scene.value_label = colour;
  } else if (colour == "min-angle") {
    scene.triangle_values = minimum_angles(mesh);
    scene.value_label = "min angle (deg)";
  } else if (colour == "area") {
    scene.triangle_values = areas(mesh);
    scene.value_label = "area";
  } else if (colour == "curvature") {
    scene.triangle_values = gaussian_curvature(mesh_in_view.ambient_dimension() == 3
                                                   ? mesh_in_view
                                                   : TriangleMesh(scene.positions, scene.triangles));
    scene.value_label = "Gauss curvature";
  } else if (colour == "distance") {
    TESSERA_CHECK(setup != nullptr,
                  "--colour distance measures the distance to M: give the problem (--problem)");
    TESSERA_CHECK(setup->problem->ambient_dimension() == mesh.ambient_dimension(),
                  "--colour distance: the mesh lies in R^" << mesh.ambient_dimension()
                                                           << ", the problem in R^"
                                                           << setup->problem->ambient_dimension());
    scene.triangle_values = centroid_distances(mesh, *setup->problem);
    scene.value_label = "distance to M";
  } else if (colour == "stability") {
    const VertexScalars* counts = find_scalars(vertex_data, "unstable_count");
    TESSERA_CHECK(counts != nullptr,
                  "--colour stability needs the vertex data 'unstable_count' (the number of "
                  "unstable eigenvalues at each vertex): run tessera mesh … --stability");
    colour_by_stability(scene, counts->values);
  } else if (scalars != nullptr) {
    scene.vertex_values = Eigen::Map<const Eigen::VectorXd>(
        scalars->values.data(), static_cast<Eigen::Index>(scalars->values.size()));
    scene.value_label = colour;
  } else if (colour != "none") {
    std::string known;
    for (const auto& name : picture_quantities()) {
      known += (known.empty() ? "" : ", ") + name;
    }
    for (const auto& name : names) {
      known += ", " + name;
    }
    for (const auto& data : vertex_data) {
      known += ", " + data.name;
    }
    TESSERA_CHECK(false, "--colour " << colour << ": unknown quantity (known: " << known << ")");
  }
  if (draw_boundary) {
    scene.curves = boundary_curves(TriangleMesh(scene.positions, scene.triangles));
  }
  // Over the blue, orange and red of stability the curves are near-black: the dash tells the
  // kind (fold solid, Hopf dashed, neutral saddle dotted).
  const bool is_categorical = !scene.vertex_categories.empty();
  std::vector<Eigen::Vector3d> markers;
  for (const PolylineFile& file : curve_files) {
    const CurveKind kind = curve_kind_from_name(file.options.kind);
    const CurveStyle style = is_categorical ? dark_curve_style(kind, file.options.kind)
                                            : curve_style(kind, file.options.kind);
    const PointKind point_kind = point_kind_from_marker_name(file.options.marker_name);
    for (const Polyline& line : file.polylines) {
      const int rows = std::min(static_cast<int>(line.points.rows()), 3);
      Eigen::Matrix3Xd points = Eigen::Matrix3Xd::Zero(3, line.points.cols());
      points.topRows(rows) = line.points.topRows(rows);
      TESSERA_CHECK(points.allFinite(),
                    "--curves: a polyline of kind '" << file.options.kind
                        << "' has a point whose drawn coordinates (its first three columns) are "
                           "not numbers");
      for (Eigen::Index i = 0; i < line.points.cols(); ++i) {
        if (!line.marked.empty() && line.marked[static_cast<std::size_t>(i)]) {
          markers.push_back(points.col(i));
          scene.marker_kinds.push_back(point_kind);
        }
      }
      scene.curves.push_back(styled_curve(std::move(points), line.is_closed, style));
    }
  }
  scene.markers.resize(3, static_cast<Eigen::Index>(markers.size()));
  for (std::size_t i = 0; i < markers.size(); ++i) {
    scene.markers.col(static_cast<Eigen::Index>(i)) = markers[i];
  }
  // A continuation view: the axes have units to read, and the folds want a view that shows
  // them. Its bifurcation curves make it one whatever the aspect (Whitney's pleat in (λ, μ, x)
  // has comparable extents).
  bool has_bifurcation_curves = false;
  for (const PolylineFile& file : curve_files) {
    const CurveKind kind = curve_kind_from_name(file.options.kind);
    has_bifurcation_curves =
        has_bifurcation_curves ||
        ((kind == CurveKind::Fold || kind == CurveKind::Hopf) && !file.polylines.empty());
  }
  const bool is_continuation =
      has_bifurcation_curves || has_axes_scaled_apart(scene.positions, options.aspect);
  if (is_continuation && options.axes == PictureAxes::Automatic && !is_flat) {
    options.axes = PictureAxes::Ticked;
  }
  options.choose_view = options.choose_view && is_continuation;
  write_picture(path, scene, options);
}

int run_diagram(const RenderCommand& command, int width, int height) {
  const auto [p1, p2] = parse_parameter_pair(command.diagram);
  TESSERA_CHECK(command.mesh.empty(),
                "--diagram draws the --curves files alone; leave out the "
                "mesh '"
                    << command.mesh << "'");
  TESSERA_CHECK(!command.curves.empty(),
                "--diagram " << command.diagram << " needs --curves FILE (repeatable), e.g. "
                             << "--curves X.folds.json --curves X.hopf.json");
  BifurcationDiagramScene scene;
  scene.parameter_names = {p1, p2};
  for (const auto& path : command.curves) {
    const PolylineFile file = read_polylines(path);
    try {
      add_to_diagram(scene, file.polylines, file.options, p1, p2);
    } catch (const InvalidArgument& error) {
      throw InvalidArgument("--diagram " + command.diagram + ": " + path + ": " + error.what());
    }
  }
  BifurcationDiagramOptions options;
  options.width = width;
  options.height = height;
  options.title = command.title;
  write_bifurcation_diagram(command.output, scene, options);
  std::cout << "wrote " << command.output << "\n";
  return 0;
}

int run_render(const RenderCommand& command) {
  TESSERA_CHECK(is_picture_file(command.output),
                "-o " << command.output << ": a picture is .png or .svg");
  check_output_folder(command.output);
  const auto [width, height] = parse_size(command.size);
  if (!command.diagram.empty()) {
    return run_diagram(command, width, height);
  }
  TESSERA_CHECK(!command.mesh.empty(),
                "render needs a mesh file (or --diagram P1,P2 with "
                "--curves files)");
  PictureOptions options;
  options.width = width;
  options.height = height;
  options.azimuth_degrees = command.azimuth.value_or(PictureOptions{}.azimuth_degrees);
  options.elevation_degrees = command.elevation.value_or(PictureOptions{}.elevation_degrees);
  options.choose_view = !command.azimuth && !command.elevation && !command.top;
  options.axes = command.axes == "ticks"   ? PictureAxes::Ticked
                 : command.axes == "triad" ? PictureAxes::Triad
                 : command.axes == "off"   ? PictureAxes::Off
                                           : PictureAxes::Automatic;
  options.zoom = command.zoom;
  options.perspective = command.perspective;
  options.aspect = command.aspect == "equal" ? PictureAspect::Equal
                   : command.aspect == "box" ? PictureAspect::Box
                                             : PictureAspect::Automatic;
  options.title = command.title;
  if (command.top) {
    options.azimuth_degrees = -90.0;
    options.elevation_degrees = 90.0;
    options.flat_shading = true;  // a map: the colours as they are
  }
  TESSERA_CHECK(command.view.empty() || !command.problem.empty(),
                "--view " << command.view << " needs --problem (a view names the problem's coordinates)");
  std::optional<ProblemSetup> setup;
  if (!command.problem.empty()) {
    setup = resolve_problem(command.problem);
  }
  std::vector<PolylineFile> curves;
  for (const auto& path : command.curves) {
    curves.push_back(read_polylines(path));
  }
  std::vector<VertexScalars> vertex_data;
  const TriangleMesh mesh = read_mesh(command.mesh, vertex_data);
  TESSERA_CHECK(command.colour != "stability" || find_scalars(vertex_data, "unstable_count"),
                "--colour stability: " << command.mesh
                                       << " has no vertex data 'unstable_count' (the number of "
                                          "unstable eigenvalues at each vertex); run tessera "
                                          "mesh … --stability to write it");
  TESSERA_CHECK(mesh.triangle_count() > 0, command.mesh << ": the mesh has no triangles to draw");
  const int n = mesh.ambient_dimension();
  TESSERA_CHECK(!setup || setup->problem->ambient_dimension() == n,
                command.mesh << " lies in R^" << n << ", problem '" << command.problem
                             << "' in R^" << setup->problem->ambient_dimension());
  TriangleMesh in_view;
  std::vector<std::string> names;
  if (!command.view.empty()) {
    View view;
    try {
      view = parse_view(command.view, *setup->problem);
    } catch (const ViewSpecificationError& error) {
      throw InvalidArgument("--view " + command.view + ": " + error.reason());
    }
    in_view = mesh_in_view(mesh, view);
    names = coordinate_names_in_view(view);
  } else {
    // Without a problem, the names the file carries (a mesh written in a view keeps its
    // columns, e.g. lambda, epsilon, max_u): axis labels and --colour by a column.
    names = setup ? setup->problem->coordinate_names() : read_coordinate_names(command.mesh, n);
    if (n <= 3) {
      in_view = mesh;
    } else {
      in_view = TriangleMesh(mesh.points().topRows(3), mesh.triangles());
      names.resize(3);
    }
  }
  options.edges = command.edges == "on"    ? PictureEdges::On
                  : command.edges == "off" ? PictureEdges::Off
                                           : PictureEdges::Automatic;
  write_mesh_picture(command.output, mesh, in_view, names, curves, vertex_data, command.colour,
                     options, setup ? &*setup : nullptr, !command.no_boundary);
  std::cout << "wrote " << command.output << "\n";
  return 0;
}

}  // namespace tessera::app
