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

AtlasCheckpointing make_python_checkpointing(const CheckpointRequest& request) {
  AtlasCheckpointing hooks;
  if (!request.resume_state.empty()) {
    hooks.resume_from = std::make_shared<const std::string>(request.resume_state);
  }
  hooks.extend = request.extend;
  if (request.path.empty()) {
    return hooks;
  }
  check_output_folder(request.path);
  TESSERA_CHECK(std::filesystem::path(request.path).extension() == ".tsc",
                "checkpoint " << request.path
                              << ": a checkpoint file must end in .tsc (so that no mesh or "
                                 "summary is replaced by one)");
  TESSERA_CHECK(request.every > 0, "checkpoint_every = " << request.every << " must be > 0");
  using Clock = std::chrono::steady_clock;
  const auto last = std::make_shared<Clock::time_point>(Clock::now());
  const double every = request.every;
  hooks.is_due = [last, every] {
    return std::chrono::duration<double>(Clock::now() - *last).count() >= every;
  };
  const auto header = std::make_shared<CheckpointFile>();
  header->sections = {{"python", request.record}, {"method", "atlas"}};
  const std::string path = request.path;
  // (Called from the run's thread without the GIL: C++ only.)
  hooks.save = [last, header, path](std::string state) {
    CheckpointFile file = *header;
    file.sections.emplace_back("atlas", std::move(state));
    try {
      write_checkpoint_file(path, file);
    } catch (const std::exception& error) {
      std::fprintf(stderr, "tessera: warning: checkpoint not written: %s\n", error.what());
    }
    *last = Clock::now();
  };
  return hooks;
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
