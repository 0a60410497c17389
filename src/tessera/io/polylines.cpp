// SPDX-License-Identifier: MIT
#include "tessera/io/polylines.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "tessera/core/error.h"
#include "tessera/io/file_names.h"
#include "tessera/io/detail/file_buffer.h"
#include "tessera/io/text_file.h"

namespace tessera {

namespace {

int point_total(const std::vector<Polyline>& polylines) {
  int total = 0;
  for (const Polyline& line : polylines) {
    total += static_cast<int>(line.points.cols());
  }
  return total;
}

bool is_marked(const Polyline& line, int i) {
  return !line.marked.empty() && line.marked[static_cast<std::size_t>(i)];
}

// The point indices of each polyline in the file's numbering; a closed one repeats its first.
std::vector<std::vector<int>> line_indices(const std::vector<Polyline>& polylines) {
  std::vector<std::vector<int>> lines;
  int offset = 0;
  for (const Polyline& line : polylines) {
    const int m = static_cast<int>(line.points.cols());
    std::vector<int> indices;
    for (int i = 0; i < m; ++i) {
      indices.push_back(offset + i);
    }
    if (line.is_closed && m > 2) {
      indices.push_back(offset);
    }
    lines.push_back(std::move(indices));
    offset += m;
  }
  return lines;
}

// The VTK cells of the polylines: one line segment (VTK_LINE, 3) per pair of consecutive points,
// in order, and a vertex (VTK_VERTEX, 1) for a polyline of one point. Segments rather than one
// VTK_POLY_LINE per polyline: meshio reads no poly lines. read_polylines joins the segments again.
struct VtkCell {
  int type;
  std::vector<int> points;
};

std::vector<VtkCell> vtk_cells(const std::vector<Polyline>& polylines) {
  constexpr int kVtkVertex = 1;
  constexpr int kVtkLine = 3;
  std::vector<VtkCell> cells;
  for (const auto& indices : line_indices(polylines)) {
    if (indices.size() == 1) {
      cells.push_back({kVtkVertex, indices});
    }
    for (std::size_t i = 1; i < indices.size(); ++i) {
      cells.push_back({kVtkLine, {indices[i - 1], indices[i]}});
    }
  }
  return cells;
}

// Calls f(line, i) for every point in file order.
template <class Function>
void for_each_point(const std::vector<Polyline>& polylines, Function f) {
  for (const Polyline& line : polylines) {
    for (int i = 0; i < line.points.cols(); ++i) {
      f(line, i);
    }
  }
}

void write_values(io_detail::OutputFile& file, const std::vector<Polyline>& polylines,
                  int coordinate) {
  for_each_point(polylines, [&](const Polyline& line, int i) {
    file.real(line.points(coordinate, i));
    file.character('\n');
  });
}

void write_xyz(io_detail::OutputFile& file, const Polyline& line, int i, char separator) {
  const int k = static_cast<int>(line.points.rows());
  for (int c = 0; c < 3; ++c) {
    if (c > 0) {
      file.character(separator);
    }
    file.real(c < k ? line.points(c, i) : 0.0);
  }
}

void write_vtk(const std::string& path, const std::vector<Polyline>& polylines,
               const PolylineFileOptions& options) {
  io_detail::OutputFile file("VTK", path);
  std::string title = "tessera polylines";
  if (!options.kind.empty()) {
    title += "; kind: " + options.kind;
  }
  for (const auto& comment : options.comments) {
    title += "; " + comment;
  }
  title = title.substr(0, 255);  // the legacy format's limit
  file.text("# vtk DataFile Version 4.2\n");
  file.text(title);
  // UNSTRUCTURED_GRID: the only legacy dataset meshio reads (tessera wrote POLYDATA before).
  file.text("\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS ");
  const int total = point_total(polylines);
  file.integer(total);
  file.text(" double\n");
  for_each_point(polylines, [&](const Polyline& line, int i) {
    write_xyz(file, line, i, ' ');
    file.character('\n');
  });
  const auto cells = vtk_cells(polylines);
  std::int64_t size = 0;
  for (const auto& cell : cells) {
    size += static_cast<std::int64_t>(cell.points.size()) + 1;
  }
  file.text("CELLS ");
  file.integer(static_cast<std::int64_t>(cells.size()));
  file.character(' ');
  file.integer(size);
  file.character('\n');
  for (const auto& cell : cells) {
    file.integer(static_cast<std::int64_t>(cell.points.size()));
    for (const int index : cell.points) {
      file.character(' ');
      file.integer(index);
    }
    file.character('\n');
  }
  file.text("CELL_TYPES ");
  file.integer(static_cast<std::int64_t>(cells.size()));
  file.character('\n');
  for (const auto& cell : cells) {
    file.integer(cell.type);
    file.character('\n');
  }
  file.text("POINT_DATA ");
  file.integer(total);
  file.character('\n');
  for (std::size_t c = 0; c < options.names.size(); ++c) {
    file.text("SCALARS " + options.names[c] + " double 1\nLOOKUP_TABLE default\n");
    write_values(file, polylines, static_cast<int>(c));
  }
  file.text("SCALARS " + options.marker_name + " int 1\nLOOKUP_TABLE default\n");
  for_each_point(polylines, [&](const Polyline& line, int i) {
    file.integer(is_marked(line, i) ? 1 : 0);
    file.character('\n');
  });
  file.close();
}

void write_vtu(const std::string& path, const std::vector<Polyline>& polylines,
               const PolylineFileOptions& options) {
  io_detail::OutputFile file("VTU", path);
  const auto cells = vtk_cells(polylines);
  file.text("<?xml version=\"1.0\"?>\n");
  if (!options.kind.empty()) {
    file.text("<!-- kind: " + options.kind + " -->\n");
  }
  for (const auto& comment : options.comments) {
    file.text("<!-- " + xml_comment_text(comment) + " -->\n");
  }
  file.text("<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
            "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"");
  file.integer(point_total(polylines));
  file.text("\" NumberOfCells=\"");
  file.integer(static_cast<std::int64_t>(cells.size()));
  file.text("\">\n      <PointData>\n");
  for (std::size_t c = 0; c < options.names.size(); ++c) {
    file.text("        <DataArray type=\"Float64\" Name=\"" + xml_escaped(options.names[c]) +
              "\" format=\"ascii\">\n");
    write_values(file, polylines, static_cast<int>(c));
    file.text("        </DataArray>\n");
  }
  file.text("        <DataArray type=\"Int32\" Name=\"" + xml_escaped(options.marker_name) +
            "\" format=\"ascii\">\n");
  for_each_point(polylines, [&](const Polyline& line, int i) {
    file.integer(is_marked(line, i) ? 1 : 0);
    file.character('\n');
  });
  file.text("        </DataArray>\n      </PointData>\n      <Points>\n"
            "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
  for_each_point(polylines, [&](const Polyline& line, int i) {
    write_xyz(file, line, i, ' ');
    file.character('\n');
  });
  file.text("        </DataArray>\n      </Points>\n      <Cells>\n"
            "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
  for (const auto& cell : cells) {
    for (const int index : cell.points) {
      file.integer(index);
      file.character(' ');
    }
    file.character('\n');
  }
  file.text("        </DataArray>\n"
            "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
  std::int64_t offset = 0;
  for (const auto& cell : cells) {
    offset += static_cast<std::int64_t>(cell.points.size());
    file.integer(offset);
    file.character('\n');
  }
  file.text("        </DataArray>\n"
            "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
  for (const auto& cell : cells) {
    file.integer(cell.type);
    file.character('\n');
  }
  file.text("        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n"
            "</VTKFile>\n");
  file.close();
}

void write_ply(const std::string& path, const std::vector<Polyline>& polylines,
               const PolylineFileOptions& options) {
  io_detail::OutputFile file("PLY", path);
  const auto lines = line_indices(polylines);
  long edge_count = 0;
  for (const auto& indices : lines) {
    edge_count += std::max<long>(0, static_cast<long>(indices.size()) - 1);
  }
  file.text("ply\nformat ascii 1.0\n");
  if (!options.kind.empty()) {
    file.text("comment kind: " + options.kind + "\n");
  }
  for (const auto& comment : options.comments) {
    file.text("comment " + comment + "\n");
  }
  std::string names;
  for (const auto& name : options.names) {
    names += " " + name;
  }
  file.text("comment coordinate names:" + names + "\n");
  file.text("element vertex ");
  file.integer(point_total(polylines));
  file.text("\nproperty double x\nproperty double y\nproperty double z\n");
  for (std::size_t c = 3; c < options.names.size(); ++c) {
    file.text("property double " + options.names[c] + "\n");
  }
  file.text("property uchar " + options.marker_name + "\nelement edge ");
  file.integer(edge_count);
  file.text("\nproperty int vertex1\nproperty int vertex2\nend_header\n");
  for_each_point(polylines, [&](const Polyline& line, int i) {
    write_xyz(file, line, i, ' ');
    for (int c = 3; c < line.points.rows(); ++c) {
      file.character(' ');
      file.real(line.points(c, i));
    }
    file.text(is_marked(line, i) ? " 1\n" : " 0\n");
  });
  for (const auto& indices : lines) {
    for (std::size_t i = 1; i < indices.size(); ++i) {
      file.integer(indices[i - 1]);
      file.character(' ');
      file.integer(indices[i]);
      file.character('\n');
    }
  }
  file.close();
}

void write_json(const std::string& path, const std::vector<Polyline>& polylines,
                const PolylineFileOptions& options) {
  nlohmann::json document;
  document["columns"] = options.names;
  document["marker"] = options.marker_name;
  if (!options.kind.empty()) {
    document["kind"] = options.kind;
  }
  document["comments"] = options.comments;
  document["polylines"] = nlohmann::json::array();
  for (const Polyline& line : polylines) {
    nlohmann::json points = nlohmann::json::array();
    nlohmann::json marked = nlohmann::json::array();
    for (int i = 0; i < line.points.cols(); ++i) {
      points.push_back(std::vector<double>(line.points.col(i).data(),
                                           line.points.col(i).data() + line.points.rows()));
      if (is_marked(line, i)) {
        marked.push_back(i);
      }
    }
    document["polylines"].push_back(
        {{"closed", line.is_closed}, {"points", std::move(points)}, {"marked", std::move(marked)}});
  }
  io_detail::write_whole_file("JSON", path, document.dump(1) + "\n");
}

void write_csv(const std::string& path, const std::vector<Polyline>& polylines,
               const PolylineFileOptions& options) {
  io_detail::OutputFile file("CSV", path);
  for (const auto& comment : options.comments) {
    file.text("# " + comment + "\n");
  }
  if (!options.kind.empty()) {
    file.text("# kind: " + options.kind + "\n");
  }
  file.text("curve,point");
  for (const auto& name : options.names) {
    file.text("," + name);
  }
  file.text("," + options.marker_name + "\n");
  int curve = 0;
  for (const Polyline& line : polylines) {
    for (int i = 0; i < line.points.cols(); ++i) {
      file.integer(curve);
      file.character(',');
      file.integer(i);
      for (int c = 0; c < line.points.rows(); ++c) {
        file.character(',');
        file.real(line.points(c, i));
      }
      file.text(is_marked(line, i) ? ",1\n" : ",0\n");
    }
    ++curve;
  }
  file.close();
}

bool is_name(const std::string& name) {
  if (name.empty()) {
    return false;
  }
  for (const char c : name) {
    if (std::isspace(static_cast<unsigned char>(c)) || c == ',' || c == '"') {
      return false;
    }
  }
  return true;
}

// Letters, digits and '_': a kind goes into comments of every format (an XML comment may not
// hold "--").
bool is_word(const std::string& text) {
  return !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
}

}  // namespace

bool is_polyline_file(const std::string& path) {
  static const std::set<std::string> known = {".vtk", ".vtu", ".ply", ".json", ".csv"};
  return known.count(lowercase_extension(path)) != 0;
}

void write_polylines(const std::string& path, const std::vector<Polyline>& polylines,
                     const PolylineFileOptions& options) {
  const int k = static_cast<int>(options.names.size());
  TESSERA_CHECK(k >= 2, "polylines '" << path << "': need at least two coordinate names, got "
                                      << k);
  std::set<std::string> seen{options.marker_name};
  TESSERA_CHECK(is_name(options.marker_name),
                "polylines '" << path << "': bad marker name '" << options.marker_name << "'");
  TESSERA_CHECK(options.kind.empty() || is_word(options.kind),
                "polylines '" << path << "': bad kind '" << options.kind
                              << "' (a word such as fold, hopf, neutral_saddle, level)");
  for (const auto& name : options.names) {
    TESSERA_CHECK(is_name(name), "polylines '" << path << "': bad coordinate name '" << name
                                               << "' (empty, or with a space, comma or quote)");
    TESSERA_CHECK(seen.insert(name).second,
                  "polylines '" << path << "': the name '" << name << "' occurs twice");
  }
  for (const Polyline& line : polylines) {
    TESSERA_CHECK(line.points.rows() == k, "polylines '" << path << "': a polyline has points in R^"
                                                         << line.points.rows() << ", the names R^"
                                                         << k);
    TESSERA_CHECK(line.marked.empty() || line.marked.size() == static_cast<std::size_t>(line.points.cols()),
                  "polylines '" << path << "': " << line.marked.size() << " marks for "
                                << line.points.cols() << " points");
  }
  const std::string extension = lowercase_extension(path);
  if (extension == ".vtk") {
    write_vtk(path, polylines, options);
  } else if (extension == ".vtu") {
    write_vtu(path, polylines, options);
  } else if (extension == ".ply") {
    write_ply(path, polylines, options);
  } else if (extension == ".json") {
    write_json(path, polylines, options);
  } else if (extension == ".csv") {
    write_csv(path, polylines, options);
  } else {
    TESSERA_CHECK(false, "cannot write polylines to '" << path << "': unknown extension '"
                                                        << extension
                                                        << "' (use .vtk, .vtu, .ply, .json or .csv)");
  }
}

}  // namespace tessera
