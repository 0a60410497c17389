// SPDX-License-Identifier: MIT
#include "tessera/problems/view.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <unordered_map>
#include <utility>

#include "tessera/core/describe.h"
#include "tessera/problems/detail/name_characters.h"

namespace tessera {

namespace {

using Kind = ViewFunctionalKind;

// The block functionals by the word that names them in a specification ("max:u").
struct BlockFunctionalWord {
  const char* word;
  Kind kind;
};
constexpr BlockFunctionalWord block_functional_words[] = {{"max", Kind::BlockMaximum},
                                                          {"min", Kind::BlockMinimum},
                                                          {"mean", Kind::BlockMean},
                                                          {"absmax", Kind::BlockAbsMaximum},
                                                          {"norm", Kind::BlockNorm}};

bool is_space(char c) { return c == ' ' || c == '\t'; }

// [begin, end) of `text` without surrounding spaces.
std::pair<std::size_t, std::size_t> trimmed_range(std::string_view text, std::size_t begin,
                                                  std::size_t end) {
  while (begin < end && is_space(text[begin])) {
    ++begin;
  }
  while (end > begin && is_space(text[end - 1])) {
    --end;
  }
  return {begin, end};
}

using detail::is_name_char;
using detail::is_name_start;

// Every name in an expression text with its 0-based position; numbers such as 1e-3 are skipped
// whole so that their 'e' is not taken for a name.
std::vector<std::pair<std::string, std::size_t>> names_in_expression(std::string_view text) {
  std::vector<std::pair<std::string, std::size_t>> names;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (is_name_start(c)) {
      const std::size_t start = i;
      while (i < text.size() && is_name_char(text[i])) {
        ++i;
      }
      names.emplace_back(std::string(text.substr(start, i - start)), start);
    } else if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
      while (i < text.size() &&
             (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '.')) {
        ++i;
      }
      if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
        std::size_t j = i + 1;
        if (j < text.size() && (text[j] == '+' || text[j] == '-')) {
          ++j;
        }
        if (j < text.size() && std::isdigit(static_cast<unsigned char>(text[j]))) {
          i = j;
          while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) {
            ++i;
          }
        }
      }
    } else {
      ++i;
    }
  }
  return names;
}

bool is_reserved_in_expressions(const std::string& name) {
  const auto& functions = Expression::function_names();
  return name == "pi" || std::find(functions.begin(), functions.end(), name) != functions.end();
}

ViewFunctional coordinate_functional(int index, const std::string& name) {
  ViewFunctional functional;
  functional.kind = Kind::Coordinate;
  functional.label = name;
  functional.name = name;
  functional.first = index;
  functional.size = 1;
  return functional;
}

ViewFunctional block_functional(Kind kind, const std::string& word, const CoordinateBlock& block) {
  ViewFunctional functional;
  functional.kind = kind;
  functional.label = word + ":" + block.name;
  functional.name = word + "_" + block.name;
  functional.first = block.first;
  functional.size = block.size;
  functional.weight = kind == Kind::BlockNorm ? block.weight : 1.0;
  return functional;
}

ViewFunctional norm_functional(int n) {
  ViewFunctional functional;
  functional.kind = Kind::Norm;
  functional.label = "norm";
  functional.name = "norm";
  functional.first = 0;
  functional.size = n;
  return functional;
}

// Reads one specification against one problem; knows the problem's names and blocks.
class ViewParser {
 public:
  ViewParser(std::string_view specification, const ImplicitProblem& problem,
             const std::map<std::string, double>& parameters)
      : specification_(specification),
        problem_(problem),
        n_(problem.ambient_dimension()),
        names_(problem.coordinate_names()),
        blocks_(problem.coordinate_blocks()),
        weights_(metric_weights(problem)),  // checks the blocks
        parameters_(parameters) {
    TESSERA_CHECK(static_cast<int>(names_.size()) == n_,
                  "problem '" << problem.name() << "' has " << names_.size()
                              << " coordinate names for n = " << n_ << " coordinates");
    for (int i = 0; i < n_; ++i) {
      index_of_name_.emplace(names_[static_cast<std::size_t>(i)], i);  // the first one wins
    }
  }

