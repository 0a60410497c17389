// SPDX-License-Identifier: MIT
#include "tessera/core/describe.h"

#include <algorithm>
#include <sstream>

namespace tessera {

std::string describe_point(const Eigen::Ref<const Eigen::VectorXd>& x, int shown) {
  std::ostringstream out;
  out.precision(4);
  out << "(";
  const int count = std::min<int>(static_cast<int>(x.size()), shown);
  for (int i = 0; i < count; ++i) {
    out << (i ? ", " : "") << x(i);
  }
  if (x.size() > count) {
    out << ", … " << x.size() - count << " more";
  }
  out << ")";
  return out.str();
}

}  // namespace tessera
