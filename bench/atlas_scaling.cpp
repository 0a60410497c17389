// SPDX-License-Identifier: MIT
// Atlas scaling: time and peak memory per vertex on the sphere and the torus, one fresh
// process per run (peak memory, VmHWM, is process-wide).
//
//     build-bench/bench/tessera_atlas_scaling sphere 1e-4      # one run: prints one table row
//     bench/run.sh                                             # the whole table (10^3 … 10^6)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "tessera/methods/atlas/atlas.h"
#include "tessera/problems/catalogue.h"

namespace {

long peak_resident_kilobytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) {
      return std::atol(line.c_str() + 6);
    }
  }
  return -1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s PROBLEM TOLERANCE\n", argv[0]);
    return 2;
  }
  const tessera::ProblemSetup setup = tessera::make_catalogue_problem(argv[1]);
  tessera::AtlasOptions options;
  options.tolerance = std::atof(argv[2]);
  options.step = 2.0 * setup.suggested_step;
  options.max_vertices = 20'000'000;
  const long before = peak_resident_kilobytes();
  const auto start = std::chrono::steady_clock::now();
  const tessera::CoveringResult result =
      tessera::cover_by_atlas(*setup.problem, setup.start, setup.domain, options);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const long after = peak_resident_kilobytes();
  const int vertices = result.mesh.vertex_count();
  std::printf("| %s | %g | %d | %s | %.3f | %.0f | %.2f | %.0f |\n", argv[1], options.tolerance,
              vertices, tessera::to_string(result.summary.termination), seconds, vertices / seconds,
              1e6 * seconds / vertices, 1024.0 * static_cast<double>(after - before) / vertices);
  return result.summary.is_complete() ? 0 : 1;
}
