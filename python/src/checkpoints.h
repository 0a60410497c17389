// SPDX-License-Identifier: MIT
// Checkpoints of mesh(checkpoint=...) and their continuation by tessera.resume / tessera.extend
// (docs/checkpoints.md, "From Python"). The file is the CLI's format (io/checkpoint_file.h) with
// a "python" section in place of the command line: the JSON record of the mesh() call that
// tessera/__init__.py writes and reads again.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

#include "tessera/methods/covering_methods.h"

namespace tessera::python {

struct CheckpointRequest {
  std::string path;           ///< the .tsc file; empty: no checkpoints
  double every = 300.0;       ///< seconds of build between two checkpoints
  std::string record;         ///< the "python" section: the mesh() call as JSON
  std::string resume_state;   ///< a method's state to continue; empty: start afresh
  bool extend = false;        ///< AtlasCheckpointing::extend (the atlas only)
  bool is_used() const { return !path.empty() || !resume_state.empty(); }
};

/// The hooks of `method` ("atlas" or "front") for `request`, in `settings`: saves every `every`
/// seconds, at a stop and at the end of the build, each a checkpoint file written atomically (a
/// failed write is a warning on stderr: the mesh matters more); continues request.resume_state
/// if given. \throw InvalidArgument for another method, a path that is not .tsc, or extend with
/// the front.
void apply_python_checkpointing(const CheckpointRequest& request, const std::string& method,
                                MethodSettings& settings);

/// read_checkpoint(path) -> {section name: bytes}, checked (InvalidArgument naming what is
/// wrong); atlas_state_header(bytes) -> {"problem", "dimension", "charts", "tolerance", "step"}.
void register_checkpoint_functions(pybind11::module_& module);

}  // namespace tessera::python
