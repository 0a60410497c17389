// SPDX-License-Identifier: MIT
#include "tessera/core/describe.h"

#include <algorithm>
#include <sstream>

#include "tessera/core/ambient_space.h"

namespace tessera {

namespace {

// "(x0, x1, …)" of a point with n coordinates, coordinate(i) its i-th.
template <typename Coordinate>
std::string describe(int n, int shown, Coordinate coordinate) {
  std::ostringstream out;
  out.precision(4);
  out << "(";
  if (n <= shown) {
    for (int i = 0; i < n; ++i) {
      out << (i ? ", " : "") << coordinate(i);
    }
  } else {
    // The last two too: the parameters of a discretised problem (λ, ε of the catalogue's
    // PDEs) are its last coordinates, and what a user needs to find the place.
    const int tail = shown >= 3 ? 2 : 0;
    for (int i = 0; i < shown - tail; ++i) {
      out << (i ? ", " : "") << coordinate(i);
    }
    out << ", … " << n - shown << " more";
    for (int i = n - tail; i < n; ++i) {
      out << ", " << coordinate(i);
    }
  }
  out << ")";
  return out.str();
}

}  // namespace

std::string describe_point(const Eigen::Ref<const Eigen::VectorXd>& x, int shown) {
  return describe(static_cast<int>(x.size()), shown, [&](int i) { return x(i); });
}

std::string describe_point(const Eigen::Ref<const Eigen::VectorXd>& x, const AmbientSpace& space,
                           int shown) {
  if (!space.is_distributed()) {
    return describe_point(x, shown);
  }
  return describe(space.dimension(), shown, [&](int i) { return space.coordinate(x, i); });
}

std::string join_words(const std::vector<std::string>& words, const std::string& separator) {
  std::string joined;
  for (const auto& word : words) {
    joined += (joined.empty() ? "" : separator) + word;
  }
  return joined;
}

}  // namespace tessera