  View parse() {
    const auto [begin, end] = trimmed_range(specification_, 0, specification_.size());
    if (begin == end) {
      fail(1, "the view is empty; name the functionals to write, e.g. " + example());
    }
    std::size_t item_begin = 0;
    while (true) {
      const std::size_t comma =
          std::min(specification_.find(',', item_begin), specification_.size());
      read_item(item_begin, comma);
      if (comma == specification_.size()) {
        break;
      }
      item_begin = comma + 1;
    }
    return View(n_, std::move(functionals_), weights_);
  }

 private:
  [[noreturn]] void fail(std::size_t column, const std::string& reason) const {
    throw ViewSpecificationError(std::string(specification_), static_cast<int>(column), reason);
  }

  std::string example() const {
    if (!blocks_.empty()) {
      return "max:" + blocks_.front().name + " or norm:" + blocks_.front().name;
    }
    return names_.size() >= 3 ? names_[0] + ", " + names_[1] + ", " + names_[2] : "all";
  }

  // What an item can be, for messages: coordinates compactly, blocks, the other forms.
  std::string available() const {
    std::string text = "coordinates: " + describe_coordinates(problem_);
    std::vector<std::string> block_names;
    for (const CoordinateBlock& block : blocks_) {
      block_names.push_back(block.name);
    }
    if (!block_names.empty()) {
      text +=
          "; max:B, min:B, mean:B, absmax:B, norm:B of a block B (blocks: " + join_words(block_names) +
          ")";
    }
    return text + "; norm; all; or NAME = EXPRESSION";
  }

  const CoordinateBlock* find_block(const std::string& name) const {
    for (const CoordinateBlock& block : blocks_) {
      if (block.name == name) {
        return &block;
      }
    }
    return nullptr;
  }

  void add(ViewFunctional functional, std::size_t column, const std::string& item) {
    const auto [earlier, is_new] = item_of_column_.emplace(functional.name, item);
    if (!is_new) {
      fail(column, earlier->second == item
                       ? "'" + item + "' is given twice"
                       : "'" + item + "' gives the column '" + functional.name + "', as '" +
                             earlier->second + "' does (every column needs its own name)");
    }
    functionals_.push_back(std::move(functional));
  }

  void read_item(std::size_t raw_begin, std::size_t raw_end) {
    const auto [begin, end] = trimmed_range(specification_, raw_begin, raw_end);
    const std::size_t column = begin + 1;
    if (begin == end) {
      fail(column, "empty item (a comma too many?); items are separated by single commas");
    }
    const std::string item(specification_.substr(begin, end - begin));
    // Whole names first, so that a coordinate whose name holds ':' or '=' can still be named.
    if (const auto found = index_of_name_.find(item); found != index_of_name_.end()) {
      add(coordinate_functional(found->second, item), column, item);
      return;
    }
    if (const CoordinateBlock* block = find_block(item)) {
      for (int i = block->first; i < block->first + block->size; ++i) {
        add(coordinate_functional(i, names_[static_cast<std::size_t>(i)]), column, item);
      }
      return;
    }
    if (item.find('=') != std::string::npos) {
      read_expression(begin, end);
      return;
    }
    if (const auto colon = item.find(':'); colon != std::string::npos) {
      read_block_functional(begin, begin + colon, end);
      return;
    }
    if (item == "norm") {
      add(norm_functional(n_), column, item);
      return;
    }
    if (item == "all") {
      for (int i = 0; i < n_; ++i) {
        add(coordinate_functional(i, names_[static_cast<std::size_t>(i)]), column, item);
      }
      return;
    }
    fail(column, "'" + item + "' is no coordinate, block or functional of problem '" +
                     problem_.name() + "' (" + available() + ")");
  }

