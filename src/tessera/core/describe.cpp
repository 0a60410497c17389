// SPDX-License-Identifier: MIT
#include "tessera/core/describe.h"

#include <algorithm>
#include <sstream>

namespace tessera {

std::string describe_point(const Eigen::Ref<const Eigen::VectorXd>& x, int shown) {
  std::ostringstream out;
  out.precision(4);
  out << "(";
  const int n = static_cast<int>(x.size());
  if (n <= shown) {
    for (int i = 0; i < n; ++i) {
      out << (i ? ", " : "") << x(i);
    }
  } else {
    // The last two too: the parameters of a discretised problem (λ, ε of the catalogue's
    // PDEs) are its last coordinates, and what a user needs to find the place.
    const int tail = shown >= 3 ? 2 : 0;
    for (int i = 0; i < shown - tail; ++i) {
      out << (i ? ", " : "") << x(i);
    }
    out << ", … " << n - shown << " more";
    for (int i = n - tail; i < n; ++i) {
      out << ", " << x(i);
    }
  }
  out << ")";
  return out.str();
}

}  // namespace tessera
