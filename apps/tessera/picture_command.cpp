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

Eigen::VectorXd column_means(const TriangleMesh& mesh_in_view, int column) {
  Eigen::VectorXd values(mesh_in_view.triangle_count());
  for (int t = 0; t < mesh_in_view.triangle_count(); ++t) {
    double sum = 0.0;
    for (const int v : mesh_in_view.triangle(t)) {
      sum += mesh_in_view.point(v)(column);
    }
    values(t) = sum / 3.0;
  }
  return values;
}

// Polylines as `tessera mesh --folds` writes them in JSON or CSV.
std::vector<Polyline> read_polylines(const std::string& path) {
  const std::string extension = lowercase_extension(path);
  std::ifstream in(path);
  TESSERA_CHECK(in, "--curves " << path << ": cannot open the file");
  std::stringstream text;
  text << in.rdbuf();
  std::vector<Polyline> lines;
  if (extension == ".json") {
    nlohmann::json document;
    try {
      document = nlohmann::json::parse(text.str());
      for (const auto& item : document.at("polylines")) {
        const auto& points = item.at("points");
        Polyline line;
        const int k = points.empty() ? 3 : static_cast<int>(points[0].size());
        line.points.setZero(std::max(k, 3), static_cast<Eigen::Index>(points.size()));
        for (std::size_t i = 0; i < points.size(); ++i) {
          for (int c = 0; c < k; ++c) {
            line.points(c, static_cast<Eigen::Index>(i)) = points[i].at(static_cast<std::size_t>(c)).get<double>();
          }
        }
        line.marked.assign(points.size(), false);
        for (const auto& index : item.value("marked", nlohmann::json::array())) {
          const auto i = index.get<std::size_t>();
          TESSERA_CHECK(i < points.size(), "marked point " << i << " of " << points.size());
          line.marked[i] = true;
        }
        line.is_closed = item.value("closed", false);
        TESSERA_CHECK(line.points.allFinite(), "--curves "
                                                   << path << ": polyline " << lines.size()
                                                   << " has a coordinate that is not finite");
        lines.push_back(std::move(line));
      }
    } catch (const nlohmann::json::exception& error) {
      throw InvalidArgument("--curves " + path + ": not a polylines file of `tessera mesh --folds` (" +
                            error.what() + ")");
    }
  } else if (extension == ".csv") {
    std::string line_text;
    bool has_header = false;
    int columns = 0;
    int current = -1;
    int line_number = 0;
    while (std::getline(text, line_text)) {
      ++line_number;
      if (!line_text.empty() && line_text.back() == '\r') {
        line_text.pop_back();  // a file written on Windows
      }
      if (line_text.empty() || line_text[0] == '#') {
        continue;
      }
      std::vector<std::string> fields;
      std::stringstream row(line_text);
      for (std::string field; std::getline(row, field, ',');) {
        fields.push_back(field);
      }
      if (!has_header) {
        TESSERA_CHECK(fields.size() >= 5 && fields[0] == "curve" && fields[1] == "point",
                      "--curves " << path << ", line " << line_number
                                  << ": expected the header curve,point,<columns>,cusp");
        columns = static_cast<int>(fields.size()) - 3;
        has_header = true;
        continue;
      }
      TESSERA_CHECK(static_cast<int>(fields.size()) == columns + 3,
                    "--curves " << path << ", line " << line_number << ": " << fields.size()
                                << " fields, the header has " << columns + 3);
      try {
        const int curve = std::stoi(fields[0]);
        if (curve != current) {
          lines.emplace_back();
          lines.back().points.resize(std::max(columns, 3), 0);
          current = curve;
        }
        Polyline& line = lines.back();
        const auto m = line.points.cols();
        line.points.conservativeResize(Eigen::NoChange, m + 1);
        line.points.col(m).setZero();
        for (int c = 0; c < columns; ++c) {
          line.points(c, m) = std::stod(fields[static_cast<std::size_t>(2 + c)]);
          if (!std::isfinite(line.points(c, m))) {
            throw std::invalid_argument("not finite");
          }
        }
        line.marked.push_back(fields.back() == "1");
      } catch (const std::exception&) {
        throw InvalidArgument("--curves " + path + ", line " + std::to_string(line_number) +
                              ": not a finite number");
      }
    }
  } else {
    TESSERA_CHECK(false, "--curves " << path
                                     << ": use the .json or .csv polylines of `tessera mesh "
                                        "--folds` (this reads no '"
                                     << extension << "')");
  }
  return lines;
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
  return {"height", "none", "min-angle", "area", "curvature", "distance"};
}

