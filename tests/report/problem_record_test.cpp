// SPDX-License-Identifier: MIT
// The problem a mesh file records in its comments (issue 34: `tessera check FILE` demanded
// --problem where the file named it): the record of `tessera mesh` and `improve`, the command
// lines of earlier files, and the refusal of a problem file that is gone or has changed.
#include "tessera/report/problem_record.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "support/test_support.h"
#include "tessera/core/error.h"

namespace tessera {
namespace {

std::string message_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const InvalidArgument& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(ProblemRecord, CatalogueProblemIsRecordedAsGivenAndFoundAgain) {
  const auto comments = problem_record_comments("torus:R=2,r=0.5");
  EXPECT_EQ(comments, std::vector<std::string>{"problem: torus:R=2,r=0.5"});
  const auto recorded =
      find_recorded_problem({"tessera mesh torus:R=2,r=0.5, method atlas", comments[0]});
  ASSERT_TRUE(recorded.has_value());
  EXPECT_EQ(recorded->specification, "torus:R=2,r=0.5");
  EXPECT_EQ(recorded->file_hash, "");
  EXPECT_EQ(resolve_recorded_problem(*recorded, "t.ply").problem->ambient_dimension(), 3);
}

TEST(ProblemRecord, CommandLinesOfEarlierFilesNameTheProblem) {
  // A specification with commas, before ", method".
  auto recorded = find_recorded_problem(
      {"written by tessera: triangle mesh in R^3", "tessera mesh torus:R=2,r=0.5, method front"});
  ASSERT_TRUE(recorded.has_value());
  EXPECT_EQ(recorded->specification, "torus:R=2,r=0.5");
  // improve, in PLY and in VTU, whose comments hold "- -" for "--".
  for (const std::string dashes : {"--", "- -"}) {
    recorded = find_recorded_problem(
        {"tessera improve cap.ply " + dashes + "problem sphere_cut " + dashes + "criterion angle"});
    ASSERT_TRUE(recorded.has_value()) << dashes;
    EXPECT_EQ(recorded->specification, "sphere_cut");
  }
  EXPECT_FALSE(find_recorded_problem({"tessera ddt, criterion angle", "coordinates: x y z"}));
  EXPECT_FALSE(find_recorded_problem({}));
}

TEST(ProblemRecord, ProblemFileIsRecordedByAbsolutePathAndHashAndRefusedWhenChangedOrGone) {
  const std::string dir = testing::temporary_directory("problem_record");
  const std::string path = dir + "/ball.tsr";
  std::ofstream(path) << "name ball\nvariables x y z\nparameter r = 1\n"
                         "equation x^2 + y^2 + z^2 - r^2\nstart 0 0 r\n";
  // With a parameter set after ':', which the record keeps.
  const auto comments = problem_record_comments(path + ":r=2");
  ASSERT_EQ(comments.size(), 2u);
  EXPECT_EQ(comments[0], "problem: " + path + ":r=2");
  EXPECT_EQ(comments[1], "problem file fnv1a64: " + file_fnv1a64(path));
  auto recorded = find_recorded_problem(comments);
  ASSERT_TRUE(recorded.has_value());
  EXPECT_EQ(recorded->file_hash.size(), 16u);
  EXPECT_EQ(resolve_recorded_problem(*recorded, "m.ply").problem->ambient_dimension(), 3);

  std::ofstream(path, std::ios::app) << "# a comment, and the file is no longer the same\n";
  std::string message = message_of([&] { resolve_recorded_problem(*recorded, "m.ply"); });
  EXPECT_NE(message.find("'m.ply' records the problem '" + path), std::string::npos) << message;
  EXPECT_NE(message.find("has changed since the mesh was written"), std::string::npos) << message;
  EXPECT_NE(message.find("--problem"), std::string::npos) << message;

  std::filesystem::remove(path);
  message = message_of([&] { resolve_recorded_problem(*recorded, "m.ply"); });
  EXPECT_NE(message.find("'" + path + "' no longer exists"), std::string::npos) << message;

  // An earlier file: a relative path, no hash.
  recorded = find_recorded_problem({"tessera mesh problems/ball.tsr, method atlas"});
  ASSERT_TRUE(recorded.has_value());
  message = message_of([&] { resolve_recorded_problem(*recorded, "m.ply"); });
  EXPECT_NE(message.find("is not found from here"), std::string::npos) << message;
}

TEST(ProblemRecord, TheBoxOfTheRunIsRecordedAndApplied) {
  const auto comments = problem_record_comments("sphere", "-1,1,-1,1,-0.8,1");
  EXPECT_EQ(comments, (std::vector<std::string>{"problem: sphere", "box: -1,1,-1,1,-0.8,1"}));
  const auto recorded = find_recorded_problem(comments);
  ASSERT_TRUE(recorded.has_value());
  EXPECT_EQ(recorded->box, "-1,1,-1,1,-0.8,1");
  const ProblemSetup setup = resolve_recorded_problem(*recorded, "cap.ply");
  EXPECT_FALSE(setup.expected_euler_characteristic.has_value());  // a cap, not the sphere
  const std::string message = message_of([] {
    resolve_recorded_problem({"sphere", "", "problem: sphere", "-1,1"}, "cap.ply");
  });
  EXPECT_NE(message.find("records the box '-1,1', which does not fit the problem 'sphere'"),
            std::string::npos)
      << message;
}

TEST(ProblemRecord, AHashCutShortIsNotTakenForOne) {
  // write_vtk cuts its title at 255 characters: a hash cut short is no hash.
  const auto recorded = find_recorded_problem({"problem: sphere", "problem file fnv1a64: 0123"});
  ASSERT_TRUE(recorded.has_value());
  EXPECT_EQ(recorded->file_hash, "");
}

}  // namespace
}  // namespace tessera
