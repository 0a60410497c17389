// SPDX-License-Identifier: MIT
#include "tessera/core/error.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace {

// Sets TESSERA_DEBUG for one scope and restores what was there.
class DebugVariable {
 public:
  explicit DebugVariable(const char* value) {
    if (const char* old = std::getenv("TESSERA_DEBUG")) {
      old_ = old;
      had_ = true;
    }
    if (value == nullptr) {
      unsetenv("TESSERA_DEBUG");
    } else {
      setenv("TESSERA_DEBUG", value, 1);
    }
  }
  ~DebugVariable() {
    if (had_) {
      setenv("TESSERA_DEBUG", old_.c_str(), 1);
    } else {
      unsetenv("TESSERA_DEBUG");
    }
  }

 private:
  std::string old_;
  bool had_ = false;
};

tessera::InvalidArgument failed_check(double step) {
  try {
    TESSERA_CHECK(step > 0, "step = " << step << " must be > 0");
  } catch (const tessera::InvalidArgument& e) {
    return e;
  }
  ADD_FAILURE() << "no exception";
  return tessera::InvalidArgument("");
}

TEST(Error, CheckNamesTheValueAndTheRule) {
  const DebugVariable debug(nullptr);
  const tessera::InvalidArgument e = failed_check(-0.1);
  // The message a user reads (the CLI's stderr, Python's ValueError) is the rule alone: no
  // "(error_test.cpp:40)" of tessera's sources (issue 34).
  EXPECT_EQ(std::string(e.what()), "step = -0.1 must be > 0");
  // The place stays available for a bug report.
  EXPECT_EQ(e.source_location().rfind("error_test.cpp:", 0), 0u) << e.source_location();
}

TEST(Error, DebugVariableAppendsTheSourceLocation) {
  {
    const DebugVariable debug("1");
    const tessera::InvalidArgument e = failed_check(-0.1);
    EXPECT_EQ(std::string(e.what()), "step = -0.1 must be > 0 (" + e.source_location() + ")");
  }
  {
    const DebugVariable debug("0");
    EXPECT_EQ(std::string(failed_check(-0.1).what()), "step = -0.1 must be > 0");
  }
}

TEST(Error, InternalErrorKeepsItsLocationForTheReport) {
  try {
    TESSERA_ASSERT(1 + 1 == 3);
    FAIL() << "no exception";
  } catch (const tessera::InternalError& e) {
    EXPECT_NE(std::string(e.what()).find("error_test.cpp:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("please report this"), std::string::npos) << e.what();
  }
}

}  // namespace
