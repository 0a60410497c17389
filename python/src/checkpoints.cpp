// SPDX-License-Identifier: MIT
#include "checkpoints.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "tessera/core/error.h"
#include "tessera/io/checkpoint_file.h"
#include "tessera/io/output_checks.h"

namespace py = pybind11;

namespace tessera::python {

namespace {

// The hooks every method's checkpointing has (AtlasCheckpointing, FrontCheckpointing).
template <typename Hooks>
Hooks make_hooks(const CheckpointRequest& request, const std::string& method) {
  Hooks hooks;
  if (!request.resume_state.empty()) {
    hooks.resume_from = std::make_shared<const std::string>(request.resume_state);
  }
  if (request.path.empty()) {
    return hooks;
  }
  using Clock = std::chrono::steady_clock;
  const auto last = std::make_shared<Clock::time_point>(Clock::now());
  const double every = request.every;
  hooks.is_due = [last, every] {
    return std::chrono::duration<double>(Clock::now() - *last).count() >= every;
  };
  const auto header = std::make_shared<CheckpointFile>();
  header->sections = {{"python", request.record}, {"method", method}};
  const std::string path = request.path;
  // (Called from the run's thread without the GIL: C++ only.)
  hooks.save = [last, header, path, method](std::string state) {
    CheckpointFile file = *header;
    file.sections.emplace_back(method, std::move(state));
    try {
      write_checkpoint_file(path, file);
    } catch (const std::exception& error) {
      std::fprintf(stderr, "tessera: warning: checkpoint not written: %s\n", error.what());
    }
    *last = Clock::now();
  };
  return hooks;
}

}  // namespace

void apply_python_checkpointing(const CheckpointRequest& request, const std::string& method,
                                MethodSettings& settings) {
  if (!request.is_used()) {
    return;
  }
  TESSERA_CHECK(method == "atlas" || method == "front",
                "checkpoint: checkpoints are supported for methods 'atlas' and 'front', not for '"
                    << method << "'");
  TESSERA_CHECK(!request.extend || method == "atlas",
                "extend continues an atlas; a checkpoint of method '"
                    << method << "' is continued by resume");
  if (!request.path.empty()) {
    check_output_folder(request.path);
    TESSERA_CHECK(std::filesystem::path(request.path).extension() == ".tsc",
                  "checkpoint " << request.path
                                << ": a checkpoint file must end in .tsc (so that no mesh or "
                                   "summary is replaced by one)");
    TESSERA_CHECK(request.every > 0, "checkpoint_every = " << request.every << " must be > 0");
  }
  if (method == "atlas") {
    settings.atlas_checkpoint = make_hooks<AtlasCheckpointing>(request, method);
    settings.atlas_checkpoint.extend = request.extend;
  } else {
    settings.front_checkpoint = make_hooks<FrontCheckpointing>(request, method);
  }
}

void register_checkpoint_functions(py::module_& module) {
  module.def("read_checkpoint", [](const std::string& path) {
    const CheckpointFile file = read_checkpoint_file(path);
    py::dict sections;
    for (const auto& [name, payload] : file.sections) {
      sections[py::str(name)] = py::bytes(payload);
    }
    return sections;
  });
  module.def("atlas_state_header", [](const py::bytes& state) {
    const AtlasStateHeader header = read_atlas_state_header(std::string(state));
    return py::dict(py::arg("problem") = header.problem, py::arg("dimension") = header.dimension,
                    py::arg("charts") = header.charts, py::arg("tolerance") = header.tolerance,
                    py::arg("step") = header.step);
  });
}

}  // namespace tessera::python
