// SPDX-License-Identifier: MIT
// `tessera improve`: edge swaps on a mesh of M (Lawson's procedure in the tangent plane of M).
#pragma once

#include <string>

namespace CLI {
class App;
}  // namespace CLI

namespace tessera::app {

struct ImproveCommand {
  std::string mesh;                 ///< input mesh file (.ply, .obj, .vtk, .vtu)
  std::string problem;              ///< catalogue name or problem file
  std::string criterion = "angle";  ///< angle, normal or distance
  std::string output;               ///< improved mesh (.ply, .obj, .vtk, .vtu)
  std::string summary;              ///< optional JSON with the before/after numbers
  int max_sweeps = 50;
  int smooth = 0;  ///< passes of tangential smoothing after the swaps (then swaps once more)
};

/// Registers the subcommand and its options on `app`.
CLI::App* add_improve_command(CLI::App& app, ImproveCommand& command);

/// Runs it; returns the process exit code (1 if the improved mesh is not valid).
/// \throw InvalidArgument for bad input.
int run_improve(const ImproveCommand& command);

}  // namespace tessera::app
