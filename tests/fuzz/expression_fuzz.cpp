// SPDX-License-Identifier: MIT
// Fuzzes the expression parser and its reverse-mode differentiation: an Expression of x, y, z
// (and a parameter r) whose value and gradient can be evaluated, or InvalidArgument.
#include <Eigen/Core>
#include <string>

#include "fuzz/fuzz_support.h"
#include "tessera/problems/expression.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  tessera::fuzzing::expect_only_invalid_argument([&] {
    const tessera::Expression f(text, {"x", "y", "z"}, {{"r", 1.5}});
    // A point with negative, fractional and zero coordinates reaches the edges of the
    // functions' domains (log, sqrt, asin, x^p with p fractional).
    const Eigen::Vector3d x(-0.5, 0.0, 2.25);
    Eigen::VectorXd gradient(3);
    const double value = f.value_and_gradient(x, gradient);
    const double value_alone = f.value(x);
    if (!(value == value_alone || (value != value && value_alone != value_alone))) {
      tessera::fuzzing::fail("value_and_gradient and value disagree");
    }
    for (int k = 0; k < 3; ++k) {
      if (!f.depends_on(k) && gradient[k] != 0.0) {
        tessera::fuzzing::fail("a nonzero partial derivative for a variable the tape lacks");
      }
    }
  });
  return 0;
}
