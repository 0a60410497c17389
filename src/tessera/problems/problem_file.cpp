// SPDX-License-Identifier: MIT
#include "tessera/problems/problem_file.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

#include "tessera/core/describe.h"
#include "tessera/core/dynamics.h"
#include "tessera/core/error.h"
#include "tessera/problems/detail/statement_reader.h"
#include "tessera/problems/expression.h"
#include "tessera/problems/expression_problem.h"
#include "tessera/problems/view.h"

namespace tessera {

namespace {

using detail::Statement;
using detail::Word;

const std::vector<std::string> all_keywords = {
    "name", "description", "variables", "parameter", "equation", "start",   "step",
    "box",  "halfspace",   "euler",     "area",      "view",     "dynamics"};
const std::vector<std::string> repeatable_keywords = {"parameter", "equation", "box", "halfspace"};

bool contains(const std::vector<std::string>& list, const std::string& word) {
  return std::find(list.begin(), list.end(), word) != list.end();
}

std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::string plural(std::size_t count, const std::string& noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

/// Reads the statements of a problem file and turns them into a ProblemSetup, in dependency
/// order (variables, parameters, equations, the rest) rather than file order, so that only
/// parameters need to be written before their use.
class ProblemFileParser {
 public:
  ProblemFileParser(std::string source, const std::map<std::string, double>& overrides)
      : source_(std::move(source)), overrides_(overrides) {}

  ProblemSetup parse(const std::string& text) {
    split_into_statements(text);
    name_ = read_name();
    read_variables();
    read_parameters();
    std::vector<Expression> equations = read_equations();
    std::optional<Dynamics> dynamics;
    if (const Statement* statement = single("dynamics")) {
      dynamics = read_dynamics(*statement);
    }
    ProblemSetup setup;
    setup.start = read_start();
    setup.domain = read_domain();
    if (const Statement* step = single("step")) {
      setup.suggested_step = positive_value(*step, "step");
    }
    if (const Statement* area = single("area")) {
      setup.exact_area = positive_value(*area, "area");
    }
    if (const Statement* euler = single("euler")) {
      setup.expected_euler_characteristic = read_euler(*euler);
    }
    setup.problem =
        std::make_unique<ExpressionProblem>(name_, std::move(equations), std::move(dynamics));
    setup.description = describe();
    check_start(setup);
    if (const Statement* view = single("view")) {
      setup.view = read_view(*view, *setup.problem);
    }
    return setup;
  }

 private:
  [[noreturn]] void fail_file(const std::string& message) const {
    throw InvalidArgument(source_ + ": " + message);
  }

  [[noreturn]] void fail(const Statement& statement, const std::string& message,
                         int column = 0) const {
    detail::throw_at(source_, statement, message, column);
  }

  void split_into_statements(const std::string& text) {
    statements_ = detail::read_statements(text);
    for (std::size_t i = 0; i < statements_.size(); ++i) {
      check_keyword(i);
    }
  }

  // Statement i against the keyword list and against the single-use keywords before it.
  void check_keyword(std::size_t i) const {
    const Statement& statement = statements_[i];
    const std::string& keyword = statement.keyword.text;
    if (!contains(all_keywords, keyword)) {
      fail(statement, "unknown keyword '" + keyword + "' (keywords: " + join_words(all_keywords) + ")",
           statement.keyword.column);
    }
    if (contains(repeatable_keywords, keyword)) {
      return;
    }
    for (std::size_t k = 0; k < i; ++k) {
      const Statement& earlier = statements_[k];
      if (earlier.keyword.text == keyword) {
        fail(statement,
             "duplicate '" + keyword + "' line (first given on line " +
                 std::to_string(earlier.line) + ")",
             statement.keyword.column);
      }
    }
  }

  std::vector<const Statement*> all(const std::string& keyword) const {
    std::vector<const Statement*> found;
    for (const Statement& statement : statements_) {
      if (statement.keyword.text == keyword) {
        found.push_back(&statement);
      }
    }
    return found;
  }
  const Statement* single(const std::string& keyword) const {
    const auto found = all(keyword);
    return found.empty() ? nullptr : found.front();
  }

  // An expression at `column` of `statement`; syntax errors are reported at their place in
  // the line, not in the expression.
  Expression expression_at(const Statement& statement, const std::string& text, int column,
                           const std::vector<std::string>& variables,
                           const std::string& what) const {
    try {
      return Expression(text, variables, parameters_);
    } catch (const ExpressionSyntaxError& error) {
      fail(statement, what + ": " + error.reason(), column + error.column() - 1);
    }
  }

  // A value given as an expression of the parameters (a number, `-pi`, `2*r`); it must be finite.
  double constant_at(const Statement& statement, const std::string& text, int column,
                     const std::string& what) const {
    if (text.empty()) {
      fail(statement, what + ": expected a value after '" + statement.keyword.text + "'", column);
    }
    const double value = expression_at(statement, text, column, {}, what).value(Eigen::VectorXd(0));
    if (!std::isfinite(value)) {
      fail(statement, what + " = " + format_number(value) + " is not a finite number", column);
    }
    return value;
  }
  double constant_at(const Statement& statement, const Word& word, const std::string& what) const {
    return constant_at(statement, word.text, word.column, what);
  }

  double positive_value(const Statement& statement, const std::string& what) const {
    const double value = constant_at(statement, statement.rest, statement.rest_column, what);
    if (!(value > 0.0)) {
      fail(statement, what + " = " + format_number(value) + " must be > 0", statement.rest_column);
    }
    return value;
  }

  void read_variables() {
    variables_statement_ = single("variables");
    if (variables_statement_ == nullptr) {
      fail_file("missing 'variables' line: declare the coordinates, e.g. 'variables x y z'");
    }
    const Statement& statement = *variables_statement_;
    for (const Word& word : statement.words) {
      std::string why;
      if (!Expression::is_valid_name(word.text, &why)) {
        fail(statement, "variables: " + why, word.column);
      }
      if (contains(variables_, word.text)) {
        fail(statement, "variables: duplicate variable '" + word.text + "'", word.column);
      }
      variables_.push_back(word.text);
    }
    if (variables_.size() < 3) {
      fail(statement, "variables: " + plural(variables_.size(), "variable") +
                          " given, need at least 3 (a 2-manifold in R^n is given by n-2 "
                          "equations)");
    }
  }

  void read_parameters() {
    std::map<std::string, int> defined_on_line;
    for (const Statement* statement : all("parameter")) {
      // parameter NAME = VALUE; the name ends at a space or at '=' so that "r=1" also works.
      const std::string& rest = statement->rest;
      const std::size_t name_end = std::min(rest.find_first_of(" =", 0), rest.size());
      const std::string name = rest.substr(0, name_end);
      const std::size_t equals = rest.find_first_not_of(' ', name_end);
      if (name.empty() || equals == std::string::npos || rest[equals] != '=') {
        fail(*statement, "parameter: expected 'parameter NAME = VALUE', e.g. 'parameter r = 1'",
             statement->rest_column +
                 static_cast<int>(name.empty() ? 0 : std::min(equals, rest.size())));
      }
      std::string why;
      if (!Expression::is_valid_name(name, &why)) {
        fail(*statement, "parameter: " + why, statement->rest_column);
      }
      if (contains(variables_, name)) {
        fail(*statement, "parameter '" + name + "' has the same name as a variable",
             statement->rest_column);
      }
      if (defined_on_line.count(name) > 0) {
        fail(*statement,
             "duplicate parameter '" + name + "' (first defined on line " +
                 std::to_string(defined_on_line[name]) + ")",
             statement->rest_column);
      }
      const std::size_t value_start =
          std::min(rest.find_first_not_of(' ', equals + 1), rest.size());
      // The file's value is parsed even when overridden, so that the file stays valid on its own.
      double value = constant_at(*statement, rest.substr(value_start),
                                 statement->rest_column + static_cast<int>(value_start),
                                 "parameter '" + name + "'");
      if (const auto override_value = overrides_.find(name); override_value != overrides_.end()) {
        value = override_value->second;
        if (!std::isfinite(value)) {
          fail_file("parameter override " + name + " = " + format_number(value) +
                    " is not a finite number");
        }
      }
      defined_on_line[name] = statement->line;
      parameter_lines_[name] = statement->line;
      parameters_[name] = value;
      parameter_order_.push_back(name);
    }
    for (const auto& [name, value] : overrides_) {
      if (parameters_.count(name) == 0) {
        fail_file(
            "parameter override '" + name + "' names no parameter of the file (" +
            (parameter_order_.empty() ? "it has none" : "parameters: " + join_words(parameter_order_)) +
            ")");
      }
    }
  }

  std::vector<Expression> read_equations() const {
    const auto statements = all("equation");
    const std::size_t expected = variables_.size() - 2;
    std::vector<std::string> lines;
    for (const Statement* statement : statements) {
      lines.push_back(std::to_string(statement->line));
    }
    const std::string counts = plural(variables_.size(), "variable") +
                               " need n-2 = " + plural(expected, "equation") + ", found " +
                               std::to_string(statements.size());
    if (statements.empty()) {
      fail_file("missing equations: no 'equation' line; " + counts);
    }
    if (statements.size() > expected) {
      fail(*statements[expected], "too many equations: " + counts + " (lines " + join_words(lines) + ")");
    }
    if (statements.size() < expected) {
      fail(*variables_statement_, "too few equations: " + counts + " (line" +
                                      (lines.size() == 1 ? " " : "s ") + join_words(lines) + ")");
    }
    std::vector<Expression> equations;
    for (std::size_t i = 0; i < statements.size(); ++i) {
      const Statement& statement = *statements[i];
      if (statement.rest.empty()) {
        fail(statement, "equation: expected an expression after 'equation'", statement.rest_column);
      }
      equations.push_back(expression_at(statement, statement.rest, statement.rest_column,
                                        variables_, "equation " + std::to_string(i + 1)));
    }
    return equations;
  }

  // dynamics parameters P1 P2 [sign S] [mass B1 … Bm]: the sections in any order, each once. The
  // two words after `parameters` are variables even where they are spelled like a section, so
  // that variables may be called `sign` or `mass` too.
  Dynamics read_dynamics(const Statement& statement) const {
    const std::vector<std::string> section_names = {"parameters", "sign", "mass"};
    const std::string usage =
        "expected 'dynamics parameters P1 P2 [sign -1] [mass B1 … Bm]', e.g. 'dynamics "
        "parameters " +
        variables_[variables_.size() - 2] + " " + variables_.back() + " sign -1'";
    if (statement.words.empty()) {
      fail(statement, "dynamics: " + usage, statement.rest_column);
    }
    std::map<std::string, std::vector<Word>> sections;
    std::map<std::string, Word> section_words;
    std::string current;
    for (const Word& word : statement.words) {
      const bool is_parameter_word = current == "parameters" && sections[current].size() < 2 &&
                                     contains(variables_, word.text);
      if (contains(section_names, word.text) && !is_parameter_word) {
        if (section_words.count(word.text) > 0) {
          fail(statement, "dynamics: '" + word.text + "' is given twice", word.column);
        }
        current = word.text;
        section_words[current] = word;
        sections[current];
        continue;
      }
      if (current.empty()) {
        fail(statement,
             "dynamics: found '" + word.text +
                 "' where 'parameters', 'sign' or 'mass' was expected; " + usage,
             word.column);
      }
      sections[current].push_back(word);
    }
    if (sections.count("parameters") == 0) {
      fail(statement,
           "dynamics: missing 'parameters P1 P2', the two variables that are the "
           "dynamics' parameters (the others are its state)",
           statement.rest_column);
    }
    Dynamics dynamics;
    read_dynamics_parameters(statement, section_words.at("parameters"), sections.at("parameters"),
                             dynamics);
    if (sections.count("sign") > 0) {
      const auto& words = sections.at("sign");
      if (words.size() != 1) {
        fail(statement,
             "dynamics: sign: expected one value, 1 or -1, found " + plural(words.size(), "word"),
             section_words.at("sign").column);
      }
      dynamics.sign = constant_at(statement, words[0], "dynamics: sign");
      if (dynamics.sign != 1.0 && dynamics.sign != -1.0) {
        fail(statement,
             "dynamics: sign = " + format_number(dynamics.sign) +
                 " must be 1 (B·u' = F) or -1 (B·u' = -F)",
             words[0].column);
      }
    }
    if (sections.count("mass") > 0) {
      dynamics.mass_diagonal = read_mass(statement, section_words.at("mass"), sections.at("mass"));
    }
    return dynamics;
  }

  void read_dynamics_parameters(const Statement& statement, const Word& keyword,
                                const std::vector<Word>& words, Dynamics& dynamics) const {
    if (words.size() != 2) {
      fail(statement,
           "dynamics: parameters: expected two variables, found " + plural(words.size(), "word"),
           keyword.column);
    }
    for (std::size_t k = 0; k < 2; ++k) {
      const Word& word = words[k];
      if (parameters_.count(word.text) > 0) {
        fail(statement,
             "dynamics: '" + word.text + "' is a constant ('parameter' on line " +
                 std::to_string(parameter_lines_.at(word.text)) +
                 "), not a variable of M; the dynamics' parameters are two of the variables (" +
                 join_words(variables_) + ")",
             word.column);
      }
      const auto variable = std::find(variables_.begin(), variables_.end(), word.text);
      if (variable == variables_.end()) {
        fail(statement,
             "dynamics: unknown variable '" + word.text +
                 "' (variables: " + join_words(variables_) + ")",
             word.column);
      }
      dynamics.parameters[k] = static_cast<int>(variable - variables_.begin());
    }
    if (dynamics.parameters[0] == dynamics.parameters[1]) {
      fail(statement,
           "dynamics: the parameters are the same variable '" + words[1].text +
               "' twice; give two different variables",
           words[1].column);
    }
  }

  // B's diagonal: one entry per equation, in the order of the equation lines.
  Eigen::VectorXd read_mass(const Statement& statement, const Word& keyword,
                            const std::vector<Word>& words) const {
    const std::size_t expected = variables_.size() - 2;
    if (words.size() != expected) {
      fail(statement,
           "dynamics: mass has " + plural(words.size(), "value") + ", expected " +
               std::to_string(expected) + " (the diagonal of B: one per equation, in order)",
           keyword.column);
    }
    Eigen::VectorXd mass(static_cast<Eigen::Index>(expected));
    for (std::size_t i = 0; i < expected; ++i) {
      const std::string what = "dynamics: mass entry " + std::to_string(i + 1);
      const double value = constant_at(statement, words[i], what);
      if (!(value >= 0.0)) {
        fail(statement,
             what + " = " + format_number(value) + " must be >= 0 (0: an algebraic equation)",
             words[i].column);
      }
      mass(static_cast<Eigen::Index>(i)) = value;
    }
    return mass;
  }

  // n values, one per variable, each a constant expression.
  Eigen::VectorXd read_point(const Statement& statement, const std::vector<Word>& words,
                             const std::string& what) const {
    if (words.size() != variables_.size()) {
      fail(statement, what + " has " + plural(words.size(), "value") + ", expected " +
                          std::to_string(variables_.size()) +
                          " (one per variable: " + join_words(variables_) + ")");
    }
    Eigen::VectorXd point(static_cast<Eigen::Index>(words.size()));
    for (std::size_t i = 0; i < words.size(); ++i) {
      point(static_cast<Eigen::Index>(i)) =
          constant_at(statement, words[i], what + " (" + variables_[i] + ")");
    }
    return point;
  }

  Eigen::VectorXd read_start() {
    start_statement_ = single("start");
    if (start_statement_ == nullptr) {
      fail_file("missing 'start' line: give a point near the manifold, one value per variable (" +
                join_words(variables_, " ") + ")");
    }
    return read_point(*start_statement_, start_statement_->words, "start");
  }

  Domain read_domain() const {
    const int n = static_cast<int>(variables_.size());
    Eigen::VectorXd lower = Eigen::VectorXd::Constant(n, -std::numeric_limits<double>::infinity());
    Eigen::VectorXd upper = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
    std::map<std::string, int> bounded_on_line;
    for (const Statement* statement : all("box")) {
      const auto& words = statement->words;
      if (words.size() != 3) {
        fail(*statement, "box: expected 'box VARIABLE LOWER UPPER', e.g. 'box x -1.5 1.5', found " +
                             plural(words.size(), "word") + " after 'box'");
      }
      const auto variable = std::find(variables_.begin(), variables_.end(), words[0].text);
      if (variable == variables_.end()) {
        fail(*statement,
             "box: unknown variable '" + words[0].text + "' (variables: " + join_words(variables_) + ")",
             words[0].column);
      }
      if (bounded_on_line.count(words[0].text) > 0) {
        fail(*statement,
             "box: variable '" + words[0].text + "' is already bounded on line " +
                 std::to_string(bounded_on_line[words[0].text]),
             words[0].column);
      }
      bounded_on_line[words[0].text] = statement->line;
      const auto i = variable - variables_.begin();
      lower(i) = constant_at(*statement, words[1], "box lower bound of " + words[0].text);
      upper(i) = constant_at(*statement, words[2], "box upper bound of " + words[0].text);
      if (!(lower(i) < upper(i))) {
        fail(*statement,
             "box: empty domain: lower bound " + format_number(lower(i)) + " of " + words[0].text +
                 " is not below the upper bound " + format_number(upper(i)),
             words[1].column);
      }
    }
    Domain domain = bounded_on_line.empty() ? Domain(n) : Domain::box(lower, upper, variables_);
    for (const Statement* statement : all("halfspace")) {
      const auto& words = statement->words;
      const auto point_keyword = std::find_if(
          words.begin(), words.end(), [](const Word& word) { return word.text == "point"; });
      if (words.empty() || words[0].text != "normal" || point_keyword == words.end()) {
        fail(*statement,
             "halfspace: expected 'halfspace normal N1 … Nn point P1 … Pn' "
             "(the half-space normal·(x − point) >= 0)");
      }
      const Eigen::VectorXd normal = read_point(
          *statement, std::vector<Word>(words.begin() + 1, point_keyword), "halfspace normal");
      const Eigen::VectorXd point = read_point(
          *statement, std::vector<Word>(point_keyword + 1, words.end()), "halfspace point");
      if (normal.isZero(0.0)) {
        fail(*statement, "halfspace: the normal is zero", words[1].column);
      }
      domain.add_half_space(normal, point, half_space_label(normal, point));
    }
    return domain;
  }

  // "2*x - y >= 0.5", in the expression language, for domain descriptions.
  std::string half_space_label(const Eigen::VectorXd& normal, const Eigen::VectorXd& point) const {
    std::ostringstream label;
    bool first = true;
    for (Eigen::Index i = 0; i < normal.size(); ++i) {
      const double c = normal(i);
      if (c == 0.0) {
        continue;
      }
      label << (first ? (c < 0 ? "-" : "") : (c < 0 ? " - " : " + "));
      if (std::abs(c) != 1.0) {
        label << std::abs(c) << "*";
      }
      label << variables_[static_cast<std::size_t>(i)];
      first = false;
    }
    label << " >= " << normal.dot(point);
    return label.str();
  }

  // The functionals the surface is written in: variables, `norm`, `NAME = EXPRESSION` (the file
  // declares no blocks, so no max:B); errors point at their column in the line.
  View read_view(const Statement& statement, const ImplicitProblem& problem) const {
    if (statement.rest.empty()) {
      fail(statement,
           "view: expected functionals after 'view', e.g. 'view " +
               join_words(std::vector<std::string>(variables_.begin(), variables_.begin() + 3)) +
               "' or 'view " + variables_[0] + ", " + variables_[1] + ", r = sqrt(" +
               variables_[0] + "^2 + " + variables_[1] + "^2)'",
           statement.rest_column);
    }
    View view;
    try {
      view = parse_view(statement.rest, problem, parameters_);
    } catch (const ViewSpecificationError& error) {
      fail(statement, "view: " + error.reason(), statement.rest_column + error.column() - 1);
    }
    if (view.size() < 2) {
      fail(statement,
           "view: " + plural(static_cast<std::size_t>(view.size()), "functional") +
               " given, need at least 2 to place the vertices (3 for a surface in space)",
           statement.rest_column);
    }
    return view;
  }

  int read_euler(const Statement& statement) const {
    int value = 0;
    const std::string& text = statement.rest;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
      fail(statement,
           "euler: expected an integer Euler characteristic (e.g. 2 for a sphere), "
           "found '" +
               text + "'",
           statement.rest_column);
    }
    return value;
  }

  std::string read_name() const {
    const Statement* statement = single("name");
    if (statement == nullptr) {
      const std::string stem = std::filesystem::path(source_).stem().string();
      return stem.empty() || stem.front() == '<' ? "problem" : stem;
    }
    if (statement->words.size() != 1) {
      fail(*statement,
           "name: expected one word, e.g. 'name sphere_cut', found " +
               plural(statement->words.size(), "word"),
           statement->rest_column);
    }
    return statement->rest;
  }

  std::string describe() const {
    const Statement* description = single("description");
    std::string text = description != nullptr && !description->rest.empty()
                           ? description->rest
                           : name_ + " from " + source_;
    std::vector<std::string> values;
    for (const auto& name : parameter_order_) {
      values.push_back(name + " = " + format_number(parameters_.at(name)));
    }
    return values.empty() ? text : text + " (" + join_words(values) + ")";
  }

  // The start is the user's promise of a point near M inside S; a broken promise here is far
  // easier to understand than a corrector failure later.
  void check_start(const ProblemSetup& setup) const {
    const Statement& statement = *start_statement_;
    for (std::size_t k = 0; k < setup.domain.half_spaces().size(); ++k) {
      if (setup.domain.signed_distance(static_cast<int>(k), setup.start) < 0.0) {
        fail(statement,
             "start lies outside the domain: it violates " + setup.domain.half_spaces()[k].label);
      }
    }
    Eigen::VectorXd F(static_cast<Eigen::Index>(variables_.size() - 2));
    setup.problem->evaluate(setup.start, F);
    for (Eigen::Index i = 0; i < F.size(); ++i) {
      if (!std::isfinite(F(i))) {
        fail(statement, "start: equation " + std::to_string(i + 1) + " is " + format_number(F(i)) +
                            " at the start; it must be finite (is the start in the domain of "
                            "log, sqrt, …?)");
      }
    }
  }

  std::string source_;
  std::string name_;
  const std::map<std::string, double>& overrides_;
  std::vector<Statement> statements_;
  const Statement* variables_statement_ = nullptr;
  const Statement* start_statement_ = nullptr;
  std::vector<std::string> variables_;
  std::map<std::string, double> parameters_;
  std::vector<std::string> parameter_order_;  ///< file order, for the description
  std::map<std::string, int> parameter_lines_;  ///< where each parameter is defined
};

}  // namespace

ProblemSetup parse_problem(const std::string& text, const std::string& source_name,
                           const std::map<std::string, double>& parameter_overrides) {
  return ProblemFileParser(source_name, parameter_overrides).parse(text);
}

ProblemSetup parse_problem(const std::string& text, const std::string& source_name) {
  return parse_problem(text, source_name, {});
}

ProblemSetup load_problem_file(const std::string& path,
                               const std::map<std::string, double>& parameter_overrides) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw InvalidArgument("problem file '" + path + "' does not exist or is not a regular file");
  }
  std::ifstream file(path, std::ios::binary);
  std::ostringstream text;
  text << file.rdbuf();
  if (!file) {
    throw InvalidArgument("cannot read problem file '" + path + "'");
  }
  return parse_problem(text.str(), path, parameter_overrides);
}

ProblemSetup load_problem_file(const std::string& path) { return load_problem_file(path, {}); }

}  // namespace tessera
