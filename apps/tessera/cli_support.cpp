// SPDX-License-Identifier: MIT
#include "cli_support.h"

#include <algorithm>
#include <cctype>
#include <CLI/CLI.hpp>
#include <cmath>
#include <exception>
#include <string>

namespace tessera::app {

const CLI::Validator& finite_positive() {
  static const CLI::Validator validator(
      [](std::string& text) -> std::string {
        try {
          std::size_t used = 0;
          const double value = std::stod(text, &used);
          if (used == text.size() && std::isfinite(value) && value > 0) {
            return {};
          }
        } catch (const std::exception&) {
        }
        return "'" + text + "' is not a finite number > 0";
      },
      "POSITIVE", "finite positive number");
  return validator;
}

int edit_distance(const std::string& a, const std::string& b) {
  // d[i][j]: distance between the first i characters of a and the first j of b.
  const std::size_t m = a.size();
  const std::size_t n = b.size();
  std::vector<std::vector<int>> d(m + 1, std::vector<int>(n + 1, 0));
  for (std::size_t i = 0; i <= m; ++i) {
    d[i][0] = static_cast<int>(i);
  }
  for (std::size_t j = 0; j <= n; ++j) {
    d[0][j] = static_cast<int>(j);
  }
  for (std::size_t i = 1; i <= m; ++i) {
    for (std::size_t j = 1; j <= n; ++j) {
      const int substitution = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + substitution});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);  // "tolernace": two letters swapped
      }
    }
  }
  return d[m][n];
}

std::vector<std::string> nearest_names(const std::string& typed,
                                       const std::vector<std::string>& candidates) {
  const auto without_dashes = [](const std::string& name) {
    return name.substr(std::min(name.find_first_not_of('-'), name.size()));
  };
  const std::string word = without_dashes(typed);
  if (word.size() < 2) {
    return {};  // "-x": every short option is one edit away
  }
  // A third of the word: "tolerence" (9 letters) may be 3 edits from the option, "stpe" 1.
  const int threshold = std::max(1, static_cast<int>(word.size()) / 3);
  int best = threshold;
  std::vector<std::string> nearest;
  for (const std::string& candidate : candidates) {
    const int distance = edit_distance(typed, candidate);
    if (distance > threshold) {
      continue;
    }
    if (distance < best) {
      best = distance;
      nearest.clear();
    }
    if (distance == best) {
      nearest.push_back(candidate);
    }
  }
  if (!nearest.empty() || word.size() < 3) {
    return nearest;
  }
  // An abbreviation: "--tol" for "--tolerance" (CLI11 takes only whole names).
  for (const std::string& candidate : candidates) {
    if (candidate.size() > typed.size() && candidate.compare(0, typed.size(), typed) == 0) {
      nearest.push_back(candidate);
    }
  }
  return nearest;
}

namespace {

// "'--tolerance'", "'--step' or '--start'", "one of '--a', '--b', '--c'".
std::string quoted_choices(const std::vector<std::string>& names) {
  std::string text = names.size() > 2 ? "one of " : "";
  for (std::size_t i = 0; i < names.size(); ++i) {
    text += (i == 0 ? "" : names.size() == 2 ? " or " : ", ") + ("'" + names[i] + "'");
  }
  return text;
}

// Every long and short name of app's options, with their dashes ("--tolerance", "-t").
std::vector<std::string> option_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::Option* option : app.get_options()) {
    for (const std::string& name : option->get_lnames()) {
      names.push_back("--" + name);
    }
    for (const std::string& name : option->get_snames()) {
      names.push_back("-" + name);
    }
  }
  return names;
}

std::vector<const CLI::App*> all_subcommands(const CLI::App& app) {
  return app.get_subcommands([](const CLI::App*) { return true; });
}

std::string command_path(const CLI::App& root, const CLI::App* command) {
  return command == &root ? "tessera" : "tessera " + command->get_name();
}

}  // namespace

std::optional<std::string> explain_parse_error(const CLI::App& app, const CLI::ParseError& error) {
  const bool is_extras = dynamic_cast<const CLI::ExtrasError*>(&error) != nullptr;
  const bool is_required = dynamic_cast<const CLI::RequiredError*>(&error) != nullptr;
  if (!is_extras && !is_required) {
    return std::nullopt;
  }
  // The command the arguments were given to: the subcommand named on the line, else tessera.
  const std::vector<CLI::App*> parsed = app.get_subcommands();
  const CLI::App* command = parsed.empty() ? &app : parsed.back();
  const std::vector<std::string> left_over = app.remaining(true);
  const auto word = std::find_if(left_over.begin(), left_over.end(),
                                 [](const std::string& a) { return !a.empty() && a[0] != '-'; });
  if (parsed.empty() && word != left_over.end()) {
    // `tessera mesg ...`: CLI11 says "A subcommand is required".
    std::vector<std::string> commands;
    for (const CLI::App* subcommand : all_subcommands(app)) {
      commands.push_back(subcommand->get_name());
    }
    const std::vector<std::string> nearest = nearest_names(*word, commands);
    std::string list;
    for (const std::string& name : commands) {
      list += (list.empty() ? "" : ", ") + name;
    }
    return "unknown command '" + *word + "'" +
           (nearest.empty() ? "" : "; did you mean " + quoted_choices(nearest) + "?") +
           " (commands: " + list + ")";
  }
  // An argument that looks like an option and that no option took. A misspelt option also
  // leaves its value behind, and makes a required option look missing (`render x --ouptut
  // y.png` says "--output is required"): the misspelling is the mistake to name.
  const auto option = std::find_if(left_over.begin(), left_over.end(), [](const std::string& a) {
    return a.size() > 1 && a[0] == '-' && !std::isdigit(static_cast<unsigned char>(a[1])) &&
           a[1] != '.';
  });
  if (option == left_over.end()) {
    return std::nullopt;  // a stray positional argument or a missing option: CLI11 says which
  }
  const std::string typed = option->substr(0, option->find('='));  // "--tolerence=1e-3"
  const std::string path = command_path(app, command);
  std::string message = "unknown option '" + typed + "' for '" + path + "'";
  const std::vector<std::string> nearest = nearest_names(typed, option_names(*command));
  if (!nearest.empty()) {
    return message + "; did you mean " + quoted_choices(nearest) + "?";
  }
  // An option of another command: `tessera compare sphere --method front`.
  std::vector<std::string> owners;
  for (const CLI::App* other : all_subcommands(app)) {
    const std::vector<std::string> names = option_names(*other);
    if (other != command && std::find(names.begin(), names.end(), typed) != names.end()) {
      owners.push_back("tessera " + other->get_name());
    }
  }
  if (!owners.empty()) {
    std::string list;
    for (const std::string& owner : owners) {
      list += (list.empty() ? "'" : ", '") + owner + "'";
    }
    return message + "; it is an option of " + list + " (see '" + path + " --help')";
  }
  return message + " (see '" + path + " --help')";
}

}  // namespace tessera::app
