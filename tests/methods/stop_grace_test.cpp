// SPDX-License-Identifier: MIT
// after_grace: a stop request that says stop a grace period after the request first did.
#include "tessera/methods/stop_grace.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "tessera/core/error.h"

namespace tessera {
namespace {

TEST(StopGrace, SaysStopOnlyAfterTheGraceSinceTheRequest) {
  int polls = 0;
  bool requested = false;
  const StopRequest stop = after_grace(
      [&] {
        ++polls;
        return requested;
      },
      0.05);
  EXPECT_FALSE(stop());
  EXPECT_FALSE(stop());
  EXPECT_EQ(polls, 2);
  requested = true;
  EXPECT_FALSE(stop());  // the grace begins here
  EXPECT_EQ(polls, 3);
  std::this_thread::sleep_for(std::chrono::milliseconds(80));
  EXPECT_TRUE(stop());
  EXPECT_EQ(polls, 3);  // the request is not asked again once it said stop
}

TEST(StopGrace, ZeroGraceStopsAtTheFirstTrueAndCopiesShareTheClock) {
  const StopRequest stop = after_grace([] { return true; }, 0.0);
  const StopRequest copy = stop;
  EXPECT_TRUE(copy());
  EXPECT_TRUE(stop());
  const StopRequest late = after_grace([] { return true; }, 3600.0);
  const StopRequest late_copy = late;
  EXPECT_FALSE(late());
  EXPECT_FALSE(late_copy());
}

TEST(StopGrace, NoRequestNeverStopsAndANegativeGraceIsRefused) {
  EXPECT_FALSE(static_cast<bool>(after_grace(StopRequest())));
  EXPECT_THROW(after_grace([] { return true; }, -1.0), InvalidArgument);
}

}  // namespace
}  // namespace tessera
