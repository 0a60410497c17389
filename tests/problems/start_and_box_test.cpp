// SPDX-License-Identifier: MIT
// The start and box of a run from the user's text (`--start`, `--box`, the bindings' start=,
// box=): the values, and usage errors that name the option and the item.
#include "tessera/problems/start_and_box.h"

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "tessera/core/error.h"
#include "tessera/problems/catalogue.h"

namespace tessera {
namespace {

std::string message_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const InvalidArgument& error) {
    return error.what();
  }
  return "";
}

TEST(StartAndBox, ParsesCommaSeparatedNumbers) {
  EXPECT_EQ(parse_numbers("0,-1.5, 2e3", "--start"), (std::vector<double>{0.0, -1.5, 2000.0}));
  const std::string message = message_of([] { parse_numbers("0,x,1", "--start"); });
  EXPECT_NE(message.find("--start: 'x' is not a number"), std::string::npos) << message;
}

TEST(StartAndBox, SetsTheStartAndClipsToABoxThatVoidsTheKnownTopology) {
  ProblemSetup setup = make_catalogue_problem("sphere");
  ASSERT_TRUE(setup.expected_euler_characteristic.has_value());
  apply_start_and_box(setup, "0,0,1", "-1,1,-1,1,0,1");
  EXPECT_EQ(setup.start, Eigen::VectorXd(Eigen::Vector3d(0, 0, 1)));
  EXPECT_FALSE(setup.domain.is_unbounded());
  EXPECT_TRUE(setup.domain.contains(Eigen::Vector3d(0, 0, 0.5)));
  EXPECT_FALSE(setup.domain.contains(Eigen::Vector3d(0, 0, -0.5)));
  EXPECT_FALSE(setup.expected_euler_characteristic.has_value());
  EXPECT_FALSE(setup.exact_area.has_value());
}

TEST(StartAndBox, BoundsNamedCoordinatesOnEitherSide) {
  ProblemSetup setup = make_catalogue_problem("sphere");
  const auto names = setup.problem->coordinate_names();
  apply_start_and_box(setup, "", names[2] + "=0:");  // z ≥ 0, unbounded above
  EXPECT_TRUE(setup.domain.contains(Eigen::Vector3d(5, 5, 0.5)));
  EXPECT_FALSE(setup.domain.contains(Eigen::Vector3d(0, 0, -0.5)));
}

TEST(StartAndBox, WrongCountsAndNamesAreUsageErrorsThatSayWhat) {
  ProblemSetup setup = make_catalogue_problem("sphere");
  std::string message = message_of([&] { apply_start_and_box(setup, "0,1", ""); });
  EXPECT_NE(message.find("--start has 2 values"), std::string::npos) << message;
  message = message_of([&] { apply_start_and_box(setup, "", "-1,1"); });
  EXPECT_NE(message.find("expected 6"), std::string::npos) << message;
  message = message_of([&] { apply_start_and_box(setup, "", "nowhere=0:1"); });
  EXPECT_NE(message.find("--box names coordinate 'nowhere'"), std::string::npos) << message;
  message = message_of(
      [&] { apply_start_and_box(setup, "", setup.problem->coordinate_names()[0] + "=2:1"); });
  EXPECT_NE(message.find("--box is empty"), std::string::npos) << message;
}

// Every "e.g. '…'" of a message, in order.
std::vector<std::string> examples_in(const std::string& message) {
  std::vector<std::string> examples;
  const std::string marker = "e.g. '";
  for (auto at = message.find(marker); at != std::string::npos; at = message.find(marker, at)) {
    at += marker.size();
    const auto end = message.find('\'', at);
    examples.push_back(message.substr(at, end - at));
  }
  for (auto at = message.find(", or '"); at != std::string::npos; at = message.find(", or '", at)) {
    at += 6;
    examples.push_back(message.substr(at, message.find('\'', at) - at));
  }
  return examples;
}

// Issue 34: the hint of a wrong --box showed --start's syntax ("a comma-separated list such as
// 0,0,1") and named coordinates the problem did not have ("lambda=5:20" for a sphere). Every
// example a message gives must be a --box that parses, for small n and large.
TEST(StartAndBox, EveryHintedBoxParses) {
  for (const std::string problem : {"sphere", "plane", "bvp:points=10"}) {
    const ProblemSetup original = resolve_problem(problem);
    const std::string first = original.problem->coordinate_names().front();
    for (const std::string box : {std::string("lambda"), std::string("1,2"), first + "=1",
                                  first + "=a:1", first + ":0:1", std::string("w=0")}) {
      ProblemSetup setup = resolve_problem(problem);
      const std::string message = message_of([&] { apply_start_and_box(setup, "", box); });
      ASSERT_FALSE(message.empty()) << problem << " --box " << box;
      EXPECT_EQ(message.find("0,0,1"), std::string::npos) << message;  // --start's example
      const std::vector<std::string> examples = examples_in(message);
      EXPECT_FALSE(examples.empty()) << message;
      for (const std::string& example : examples) {
        ProblemSetup hinted = resolve_problem(problem);
        EXPECT_NO_THROW(apply_start_and_box(hinted, "", example))
            << problem << ": the hint '" << example << "' of\n  " << message << "\n  "
            << message_of([&] { apply_start_and_box(hinted, "", example); });
        EXPECT_FALSE(hinted.domain.is_unbounded()) << example;
      }
    }
  }
}

}  // namespace
}  // namespace tessera
