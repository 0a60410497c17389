// SPDX-License-Identifier: MIT
// `tessera mesh`: cover a problem's surface with a triangle mesh by one of the methods.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "tessera/methods/covering_methods.h"

namespace CLI {
class App;
}  // namespace CLI

namespace tessera::app {

struct MeshCommand {
  std::string problem;  ///< catalogue name (with parameters) or problem file
  std::string method;   ///< one of covering_method_names(); empty: the default (the first)
  MethodSettings settings;
  /// --start, once or more: each start not on a component covered before starts one.
  std::vector<std::string> starts;
  /// --components: "start" (the components of the starts, default) or "all" (also every
  /// component that seeds over the bounded region land on).
  std::string components = "start";
  int component_seeds = 0;  ///< --component-seeds: seeds of the search; 0: the default (512)
  std::string box;
  std::string output;
  std::string summary;
  std::string obj_coordinates;  ///< deprecated: the view of three coordinate indices
  std::string view;             ///< --view: a view specification (problems/view.h)
  std::string states;           ///< --states: the vertices as .npy (and the triangles beside)
  std::string folds;            ///< --folds: the parameter plane of the fold curves, e.g. lambda,mu
  std::string folds_output;     ///< --folds-output: their file (default beside the mesh)
  std::string picture;          ///< --picture: a .png or .svg of the mesh in its view
  bool stability = false;       ///< --stability: eigenvalues at every vertex (point data)
  int eigenvalues = 6;          ///< --eigenvalues: k nearest 0 for sparse problems
  bool hopf = false;            ///< --hopf: Hopf curves and Bogdanov–Takens points
  std::string hopf_output;      ///< --hopf-output: their file (default beside the mesh)
  std::string level;            ///< --level: 'FUNCTIONAL=VALUE', a level curve on M
  std::string level_output;     ///< --level-output: its file (default beside the mesh)
  std::string diagram;          ///< --diagram: the two-parameter bifurcation diagram (.png/.svg)
  int report_samples = -1;  ///< --report-samples: -1 the default (make_report), 0 all
  bool ascii = false;
  bool quiet = false;
  bool progress = false;  ///< --progress: progress as lines on stderr, also off a terminal
  bool improve = false;
  int refine = 0;       ///< bezier: evaluate the cubic patches on a K×K subdivision (0: off)
  std::string patches;  ///< bezier: write the Bézier control points to this file
  std::string checkpoint;  ///< --checkpoint: the build (atlas, front) is saved there
                           ///< (checkpoint_command.h)
  double checkpoint_every = 300.0;  ///< --checkpoint-every: seconds of build between checkpoints
  /// The command line after `tessera` ("mesh", …): saved in the checkpoints for `resume`.
  std::vector<std::string> arguments;
  /// Set by `tessera resume`: the method's state to continue (AtlasCheckpointing or
  /// FrontCheckpointing::resume_from).
  std::shared_ptr<const std::string> resume_state;
  /// Set by `tessera extend`: resume_state is continued into a larger box
  /// (AtlasCheckpointing::extend).
  bool extend = false;
  std::string backend = "serial";          ///< --backend: serial or petsc (solver_backend.h)
  std::vector<std::string> petsc_options;  ///< PETSc's own options from the command line
};

CLI::App* add_mesh_command(CLI::App& app, MeshCommand& command);

/// Runs it; the mesh (even a partial one) is written before a failure is reported.
/// \return 0, or 1 if the method stopped early or the mesh is not valid.
/// \throw InvalidArgument for bad input, before any computation.
int run_mesh(const MeshCommand& command);

}  // namespace tessera::app
