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
  AtlasCheckpointing hooks = make_checkpointing<AtlasCheckpointing>(command, "atlas", progress_lines);
  hooks.extend = command.extend;
  return hooks;
}

FrontCheckpointing make_front_checkpointing(const MeshCommand& command, bool progress_lines) {
  return make_checkpointing<FrontCheckpointing>(command, "front", progress_lines);
}

namespace {

// A checkpoint's run: its command line parsed again (in the folder it was given in, which
// becomes the working folder), its method and the method's state.
struct CheckpointedRun {
  MeshCommand mesh;
  std::string method;  // "atlas" or "front"
  std::shared_ptr<const std::string> state;
};

// Reads the checkpoint, checks it (the file, the problem file's hash) and parses its command
// line again. \throw InvalidArgument naming what is wrong.
CheckpointedRun load_checkpointed_run(const std::string& path) {
  const CheckpointFile file = read_checkpoint_file(path);
  for (const auto& section : file.sections) {
    TESSERA_CHECK(section.first != "python",
                  "checkpoint file '" << path
                                      << "' was written by Python's tessera.mesh(checkpoint=...): "
                                         "continue it with tessera.resume or tessera.extend");
  }
  const std::string& method = file.section("method", path);
  TESSERA_CHECK(method == "atlas" || method == "front",
                "checkpoint file '" << path << "' is of method '" << method
                                    << "': checkpoints are supported for --method atlas and "
                                       "front");
  // The original command line, parsed again in the folder it was given in (its relative paths
  // name the same files).
  BinaryReader command(file.section("command", path),
                       "checkpoint file '" + path + "', its command");
  const std::string folder = command.string("folder");
  std::vector<std::string> words = {"tessera"};
  const std::size_t count = command.count("arguments", 8);
  for (std::size_t k = 0; k < count; ++k) {
    words.push_back(command.string("argument"));
  }
  TESSERA_CHECK(words.size() >= 2 && words[1] == "mesh",
                "checkpoint file '" << path << "' holds no `tessera mesh` command");
  std::error_code error;
  if (!folder.empty() && std::filesystem::current_path(error) != folder) {
    TESSERA_CHECK(chdir(folder.c_str()) == 0,
                  "checkpoint file '" << path << "': the run was started in " << folder
                                      << ", which is gone; its relative paths "
                                      << "cannot be resolved");
  }
  CheckpointedRun run;
  {
    CLI::App app;
    add_mesh_command(app, run.mesh);
    std::vector<char*> argv;
    for (std::string& word : words) {
      argv.push_back(word.data());
    }
    try {
      app.parse(static_cast<int>(argv.size()), argv.data());
    } catch (const CLI::ParseError& e) {
      throw InvalidArgument("checkpoint file '" + path +
                            "': its command line does not parse: " + e.what());
    }
  }
  run.mesh.arguments.assign(words.begin() + 1, words.end());
  // The state is the method's: a command line of another method would read it as its own.
  const std::string command_method =
      run.mesh.method.empty() ? covering_methods().front().name : run.mesh.method;
  TESSERA_CHECK(command_method == method, "checkpoint file '"
                                              << path << "' holds a state of --method " << method
                                              << ", but its command line runs --method "
                                              << command_method);
  // The problem file must be the one the checkpoint was made from.
  BinaryReader problem(file.section("problem", path),
                       "checkpoint file '" + path + "', its problem");
  problem.string("specification");  // (the command line holds it too)
  const std::string problem_file = problem.string("problem file");
  if (!problem_file.empty()) {
    const std::uint64_t size = problem.u64("problem file size");
    const std::uint64_t hash = problem.u64("problem file hash");
    TESSERA_CHECK(std::filesystem::is_regular_file(problem_file, error),
                  "problem file '" << problem_file << "' of the checkpoint is gone");
    const FileFingerprint now = fingerprint_file(problem_file);
    TESSERA_CHECK(now.size == size && now.checksum == hash,
                  "problem file '" << problem_file << "' changed since checkpoint '" << path
                                   << "' was written (" << size << " bytes then, " << now.size
                                   << " now, or other contents): resuming would continue an "
                                      "build of another problem");
  }
  run.method = method;
  run.state = std::make_shared<const std::string>(file.section(method, path));
  return run;
}

std::string absolute_path(const std::string& path) {
  return path.empty() ? path : std::filesystem::absolute(path).string();
}

// The options of `resume` and `extend` that replace the original run's.
void apply_run_overrides(MeshCommand& mesh, const std::string& output, const std::string& summary,
                         bool quiet, bool progress) {
  mesh.quiet = mesh.quiet || quiet;
  mesh.progress = mesh.progress || progress;
  if (!output.empty()) {
    mesh.output = output;
  }
  if (!summary.empty()) {
    mesh.summary = summary;
  }
}

// Removes every occurrence of the option (each of `names`, with its value as the next word or
// after '=', or glued to a one-letter name as in -t1e-3) and appends `name value`.
void replace_option(std::vector<std::string>& words, const std::vector<std::string>& names,
                    const std::string& value) {
  std::vector<std::string> kept;
  for (std::size_t k = 0; k < words.size(); ++k) {
    const std::string& word = words[k];
    bool matched = false;
    for (const std::string& name : names) {
      if (word == name) {
        ++k;  // its value
        matched = true;
      } else if (word.rfind(name + "=", 0) == 0 ||
                 (name.size() == 2 && word.size() > 2 && word.rfind(name, 0) == 0)) {
        matched = true;
      }
    }
    if (!matched) {
      kept.push_back(word);
    }
  }
  kept.push_back(names.front());
  kept.push_back(value);
  words = std::move(kept);
}

std::string shortest(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

}  // namespace

int run_resume(const ResumeCommand& resume) {
  // (Paths given here are relative to this folder; the run's to the one it was started in.)
  const std::string checkpoint = absolute_path(resume.checkpoint);
  const std::string output = absolute_path(resume.output);
  const std::string summary = absolute_path(resume.summary);
  CheckpointedRun run = load_checkpointed_run(resume.checkpoint);
  MeshCommand& mesh = run.mesh;
  mesh.checkpoint = checkpoint;
  apply_run_overrides(mesh, output, summary, resume.quiet, resume.progress);
  mesh.resume_state = run.state;
  return run_mesh(mesh);
}

CLI::App* add_extend_command(CLI::App& app, ExtendCommand& command) {
  auto* extend = app.add_subcommand(
      "extend",
      "continue the atlas of a `tessera mesh --checkpoint FILE` run into a larger --box, or "
      "refine it to a finer --tolerance, keeping what it has (docs/checkpoints.md)");
  extend->add_option("checkpoint", command.checkpoint, "the checkpoint file (.tsc)")->required();
  extend->add_option("--box", command.box,
                     "the larger box, in the syntax of `tessera mesh --box`; it must contain "
                     "the run's box");
  extend
      ->add_option("--tolerance,-t", command.tolerance,
                   "a finer tolerance: the atlas's charts are kept and every triangle is "
                   "bisected on M until it meets it")
      ->check(CLI::PositiveNumber);
  extend->add_option("-o,--output", command.output,
                     "mesh file instead of the original run's (default: its -o)");
  extend->add_option("--summary", command.summary,
                     "summary file instead of the original run's (default: its --summary)");
  extend->add_option("--checkpoint", command.new_checkpoint,
                     "the extended run's checkpoints go here (.tsc) instead of replacing FILE's");
  extend->add_flag("--quiet,-q", command.quiet, "print nothing but errors");
  extend->add_flag("--progress", command.progress, "progress as lines on stderr");
  return extend;
}

int run_extend(const ExtendCommand& extend) {
  TESSERA_CHECK(!extend.box.empty() || extend.tolerance > 0,
                "tessera extend " << extend.checkpoint
                                  << ": give a larger --box, a finer --tolerance, or both");
  const std::string checkpoint =
      absolute_path(extend.new_checkpoint.empty() ? extend.checkpoint : extend.new_checkpoint);
  const std::string output = absolute_path(extend.output);
  const std::string summary = absolute_path(extend.summary);
  if (!extend.new_checkpoint.empty()) {
    TESSERA_CHECK(std::filesystem::path(checkpoint).extension() == ".tsc",
                  "--checkpoint " << extend.new_checkpoint
                                  << ": a checkpoint file must end in .tsc");
  }
  CheckpointedRun run = load_checkpointed_run(extend.checkpoint);
  TESSERA_CHECK(run.method == "atlas", "tessera extend " << extend.checkpoint
                                                         << ": extend continues an atlas; this "
                                                            "checkpoint is of --method "
                                                         << run.method << " (resume it instead)");
  MeshCommand& mesh = run.mesh;
  const AtlasStateHeader header = read_atlas_state_header(*run.state);
  std::vector<std::string>& words = mesh.arguments;
  if (!extend.box.empty()) {
    // The containment is checked where the state is read (AtlasCheckpointing::extend).
    mesh.box = extend.box;
    replace_option(words, {"--box"}, extend.box);
  }
  if (extend.tolerance > 0) {
    // The charts stay as they were sized; the refinement alone meets the finer tolerance.
    const double before = mesh.settings.tolerance > 0 ? mesh.settings.tolerance : header.tolerance;
    TESSERA_CHECK(extend.tolerance < before,
                  "tessera extend --tolerance " << extend.tolerance
                                                << " is not finer than the run's " << before
                                                << ": its mesh meets that already (a coarser "
                                                   "mesh needs a new run)");
    mesh.settings.tolerance = extend.tolerance;
    mesh.settings.atlas_chart_tolerance = header.tolerance;
    replace_option(words, {"--tolerance", "-t"}, shortest(extend.tolerance));
    replace_option(words, {"--chart-tolerance"}, shortest(header.tolerance));
  }
  mesh.checkpoint = checkpoint;
  apply_run_overrides(mesh, output, summary, extend.quiet, extend.progress);
  mesh.resume_state = run.state;
  mesh.extend = true;
  return run_mesh(mesh);
}

}  // namespace tessera::app
