// SPDX-License-Identifier: MIT
// Files other tools can read: meshio (Debian's python3-meshio) opens tessera's PLY files for
// n = 3, 4, 6 and finds every coordinate, bit for bit: x, y, z as its points, the coordinates
// beyond the third as point data; and it opens every mesh and curve file that `tessera mesh`,
// `improve` and `ddt` write, in every format they offer (issue 34: it refused the legacy .vtk
// files, which were POLYDATA), as does VTK's Python (Debian's python3-vtk9) where installed.
// Fails, not skips, when meshio is missing: it is a dependency of the test suite
// (scripts/install-dependencies.sh); VTK is not (about 300 MB installed), and its part is
// skipped without it.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "io/io_test_support.h"
#include "tessera/io/ply.h"

namespace tessera {
namespace {

using namespace io_test;

// The first of $TESSERA_PYTHON, /usr/bin/python3 and python3 that can import meshio (a python3
// of pyenv or a virtualenv may not see Debian's packages), or "" if none can.
std::string python_with_meshio() {
  std::vector<std::string> candidates;
  if (const char* configured = std::getenv("TESSERA_PYTHON")) {
    candidates.emplace_back(configured);
  }
  candidates.insert(candidates.end(), {"/usr/bin/python3", "python3"});
  for (const auto& python : candidates) {
    if (std::system((python + " -c 'import meshio' >/dev/null 2>&1").c_str()) == 0) {
      return python;
    }
  }
  return "";
}

// What meshio reads: one line "<points rows> <points columns> <triangles>", one line with the
// sorted point-data names, then per vertex its points row and the point data `extra` (in that
// order) as Python's shortest round-trip repr, then the triangles.
std::string read_with_meshio(const std::string& python, const std::string& path,
                             const std::vector<std::string>& extra) {
  const std::string script = test_path("read_with_meshio.py");
  write_text(script,
             "import sys, meshio\n"
             "m = meshio.read(sys.argv[1])\n"
             "extra = sys.argv[2:]\n"
             "triangles = m.cells_dict.get('triangle', [])\n"
             "print(m.points.shape[0], m.points.shape[1], len(triangles))\n"
             "print(' '.join(sorted(m.point_data.keys())))\n"
             "for v in range(m.points.shape[0]):\n"
             "    values = list(m.points[v]) + [m.point_data[name][v] for name in extra]\n"
             "    print(' '.join(repr(float(x)) for x in values))\n"
             "for t in triangles:\n"
             "    print(*t)\n");
  std::string command = python + " '" + script + "' '" + path + "'";
  for (const auto& name : extra) {
    command += " " + name;
  }
  command += " 2>&1";
  std::string output;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[4096];
    std::size_t count = 0;
    while ((count = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) {
      output.append(buffer, count);
    }
    const int status = pclose(pipe);
    EXPECT_EQ(status, 0) << command << "\n" << output;
  }
  return output;
}

// Runs `command` and returns its exit status and its stdout and stderr together.
std::pair<int, std::string> run_command(const std::string& command) {
  std::string output;
  int status = -1;
  if (FILE* pipe = popen((command + " 2>&1").c_str(), "r")) {
    char buffer[4096];
    std::size_t count = 0;
    while ((count = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) {
      output.append(buffer, count);
    }
    status = pclose(pipe);
  }
  return {status, output};
}

// Reads each FILE:CELL:NAMES argument with meshio (and VTK where --vtk is given): the file must
// hold points, cells of type CELL (triangle or line) and, where NAMES (comma separated) is not
// empty, point-data arrays of those names. Prints one line per problem and exits 1 if any.
constexpr const char* kReadEveryFile = R"(import sys, math, warnings
import meshio
use_vtk = sys.argv[1] == "--vtk"
problems = []
for item in sys.argv[2:]:
    path, cell, names = item.split(":")
    names = [n for n in names.split(",") if n]
    extension = path.rsplit(".", 1)[1]
    # The curves of a PLY file are its standard `edge` element, which meshio 7 refuses (it reads
    # vertex and face elements only; two-point faces instead would break VTK's PLY reader).
    meshio_reads = not (extension == "ply" and cell == "line")
    try:
        if not meshio_reads:
            raise StopIteration
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # meshio warns and drops the cells it cannot read
            mesh = meshio.read(path)
        cells = {block.type: len(block.data) for block in mesh.cells}
        if len(mesh.points) == 0 or cells.get(cell, 0) == 0:
            problems.append(f"meshio: {path}: {len(mesh.points)} points, cells {cells}, expected {cell}")
        missing = [n for n in names if n not in mesh.point_data]
        if missing:
            problems.append(f"meshio: {path}: no point data {missing} in {sorted(mesh.point_data)}")
    except StopIteration:
        pass
    except Exception as error:
        problems.append(f"meshio: {path}: {type(error).__name__}: {error}")
    if not use_vtk:
        continue
    import vtk
    reader = {"vtk": vtk.vtkUnstructuredGridReader, "vtu": vtk.vtkXMLUnstructuredGridReader,
              "ply": vtk.vtkPLYReader, "obj": vtk.vtkOBJReader}[extension]()
    reader.SetFileName(path)
    if extension == "vtk":
        reader.ReadAllScalarsOn()  # else VTK keeps only the first SCALARS array
    reader.Update()
    data = reader.GetOutput()
    vtk_type = {"triangle": 5, "line": 3}[cell]
    types = [data.GetCellType(i) for i in range(data.GetNumberOfCells())]
    arrays = [data.GetPointData().GetArrayName(i) for i in range(data.GetPointData().GetNumberOfArrays())]
    # VTK's legacy ASCII reader cannot parse "nan" (ParaView issue 19042) and drops the point
    # data from there on: the Hopf curves' l1 is NaN at a Bogdanov-Takens point.
    if extension == "vtk" and b"nan" in open(path, "rb").read():
        names = []
    if data.GetNumberOfPoints() == 0:
        problems.append(f"vtk: {path}: no points")
    # VTK reads no PLY edges (the curves' segments) and no PLY properties beyond the standard ones.
    elif extension != "ply" or cell != "line":
        if vtk_type not in types:
            problems.append(f"vtk: {path}: cell types {sorted(set(types))}, expected {vtk_type}")
        missing = [n for n in names if n not in arrays] if extension != "ply" else []
        if missing:
            problems.append(f"vtk: {path}: no point data {missing} in {arrays}")
for problem in problems:
    print(problem)
print(f"read {len(sys.argv) - 2} files" + (" with meshio and VTK" if use_vtk else " with meshio"))
sys.exit(1 if problems else 0)
)";

// Every file of every format that tessera writes for other tools, from the commands that write
// them: the mesh and its fold, Hopf, neutral saddle and level curves (`tessera mesh`, each curve
// file in the mesh's format), a mesh in a view, `improve` and `ddt`, read by meshio and VTK.
TEST(OtherTools, ReadEveryMeshAndCurveFileOfEveryFormat) {
  const std::string python = python_with_meshio();
  ASSERT_FALSE(python.empty())
      << "meshio is not installed: run scripts/install-dependencies.sh (python3-meshio)";
  const bool has_vtk = std::system((python + " -c 'import vtk' >/dev/null 2>&1").c_str()) == 0;
  const std::string dir = testing::temporary_directory("other_tools");
  std::vector<std::string> files;
  for (const std::string extension : {"ply", "vtk", "vtu", "obj"}) {
    SCOPED_TRACE(extension);
    const std::string mesh = dir + "/cstr." + extension;
    // Curves in the mesh's format; OBJ has no place for curves, which then go to .vtu.
    const std::string curves = extension == "obj" ? "vtu" : extension;
    const auto run = testing::run_cli(
        "mesh cstr --hopf --folds Da,B --level x1=0.5 -q -o " + mesh + " --folds-output " + dir +
        "/cstr_" + extension + ".folds." + curves + " --hopf-output " + dir + "/cstr_" + extension +
        ".hopf." + curves + " --level-output " + dir + "/cstr_" + extension + ".level." + curves);
    ASSERT_EQ(run.exit_code, 0) << run.output;
    // .ply names the coordinates beyond the third x3, x4, … (for meshio and ParaView).
    const std::string names = extension == "ply"   ? "x3,unstable_count"
                              : extension == "obj" ? ""
                                                   : "x1,x2,Da,B,unstable_count";
    files.push_back(mesh + ":triangle:" + names);
    const std::string prefix = dir + "/cstr_" + extension;
    files.push_back(prefix + ".folds." + curves + ":line:x1,Da,B,cusp");
    files.push_back(prefix + ".hopf." + curves + ":line:Da,B,omega,bogdanov_takens");
    files.push_back(prefix + ".neutral_saddles." + curves + ":line:Da,B");
    files.push_back(prefix + ".level." + curves + ":line:Da,B");
    if (extension != "obj") {
      const std::string view = dir + "/cstr_view." + extension;
      const auto in_view =
          testing::run_cli("mesh cstr --view 'Da, B, r = sqrt(x1^2 + x2^2)' -q -o " + view);
      ASSERT_EQ(in_view.exit_code, 0) << in_view.output;
      files.push_back(view + ":triangle:" + (extension == "ply" ? "" : "Da,B,r"));
    }
    const std::string improved = dir + "/cstr_improved." + extension;
    const auto improve =
        testing::run_cli("improve " + dir + "/cstr.ply --problem cstr -o " + improved);
    ASSERT_EQ(improve.exit_code, 0) << improve.output;
    files.push_back(improved + ":triangle:");
    const std::string planar = dir + "/ddt." + extension;
    const auto ddt = testing::run_cli("ddt " + testing::source_path("examples/data/franke33.csv") +
                                      " --function F2 -o " + planar);
    ASSERT_EQ(ddt.exit_code, 0) << ddt.output;
    files.push_back(planar + ":triangle:");
  }
  const std::string script = dir + "/read_every_file.py";
  write_text(script, kReadEveryFile);
  std::string command = python + " '" + script + "' " + (has_vtk ? "--vtk" : "--no-vtk");
  for (const auto& file : files) {
    command += " '" + file + "'";
  }
  const auto [status, output] = run_command(command);
  EXPECT_EQ(status, 0) << output;
  if (!has_vtk) {
    std::cout
        << "[ note ] VTK's Python (python3-vtk9) is not installed: files read by meshio only\n";
  }
}

class MeshioReadsPly : public ::testing::TestWithParam<std::tuple<int, bool>> {};

TEST_P(MeshioReadsPly, AllCoordinatesBitForBit) {
  const auto [n, binary] = GetParam();
  const std::string python = python_with_meshio();
  ASSERT_FALSE(python.empty())
      << "meshio is not installed: run scripts/install-dependencies.sh (python3-meshio)";
  // Moderate values: meshio's ASCII reader parses with NumPy, exact for every double, but the
  // bit patterns of random_mesh include subnormals whose repr we do not want to depend on.
  auto mesh = random_mesh(n, 60, 80, 5);
  Eigen::MatrixXd points = mesh.points();
  for (Eigen::Index i = 0; i < points.size(); ++i) {
    points.data()[i] = std::sin(1.0 + static_cast<double>(i)) * 3.0;
  }
  mesh = TriangleMesh(points, mesh.triangles());
  const std::string path = test_path("meshio_" + std::to_string(n) + (binary ? "b" : "a") + ".ply");
  write_ply(path, mesh,
            {.binary = binary, .vertex_scalars = {{"residual", std::vector<double>(60, 0.5)}}});
  std::vector<std::string> extra;
  for (int k = 3; k < n; ++k) {
    extra.push_back("x" + std::to_string(k));
  }
  std::istringstream in(read_with_meshio(python, path, extra));
  int rows = 0, columns = 0, triangles = 0;
  in >> rows >> columns >> triangles;
  ASSERT_EQ(rows, 60) << in.str();
  EXPECT_EQ(columns, 3);
  EXPECT_EQ(triangles, 80);
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  std::vector<std::string> expected_names = extra;
  expected_names.push_back("residual");
  std::sort(expected_names.begin(), expected_names.end());
  std::string joined;
  for (const auto& name : expected_names) {
    joined += (joined.empty() ? "" : " ") + name;
  }
  EXPECT_EQ(line, joined);
  for (int v = 0; v < 60; ++v) {
    const auto values = read_numbers(in, n);
    for (int k = 0; k < n; ++k) {
      ASSERT_EQ(std::bit_cast<std::uint64_t>(values[static_cast<std::size_t>(k)]),
                std::bit_cast<std::uint64_t>(mesh.point(v)(k)))
          << "vertex " << v << " coordinate " << k;
    }
  }
  for (int t = 0; t < 80; ++t) {
    Triangle triangle{};
    in >> triangle[0] >> triangle[1] >> triangle[2];
    ASSERT_EQ(triangle, mesh.triangle(t)) << "triangle " << t;
  }
}

INSTANTIATE_TEST_SUITE_P(DimensionAndEncoding, MeshioReadsPly,
                         ::testing::Combine(::testing::Values(3, 4, 6),
                                            ::testing::Values(true, false)));

}  // namespace
}  // namespace tessera
