// SPDX-License-Identifier: MIT
// Parsing of Expression: names, the recursive-descent parser that emits the tape, and errors.
#include "tessera/problems/expression.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <sstream>
#include <utility>

#include "tessera/core/describe.h"
#include "tessera/problems/detail/name_characters.h"

namespace tessera {

namespace {

using detail::is_name_char;
using detail::is_name_start;
bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Names people carry over from other languages; a hint saves them a trip to the docs.
std::string hint_for_unknown_function(const std::string& name) {
  static const std::map<std::string, std::string> hints = {{"ln", "log is the natural logarithm"},
                                                           {"arctan", "write atan"},
                                                           {"arcsin", "write asin"},
                                                           {"arccos", "write acos"},
                                                           {"pow", "write x^y"},
                                                           {"fabs", "write abs"},
                                                           {"sqr", "write x^2"}};
  const auto hint = hints.find(name);
  return hint == hints.end() ? "" : "; " + hint->second;
}

}  // namespace

ExpressionSyntaxError::ExpressionSyntaxError(const std::string& text, int column,
                                             std::string reason)
    : InvalidArgument("in expression '" + text + "', column " + std::to_string(column) + ": " +
                      reason),
      column_(column),
      reason_(std::move(reason)) {}

const std::vector<std::string>& Expression::function_names() {
  static const std::vector<std::string> names = {"exp",  "log",  "sqrt", "sin",  "cos",
                                                 "tan",  "tanh", "sinh", "cosh", "atan",
                                                 "asin", "acos", "abs"};
  return names;
}

bool Expression::is_valid_name(const std::string& name, std::string* why) {
  auto refuse = [&](const std::string& reason) {
    if (why != nullptr) {
      *why = reason;
    }
    return false;
  };
  if (name.empty() || !is_name_start(name[0]) ||
      !std::all_of(name.begin(), name.end(), is_name_char)) {
    return refuse("'" + name +
                  "' is not a valid name (use letters, digits and '_', starting "
                  "with a letter or '_')");
  }
  if (name == "pi") {
    return refuse("'pi' is reserved (the constant 3.14159…)");
  }
  const auto& functions = function_names();
  if (std::find(functions.begin(), functions.end(), name) != functions.end()) {
    return refuse("'" + name + "' is reserved (a function)");
  }
  return true;
}

/// Recursive descent over the grammar in expression.h, emitting instructions as it goes: the
/// operands of an operator are parsed (and emitted) before the operator itself, so the tape
/// comes out in postfix order without an intermediate tree.
class Expression::Parser {
 public:
  Parser(std::string_view text, const std::vector<std::string>& variable_names,
         const std::map<std::string, double>& parameters, std::vector<Instruction>& tape)
      : text_(text), variables_(variable_names), parameters_(parameters), tape_(tape) {}

  void parse() {
    skip_spaces();
    if (at_end()) {
      fail(position_, "empty expression: expected a number, a name or '('");
    }
    parse_sum();
    skip_spaces();
    if (!at_end()) {
      if (text_[position_] == ')') {
        fail(position_, "unmatched ')'");
      }
      std::string reason =
          "expected an operator (+ - * / ^) or the end of the expression, found " + describe_next();
      if (is_name_start(text_[position_]) || is_digit(text_[position_]) ||
          text_[position_] == '(') {
        reason += " (implicit multiplication is not supported: write 2*x, not 2x or 2 x)";
      }
      fail(position_, reason);
    }
  }

 private:
  int parse_sum() {
    int left = parse_product();
    for (;;) {
      skip_spaces();
      if (at_end() || (text_[position_] != '+' && text_[position_] != '-')) {
        return left;
      }
      const Operation operation = text_[position_] == '+' ? Operation::Add : Operation::Subtract;
      ++position_;
      const int right = parse_product();
      left = emit_binary(operation, left, right);
    }
  }

  int parse_product() {
    int left = parse_unary();
    for (;;) {
      skip_spaces();
      if (at_end() || (text_[position_] != '*' && text_[position_] != '/')) {
        return left;
      }
      if (text_.substr(position_, 2) == "**") {
        fail(position_, "'**' is not an operator: write x^y for powers");
      }
      const Operation operation = text_[position_] == '*' ? Operation::Multiply : Operation::Divide;
      ++position_;
      const int right = parse_unary();
      left = emit_binary(operation, left, right);
    }
  }

  // Every level of nesting ('(', f(, unary signs, exponents) passes through here; the depth
  // limit turns a pathological input into an error instead of a stack overflow.
  int parse_unary() {
    skip_spaces();
    if (++depth_ > max_depth) {
      fail(position_,
           "expression is nested more than " + std::to_string(max_depth) + " levels deep");
    }
    int result = 0;
    if (!at_end() && text_[position_] == '-') {
      ++position_;
      result = emit_unary(Operation::Negate, parse_unary());
    } else if (!at_end() && text_[position_] == '+') {
      ++position_;
      result = parse_unary();
    } else {
      result = parse_power();
    }
    --depth_;
    return result;
  }

