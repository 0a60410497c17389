// SPDX-License-Identifier: MIT
// `tessera mesh --checkpoint FILE` (the atlas's or the front's build saved as it goes) and `tessera resume
// FILE` (the run continued from it, to the same mesh bit for bit). docs/checkpoints.md.
#pragma once

#include <string>

#include "mesh_command.h"
#include "tessera/methods/atlas/atlas_checkpoint.h"
#include "tessera/methods/front/front_checkpoint.h"

namespace CLI {
class App;
}  // namespace CLI

namespace tessera::app {

struct ResumeCommand {
  std::string checkpoint;  ///< the .tsc file of `tessera mesh --checkpoint`
  std::string output;      ///< -o: instead of the original run's mesh file
  std::string summary;     ///< --summary: instead of the original run's summary file
  bool quiet = false;      ///< -q: print nothing but errors (also if the original run did not)
  bool progress = false;   ///< --progress: progress lines on stderr
};

CLI::App* add_resume_command(CLI::App& app, ResumeCommand& command);

struct ExtendCommand {
  std::string checkpoint;      ///< the .tsc file of `tessera mesh --checkpoint`
  std::string box;             ///< --box: the larger box (containing the run's)
  double tolerance = 0.0;      ///< --tolerance: a finer tolerance (0: the run's)
  std::string output;          ///< -o: instead of the original run's mesh file
  std::string summary;         ///< --summary: instead of the original run's summary file
  std::string new_checkpoint;  ///< --checkpoint: where the extended run saves (default: FILE)
  bool quiet = false;
  bool progress = false;
};

CLI::App* add_extend_command(CLI::App& app, ExtendCommand& command);

/// Checks the checkpoint options of `command` for the chosen method and run (the atlas or the
/// front, one start, the serial backend). \throw InvalidArgument naming the option and the rule.
void check_checkpoint_options(const MeshCommand& command, const std::string& method,
                              bool covers_several);

/// The atlas's checkpoint hooks for `command`: due every command.checkpoint_every seconds,
/// each save a checkpoint file written atomically (the command line, the problem file's hash,
/// the atlas's state), and the state of `tessera resume` to continue from.
/// `progress_lines`: say on stderr what each checkpoint took (with --progress).
AtlasCheckpointing make_atlas_checkpointing(const MeshCommand& command, bool progress_lines);
/// The same for the front (the state in section "front").
FrontCheckpointing make_front_checkpointing(const MeshCommand& command, bool progress_lines);

/// Reads the checkpoint, checks it (the file, the problem file's hash), parses the original
/// command line again in its folder, and runs it continued from the checkpoint.
/// \throw InvalidArgument naming what is wrong, before anything is written.
int run_resume(const ResumeCommand& command);

/// Continues the checkpoint's atlas into a larger box (the charts grow from where they were
/// left open) or to a finer tolerance (the charts kept, the mesh refined), or both: the
/// original command line with --box and --tolerance replaced (and --chart-tolerance set to the
/// atlas's), saved as such in the extended run's checkpoints. \throw InvalidArgument for a box
/// that does not contain the run's or a tolerance that is not finer, before anything is written.
int run_extend(const ExtendCommand& command);

}  // namespace tessera::app
