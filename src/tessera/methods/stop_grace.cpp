// SPDX-License-Identifier: MIT
#include "tessera/methods/stop_grace.h"

#include <chrono>
#include <memory>
#include <optional>
#include <utility>

#include "tessera/core/error.h"

namespace tessera {

StopRequest after_grace(StopRequest request, double grace_seconds) {
  TESSERA_CHECK(grace_seconds >= 0,
                "after_grace: grace_seconds = " << grace_seconds << " must be >= 0");
  if (!request) {
    return {};
  }
  using Clock = std::chrono::steady_clock;
  // Shared: std::function copies its target, and every copy must count from the same stop.
  auto stopped_at = std::make_shared<std::optional<Clock::time_point>>();
  const auto grace =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(grace_seconds));
  return [request = std::move(request), stopped_at, grace] {
    if (!stopped_at->has_value()) {
      if (!request()) {
        return false;
      }
      *stopped_at = Clock::now();
    }
    return Clock::now() - **stopped_at >= grace;
  };
}

}  // namespace tessera
