// SPDX-License-Identifier: MIT
// Every file tessera writes replaces its target atomically: a write that fails midway (file
// size limit, full disk, an exception) leaves the previous file intact and no temporary behind.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>

#include "io/io_test_support.h"
#include "tessera/io/bezier_patches.h"
#include "tessera/io/detail/file_buffer.h"
#include "tessera/io/mesh_io.h"
#include "tessera/io/npy.h"
#include "tessera/io/text_file.h"
#include "tessera/report/summary_json.h"

namespace tessera {
namespace {

using namespace io_test;
namespace fs = std::filesystem;

// A folder of its own per test, so that "no temporary is left" can look at every entry.
std::string fresh_folder(const std::string& name) {
  const fs::path folder = fs::path(test_path("replacement")) / name;
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder.string();
}

std::vector<std::string> entries(const std::string& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// Lowers the file size limit of this process while alive: a write past it fails with EFBIG, a
// real failure midway through a file (SIGXFSZ is ignored so that write(2) returns the error).
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    previous_handler_ = signal(SIGXFSZ, SIG_IGN);
    rlimit limit = saved_;
    limit.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    signal(SIGXFSZ, previous_handler_);
  }

 private:
  rlimit saved_{};
  sighandler_t previous_handler_ = SIG_DFL;
};

// Writers of every kind of file tessera writes.
std::vector<std::pair<std::string, std::function<void(const std::string&)>>> writers() {
  static const auto mesh = random_mesh(4, 3000, 5000);
  return {
      {"m.ply", [](const std::string& p) { write_mesh(p, mesh); }},
      {"m_ascii.ply", [](const std::string& p) { write_mesh(p, mesh, {.binary = false}); }},
      {"m.obj",
       [](const std::string& p) {
         write_mesh(p, mesh, {.obj_coordinates = {0, 1, 3}});
       }},
      {"m.vtk", [](const std::string& p) { write_mesh(p, mesh); }},
      {"m.vtu", [](const std::string& p) { write_mesh(p, mesh); }},
      {"states.npy", [](const std::string& p) { write_npy(p, mesh.points()); }},
      {"triangles.npy", [](const std::string& p) { write_npy(p, mesh.triangles()); }},
      {"summary.json", [](const std::string& p) { write_summary_json(p, MeshReport{}); }},
      {"text.json", [](const std::string& p) { write_text_file(p, std::string(1 << 21, ' ')); }},
      {"patches.json",
       [](const std::string& p) {
         BezierSurfaceFile surface;
         surface.mesh = random_mesh(3, 300, 0);
         for (int t = 0; t < 400; ++t) {
           surface.mesh.add_triangle(t % 300, (t + 1) % 300, (t + 2) % 300);
           surface.patches.emplace_back(Eigen::MatrixXd::Constant(3, 10, 1.0 / 3.0));
         }
         surface.coordinate_names = {"x", "y", "z"};
         write_bezier_patches(p, surface);
       }},
  };
}

TEST(FileReplacement, SuccessfulWriteReplacesTheFileAndLeavesNoTemporary) {
  for (const auto& [name, write] : writers()) {
    SCOPED_TRACE(name);
    const auto folder = fresh_folder("success");
    const auto path = folder + "/" + name;
    write_text(path, "the previous version");
    write(path);
    EXPECT_GT(fs::file_size(path), 100u);
    EXPECT_EQ(entries(folder), std::vector<std::string>{name});
  }
}

TEST(FileReplacement, WriteFailingMidwayKeepsThePreviousFileAndLeavesNoTemporary) {
  for (const auto& [name, write] : writers()) {
    SCOPED_TRACE(name);
    const auto folder = fresh_folder("failure");
    const auto path = folder + "/" + name;
    write(path);
    const auto complete_size = fs::file_size(path);
    const std::string previous = "the previous version, which must survive";
    write_text(path, previous);
    {
      const FileSizeLimit limit(complete_size / 2);  // the write fails halfway
      expect_invalid_argument([&] { write(path); },
                              {"'" + path + "'", "File too large", "the file was not changed"});
    }
    EXPECT_EQ(file_text(path), previous);
    EXPECT_EQ(entries(folder), std::vector<std::string>{name});
  }
}

TEST(FileReplacement, FullDiskIsAnErrorNamingTheFile) {
  if (!fs::exists("/dev/full")) {
    GTEST_SKIP() << "no /dev/full on this system";
  }
  // A device is written in place (there is no folder to rename in), so the error comes from the
  // write itself: ENOSPC, reported with the file's name, never a silent truncation.
  expect_invalid_argument([] { write_text_file("/dev/full", std::string(3 << 20, 'x')); },
                          {"'/dev/full'", "No space left on device"});
  expect_invalid_argument([] { write_text_file("/dev/full", "x"); },
                          {"'/dev/full'", "No space left on device"});
}

TEST(FileReplacement, WriterLeftByAnExceptionKeepsThePreviousFile) {
  const auto folder = fresh_folder("exception");
  const auto path = folder + "/m.ply";
  write_text(path, "previous");
  try {
    io_detail::OutputFile file("PLY", path);
    file.text("half of a file");
    throw std::runtime_error("the writer failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(file_text(path), "previous");
  EXPECT_EQ(entries(folder), std::vector<std::string>{"m.ply"});
}

// A process killed in the middle of writing (here: with 8 MiB written, before close) leaves the
// previous file whole; only the hidden temporary remains.
TEST(FileReplacement, KillMidwayKeepsThePreviousFile) {
  const auto folder = fresh_folder("kill");
  const auto path = folder + "/m.vtu";
  write_text(path, "previous");
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    io_detail::OutputFile file("VTU", path);
    const std::string block(1 << 20, 'x');
    for (int i = 0; i < 8; ++i) {
      file.text(block);
    }
    file.text("y");  // pushes the 8th block out of the buffer
    pause();         // killed here, before close()
    _exit(0);
  }
  // Wait until the child has written its 8 MiB to the temporary.
  std::string temporary;
  for (int attempt = 0; attempt < 2000 && temporary.empty(); ++attempt) {
    for (const auto& name : entries(folder)) {
      if (name.rfind(".m.vtu.tmp.", 0) == 0 && fs::file_size(folder + "/" + name) >= (8u << 20)) {
        temporary = name;
      }
    }
    usleep(10'000);
  }
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_FALSE(temporary.empty()) << "the child never wrote its temporary";
  EXPECT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(file_text(path), "previous");
  EXPECT_EQ(entries(folder), (std::vector<std::string>{temporary, "m.vtu"}));
}

TEST(FileReplacement, MissingFolderIsAnErrorNamingTheFile) {
  const auto path = test_path("no_such_folder/m.ply");
  expect_invalid_argument([&] { write_mesh(path, two_triangles()); },
                          {"'" + path + "'", "cannot open for writing", "No such file"});
  const auto folder = fresh_folder("folder_target");
  fs::create_directory(folder + "/d.ply");
  expect_invalid_argument([&] { write_mesh(folder + "/d.ply", two_triangles()); },
                          {"d.ply", "it is a folder"});
}

TEST(FileReplacement, KeepsPermissionsAndFollowsSymbolicLinks) {
  const auto folder = fresh_folder("links");
  const auto target = folder + "/target.ply";
  const auto link = folder + "/link.ply";
  write_text(target, "previous");
  fs::permissions(target, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  fs::create_symlink("target.ply", link);
  const auto mesh = two_triangles();
  write_mesh(link, mesh);
  EXPECT_TRUE(fs::is_symlink(link));
  expect_identical(mesh, read_mesh(target));
  EXPECT_EQ(fs::status(target).permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  EXPECT_EQ(entries(folder), (std::vector<std::string>{"link.ply", "target.ply"}));
}

TEST(FileReplacement, TemporaryIsHiddenInTheTargetsFolder) {
  const auto folder = fresh_folder("hidden");
  const auto path = folder + "/m.ply";
  io_detail::OutputFile file("PLY", path);
  file.text("data");
  const auto names = entries(folder);
  ASSERT_EQ(names.size(), 1u);
  EXPECT_EQ(names.front().rfind(".m.ply.tmp." + std::to_string(getpid()) + ".", 0), 0u)
      << names.front();
  EXPECT_FALSE(fs::exists(path));  // nothing at the target until close()
  file.close();
  EXPECT_EQ(file_text(path), "data");
  EXPECT_EQ(entries(folder), std::vector<std::string>{"m.ply"});
}

}  // namespace
}  // namespace tessera
