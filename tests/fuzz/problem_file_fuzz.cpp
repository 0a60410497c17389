// SPDX-License-Identifier: MIT
// Fuzzes parse_problem (problem files, docs/problem-files.md, with the expressions inside them):
// a problem whose F and DF can be evaluated at its start, or InvalidArgument.
#include <Eigen/Core>
#include <string>

#include "fuzz/fuzz_support.h"
#include "tessera/problems/problem_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  tessera::fuzzing::expect_only_invalid_argument([&] {
    const tessera::ProblemSetup setup = tessera::parse_problem(text, "fuzz.tsr");
    const int n = setup.problem->ambient_dimension();
    if (setup.start.size() != n || n < 3) {
      tessera::fuzzing::fail("a problem in R^" + std::to_string(n) + " with a start of size " +
                             std::to_string(setup.start.size()));
    }
    // Evaluation never throws: values outside F's domain are NaN or inf (expression.h).
    Eigen::VectorXd F(n - 2);
    Eigen::MatrixXd J(n - 2, n);
    setup.problem->evaluate(setup.start, F);
    setup.problem->jacobian(setup.start, J);
  });
  return 0;
}
