// SPDX-License-Identifier: MIT
// The numerical kernel of the PETSc backend on any number of ranks: a walk along M of the
// 1-D or 2-D Arrhenius–Bratu problem by tessera's own correctors on the local rows
// (petsc::DistributedProblem): at each step one factorisation at the current point (MUMPS),
// a tangent predictor of length `step` in the metric, and a chord projection from the
// factorisation. Prints one JSON line (rank 0): n, ranks, seconds per factorisation and per
// chord step, counts, and the largest peak memory of a rank. bench/petsc_scaling.sh runs it.
//
//     mpiexec -n 2 build-bench/bench/tessera_petsc_kernel 2 316 10     (bratu2d N = 316, 10 steps)
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>

#include "tessera/core/ambient_space.h"
#include "tessera/core/corrector.h"
#include "tessera/core/counted_problem.h"
#include "tessera/petsc/distributed_problem.h"
#include "tessera/petsc/petsc_bratu.h"

namespace {

// Peak resident memory of this process in MB (VmHWM).
double peak_megabytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) {
      return std::stod(line.substr(6)) / 1024.0;
    }
  }
  return 0.0;
}

}  // namespace

int main(int argc, char** argv) {
  tessera::petsc::Session session(&argc, &argv);
  // Positional arguments first; PETSc's options (-mat_mumps_icntl_7 5, …) follow and stay in argv.
  int positional = 1;
  while (positional < argc && argv[positional][0] != '-') {
    ++positional;
  }
  argc = positional;
  if (argc < 3) {
    if (session.rank() == 0) {
      std::cerr << "usage: tessera_petsc_kernel DIMENSION(1|2) N [STEPS=10] [STEP=0.1]\n";
    }
    return 2;
  }
  const int dimension = std::stoi(argv[1]);
  const int N = std::stoi(argv[2]);
  const int steps = argc > 3 ? std::stoi(argv[3]) : 10;
  const double step = argc > 4 ? std::stod(argv[4]) : 0.1;
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::time_point since) {
    return std::chrono::duration<double>(Clock::now() - since).count();
  };

  tessera::petsc::PetscArrheniusBratu bratu(session.communicator(), dimension, N);
  const tessera::petsc::ScaledPetscProblem scaled(bratu);
  const tessera::petsc::DistributedProblem distributed(scaled);
  const tessera::CountedProblem problem(distributed);
  const tessera::AmbientSpace& space = *distributed.space();
  const int n = space.dimension();
  // u = 0, λ = 0, ε = 0.1 lies on M (F = 0 there), and the metric leaves λ, ε unscaled.
  Eigen::VectorXd x = Eigen::VectorXd::Zero(space.local_rows());
  if (space.holds_row(n - 1)) {
    x(n - 1 - space.first_row()) = 0.1;
  }
  tessera::Linearization linearization;
  tessera::CorrectorOptions options;
  double factor_seconds = 0.0;        // after the first
  double first_factor_seconds = 0.0;  // with MUMPS's analysis of the pattern
  double chord_seconds = 0.0;
  long chord_steps = 0;
  int taken = 0;
  const auto started = Clock::now();
  for (; taken < steps; ++taken) {
    auto t = Clock::now();
    const Eigen::MatrixXd reference = linearization.is_factored() ? linearization.tangent_basis()
                                                                   : Eigen::MatrixXd();
    if (!linearization.factor(problem, x, reference.size() ? &reference : nullptr)) {
      break;
    }
    (taken == 0 ? first_factor_seconds : factor_seconds) += seconds(t);
    // Along the tangent direction that increases λ (the first step) or keeps going.
    const Eigen::MatrixXd& T = linearization.tangent_basis();
    Eigen::Vector2d direction(space.coordinate(T.col(0), n - 2), space.coordinate(T.col(1), n - 2));
    direction.normalize();
    Eigen::VectorXd y = x + step * (T * direction);
    t = Clock::now();
    const tessera::CorrectorSummary summary = tessera::project_chord(problem, linearization, y, options);
    chord_seconds += seconds(t);
    chord_steps += summary.iterations;
    if (!summary.is_success()) {
      break;
    }
    x = y;
  }
  const double total = seconds(started);
  const double peak = space.maximum(peak_megabytes());
  const double lambda = space.coordinate(x, n - 2);
  if (session.rank() == 0) {
    std::printf(
        "{\"dimension\": %d, \"N\": %d, \"n\": %d, \"ranks\": %d, \"steps\": %d, "
        "\"factorisations\": %ld, \"jacobians\": %ld, \"F\": %ld, \"chord_steps\": %ld, "
        "\"seconds\": %.3f, \"first_factorisation_seconds\": %.3f, \"seconds_per_factorisation\": %.4f, \"seconds_per_chord_step\": %.5f, "
        "\"peak_mb_per_rank\": %.1f, \"lambda_reached\": %.6f}\n",
        dimension, N, n, session.size(), taken, problem.factorisations(),
        problem.jacobian_evaluations(), problem.function_evaluations(), chord_steps, total,
        first_factor_seconds, factor_seconds / std::max<long>(1, problem.factorisations() - 1),
        chord_seconds / std::max<long>(1, chord_steps), peak, lambda);
  }
  return taken == steps ? 0 : 1;
}