  // WORD:B with the ':' at `colon`.
  void read_block_functional(std::size_t begin, std::size_t colon, std::size_t end) {
    const auto [word_begin, word_end] = trimmed_range(specification_, begin, colon);
    const auto [block_begin, block_end] = trimmed_range(specification_, colon + 1, end);
    const std::string word(specification_.substr(word_begin, word_end - word_begin));
    const std::string block_name(specification_.substr(block_begin, block_end - block_begin));
    const std::string item = word + ":" + block_name;
    const BlockFunctionalWord* functional = nullptr;
    for (const BlockFunctionalWord& candidate : block_functional_words) {
      if (word == candidate.word) {
        functional = &candidate;
      }
    }
    if (functional == nullptr) {
      fail(word_begin + 1, "'" + item + "': unknown block functional '" + word +
                               "' (max, min, mean, absmax, norm)");
    }
    const CoordinateBlock* block = find_block(block_name);
    if (block == nullptr) {
      std::vector<std::string> block_names;
      for (const CoordinateBlock& candidate : blocks_) {
        block_names.push_back(candidate.name);
      }
      fail(block_begin + 1,
           "'" + item + "': " +
               (block_name.empty() ? std::string("no block named after ':'")
                                   : "no block '" + block_name + "'") +
               (block_names.empty() ? " (problem '" + problem_.name() +
                                          "' has no coordinate blocks; its coordinates: " +
                                          describe_coordinates(problem_) + ")"
                                    : " (blocks: " + join_words(block_names) + ")"));
    }
    add(block_functional(functional->kind, word, *block), word_begin + 1, item);
  }

  // NAME = EXPRESSION, the '=' somewhere in [begin, end).
  void read_expression(std::size_t begin, std::size_t end) {
    const std::size_t equals = specification_.find('=', begin);
    const auto [name_begin, name_end] = trimmed_range(specification_, begin, equals);
    const auto [text_begin, text_end] = trimmed_range(specification_, equals + 1, end);
    const std::string name(specification_.substr(name_begin, name_end - name_begin));
    const std::string text(specification_.substr(text_begin, text_end - text_begin));
    const std::string item = name + " = " + text;
    std::string why;
    if (!Expression::is_valid_name(name, &why)) {
      fail(name_begin + 1, "'" + item + "': the name of an expression: " + why);
    }
    if (index_of_name_.count(name) > 0 || find_block(name) != nullptr) {
      fail(name_begin + 1, "'" + item + "': '" + name +
                               "' is a coordinate or block of the problem; give the expression "
                               "another name");
    }
    if (text.empty()) {
      fail(text_begin + 1, "'" + item + "': expected an expression after '='");
    }
    // The expression's variables are the coordinates it names, not all n: at n = 10⁵ a list of
    // every name would make each expression as large as the problem.
    ViewFunctional functional;
    functional.kind = Kind::Expression;
    functional.label = item;
    functional.name = name;
    std::vector<std::string> variable_names;
    for (const auto& [word, position] : names_in_expression(text)) {
      if (parameters_.count(word) > 0 || is_reserved_in_expressions(word)) {
        continue;
      }
      const auto found = index_of_name_.find(word);
      if (found == index_of_name_.end()) {
        std::vector<std::string> parameter_names;
        for (const auto& [parameter, value] : parameters_) {
          parameter_names.push_back(parameter);
        }
        fail(text_begin + position + 1,
             "'" + item + "': unknown name '" + word + "' (" +
                 "coordinates: " + describe_coordinates(problem_) +
                 (parameter_names.empty() ? "" : "; parameters: " + join_words(parameter_names)) +
                 (word == "e" ? "; for Euler's number write exp(1)" : "") + ")");
      }
      if (std::find(variable_names.begin(), variable_names.end(), word) == variable_names.end()) {
        variable_names.push_back(word);
        functional.variables.push_back(found->second);
      }
    }
    try {
      functional.expression.emplace(text, std::move(variable_names), parameters_);
    } catch (const ExpressionSyntaxError& error) {
      fail(text_begin + static_cast<std::size_t>(error.column()),
           "'" + item + "': " + error.reason());
    }
    add(std::move(functional), name_begin + 1, item);
  }

  std::string_view specification_;
  const ImplicitProblem& problem_;
  int n_;
  std::vector<std::string> names_;
  std::vector<CoordinateBlock> blocks_;
  Eigen::VectorXd weights_;
  const std::map<std::string, double>& parameters_;
  std::unordered_map<std::string, int> index_of_name_;
  std::vector<ViewFunctional> functionals_;
  std::unordered_map<std::string, std::string> item_of_column_;  ///< the item each column came from
};

}  // namespace

