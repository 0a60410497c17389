// SPDX-License-Identifier: MIT
#include "tessera/io/file_names.h"

#include <cctype>
#include <filesystem>

namespace tessera {

std::string lowercase_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return extension;
}

std::string curve_file_beside(const std::string& mesh_path, const std::string& kind) {
  std::filesystem::path path(mesh_path);
  std::string extension = path.extension().string();
  const std::string lower = lowercase_extension(mesh_path);
  if (lower != ".ply" && lower != ".vtk" && lower != ".vtu") {
    extension = ".csv";
  }
  path.replace_extension("." + kind + extension);
  return path.string();
}

}  // namespace tessera
