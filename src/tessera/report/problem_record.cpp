// SPDX-License-Identifier: MIT
#include "tessera/report/problem_record.h"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "tessera/core/error.h"
#include "tessera/problems/catalogue.h"
#include "tessera/problems/start_and_box.h"

namespace tessera {

namespace {

constexpr std::string_view kProblem = "problem: ";
constexpr std::string_view kProblemFileHash = "problem file fnv1a64: ";
constexpr std::string_view kBox = "box: ";

std::string trimmed(std::string_view text) {
  const auto begin = text.find_first_not_of(" \t");
  if (begin == std::string_view::npos) {
    return "";
  }
  const auto end = text.find_last_not_of(" \t\r");
  return std::string(text.substr(begin, end - begin + 1));
}

bool is_file(const std::string& path) {
  std::error_code error;
  return std::filesystem::is_regular_file(path, error);
}

// The problem file a specification names, as resolve_problem reads it: the whole specification,
// or the part before ':' that sets its parameters ("cstr.tsr:Da=0.1"). Empty for a catalogue
// problem.
struct ProblemFilePart {
  std::string path;
  std::string parameters;  ///< ":key=value,…" or empty
};

std::optional<ProblemFilePart> problem_file_part(const std::string& specification) {
  if (is_file(specification)) {
    return ProblemFilePart{specification, ""};
  }
  const auto colon = specification.find(':');
  if (colon != std::string::npos && is_file(trimmed(specification.substr(0, colon)))) {
    return ProblemFilePart{trimmed(specification.substr(0, colon)), specification.substr(colon)};
  }
  return std::nullopt;
}

// The problem file that a recorded specification names, whether or not it exists now: what
// precedes the parameters, if any. Catalogue names hold no '/' and no '.'.
std::string recorded_file_path(const std::string& specification) {
  if (is_file(specification)) {
    return specification;
  }
  return trimmed(specification.substr(0, specification.find(':')));
}

bool names_a_file(const std::string& path) {
  return path.find_first_of("/.\\") != std::string::npos;
}

// SPEC of "tessera improve MESH --problem SPEC --criterion C" (VTU comments hold "- -" for "--").
std::optional<std::string> improve_problem(const std::string& comment) {
  for (const std::string dashes : {"--", "- -"}) {
    const auto at = comment.find(" " + dashes + "problem ");
    if (at == std::string::npos) {
      continue;
    }
    const auto begin = at + dashes.size() + 9;
    const auto end = comment.find(" " + dashes, begin);
    return trimmed(
        comment.substr(begin, end == std::string::npos ? std::string::npos : end - begin));
  }
  return std::nullopt;
}

}  // namespace

std::string file_fnv1a64(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  TESSERA_CHECK(in.good(), "cannot read the problem file '" << path << "'");
  std::uint64_t hash = 14695981039346656037ULL;  // FNV-1a's offset basis
  for (std::istreambuf_iterator<char> it(in), end; it != end; ++it) {
    hash ^= static_cast<unsigned char>(*it);
    hash *= 1099511628211ULL;  // FNV's 64-bit prime
  }
  char digits[17];
  std::snprintf(digits, sizeof digits, "%016llx", static_cast<unsigned long long>(hash));
  return digits;
}

std::vector<std::string> problem_record_comments(const std::string& specification,
                                                 const std::string& box) {
  std::vector<std::string> comments;
  const auto file = problem_file_part(specification);
  if (!file) {
    comments.push_back(std::string(kProblem) + specification);
  } else {
    const std::string absolute =
        std::filesystem::absolute(file->path).lexically_normal().string() + file->parameters;
    comments.push_back(std::string(kProblem) + absolute);
    comments.push_back(std::string(kProblemFileHash) + file_fnv1a64(file->path));
  }
  if (!box.empty()) {
    comments.push_back(std::string(kBox) + box);
  }
  return comments;
}

std::optional<RecordedProblem> find_recorded_problem(const std::vector<std::string>& comments) {
  std::optional<RecordedProblem> recorded;
  std::string hash;
  std::string box;
  for (const auto& comment : comments) {
    if (comment.rfind(kProblem, 0) == 0 && !recorded) {
      recorded = RecordedProblem{trimmed(comment.substr(kProblem.size())), "", comment, ""};
    } else if (comment.rfind(kProblemFileHash, 0) == 0) {
      hash = trimmed(comment.substr(kProblemFileHash.size()));
      const bool is_hash =
          hash.size() == 16 && hash.find_first_not_of("0123456789abcdef") == std::string::npos;
      hash = is_hash ? hash : "";
    } else if (comment.rfind(kBox, 0) == 0) {
      box = trimmed(comment.substr(kBox.size()));
    }
  }
  if (recorded) {
    recorded->file_hash = hash;
    recorded->box = box;
    return recorded;
  }
  // Files of earlier versions: the command line's comment.
  for (const auto& comment : comments) {
    if (comment.rfind("tessera mesh ", 0) == 0) {
      // "tessera mesh SPEC, method M": SPEC may hold commas (torus:R=2,r=0.5).
      const auto method = comment.rfind(", method ");
      if (method != std::string::npos && method > 13) {
        return RecordedProblem{trimmed(comment.substr(13, method - 13)), "", comment, ""};
      }
    } else if (comment.rfind("tessera improve ", 0) == 0) {
      if (const auto specification = improve_problem(comment)) {
        return RecordedProblem{*specification, "", comment, ""};
      }
    }
  }
  return std::nullopt;
}

ProblemSetup resolve_recorded_problem(const RecordedProblem& recorded,
                                      const std::string& mesh_path) {
  const std::string where = "'" + mesh_path + "' records the problem '" + recorded.specification +
                            "' (its comment \"" + recorded.comment + "\")";
  const std::string remedy = "; give the problem with --problem";
  const std::string path = recorded_file_path(recorded.specification);
  if (!recorded.file_hash.empty() || (names_a_file(path) && !is_file(path))) {
    // Files of earlier versions name a problem file as given, maybe relative to the folder
    // the mesh was computed in.
    TESSERA_CHECK(is_file(path), where << ", but the problem file '" << path << "' "
                                       << (std::filesystem::path(path).is_absolute()
                                               ? "no longer exists"
                                               : "is not found from here (a path relative to the "
                                                 "folder the mesh was computed in)")
                                       << remedy);
  }
  if (!recorded.file_hash.empty()) {
    const std::string now = file_fnv1a64(path);
    TESSERA_CHECK(now == recorded.file_hash,
                  where << ", but the problem file '" << path
                        << "' has changed since the mesh was written (FNV-1a hash "
                        << recorded.file_hash << " then, " << now << " now): the mesh may not "
                        << "belong to it" << remedy
                        << " (the file as it is now, if that is meant)");
  }
  ProblemSetup setup;
  try {
    setup = resolve_problem(recorded.specification);
  } catch (const InvalidArgument& error) {
    throw InvalidArgument(where + ", which cannot be resolved here: " + error.what() + remedy);
  }
  try {
    apply_start_and_box(setup, "", recorded.box);
  } catch (const InvalidArgument& error) {
    throw InvalidArgument("'" + mesh_path + "' records the box '" + recorded.box +
                          "', which does not fit the problem '" + recorded.specification +
                          "': " + error.what() + remedy);
  }
  return setup;
}

}  // namespace tessera
