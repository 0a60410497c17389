// SPDX-License-Identifier: MIT
// tessera.mesh(...) on the C++ side: the request the Python layer fills in and the run, as
// `tessera mesh` does it (the covering, --improve, --refine, the report and the analyses).
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "checkpoints.h"
#include "handles.h"
#include "tessera/methods/covering_methods.h"
#include "tessera/problems/view.h"

namespace tessera::python {

struct MeshRequest {
  std::string method;  ///< empty: the default
  MethodSettings settings;
  std::vector<double> start;
  /// More start points after `start` (mesh(start=[[…], […]])): each not yet covered starts a
  /// component (`--start` given more than once).
  std::vector<std::vector<double>> more_starts;
  std::string components = "start";  ///< `--components`: "start" or "all"
  int component_seeds = 0;           ///< `--component-seeds`; 0: the default
  std::vector<double> box;
  /// Bounds on named coordinates, `--box`'s name=lower:upper,… form; replaces `box` if set.
  std::string named_box;
  bool improve = false;
  int refine = 0;
  int report_samples = -1;
  int threads = 0;  ///< the data-parallel steps' threads for this call; 0: thread_count()
  std::string view;
  std::string folds;  ///< the parameter plane of the fold curves (`--folds`), empty: none
  bool stability = false;  ///< `--stability`
  int eigenvalues = 6;     ///< `--eigenvalues`: sparse problems, eigenvalues nearest 0 per vertex
  bool hopf = false;       ///< `--hopf` (implies stability)
  std::string level;       ///< `--level FUNCTIONAL=VALUE`, empty: none
  std::string diagram;     ///< `--diagram` picture path (implies hopf), empty: none
  bool wants_patches = false;
  CheckpointRequest checkpoint;  ///< checkpoint=, and what resume/extend continue
};

/// Comma-separated with full precision, so that --start/--box parsing (and its messages) are the
/// CLI's own.
std::string join_numbers(const std::vector<double>& values);

/// The view of the files written: as `tessera mesh` chooses it (--view, the problem file's, the
/// default for large n).
View choose_view(const std::string& specification, const ProblemHandle& problem);

/// The request's box as `--box` spells it (empty: none).
std::string box_text(const MeshRequest& request);

/// Runs the request on the problem (the GIL released while C++ works); `progress` is the
/// Python layer's callable or mode, `handle_interrupt` whether Ctrl-C stops the run.
std::shared_ptr<MeshHandle> mesh_problem(const std::shared_ptr<ProblemHandle>& problem,
                                         MeshRequest request, const pybind11::object& progress,
                                         bool handle_interrupt);

}  // namespace tessera::python
