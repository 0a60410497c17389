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

}  // namespace tessera