ViewSpecificationError::ViewSpecificationError(const std::string& specification, int column,
                                               std::string reason)
    : InvalidArgument("in view '" + specification + "', column " + std::to_string(column) + ": " +
                      reason),
      column_(column),
      reason_(std::move(reason)) {}

View parse_view(std::string_view specification, const ImplicitProblem& problem,
                const std::map<std::string, double>& parameters) {
  return ViewParser(specification, problem, parameters).parse();
}

View all_coordinates_view(const ImplicitProblem& problem) {
  const int n = problem.ambient_dimension();
  const auto names = problem.coordinate_names();
  TESSERA_CHECK(static_cast<int>(names.size()) == n,
                "problem '" << problem.name() << "' has " << names.size()
                            << " coordinate names for n = " << n << " coordinates");
  std::vector<ViewFunctional> functionals;
  functionals.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    functionals.push_back(coordinate_functional(i, names[static_cast<std::size_t>(i)]));
  }
  return View(n, std::move(functionals), metric_weights(problem));
}

View default_view(const ImplicitProblem& problem) {
  const int n = problem.ambient_dimension();
  const std::vector<CoordinateBlock> blocks = problem.coordinate_blocks();
  if (n <= kLargeAmbientDimension || blocks.empty()) {
    return all_coordinates_view(problem);
  }
  const Eigen::VectorXd weights = metric_weights(problem);  // checks the blocks
  const auto names = problem.coordinate_names();
  std::vector<bool> in_block(static_cast<std::size_t>(n), false);
  const CoordinateBlock* largest = &blocks.front();
  for (const CoordinateBlock& block : blocks) {
    std::fill_n(in_block.begin() + block.first, block.size, true);
    if (block.size > largest->size) {
      largest = &block;
    }
  }
  std::vector<ViewFunctional> functionals;
  for (int i = 0; i < n; ++i) {
    if (!in_block[static_cast<std::size_t>(i)]) {
      functionals.push_back(coordinate_functional(i, names[static_cast<std::size_t>(i)]));
    }
  }
  for (const CoordinateBlock& block : blocks) {
    functionals.push_back(block_functional(Kind::BlockMaximum, "max", block));
  }
  if (functionals.size() < 3) {
    functionals.push_back(block_functional(Kind::BlockNorm, "norm", *largest));
  }
  if (functionals.size() < 3) {
    functionals.push_back(block_functional(Kind::BlockMinimum, "min", *largest));
  }
  return View(n, std::move(functionals), weights);
}

std::string describe_coordinates(const ImplicitProblem& problem) {
  const int n = problem.ambient_dimension();
  const auto names = problem.coordinate_names();
  const auto blocks = problem.coordinate_blocks();
  const auto name = [&](int i) {
    return i < static_cast<int>(names.size()) ? names[static_cast<std::size_t>(i)]
                                              : "x" + std::to_string(i);
  };
  std::vector<std::string> parts;
  // A run of coordinates outside blocks: listed whole when short, else its ends.
  const auto add_run = [&](int first, int end) {
    constexpr int kListedWhole = 8;
    if (end - first <= kListedWhole) {
      for (int i = first; i < end; ++i) {
        parts.push_back(name(i));
      }
      return;
    }
    parts.push_back(name(first) + ", " + name(first + 1) + ", " + name(first + 2) + ", …, " +
                    name(end - 1) + " (" + std::to_string(end - first) + " coordinates)");
  };
  int i = 0;
  int run_start = 0;
  while (i < n) {
    const auto block = std::find_if(blocks.begin(), blocks.end(),
                                    [&](const CoordinateBlock& b) { return b.first == i; });
    if (block == blocks.end() || block->size < 1) {
      ++i;
      continue;
    }
    add_run(run_start, i);
    parts.push_back(block->size == 1 ? name(i) + " (block " + block->name + ")"
                                     : name(i) + " … " + name(i + block->size - 1) + " (block " +
                                           block->name + ")");
    i += block->size;
    run_start = i;
  }
  add_run(run_start, n);
  return join_words(parts);
}

}  // namespace tessera
