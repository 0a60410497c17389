// SPDX-License-Identifier: MIT
// `tessera render` and `tessera mesh --picture`: pictures of meshes (docs/pictures.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "tessera/geometry/triangle_mesh.h"
#include "tessera/io/polylines.h"
#include "tessera/io/vertex_data.h"
#include "tessera/picture/picture.h"
#include "tessera/problems/problem_setup.h"

namespace CLI {
class App;
}  // namespace CLI

namespace tessera::app {

struct RenderCommand {
  std::string mesh;     ///< mesh file, any format read_mesh reads; empty with `diagram`
  std::string output;   ///< .png or .svg
  std::string problem;  ///< catalogue name or problem file: names, views, `distance`
  std::string view;     ///< with a problem: the view whose first three functionals are drawn
  std::string colour = "height";
  /// Polylines to draw over it or in the diagram (.json or .csv, as `mesh --folds` writes).
  std::vector<std::string> curves;
  std::string diagram;  ///< "P1,P2": the bifurcation diagram of `curves` over these columns
  std::string size = "800x600";
  std::string edges = "auto";
  std::string axes = "auto";
  std::string aspect = "auto";
  /// The camera's angles; without either, continuation views are seen from the direction that
  /// shows their folds (best_view_direction), other surfaces from (-60, 30).
  std::optional<double> azimuth;
  std::optional<double> elevation;
  double zoom = 1.0;
  bool perspective = false;
  bool top = false;
  bool no_boundary = false;
  std::string title;
};

CLI::App* add_render_command(CLI::App& app, RenderCommand& command);

/// \return 0. \throw InvalidArgument for bad input (before drawing).
int run_render(const RenderCommand& command);

/// The colour quantities `--colour` accepts besides the view's column names.
std::vector<std::string> picture_quantities();

/// A picture of `mesh` (in the problem's R^n) drawn in the view `mesh_in_view` (R^k, k ≥ 2; the
/// first three columns, a third of 0 for k = 2 gives a top view), coloured by `colour` (a
/// quantity or one of `names`), with the mesh's boundary and `curves` (in the view, e.g. fold
/// curves; their marked points as dots) over it. `setup` may be null (then `distance` is refused).
/// A continuation view (axes scaled apart, or fold or Hopf curves drawn) gets ticked axes under
/// PictureAxes::Automatic and keeps `options.choose_view`; other views drop it (geometry is seen
/// from the angles given). A flat view (constant third coordinate) is seen from above.
/// \throw InvalidArgument for an unknown quantity (listing the known ones) and as write_picture.
void write_mesh_picture(const std::string& path, const TriangleMesh& mesh,
                        const TriangleMesh& mesh_in_view, const std::vector<std::string>& names,
                        const std::vector<Polyline>& curves, const std::string& colour,
                        PictureOptions options, const ProblemSetup* setup,
                        bool draw_boundary = true);

/// As above, with curves of several kinds and the mesh's vertex data:
/// - `curve_files`: each drawn in the style of its options.kind (fold red and solid, Hopf blue
///   and dashed, neutral saddle grey and dotted; near-black over a stability colouring), its
///   marked points in the shape of its options.marker_name (cusp, bogdanov_takens, zero_hopf);
///   the columns of the polylines are the view's (as `mesh_in_view`).
/// - `vertex_data`: one value per vertex of `mesh` each; `colour` may name one (the triangle's
///   corner mean, viridis) or be "stability", which needs "unstable_count" (see
///   colour_by_stability: stable, index 1, index >= 2, unknown, with a legend).
/// \throw InvalidArgument as above, for "stability" without "unstable_count", and for vertex
///        data of the wrong length.
void write_mesh_picture(const std::string& path, const TriangleMesh& mesh,
                        const TriangleMesh& mesh_in_view, const std::vector<std::string>& names,
                        const std::vector<PolylineFile>& curve_files,
                        const std::vector<VertexScalars>& vertex_data, const std::string& colour,
                        PictureOptions options, const ProblemSetup* setup,
                        bool draw_boundary = true);

}  // namespace tessera::app
