// SPDX-License-Identifier: MIT
// The options of every subcommand, declared in their headers (mesh_command.h, …) and kept here
// together: CLI11 2.1 (Debian 12) is header-only and costs about 7 CPU seconds in each file
// that includes it, so only this file, cli_support.cpp and main.cpp do.
#include <CLI/CLI.hpp>
#include <sstream>
#include <string>

#include "cli_support.h"
#include "compare_command.h"
#include "ddt_command.h"
#include "improve_command.h"
#include "mesh_command.h"
#include "picture_command.h"
#include "tessera/methods/covering_methods.h"
#include "tessera/picture/picture.h"

namespace tessera::app {

CLI::App* add_compare_command(CLI::App& app, CompareCommand& command) {
  auto* compare = app.add_subcommand(
      "compare", "run every covering method on one problem and print a table side by side");
  compare->add_option("problem", command.problem, "catalogue name or problem file")->required();
  compare
      ->add_option("--step,-s", command.settings.step,
                   "front: edge length; atlas: largest chart radius (defaults as for mesh)")
      ->check(finite_positive());
  compare
      ->add_option("--tolerance,-t", command.settings.tolerance,
                   "bound on the distance of every triangle to M, the same for every method "
                   "(default: step/50, the atlas's default)")
      ->check(finite_positive());
  compare
      ->add_option("--placement", command.settings.atlas_placement,
                   "atlas: 'auto' (default: hexagonal where DF is dense and there is no domain, "
                   "disk otherwise), "
                   "'disk' (Henderson's) or 'hexagonal' (about 30% fewer vertices, then smoothed "
                   "on M: cheap at small n, a factorisation per vertex and pass at large n)")
      ->check(CLI::IsMember({"auto", "disk", "hexagonal"}));
  compare->add_option("--start", command.start, "start point, comma separated");
  compare->add_option("--box", command.box,
                      "clip to a box: lower,upper for each coordinate, or name=lower:upper,…");
  compare
      ->add_option("--max-vertices", command.settings.max_vertices,
                   "stop each method after this many vertices")
      ->check(CLI::Range(7, 100'000'000));
  return compare;
}

CLI::App* add_ddt_command(CLI::App& app, DdtCommand& command) {
  auto* ddt = app.add_subcommand(
      "ddt", "data-dependent triangulation of scattered data in the plane (Malcolm)");
  ddt->add_option("points", command.points, "CSV file with columns x, y[, value]")->required();
  ddt->add_option("--function", command.function,
                  "sample Franke's F1, F2, F7, F8 or F9 at the points and measure the "
                  "interpolation error against it");
  ddt->add_option("--value-column", command.value_column, "take the values from this column");
  ddt->add_option("--criterion", command.criterion,
                  "delaunay, mwt, maxmin3d, mwt3d, abn, jnd, pf, pd or equid (default abn)");
  ddt->add_option("--norm", command.norm, "cost-vector ordering: l1, l2 (default) or lex")
      ->check(CLI::IsMember({"l1", "l2", "lex"}));
  ddt->add_option("--test", command.test, "swap test: local or global (default)")
      ->check(CLI::IsMember({"local", "global"}));
  ddt->add_option("-o,--output", command.output,
                  "write the triangulation as PLY (value as z and as property 'value')");
  ddt->add_option("--grid", command.grid, "error grid size (default 33: 33×33 on [0,1]²)")
      ->check(CLI::Range(2, 10000));
  ddt->add_flag("--all-criteria", command.all_criteria,
                "print the error of every criterion (the report's table rows)");
  ddt->add_option("--orders", command.orders,
                  "with --all-criteria: also try this many sweep orders and print the spread")
      ->check(CLI::Range(1, 1000));
  ddt->add_option("--compare-report", command.compare_report,
                  "with --all-criteria and --function: print Malcolm's Table 1 (33) or 2 (100) "
                  "value beside each row")
      ->check(CLI::IsMember({33, 100}));
  return ddt;
}

CLI::App* add_improve_command(CLI::App& app, ImproveCommand& command) {
  auto* improve = app.add_subcommand(
      "improve", "improve a mesh of M by edge swaps judged in the tangent plane of M");
  improve
      ->add_option("mesh", command.mesh,
                   "mesh file (.ply, .obj, .vtk or .vtu) or the states of `mesh --states` (.npy)")
      ->required();
  improve->add_option("--problem,-p", command.problem, "catalogue name or problem file")
      ->required();
  improve
      ->add_option("--criterion", command.criterion,
                   "angle (max-min angle, Delaunay-type; default), normal (angle between "
                   "adjacent triangles' planes) or distance (distance to M of the edge midpoint)")
      ->check(CLI::IsMember({"angle", "normal", "distance"}));
  improve->add_option("-o,--output", command.output, "improved mesh: .ply, .obj, .vtk or .vtu")
      ->required();
  improve->add_option("--summary", command.summary, "write the before/after numbers as JSON");
  improve->add_option("--max-sweeps", command.max_sweeps, "most sweeps over the edges (default 50)")
      ->check(CLI::Range(1, 100000));
  improve
      ->add_option("--smooth", command.smooth,
                   "passes of tangential smoothing after the swaps, followed by one more round "
                   "of swaps (default 0: vertices do not move)")
      ->check(CLI::Range(0, 1000));
  return improve;
}

CLI::App* add_mesh_command(CLI::App& app, MeshCommand& mesh) {
  auto* mesh_app = app.add_subcommand("mesh", "cover a problem's surface with a triangle mesh");
  mesh_app
      ->add_option("problem", mesh.problem,
                   "catalogue name (see `tessera problems`) or problem file")
      ->required();
  mesh_app
      ->add_option("--method", mesh.method,
                   "covering method (default " + covering_methods().front().name + ")")
      ->check(CLI::IsMember(covering_method_names()));
  mesh_app
      ->add_option("--step,-s", mesh.settings.step,
                   "front: edge length h (default: the problem's suggestion); atlas: "
                   "largest chart radius (default 2h); bezier: initial step")
      ->check(finite_positive());
  mesh_app
      ->add_option("--tolerance,-t", mesh.settings.tolerance,
                   "bound on the distance of every point of every triangle to M, enforced by "
                   "bisection on M for every method (atlas: also sizes the charts, default "
                   "step/50; bezier: also limits the steps; front and bezier: no bound by "
                   "default)")
      ->check(finite_positive());
  mesh_app
      ->add_option("--chart-tolerance", mesh.settings.atlas_chart_tolerance,
                   "atlas: size the charts for this tolerance (>= --tolerance) and reach "
                   "--tolerance by refinement alone (what `tessera extend --tolerance` does)")
      ->check(finite_positive());
  mesh_app
      ->add_option("--placement", mesh.settings.atlas_placement,
                   "atlas: 'auto' (default: hexagonal where DF is dense and there is no domain, "
                   "disk otherwise), "
                   "'disk' (Henderson's) or 'hexagonal' (about 30% fewer vertices, then smoothed "
                   "on M: cheap at small n, a factorisation per vertex and pass at large n)")
      ->check(CLI::IsMember({"auto", "disk", "hexagonal"}));
  mesh_app
      ->add_option("--start", mesh.starts,
                   "start point, comma separated, e.g. 0,0,1; give it more than once to cover "
                   "the component of each (the report says which component each start reached)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  mesh_app
      ->add_option("--components", mesh.components,
                   "'start' (default): the components the start points lie on; 'all': also "
                   "search the bounded region (--box or the problem's domain) for every other "
                   "component with seeds projected onto M (docs/components.md)")
      ->check(CLI::IsMember({"start", "all"}));
  mesh_app
      ->add_option("--component-seeds", mesh.component_seeds,
                   "--components all: the number of seeds spread over the region (a Halton "
                   "sequence; default 512); components smaller than their spacing, which the "
                   "report prints, may be missed")
      ->check(CLI::Range(1, 10'000'000));
  mesh_app->add_option("--box", mesh.box,
                       "clip to a box: lower,upper for each coordinate, e.g. -1,1,-1,1,-0.8,1, "
                       "or bounds on named coordinates, e.g. lambda=5:20,epsilon=0.15: (an empty "
                       "side is unbounded)");
  mesh_app->add_option("-o,--output", mesh.output, "mesh file: .ply, .obj, .vtk or .vtu")
      ->required();
  mesh_app->add_option("--summary", mesh.summary, "write a JSON summary to this file");
  mesh_app->add_option("--checkpoint", mesh.checkpoint,
                       "atlas: save the build's state to this file (.tsc) every "
                       "--checkpoint-every seconds and when a signal stops the run; `tessera "
                       "resume FILE` continues it to the same mesh (docs/checkpoints.md)");
  mesh_app
      ->add_option("--checkpoint-every", mesh.checkpoint_every,
                   "seconds of build between two checkpoints (default 300; fractions allowed)")
      ->check(finite_positive());
  mesh_app->add_flag("--ascii", mesh.ascii, "write ASCII instead of binary PLY");
  mesh_app->add_flag("--improve", mesh.improve,
                     "improve the mesh: edge swaps and tangential smoothing on M (as `tessera "
                     "improve --smooth 3`)");
  mesh_app->add_option(
      "--view", mesh.view,
      "write the mesh in these functionals of x, comma separated: coordinate names, max:B, "
      "min:B, mean:B, absmax:B, norm:B of a block B, norm, NAME=EXPRESSION, or all "
      "(docs/mesh-files.md); e.g. lambda,epsilon,max:u. The first three place the vertices. "
      "Default: the problem file's view, else every coordinate, or for n > 50 the coordinates "
      "outside blocks and the maximum of each block");
  mesh_app->add_option("--states", mesh.states,
                       "also write the vertices, all n coordinates, as a NumPy array (V, n) to "
                       "this .npy file, and the triangles (T, 3) to FILE.triangles.npy");
  mesh_app->add_option(
      "--folds", mesh.folds,
      "compute the fold curves of M over this parameter plane, two differentiable functionals "
      "(coordinates, mean:B, norm:B, norm, NAME=EXPRESSION), e.g. lambda,epsilon: each point "
      "refined onto the fold by Newton's method, cusps located (docs/algorithms/folds.md)");
  mesh_app->add_option("--folds-output", mesh.folds_output,
                       "file of the fold curves in the mesh's view: .vtk, .vtu, .ply, .json or "
                       ".csv (default: beside the mesh, e.g. out.folds.ply)");
  mesh_app->add_flag("--stability", mesh.stability,
                     "compute at every vertex the eigenvalues of the dynamics B·u' = ±F(u, p) that "
                     "the problem declares: the number with positive real part (unstable_count), "
                     "the largest real part, as point data in the mesh file, counts in the report "
                     "(docs/algorithms/stability.md)");
  mesh_app->add_option("--eigenvalues", mesh.eigenvalues,
                       "sparse problems: how many eigenvalues nearest 0 --stability computes per "
                       "vertex (default 6; dense problems: all)")
      ->check(CLI::PositiveNumber);
  mesh_app->add_flag("--hopf", mesh.hopf,
                     "compute the Hopf curves (a complex pair of eigenvalues crosses the "
                     "imaginary axis; implies --stability) and the neutral saddle curves, every "
                     "point refined to solver tolerance, with the frequency omega, the first "
                     "Lyapunov coefficient l1 (dense problems) and the Bogdanov–Takens, fold–Hopf "
                     "and Bautin points");
  mesh_app->add_option("--hopf-output", mesh.hopf_output,
                       "file of the Hopf curves: .vtk, .vtu, .ply, .json or .csv (default: beside "
                       "the mesh, e.g. out.hopf.ply)");
  mesh_app->add_option("--level", mesh.level,
                       "compute the curve on M where a functional of the view takes a value, "
                       "FUNCTIONAL=VALUE, e.g. x1=0.5, mean:u=1.5, 'r=sqrt(x^2+y^2)=1' "
                       "(docs/algorithms/level-curves.md)");
  mesh_app->add_option("--level-output", mesh.level_output,
                       "file of the level curves: .vtk, .vtu, .ply, .json or .csv (default: beside "
                       "the mesh, e.g. out.level.ply)");
  mesh_app->add_option("--diagram", mesh.diagram,
                       "draw the two-parameter bifurcation diagram to this .png or .svg: the fold "
                       "curves over the dynamics' parameters (or --folds), the Hopf curves and "
                       "their special points (implies --hopf)");
  mesh_app->add_option("--picture", mesh.picture,
                       "draw the mesh in its view to this .png or .svg, coloured by height (by "
                       "stability with --stability), with its boundary and its fold, Hopf and "
                       "level curves (`tessera render` for more control)");
  mesh_app->add_option("--obj-coordinates", mesh.obj_coordinates,
                       "deprecated, use --view: the view of three coordinate indices, e.g. 0,2,3 "
                       "(every format)");
  mesh_app
      ->add_option("--report-samples", mesh.report_samples,
                   "the report measures distances to M at this many vertices, centroids and edge "
                   "midpoints each, drawn uniformly (0: all; default all for n < 500, else 300 "
                   "within a tenth of the run's time or 10 s if longer: docs/summary-json.md); "
                   "each is a projection onto M, the report's cost at large n")
      ->check(CLI::Range(0, 100'000'000));
  mesh_app->add_flag("--quiet,-q", mesh.quiet, "print nothing but errors");
  mesh_app->add_flag("--progress", mesh.progress,
                     "print the progress to stderr as lines, also when it is not a terminal (a "
                     "batch job's log): the build's counts about once a second and the start of "
                     "every later stage (clip, refine, validate, patches, report)");
  mesh_app
      ->add_option("--max-vertices", mesh.settings.max_vertices, "stop after this many vertices")
      ->check(CLI::Range(7, 100'000'000));
  mesh_app
      ->add_option("--max-start-distance", mesh.settings.max_start_distance,
                   "how far the start may be from M (default: 10 steps)")
      ->check(finite_positive());
  mesh_app
      ->add_option("--min-gap-angle", mesh.settings.front_min_gap_degrees,
                   "front: α_min in degrees (default 45.8)")
      ->check(CLI::Range(1.0, 89.0));
  mesh_app
      ->add_option("--max-valence", mesh.settings.front_max_valence,
                   "front: most triangles per vertex (paper: 6; default 7)")
      ->check(CLI::Range(6, 12));
  mesh_app
      ->add_option("--order", mesh.settings.front_order,
                   "front: 'gap' (smallest gap first, default) or 'fifo' (the paper's queue)")
      ->check(CLI::IsMember({"gap", "fifo"}));
  mesh_app
      ->add_option("--max-step", mesh.settings.bezier_max_step,
                   "bezier: upper bound on the step (default 8 × the initial step)")
      ->check(finite_positive());
  mesh_app
      ->add_option("--edge-length-factor", mesh.settings.bezier_edge_length_factor,
                   "bezier: tangent length l_ij/|y_j - y_i| of eq. 3.4 (default 1.0; paper 1.2)")
      ->check(CLI::Range(0.1, 3.0));
  mesh_app
      ->add_option("--min-tangent-cosine", mesh.settings.bezier_min_tangent_cosine,
                   "bezier: alpha_min, the smallest |<t_ij, t_ji>| on an edge (default 0.8)")
      ->check(CLI::Range(0.01, 0.999));
  mesh_app
      ->add_option("--refine", mesh.refine,
                   "bezier: write the cubic surface evaluated on a K x K subdivision of "
                   "every triangle instead of the flat triangles")
      ->check(CLI::Range(1, 64));
  mesh_app
      ->add_option("--backend", mesh.backend,
                   "where F, DF and the factorisations run: 'serial' (this process, default) or "
                   "'petsc' (PETSc's distributed objects on the ranks of mpirun, factored by "
                   "MUMPS, or KLU on one rank; for bvp and bratu2d; PETSc's own options such as "
                   "-ksp_view go last; docs/cluster.md)")
      ->check(CLI::IsMember({"serial", "petsc"}));
  mesh_app->add_option("--patches", mesh.patches,
                       "bezier: write the Bezier control points of every triangle to this file "
                       "(docs/bezier-patches.md)");
  return mesh_app;
}

CLI::App* add_render_command(CLI::App& app, RenderCommand& command) {
  auto* render = app.add_subcommand("render", "draw a mesh as a picture (.png or .svg)");
  render->add_option("mesh", command.mesh,
                     "mesh file (.ply, .obj, .vtk, .vtu or .npy states); none with --diagram");
  render->add_option("-o,--output", command.output, "picture file: .png or .svg")->required();
  render->add_option("--problem,-p", command.problem,
                     "catalogue name or problem file: coordinate names, --view, --colour distance");
  render->add_option("--view", command.view,
                     "with --problem: the functionals drawn (as `mesh --view`), the first three "
                     "place the vertices; default: the file's first three coordinates");
  render->add_option("--colour,--color", command.colour,
                     "colour the triangles by: height (the third coordinate, default), a "
                     "coordinate or view column name, min-angle, area, curvature (Gauss, angle "
                     "deficit), distance (of the centroid to M; needs --problem), stability (by "
                     "the file's unstable_count, from `mesh --stability`), a vertex data array "
                     "of the file by name, or none");
  render->add_option("--curves", command.curves,
                     "polylines drawn over the surface (or in the --diagram), repeatable: the "
                     "curve files of `mesh --folds/--hopf/--level` (.json, .csv, .vtk, .vtu, "
                     ".ply), drawn by their kind "
                     "(fold solid, hopf dashed, neutral_saddle dotted); marked points by their "
                     "marker (cusp triangle, bogdanov_takens square, zero_hopf diamond)");
  render->add_option("--diagram", command.diagram,
                     "P1,P2: draw the two-parameter bifurcation diagram of the --curves files "
                     "over their columns P1 and P2 instead of a mesh");
  render->add_option("--azimuth", command.azimuth,
                     "camera azimuth about the third axis, degrees (default -60; without it and "
                     "--elevation a continuation view is seen from where its folds show)");
  render->add_option("--elevation", command.elevation, "camera elevation, degrees (default 30)")
      ->check(CLI::Range(-90.0, 90.0));
  render->add_option("--zoom", command.zoom, "1: the surface fills the frame (default)")
      ->check(finite_positive());
  render->add_flag("--perspective", command.perspective, "perspective instead of orthographic");
  render
      ->add_option("--edges", command.edges,
                   "draw the edges: on, off or auto (where the triangles are large enough on "
                   "the screen: a median edge of 6 pixels and more, default)")
      ->check(CLI::IsMember({"on", "off", "auto"}));
  render
      ->add_option("--axes", command.axes,
                   "ticks (axes with ticks, numbers and names along the bounding box), triad, "
                   "off, or auto (ticks for continuation views and --top maps, else the "
                   "triad; default)")
      ->check(CLI::IsMember({"auto", "ticks", "triad", "off"}));
  std::ostringstream aspect_help;  // the ratio as the code uses it, not a copy that can drift
  aspect_help << "auto (equal scales unless the axes' extents differ by more than "
              << kMaxEqualAspectRatio
              << "x, default), equal or box (every axis to the same length)";
  render->add_option("--aspect", command.aspect, aspect_help.str())
      ->check(CLI::IsMember({"auto", "equal", "box"}));
  render->add_option("--size", command.size, "WIDTHxHEIGHT in pixels (default 800x600)");
  render->add_flag("--top", command.top,
                   "look from above (the first coordinate right, the second up), unshaded: "
                   "planar triangulations coloured by their data, e.g. `tessera ddt` output");
  render->add_flag("--no-boundary", command.no_boundary, "do not draw the boundary curves");
  render->add_option("--title", command.title, "a line of text at the top");
  return render;
}

}  // namespace tessera::app
