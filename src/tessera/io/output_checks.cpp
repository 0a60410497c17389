// SPDX-License-Identifier: MIT
#include "tessera/io/output_checks.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "tessera/core/error.h"
#include "tessera/io/file_names.h"
#include "tessera/io/mesh_io.h"

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

namespace {

// The keys of the top-level object of a JSON file, without keeping its values (a patches file
// may hold millions of numbers); empty if it is not a JSON object.
std::set<std::string> top_level_keys(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::set<std::string> keys;
  if (!in) {
    return keys;
  }
  using Event = nlohmann::json::parse_event_t;
  const auto keep = [&keys](int depth, Event event, nlohmann::json& parsed) {
    if (event == Event::key && depth == 1) {
      keys.insert(parsed.get<std::string>());
    }
    // Whatever lies below the top level is dropped as soon as it is parsed.
    return depth == 0 || event == Event::key || event == Event::object_start ||
           event == Event::array_start;
  };
  try {
    const nlohmann::json document = nlohmann::json::parse(in, keep);
    if (!document.is_object()) {
      keys.clear();
    }
  } catch (const nlohmann::json::exception&) {
    keys.clear();
  }
  return keys;
}

bool has_all(const std::set<std::string>& keys, std::initializer_list<const char*> wanted) {
  for (const char* key : wanted) {
    if (keys.count(key) == 0) {
      return false;
    }
  }
  return true;
}

// The header lines of a PLY file (up to end_header).
std::vector<std::string> ply_header(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<std::string> lines;
  constexpr std::size_t kMaxLines = 10000;
  for (std::string line; lines.size() < kMaxLines && std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') {
      line.pop_back();
    }
    if (line == "end_header") {
      break;
    }
    lines.push_back(line);
  }
  return lines;
}

bool starts_with(const std::string& text, const std::string& prefix) {
  return text.rfind(prefix, 0) == 0;
}

// A name for a file of `kind` beside `path` that says what it holds: torus.json -> the patches
// torus.patches.json.
std::string suggested_name(const std::string& path, TesseraFileKind kind) {
  const std::filesystem::path file(path);
  const std::string suffix = kind == TesseraFileKind::BezierPatches ? "patches"
                             : kind == TesseraFileKind::Curves      ? "curves"
                             : kind == TesseraFileKind::Mesh        ? "mesh"
                                                                    : "summary";
  return (file.parent_path() / file.stem()).string() + "." + suffix + file.extension().string();
}

}  // namespace

TesseraFileKind tessera_file_kind(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    return TesseraFileKind::None;
  }
  const std::string extension = lowercase_extension(path);
  if (extension == ".json") {
    const auto keys = top_level_keys(path);
    if (has_all(keys, {"control_points", "multi_indices"})) {
      return TesseraFileKind::BezierPatches;
    }
    if (has_all(keys, {"polylines"})) {
      return TesseraFileKind::Curves;
    }
    if (has_all(keys, {"criterion", "swaps", "before"})) {
      return TesseraFileKind::ImproveSummary;
    }
    if (has_all(keys, {"problem", "ambient_dimension"})) {
      return TesseraFileKind::MeshSummary;
    }
    return TesseraFileKind::None;
  }
  if (extension == ".ply") {
    bool is_mesh = false;
    bool has_edges = false;
    bool has_names = false;
    for (const auto& line : ply_header(path)) {
      is_mesh = is_mesh || starts_with(line, "comment written by tessera: triangle mesh");
      has_edges = has_edges || starts_with(line, "element edge ");
      has_names = has_names || starts_with(line, "comment coordinate names:");
    }
    return is_mesh                  ? TesseraFileKind::Mesh
           : has_edges && has_names ? TesseraFileKind::Curves
                                    : TesseraFileKind::None;
  }
  const auto comments = read_mesh_comments(path);
  if (extension == ".vtk" && !comments.empty()) {
    return starts_with(comments.front(), "tessera triangle mesh in R^") ? TesseraFileKind::Mesh
           : starts_with(comments.front(), "tessera polylines")         ? TesseraFileKind::Curves
                                                                        : TesseraFileKind::None;
  }
  if (extension == ".vtu") {
    for (const auto& comment : comments) {
      if (starts_with(comment, "written by tessera: triangle mesh")) {
        return TesseraFileKind::Mesh;
      }
      if (starts_with(comment, "kind: ")) {
        return TesseraFileKind::Curves;
      }
    }
  }
  return TesseraFileKind::None;
}

std::string describe(TesseraFileKind kind) {
  switch (kind) {
    case TesseraFileKind::None:
      return "no file of tessera";
    case TesseraFileKind::Mesh:
      return "a mesh of tessera";
    case TesseraFileKind::Curves:
      return "curves of tessera (--folds, --hopf or --level)";
    case TesseraFileKind::MeshSummary:
      return "the JSON summary of a `tessera mesh` run";
    case TesseraFileKind::ImproveSummary:
      return "the JSON summary of a `tessera improve` run";
    case TesseraFileKind::BezierPatches:
      return "the Bezier patches of a `tessera mesh --method bezier` run";
  }
  return "a file of tessera";
}

void check_replaces_same_kind(const std::string& option, const std::string& path,
                              TesseraFileKind kind) {
  if (path.empty()) {
    return;
  }
  const TesseraFileKind existing = tessera_file_kind(path);
  const std::string written = kind == TesseraFileKind::Mesh            ? "a mesh"
                              : kind == TesseraFileKind::Curves        ? "curves"
                              : kind == TesseraFileKind::BezierPatches ? "Bezier patches"
                                                                       : "a JSON summary";
  TESSERA_CHECK(existing == TesseraFileKind::None || existing == kind,
                option << " " << path << ": the file holds " << describe(existing)
                       << ", which this run would replace with " << written
                       << "; give the option another name, such as '" << suggested_name(path, kind)
                       << "', or remove the file first");
}

}  // namespace tessera
