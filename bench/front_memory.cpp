// SPDX-License-Identifier: MIT
// Peak memory of one advancing-front run, measured in a fresh process.
//
//     tessera_front_memory [problem] [step]        defaults: sphere 0.0125
//
// Google Benchmark cannot measure this: the peak resident set size (VmHWM in /proc/self/status)
// is a property of the whole process and never decreases. This program resets it just before the
// run (writing "5" to /proc/self/clear_refs, Linux ≥ 4.0) so that
//     peak bytes per vertex = (VmHWM after the run − VmRSS before it) / result vertices
// counts everything the run touched at its peak: the front state, the proximity grid, the queue,
// the result mesh and allocator overhead. If the reset is not permitted, the baseline is the
// VmHWM before the run instead (startup is small, so the figure changes little).
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "tessera/methods/front/advancing_front.h"
#include "tessera/problems/catalogue.h"

namespace {

// A "Vm…:  1234 kB" field of /proc/self/status, in bytes; −1 if missing.
long status_bytes(const std::string& field) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind(field + ":", 0) == 0) {
      std::istringstream values(line.substr(field.size() + 1));
      long kilobytes = -1;
      values >> kilobytes;
      return kilobytes * 1024;
    }
  }
  return -1;
}

bool reset_peak_rss() {
  std::ofstream clear_refs("/proc/self/clear_refs");
  clear_refs << "5";
  clear_refs.flush();
  return static_cast<bool>(clear_refs);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string problem_name = argc > 1 ? argv[1] : "sphere";
  const double step = argc > 2 ? std::atof(argv[2]) : 0.0125;
  try {
    const tessera::ProblemSetup setup = tessera::make_catalogue_problem(problem_name);
    tessera::FrontOptions options;
    options.step = step;

    const bool reset = reset_peak_rss();
    const long baseline = reset ? status_bytes("VmRSS") : status_bytes("VmHWM");
    const long peak_before = status_bytes("VmHWM");
    const tessera::CoveringResult result =
        tessera::triangulate_by_front(*setup.problem, setup.start, setup.domain, options);
    const long peak_after = status_bytes("VmHWM");
    const long rss_after = status_bytes("VmRSS");

    const tessera::CoveringSummary& summary = result.summary;
    const double vertices = summary.vertex_count;
    const double mesh_bytes =
        8.0 * setup.problem->ambient_dimension() * vertices + 12.0 * summary.triangle_count;
    std::printf("problem                 %s\n", problem_name.c_str());
    std::printf("step                    %g\n", step);
    std::printf("termination             %s%s%s\n", tessera::to_string(summary.termination),
                summary.message.empty() ? "" : ": ", summary.message.c_str());
    std::printf("vertices                %d\n", summary.vertex_count);
    std::printf("triangles               %d\n", summary.triangle_count);
    std::printf("wall_seconds            %.3f\n", summary.wall_seconds);
    std::printf("vertices_per_second     %.0f\n", vertices / summary.wall_seconds);
    std::printf("peak_reset              %s\n", reset ? "yes (clear_refs)" : "no (VmHWM baseline)");
    std::printf("VmHWM_before_kB         %ld\n", peak_before / 1024);
    std::printf("VmHWM_after_kB          %ld\n", peak_after / 1024);
    std::printf("VmRSS_after_kB          %ld\n", rss_after / 1024);
    std::printf("peak_bytes_per_vertex   %.1f\n", (peak_after - baseline) / vertices);
    std::printf("mesh_bytes_per_vertex   %.1f\n", mesh_bytes / vertices);
    return summary.is_complete() ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "tessera_front_memory: %s\n", error.what());
    return EXIT_FAILURE;
  }
}
