// SPDX-License-Identifier: MIT
#include "tessera/io/output_checks.h"

#include <filesystem>

#include "tessera/core/error.h"

namespace tessera {

void check_output_folder(const std::string& path) {
  if (path.empty()) {
    return;
  }
  const auto parent = std::filesystem::path(path).parent_path();
  TESSERA_CHECK(
      parent.empty() || std::filesystem::is_directory(parent),
      "cannot write '" << path << "': the folder '" << parent.string() << "' does not exist");
}

void check_mesh_output(const std::string& path) {
  check_output_folder(path);
  const std::string extension = std::filesystem::path(path).extension().string();
  TESSERA_CHECK(
      extension == ".ply" || extension == ".obj" || extension == ".vtk" || extension == ".vtu",
      "-o " << path << ": unknown extension '" << extension << "' (use .ply, .obj, .vtk or .vtu"
            << (extension == ".npy" ? "; the states go to a .npy file with --states" : "") << ")");
}

}  // namespace tessera
