// SPDX-License-Identifier: MIT
// KLU's solve with 1, 2, 4 and 8 right-hand sides on a bordered 1-D matrix like bvp's (a
// tridiagonal block, two dense parameter columns, two coordinate border rows): why tessera's
// chord iterations solve the points of one factorisation together (bench/history/RESULTS-log.md
// section 10, seventh step). A 1-D triangular solve is latency-bound; several columns fill the
// pipeline.
// Build and run (Debian's libsuitesparse-dev):
//   g++ -O2 -I/usr/include/suitesparse bench/klu_columns.cpp -lklu -o /tmp/klu_columns
//   /tmp/klu_columns 1002 && /tmp/klu_columns 10002 && /tmp/klu_columns 100002
#include <klu.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 10002;
  if (n < 10) {
    std::fprintf(stderr, "usage: klu_columns N (N >= 10: the matrix order)\n");
    return 2;
  }
  std::vector<int> Ap(n + 1);
  std::vector<int> Ai;
  std::vector<double> Ax;
  std::mt19937 generator(1);
  std::uniform_real_distribution<double> uniform(0.1, 1.0);
  const int border = n / 2;  // the first border row picks this u column, the second ε's
  for (int j = 0; j < n; ++j) {
    Ap[j] = static_cast<int>(Ai.size());
    if (j < n - 2) {
      for (int i = j - 1; i <= j + 1; ++i) {
        if (i >= 0 && i < n - 2) {
          Ai.push_back(i);
          Ax.push_back(i == j ? -2.5 : 1.0);
        }
      }
      if (j == border) {
        Ai.push_back(n - 2);
        Ax.push_back(1.0);
      }
    } else {
      for (int i = 0; i < n - 2; ++i) {
        Ai.push_back(i);
        Ax.push_back(uniform(generator));
      }
      if (j == n - 1) {
        Ai.push_back(n - 1);
        Ax.push_back(1.0);
      }
    }
  }
  Ap[n] = static_cast<int>(Ai.size());
  klu_common common;
  klu_defaults(&common);
  klu_symbolic* symbolic = klu_analyze(n, Ap.data(), Ai.data(), &common);
  klu_numeric* numeric = klu_factor(Ap.data(), Ai.data(), Ax.data(), symbolic, &common);
  if (numeric == nullptr) {
    std::fprintf(stderr, "KLU could not factor the matrix (status %d)\n", common.status);
    return 1;
  }
  std::printf("n = %d: nnz(L) %d, nnz(U) %d, off-diagonal %d\n", n, numeric->lnz, numeric->unz,
              numeric->nzoff);
  for (int columns : {1, 2, 4, 8}) {
    std::vector<double> B(static_cast<std::size_t>(n) * columns, 1.0);
    const int repetitions = std::max(4, 8000000 / (n * columns));
    const auto start = std::chrono::steady_clock::now();
    for (int r = 0; r < repetitions; ++r) {
      klu_solve(symbolic, numeric, n, columns, B.data(), &common);
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
        repetitions;
    std::printf("  %d right-hand side(s): %.1f µs per solve, %.1f µs per column\n", columns,
                1e6 * seconds, 1e6 * seconds / columns);
  }
  klu_free_numeric(&numeric, &common);
  klu_free_symbolic(&symbolic, &common);
  return 0;
}
