// SPDX-License-Identifier: MIT
// The costs a covering's strategy weighs (issue 35): one evaluation of F, one minimum-norm solve
// with a kept factorisation (with F, one chord step) and one factorisation (DF evaluated and
// factored, as Linearization::factor does it for a new chart or a Newton step), at a point half a
// suggested step from the start. The smallest mean of 7 rounds. Prints one line per problem.
// Usage: tessera_step_costs [SPEC ...]   (default: the n = 3 surfaces, cstr, bvp and bratu2d)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "tessera/core/corrector.h"
#include "tessera/core/linearization.h"
#include "tessera/problems/catalogue.h"

int main(int argc, char** argv) {
  using namespace tessera;
  std::vector<std::string> specifications(argv + 1, argv + argc);
  if (specifications.empty()) {
    specifications = {"sphere",          "torus",        "equipotential",  "cstr",
                      "bvp:points=50",   "bvp:points=1000", "bratu2d:N=32"};
  }
  std::printf("| problem | n | F µs | solve µs | factorisation µs | factorisation / F | "
              "factorisation / (F + solve) |\n|---|---|---|---|---|---|---|\n");
  for (const std::string& specification : specifications) {
    const ProblemSetup setup = make_catalogue_problem(specification);
    const ImplicitProblem& problem = *setup.problem;
    const int n = problem.ambient_dimension();
    Eigen::VectorXd x = setup.start;
    Linearization workspace;
    project_gauss_newton(problem, x, CorrectorOptions{}, workspace);
    Linearization at_start;
    at_start.factor(problem, x);
    const Eigen::VectorXd y = x + 0.5 * setup.suggested_step * at_start.tangent_basis().col(0);
    Eigen::VectorXd F(n - 2);
    Eigen::VectorXd dx(n);
    using Clock = std::chrono::steady_clock;
    const auto smallest_mean = [](auto&& operation, int repeats) {
      double best = 1e300;
      for (int round = 0; round < 7; ++round) {
        const auto started = Clock::now();
        for (int k = 0; k < repeats; ++k) {
          operation();
        }
        best = std::min(best,
                        std::chrono::duration<double>(Clock::now() - started).count() / repeats);
      }
      return best;
    };
    const int repeats = n < 100 ? 2000 : 20;
    const double evaluation = smallest_mean([&] { problem.evaluate(y, F); }, repeats);
    const double solve = smallest_mean([&] { at_start.solve_minimum_norm(F, dx); }, repeats);
    Linearization other;
    const double factorisation = smallest_mean(
        [&] { other.factor(problem, y, &at_start.tangent_basis()); }, repeats / 4 + 1);
    std::printf("| %s | %d | %.3g | %.3g | %.3g | %.1f | %.2f |\n", specification.c_str(), n,
                evaluation * 1e6, solve * 1e6, factorisation * 1e6, factorisation / evaluation,
                factorisation / (evaluation + solve));
  }
  return 0;
}
