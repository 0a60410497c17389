// SPDX-License-Identifier: MIT
#include "tessera/core/error.h"

#include <gtest/gtest.h>

TEST(Error, CheckNamesTheValueAndTheRule) {
  const double step = -0.1;
  try {
    TESSERA_CHECK(step > 0, "step = " << step << " must be > 0");
    FAIL() << "no exception";
  } catch (const tessera::InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("step = -0.1 must be > 0"), std::string::npos) << e.what();
  }
}
