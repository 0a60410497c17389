// SPDX-License-Identifier: MIT
#include "tessera/io/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "tessera/core/error.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/io/detail/file_buffer.h"
#include "tessera/io/detail/mesh_parsers.h"
#include "tessera/io/file_names.h"
#include "tessera/io/npy.h"

namespace tessera {

namespace {

std::vector<std::string> whitespace_tokens(const std::string& text) {
  std::istringstream stream(text);
  std::vector<std::string> tokens;
  for (std::string token; stream >> token;) {
    tokens.push_back(token);
  }
  return tokens;
}

// The tokens after `marker` in `line` (up to a ';', which separates the parts of a VTK title),
// or nothing if `line` does not contain `marker`.
std::vector<std::string> tokens_after(const std::string& line, const std::string& marker) {
  const std::size_t at = line.find(marker);
  if (at == std::string::npos) {
    return {};
  }
  const std::string rest = line.substr(at + marker.size());
  return whitespace_tokens(rest.substr(0, rest.find(';')));
}

// The headers are ASCII in every format; a header line longer than this is not one of ours.
constexpr std::size_t kMaxHeaderLine = 1 << 16;

std::vector<std::string> ply_coordinate_names(std::istream& in) {
  std::vector<std::string> names, coordinates;
  for (std::string line; std::getline(in, line) && line.size() < kMaxHeaderLine;) {
    if (line.rfind("end_header", 0) == 0) {
      break;
    }
    if (line.rfind("comment coordinate names:", 0) == 0) {
      names = tokens_after(line, "coordinate names:");
    } else if (line.rfind("comment coordinates:", 0) == 0) {
      coordinates = tokens_after(line, "coordinates:");
    }
  }
  return names.empty() ? coordinates : names;
}

std::vector<std::string> vtk_coordinate_names(std::istream& in, int dimension) {
  std::string line;
  std::getline(in, line);  // "# vtk DataFile Version …"
  std::string title;
  std::getline(in, title);
  if (title.rfind("tessera triangle mesh in R^", 0) != 0) {
    return tokens_after(title, "coordinates:");
  }
  std::vector<std::string> names;
  bool is_point_data = false;
  while (static_cast<int>(names.size()) < dimension && std::getline(in, line)) {
    const std::vector<std::string> tokens = whitespace_tokens(line);
    if (tokens.empty()) {
      continue;
    }
    if (tokens[0] == "POINT_DATA") {
      is_point_data = true;
    } else if (tokens[0] == "CELL_DATA") {
      is_point_data = false;
    } else if (is_point_data && tokens[0] == "SCALARS" && tokens.size() >= 2) {
      names.push_back(tokens[1]);
    }
  }
  return names;
}

std::vector<std::string> vtu_coordinate_names(std::istream& in) {
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  if (text.find("<!-- written by tessera:") == std::string::npos) {
    return {};
  }
  const std::size_t begin = text.find("<PointData");
  const std::size_t end = text.find("</PointData>", begin);
  if (begin == std::string::npos || end == std::string::npos) {
    return {};
  }
  std::vector<std::string> names;
  for (std::size_t at = text.find("<DataArray", begin); at < end;
       at = text.find("<DataArray", at + 1)) {
    const std::size_t name = text.find("Name=\"", at);
    const std::size_t tag_end = text.find('>', at);
    if (name == std::string::npos || name > tag_end) {
      return {};
    }
    const std::size_t quote = text.find('"', name + 6);
    names.push_back(text.substr(name + 6, quote - name - 6));
  }
  return names;
}

std::string without_spaces_around(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos) {
    return "";
  }
  return text.substr(begin, text.find_last_not_of(" \t\r\n") - begin + 1);
}

std::vector<std::string> ply_comments(std::istream& in) {
  std::vector<std::string> comments;
  for (std::string line; std::getline(in, line) && line.size() < kMaxHeaderLine;) {
    if (line.rfind("end_header", 0) == 0) {
      break;
    }
    if (line.rfind("comment ", 0) == 0) {
      comments.push_back(without_spaces_around(line.substr(8)));
    }
  }
  return comments;
}

std::vector<std::string> vtk_comments(std::istream& in) {
  std::string line;
  std::getline(in, line);  // "# vtk DataFile Version …"
  std::string title;
  std::getline(in, title);
  std::vector<std::string> comments;
  for (std::size_t begin = 0; begin <= title.size();) {
    const std::size_t end = std::min(title.find("; ", begin), title.size());
    comments.push_back(without_spaces_around(title.substr(begin, end - begin)));
    begin = end + 2;
  }
  // write_vtk cuts a title at 255 characters (the format's limit): the last part may be cut.
  constexpr std::size_t kMaxTitleLength = 255;
  if (title.size() >= kMaxTitleLength && comments.size() > 1) {
    comments.pop_back();
  }
  return comments;
}

std::vector<std::string> vtu_comments(std::istream& in) {
  // The comments come before <VTKFile>, within the first lines: no need to read a large file.
  std::string head;
  for (std::string line; std::getline(in, line) && line.size() < kMaxHeaderLine;) {
    head += line + "\n";
    if (line.find("<VTKFile") != std::string::npos) {
      break;
    }
  }
  const std::size_t stop = head.find("<VTKFile");
  std::vector<std::string> comments;
  for (std::size_t at = head.find("<!--"); at < stop; at = head.find("<!--", at + 4)) {
    const std::size_t end = head.find("-->", at + 4);
    if (end == std::string::npos) {
      break;
    }
    comments.push_back(without_spaces_around(head.substr(at + 4, end - at - 4)));
  }
  return comments;
}

}  // namespace

