// SPDX-License-Identifier: MIT
// Checkpoint files: sections come back as written; a file cut short, changed, of another kind
// or of another version is refused, naming the file and what is wrong.
#include "tessera/io/checkpoint_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/test_support.h"
#include "tessera/core/error.h"

namespace tessera {
namespace {

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

void expect_refused(const std::string& path, const std::string& bytes, const std::string& why) {
  std::ofstream(path, std::ios::binary) << bytes;
  try {
    read_checkpoint_file(path);
    ADD_FAILURE() << "not refused: " << why;
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find(why), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
  }
}

TEST(CheckpointFile, SectionsComeBackAndDamageIsRefused) {
  const std::string folder = testing::temporary_directory("checkpoint_file");
  const std::string path = folder + "/a.tsc";
  CheckpointFile file;
  file.sections = {{"command", std::string("mesh\0torus", 10)}, {"atlas", std::string(5000, '\7')}};
  write_checkpoint_file(path, file);
  const CheckpointFile back = read_checkpoint_file(path);
  EXPECT_EQ(back.sections, file.sections);
  EXPECT_EQ(back.section("atlas", path).size(), 5000u);
  EXPECT_THROW(back.section("front", path), InvalidArgument);
  // Nothing but the file itself is left in the folder (the temporary was renamed).
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(folder),
                          std::filesystem::directory_iterator()),
            1);

  const std::string good = bytes_of(path);
  expect_refused(folder + "/cut.tsc", good.substr(0, 3000), "truncated");
  expect_refused(folder + "/end.tsc", good.substr(0, good.size() - 3), "truncated");
  std::string flipped = good;
  flipped[2000] ^= 4;
  expect_refused(folder + "/flipped.tsc", flipped, "checksum");
  expect_refused(folder + "/ply.tsc", "ply\nformat ascii 1.0\n", "not a tessera checkpoint");
  std::string version = good;
  version[8] = 2;
  expect_refused(folder + "/version.tsc", version, "format version 2");
}

}  // namespace
}  // namespace tessera