  int parse_power() {
    const int base = parse_primary();
    skip_spaces();
    if (at_end() || text_[position_] != '^') {
      return base;
    }
    ++position_;
    // The exponent is a unary: this makes ^ right-associative (2^3^2 = 2^9) and allows 2^-1,
    // while -x^2 stays -(x^2) because the minus is consumed before the power is parsed.
    const int exponent = parse_unary();
    return emit_binary(Operation::Power, base, exponent);
  }

  int parse_primary() {
    skip_spaces();
    if (at_end()) {
      fail(position_, "expected a number, a name or '(', found the end of the expression");
    }
    const char c = text_[position_];
    if (is_digit(c) || c == '.') {
      return parse_number();
    }
    if (is_name_start(c)) {
      return parse_name();
    }
    if (c == '(') {
      ++position_;
      const int inner = parse_sum();
      expect_closing("'('");
      return inner;
    }
    fail(position_, "expected a number, a name or '(', found " + describe_next());
  }

  int parse_number() {
    const std::size_t start = position_;
    while (!at_end() && is_digit(text_[position_])) {
      ++position_;
    }
    bool has_digits = position_ > start;
    if (!at_end() && text_[position_] == '.') {
      ++position_;
      const std::size_t fraction = position_;
      while (!at_end() && is_digit(text_[position_])) {
        ++position_;
      }
      has_digits = has_digits || position_ > fraction;
    }
    if (!has_digits) {
      fail(start, "expected a number, a name or '(', found '.'");
    }
    if (!at_end() && (text_[position_] == 'e' || text_[position_] == 'E')) {
      ++position_;
      if (!at_end() && (text_[position_] == '+' || text_[position_] == '-')) {
        ++position_;
      }
      const std::size_t exponent = position_;
      while (!at_end() && is_digit(text_[position_])) {
        ++position_;
      }
      if (position_ == exponent) {
        fail(start, "malformed number '" + std::string(text_.substr(start, position_ - start)) +
                        "': expected digits after the exponent");
      }
    }
    const std::string_view digits = text_.substr(start, position_ - start);
    double value = 0.0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (error == std::errc::result_out_of_range || !std::isfinite(value)) {
      fail(start, "number '" + std::string(digits) + "' is out of the range of a double");
    }
    TESSERA_ASSERT(error == std::errc() && end == digits.data() + digits.size());
    return emit_constant(value);
  }

  int parse_name() {
    const std::size_t start = position_;
    while (!at_end() && is_name_char(text_[position_])) {
      ++position_;
    }
    const std::string name(text_.substr(start, position_ - start));
    const bool is_variable =
        std::find(variables_.begin(), variables_.end(), name) != variables_.end();
    const bool is_parameter = parameters_.count(name) > 0;
    skip_spaces();
    if (!at_end() && text_[position_] == '(') {
      const auto& functions = function_names();
      const auto found = std::find(functions.begin(), functions.end(), name);
      if (found == functions.end()) {
        if (is_variable || is_parameter) {
          fail(start, "'" + name + "' is a " + (is_variable ? "variable" : "parameter") +
                          ", not a function (implicit multiplication is not supported: write " +
                          name + "*(…))");
        }
        fail(start, "unknown function '" + name + "' (functions: " + join_words(functions) + ")" +
                        hint_for_unknown_function(name));
      }
      const auto operation = static_cast<Operation>(static_cast<int>(Operation::Exp) +
                                                    static_cast<int>(found - functions.begin()));
      ++position_;
      const int argument = parse_sum();
      expect_closing("'" + name + "('");
      return emit_unary(operation, argument);
    }
    if (is_variable) {
      const auto index = std::find(variables_.begin(), variables_.end(), name) - variables_.begin();
      return emit({Operation::Variable, static_cast<int>(index), -1, 0.0});
    }
    if (is_parameter) {
      return emit_constant(parameters_.at(name));
    }
    if (name == "pi") {
      return emit_constant(std::numbers::pi);
    }
    const auto& functions = function_names();
    if (std::find(functions.begin(), functions.end(), name) != functions.end()) {
      fail(start,
           "function '" + name + "' needs its argument in parentheses, e.g. " + name + "(x)");
    }
    fail(start, "unknown name '" + name + "' (" + known_names() + ")" +
                    (name == "e" ? "; for Euler's number write exp(1)" : ""));
  }