void write_mesh(const std::string& path, const TriangleMesh& mesh, const MeshFileOptions& options) {
  const std::string extension = lowercase_extension(path);
  if (extension == ".ply") {
    write_ply(path, mesh,
              {.binary = options.binary,
               .coordinate_names = options.coordinate_names,
               .vertex_scalars = options.vertex_scalars,
               .comments = options.comments});
  } else if (extension == ".obj") {
    write_obj(path, mesh, options.obj_coordinates);
  } else if (extension == ".vtk" || extension == ".vtu") {
    const VtkOptions vtk_options{.coordinate_names = options.coordinate_names,
                                 .vertex_scalars = options.vertex_scalars,
                                 .comments = options.comments};
    if (extension == ".vtk") {
      write_vtk(path, mesh, vtk_options);
    } else {
      write_vtu(path, mesh, vtk_options);
    }
  } else {
    TESSERA_CHECK(false, "cannot write '" << path << "': unknown extension '" << extension
                                          << "'; supported: .ply, .obj, .vtk, .vtu");
  }
}

TriangleMesh read_mesh(const std::string& path) {
  const std::string extension = lowercase_extension(path);
  if (extension == ".ply") {
    return read_ply(path);
  }
  if (extension == ".obj") {
    return read_obj(path);
  }
  if (extension == ".vtk") {
    return read_vtk(path);
  }
  if (extension == ".vtu") {
    return read_vtu(path);
  }
  if (extension == ".npy") {
    return read_states_npy(path);
  }
  TESSERA_CHECK(false, "cannot read '" << path << "': unknown extension '" << extension
                                       << "'; supported: .ply, .obj, .vtk, .vtu, .npy (states)");
  return {};
}

TriangleMesh read_mesh(const std::string& path, std::vector<VertexScalars>& vertex_scalars) {
  const std::string extension = lowercase_extension(path);
  vertex_scalars.clear();
  if (extension == ".ply") {
    return io_detail::parse_ply(io_detail::read_file("PLY", path), path, {}, &vertex_scalars);
  }
  if (extension == ".vtk") {
    return io_detail::parse_vtk(io_detail::read_file("VTK", path), path, &vertex_scalars);
  }
  if (extension == ".vtu") {
    return io_detail::parse_vtu(io_detail::read_file("VTU", path), path, &vertex_scalars);
  }
  return read_mesh(path);
}

std::vector<std::string> read_coordinate_names(const std::string& path, int dimension) {
  TESSERA_CHECK(dimension >= 1,
                "read_coordinate_names: dimension " << dimension << " must be >= 1");
  const std::string extension = lowercase_extension(path);
  std::vector<std::string> names;
  std::ifstream in(path, std::ios::binary);
  if (in) {
    if (extension == ".ply") {
      names = ply_coordinate_names(in);
    } else if (extension == ".vtk") {
      names = vtk_coordinate_names(in, dimension);
    } else if (extension == ".vtu") {
      names = vtu_coordinate_names(in);
    }
  }
  if (static_cast<int>(names.size()) > dimension && extension == ".vtu") {
    names.resize(static_cast<std::size_t>(dimension));  // the coordinates come first
  }
  const std::set<std::string> distinct(names.begin(), names.end());
  const bool is_usable = static_cast<int>(names.size()) == dimension &&
                         distinct.size() == names.size() && !distinct.contains("");
  return is_usable ? names : default_coordinate_names(dimension);
}

std::vector<std::string> read_mesh_comments(const std::string& path) {
  const std::string extension = lowercase_extension(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    return {};
  }
  if (extension == ".ply") {
    return ply_comments(in);
  }
  if (extension == ".vtk") {
    return vtk_comments(in);
  }
  if (extension == ".vtu") {
    return vtu_comments(in);
  }
  return {};
}

}  // namespace tessera