void write_mesh_picture(const std::string& path, const TriangleMesh& mesh,
                        const TriangleMesh& mesh_in_view, const std::vector<std::string>& names,
                        const std::vector<Polyline>& curves, const std::string& colour,
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
  // from above.
  if (scene.positions.cols() > 0 &&
      scene.positions.row(2).maxCoeff() == scene.positions.row(2).minCoeff() &&
      options.elevation_degrees == PictureOptions{}.elevation_degrees &&
      options.azimuth_degrees == PictureOptions{}.azimuth_degrees) {
    options.azimuth_degrees = -90.0;
    options.elevation_degrees = 90.0;
  }
  const auto column = std::find(names.begin(), names.end(), colour);
  const bool is_flat = scene.positions.cols() > 0 &&
                       scene.positions.row(2).maxCoeff() == scene.positions.row(2).minCoeff();
  if (colour == "height" && is_flat) {
    // A flat picture has no height to show.
  } else if (colour == "height") {
    scene.triangle_values = column_means(mesh_in_view, std::min(k, 3) - 1);
    scene.value_label = names.size() >= 3 ? names[2] : "height";
  } else if (column != names.end() && column - names.begin() < k) {
    scene.triangle_values = column_means(mesh_in_view, static_cast<int>(column - names.begin()));
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
  } else if (colour != "none") {
    std::string known;
    for (const auto& name : picture_quantities()) {
      known += (known.empty() ? "" : ", ") + name;
    }
    for (const auto& name : names) {
      known += ", " + name;
    }
    TESSERA_CHECK(false, "--colour " << colour << ": unknown quantity (known: " << known << ")");
  }
  if (draw_boundary) {
    scene.curves = boundary_curves(TriangleMesh(scene.positions, scene.triangles));
  }
  std::vector<Eigen::Vector3d> markers;
  for (const Polyline& line : curves) {
    PictureCurve curve;
    const int rows = std::min(static_cast<int>(line.points.rows()), 3);
    curve.points.setZero(3, line.points.cols());
    curve.points.topRows(rows) = line.points.topRows(rows);
    curve.is_closed = line.is_closed;
    curve.rgb = {0.85, 0.1, 0.1};
    curve.width = 2.5;
    for (Eigen::Index i = 0; i < line.points.cols(); ++i) {
      if (!line.marked.empty() && line.marked[static_cast<std::size_t>(i)]) {
        markers.push_back(curve.points.col(i));
      }
    }
    scene.curves.push_back(std::move(curve));
  }
  scene.markers.resize(3, static_cast<Eigen::Index>(markers.size()));
  for (std::size_t i = 0; i < markers.size(); ++i) {
    scene.markers.col(static_cast<Eigen::Index>(i)) = markers[i];
  }
  write_picture(path, scene, options);
}

CLI::App* add_render_command(CLI::App& app, RenderCommand& command) {
  auto* render = app.add_subcommand("render", "draw a mesh as a picture (.png or .svg)");
  render->add_option("mesh", command.mesh, "mesh file (.ply, .obj, .vtk, .vtu or .npy states)")
      ->required();
  render->add_option("-o,--output", command.output, "picture file: .png or .svg")->required();
  render->add_option("--problem,-p", command.problem,
                     "catalogue name or problem file: coordinate names, --view, --colour distance");
  render->add_option("--view", command.view,
                     "with --problem: the functionals drawn (as `mesh --view`), the first three "
                     "place the vertices; default: the file's first three coordinates");
  render->add_option("--colour,--color", command.colour,
                     "colour the triangles by: height (the third coordinate, default), a "
                     "coordinate or view column name, min-angle, area, curvature (Gauss, angle "
                     "deficit), distance (of the centroid to M; needs --problem) or none");
  render->add_option("--curves", command.curves,
                     "polylines drawn over the surface: the .json or .csv fold curves of `mesh "
                     "--folds` (in the same view); marked points (cusps) as dots");
  render->add_option("--azimuth", command.azimuth, "camera azimuth about the third axis, degrees (default -60)");
  render->add_option("--elevation", command.elevation, "camera elevation, degrees (default 30)")
      ->check(CLI::Range(-90.0, 90.0));
  render->add_option("--zoom", command.zoom, "1: the surface fills the frame (default)")
      ->check(finite_positive());
  render->add_flag("--perspective", command.perspective, "perspective instead of orthographic");
  render->add_option("--edges", command.edges,
                     "draw the edges: on, off or auto (on up to 20000 triangles, default)")
      ->check(CLI::IsMember({"on", "off", "auto"}));
  render->add_option("--aspect", command.aspect,
                     "auto (equal scales unless the axes' extents differ by more than 4x, "
                     "default), equal or box (every axis to the same length)")
      ->check(CLI::IsMember({"auto", "equal", "box"}));
  render->add_option("--size", command.size, "WIDTHxHEIGHT in pixels (default 800x600)");
  render->add_flag("--top", command.top,
                   "look from above (the first coordinate right, the second up), unshaded: "
                   "planar triangulations coloured by their data, e.g. `tessera ddt` output");
  render->add_flag("--no-boundary", command.no_boundary, "do not draw the boundary curves");
  render->add_option("--title", command.title, "a line of text at the top");
  return render;
}

int run_render(const RenderCommand& command) {
  TESSERA_CHECK(is_picture_file(command.output),
                "-o " << command.output << ": a picture is .png or .svg");
  check_output_folder(command.output);
  const auto [width, height] = parse_size(command.size);
  PictureOptions options;
  options.width = width;
  options.height = height;
  options.azimuth_degrees = command.azimuth;
  options.elevation_degrees = command.elevation;
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
  const std::vector<Polyline> curves =
      command.curves.empty() ? std::vector<Polyline>() : read_polylines(command.curves);
  const TriangleMesh mesh = read_mesh(command.mesh);
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
  options.edges = command.edges == "on" || (command.edges == "auto" && mesh.triangle_count() <= 20000);
  write_mesh_picture(command.output, mesh, in_view, names, curves, command.colour, options,
                     setup ? &*setup : nullptr, !command.no_boundary);
  std::cout << "wrote " << command.output << "\n";
  return 0;
}

}  // namespace tessera::app