  void expect_closing(const std::string& opener) {
    skip_spaces();
    if (at_end() || text_[position_] != ')') {
      // No column for the opener: inside a problem file it would be the wrong column, and
      // the caret already shows where the ')' is missing.
      fail(position_, "missing ')' to close " + opener + ", found " + describe_next());
    }
    ++position_;
  }

  std::string known_names() const {
    std::vector<std::string> parameter_names;
    for (const auto& [name, value] : parameters_) {
      parameter_names.push_back(name);
    }
    std::string known;
    if (!variables_.empty()) {
      known = "variables: " + join_words(variables_);
    }
    if (!parameter_names.empty()) {
      known += (known.empty() ? "" : "; ") + std::string("parameters: ") + join_words(parameter_names);
    }
    return known.empty() ? "no variables or parameters are defined" : known;
  }

  int emit(const Instruction& instruction) {
    tape_.push_back(instruction);
    return static_cast<int>(tape_.size()) - 1;
  }
  int emit_constant(double value) { return emit({Operation::Constant, -1, -1, value}); }

  // Constant folding relies on postfix order: a constant operand is a single instruction, so
  // when both operands are constants they are the last two instructions on the tape.
  int emit_binary(Operation operation, int left, int right) {
    const bool left_constant = tape_[left].operation == Operation::Constant;
    const bool right_constant = tape_[right].operation == Operation::Constant;
    if (left_constant && right_constant) {
      TESSERA_ASSERT(right == static_cast<int>(tape_.size()) - 1 && left == right - 1);
      const double value = apply(operation, tape_[left].constant, tape_[right].constant);
      tape_.resize(tape_.size() - 2);
      return emit_constant(value);
    }
    if (operation == Operation::Power && right_constant) {
      // x^p with p fixed: the derivative p x^(p-1) needs no log(x), which would be NaN for x < 0.
      TESSERA_ASSERT(right == static_cast<int>(tape_.size()) - 1);
      const double exponent = tape_[right].constant;
      tape_.pop_back();
      return emit({Operation::PowerConstant, left, -1, exponent});
    }
    return emit({operation, left, right, 0.0});
  }

  int emit_unary(Operation operation, int argument) {
    if (tape_[argument].operation == Operation::Constant) {
      tape_[argument].constant = apply(operation, tape_[argument].constant, 0.0);
      return argument;
    }
    return emit({operation, argument, -1, 0.0});
  }

  void skip_spaces() {
    while (!at_end() && (text_[position_] == ' ' || text_[position_] == '\t')) {
      ++position_;
    }
  }
  bool at_end() const { return position_ >= text_.size(); }

  std::string describe_next() const {
    if (at_end()) {
      return "the end of the expression";
    }
    std::size_t end = position_ + 1;
    if (is_name_start(text_[position_])) {
      while (end < text_.size() && is_name_char(text_[end])) {
        ++end;
      }
    } else if (is_digit(text_[position_])) {
      while (end < text_.size() && (is_digit(text_[end]) || text_[end] == '.')) {
        ++end;
      }
    }
    return "'" + std::string(text_.substr(position_, end - position_)) + "'";
  }

  [[noreturn]] void fail(std::size_t position, const std::string& reason) const {
    throw ExpressionSyntaxError(std::string(text_), static_cast<int>(position) + 1, reason);
  }

  static constexpr int max_depth = 200;
  std::string_view text_;
  std::size_t position_ = 0;
  int depth_ = 0;
  const std::vector<std::string>& variables_;
  const std::map<std::string, double>& parameters_;
  std::vector<Instruction>& tape_;
};

Expression::Expression(std::string_view text, std::vector<std::string> variable_names,
                       const std::map<std::string, double>& parameters)
    : text_(text), variable_names_(std::move(variable_names)) {
  std::string why;
  for (std::size_t i = 0; i < variable_names_.size(); ++i) {
    TESSERA_CHECK(is_valid_name(variable_names_[i], &why), "variable " << i << ": " << why);
    TESSERA_CHECK(std::find(variable_names_.begin() + static_cast<std::ptrdiff_t>(i) + 1,
                            variable_names_.end(), variable_names_[i]) == variable_names_.end(),
                  "variable '" << variable_names_[i] << "' is declared twice");
  }
  for (const auto& [name, value] : parameters) {
    TESSERA_CHECK(is_valid_name(name, &why), "parameter: " << why);
    TESSERA_CHECK(std::isfinite(value),
                  "parameter " << name << " = " << value << " must be finite");
    TESSERA_CHECK(
        std::find(variable_names_.begin(), variable_names_.end(), name) == variable_names_.end(),
        "'" << name << "' is both a variable and a parameter");
  }
  Parser(text_, variable_names_, parameters, tape_).parse();
}

}  // namespace tessera
