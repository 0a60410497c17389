// SPDX-License-Identifier: MIT
#include "checkpoint_command.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "tessera/core/binary_stream.h"
#include "tessera/core/error.h"
#include "tessera/io/checkpoint_file.h"
#include "tessera/io/output_checks.h"

namespace tessera::app {
namespace {

// The problem file named by a problem specification ("file.tsr" or "file.tsr:a=1"); empty for a
// catalogue problem.
std::string problem_file_of(const std::string& specification) {
  std::error_code error;
  if (std::filesystem::is_regular_file(specification, error)) {
    return specification;
  }
  const std::string before_colon = specification.substr(0, specification.find(':'));
  if (std::filesystem::is_regular_file(before_colon, error)) {
    return before_colon;
  }
  return "";
}

// The "problem" section: the problem file's path, size and checksum (empty for the catalogue).
std::string problem_section(const std::string& specification) {
  BinaryWriter out;
  const std::string file = problem_file_of(specification);
  out.string(specification);
  out.string(file);
  if (!file.empty()) {
    const FileFingerprint fingerprint = fingerprint_file(file);
    out.u64(fingerprint.size);
    out.u64(fingerprint.checksum);
  }
  return out.take();
}

std::string command_section(const MeshCommand& command) {
  BinaryWriter out;
  std::error_code error;
  out.string(std::filesystem::current_path(error).string());
  out.u64(command.arguments.size());
  for (const std::string& word : command.arguments) {
    out.string(word);
  }
  return out.take();
}

}  // namespace

CLI::App* add_resume_command(CLI::App& app, ResumeCommand& command) {
  auto* resume = app.add_subcommand(
      "resume", "continue a `tessera mesh --checkpoint FILE` run from its checkpoint");
  resume->add_option("checkpoint", command.checkpoint, "the checkpoint file (.tsc)")->required();
  resume->add_option("-o,--output", command.output,
                     "mesh file instead of the original run's (default: its -o)");
  resume->add_option("--summary", command.summary,
                     "summary file instead of the original run's (default: its --summary)");
  resume->add_flag("--quiet,-q", command.quiet, "print nothing but errors");
  resume->add_flag("--progress", command.progress,
                   "progress as lines on stderr (and what each checkpoint took)");
  return resume;
}

void check_checkpoint_options(const MeshCommand& command, const std::string& method,
                              bool covers_several) {
  if (command.checkpoint.empty()) {
    return;
  }
  TESSERA_CHECK(method == "atlas" || method == "front",
                "--checkpoint " << command.checkpoint
                                << ": checkpoints are supported for --method atlas and front, not "
                                   "yet for '"
                                << method << "'");
  TESSERA_CHECK(!covers_several, "--checkpoint " << command.checkpoint
                                                 << ": checkpoints are for runs of one start's "
                                                    "component (not --components all or several "
                                                    "--start)");
  TESSERA_CHECK(command.backend == "serial", "--checkpoint " << command.checkpoint
                                                             << " is not yet available with "
                                                                "--backend "
                                                             << command.backend);
  check_output_folder(command.checkpoint);
  TESSERA_CHECK(std::filesystem::path(command.checkpoint).extension() == ".tsc",
                "--checkpoint " << command.checkpoint
                                << ": a checkpoint file must end in .tsc (so that no mesh or "
                                   "summary is replaced by one)");
}

namespace {

// The hooks of either method (AtlasCheckpointing, FrontCheckpointing: the same members); the
// state goes to the file's section named `method`.
template <typename Hooks>
Hooks make_checkpointing(const MeshCommand& command, const std::string& method,
                         bool progress_lines) {
  Hooks hooks;
  hooks.resume_from = command.resume_state;
  if (command.checkpoint.empty()) {
    return hooks;
  }
  using Clock = std::chrono::steady_clock;
  const auto last = std::make_shared<Clock::time_point>(Clock::now());
  // When is_due said yes: the state is made between then and the save (--progress says both).
  const auto due_at = std::make_shared<Clock::time_point>();
  const double every = command.checkpoint_every;
  hooks.is_due = [last, due_at, every] {
    const Clock::time_point now = Clock::now();
    if (std::chrono::duration<double>(now - *last).count() < every) {
      return false;
    }
    *due_at = now;
    return true;
  };
  // The parts that stay the same are made once.
  const auto header = std::make_shared<CheckpointFile>();
  header->sections = {{"command", command_section(command)},
                      {"problem", problem_section(command.problem)},
                      {"method", method}};
  const std::string path = command.checkpoint;
  hooks.save = [last, due_at, header, path, method, progress_lines](std::string state) {
    const auto begin = Clock::now();
    // (A save at a stop or at the end of the build was not asked by is_due: its state's time
    // is not known.)
    const double state_seconds =
        *due_at == Clock::time_point() ? -1.0
                                       : std::chrono::duration<double>(begin - *due_at).count();
    *due_at = Clock::time_point();
    CheckpointFile file = *header;
    const std::size_t bytes = state.size();
    file.sections.emplace_back(method, std::move(state));
    try {
      write_checkpoint_file(path, file);
    } catch (const std::exception& error) {
      // The run goes on without it: its mesh matters more than a checkpoint.
      std::fprintf(stderr, "tessera: warning: checkpoint not written: %s\n", error.what());
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - begin).count();
    if (progress_lines) {
      std::fprintf(stderr, "tessera: checkpoint: %zu bytes to %s in %.3f s", bytes, path.c_str(),
                   seconds);
      if (state_seconds >= 0) {
        std::fprintf(stderr, " (its state made in %.3f s before)", state_seconds);
      }
      std::fprintf(stderr, "\n");
    }
    *last = Clock::now();
  };
  return hooks;
}

}  // namespace

AtlasCheckpointing make_atlas_checkpointing(const MeshCommand& command, bool progress_lines) {
  return make_checkpointing<AtlasCheckpointing>(command, "atlas", progress_lines);
}

FrontCheckpointing make_front_checkpointing(const MeshCommand& command, bool progress_lines) {
  return make_checkpointing<FrontCheckpointing>(command, "front", progress_lines);
}

int run_resume(const ResumeCommand& resume) {
  const CheckpointFile file = read_checkpoint_file(resume.checkpoint);
  const std::string& method = file.section("method", resume.checkpoint);
  TESSERA_CHECK(method == "atlas" || method == "front",
                "checkpoint file '" << resume.checkpoint << "' is of method '" << method
                                    << "': checkpoints are supported for --method atlas and "
                                       "front");
  // The original command line, parsed again in the folder it was given in (its relative paths
  // name the same files); the paths given here are taken from this folder.
  BinaryReader command(file.section("command", resume.checkpoint),
                       "checkpoint file '" + resume.checkpoint + "', its command");
  const std::string folder = command.string("folder");
  std::vector<std::string> words = {"tessera"};
  const std::size_t count = command.count("arguments", 8);
  for (std::size_t k = 0; k < count; ++k) {
    words.push_back(command.string("argument"));
  }
  TESSERA_CHECK(words.size() >= 2 && words[1] == "mesh",
                "checkpoint file '" << resume.checkpoint << "' holds no `tessera mesh` command");
  const auto absolute = [](const std::string& path) {
    return path.empty() ? path : std::filesystem::absolute(path).string();
  };
  const std::string checkpoint = absolute(resume.checkpoint);
  const std::string output = absolute(resume.output);
  const std::string summary = absolute(resume.summary);
  std::error_code error;
  if (!folder.empty() && std::filesystem::current_path(error) != folder) {
    TESSERA_CHECK(chdir(folder.c_str()) == 0,
                  "checkpoint file '" << resume.checkpoint << "': the run was started in " << folder
                                      << ", which is gone; its relative paths "
                                      << "cannot be resolved");
  }
  CLI::App app;
  MeshCommand mesh;
  add_mesh_command(app, mesh);
  std::vector<char*> argv;
  for (std::string& word : words) {
    argv.push_back(word.data());
  }
  try {
    app.parse(static_cast<int>(argv.size()), argv.data());
  } catch (const CLI::ParseError& e) {
    throw InvalidArgument("checkpoint file '" + resume.checkpoint +
                          "': its command line does not parse: " + e.what());
  }
  mesh.arguments.assign(words.begin() + 1, words.end());
  // The state is the method's: a command line of another method would read it as its own.
  const std::string command_method =
      mesh.method.empty() ? covering_methods().front().name : mesh.method;
  TESSERA_CHECK(command_method == method, "checkpoint file '"
                                              << resume.checkpoint << "' holds a state of --method "
                                              << method << ", but its command line runs --method "
                                              << command_method);
  // The problem file must be the one the checkpoint was made from.
  BinaryReader problem(file.section("problem", resume.checkpoint),
                       "checkpoint file '" + resume.checkpoint + "', its problem");
  problem.string("specification");  // (the command line holds it too)
  const std::string problem_file = problem.string("problem file");
  if (!problem_file.empty()) {
    const std::uint64_t size = problem.u64("problem file size");
    const std::uint64_t hash = problem.u64("problem file hash");
    TESSERA_CHECK(std::filesystem::is_regular_file(problem_file, error),
                  "problem file '" << problem_file << "' of the checkpoint is gone");
    const FileFingerprint now = fingerprint_file(problem_file);
    TESSERA_CHECK(now.size == size && now.checksum == hash,
                  "problem file '" << problem_file << "' changed since checkpoint '"
                                   << resume.checkpoint << "' was written (" << size
                                   << " bytes then, " << now.size
                                   << " now, or other contents): resuming would continue an "
                                      "build of another problem");
  }
  mesh.checkpoint = checkpoint;
  mesh.quiet = mesh.quiet || resume.quiet;
  mesh.progress = mesh.progress || resume.progress;
  if (!output.empty()) {
    mesh.output = output;
  }
  if (!summary.empty()) {
    mesh.summary = summary;
  }
  mesh.resume_state = std::make_shared<const std::string>(file.section(method, resume.checkpoint));
  return run_mesh(mesh);
}

}  // namespace tessera::app
