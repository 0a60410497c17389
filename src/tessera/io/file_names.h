// SPDX-License-Identifier: MIT
// What a file's name says: its extension, by which every reader and writer chooses a format.
#pragma once

#include <string>

namespace tessera {

/// The extension of `path` with its dot, in lower case: "mesh.PLY" → ".ply", "a/b" → "".
std::string lowercase_extension(const std::string& path);

}  // namespace tessera
