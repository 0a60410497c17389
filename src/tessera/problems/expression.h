// SPDX-License-Identifier: MIT
// A small expression language for users who do not write C++: f(x1, …, xn) with an exact gradient.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/core/error.h"

namespace tessera {

/// A syntax error in an expression. Derives from InvalidArgument, so callers that only want a
/// message can catch that; callers that embed expressions in a larger text (problem files) use
/// `column()` and `reason()` to point at the right place in their own source.
class ExpressionSyntaxError : public InvalidArgument {
 public:
  ExpressionSyntaxError(const std::string& text, int column, std::string reason);
  /// 1-based column in the expression text (text length + 1 for "at end of expression").
  int column() const { return column_; }
  /// What was expected and what was found, e.g. "unknown function 'expp' (functions: exp, …)".
  const std::string& reason() const { return reason_; }

 private:
  int column_;
  std::string reason_;
};

/// Scratch memory for evaluating expressions; reusing one keeps evaluation free of allocations.
/// One workspace may serve any number of expressions, but one thread at a time.
struct ExpressionWorkspace {
  std::vector<double> values;    ///< value of each tape instruction, filled by the forward sweep
  std::vector<double> adjoints;  ///< ∂f/∂(value of instruction), filled by the reverse sweep
};

/// A real-valued expression f(x) of named variables x = (x1, …, xn), parsed once into a tape and
/// evaluated many times, with its exact gradient by reverse-mode automatic differentiation.
///
/// Grammar (docs/problem-files.md has the user's version):
///
///     sum     := product (('+' | '-') product)*
///     product := unary (('*' | '/') unary)*
///     unary   := ('-' | '+') unary | power
///     power   := primary ('^' unary)?          right-associative; -x^2 = -(x^2), 2^-1 = 0.5
///     primary := number | name | function '(' sum ')' | '(' sum ')'
///
/// Numbers are decimal with an optional exponent (2, 0.5, .5, 1e-3, 2.5E+2). A name is a
/// variable, a parameter (a named constant fixed at parse time) or `pi`. Functions: exp, log
/// (natural), sqrt, sin, cos, tan, tanh, sinh, cosh, atan, asin, acos, abs. The derivative of
/// abs is taken as sign(x), 0 at x = 0.
///
/// The tape is a postfix (Wengert) list: each instruction refers to its operands by index, and
/// operands come first. Sub-expressions that depend only on numbers and parameters are folded
/// into one constant at parse time, so `r^2` costs nothing per evaluation.
///
/// Outside the mathematical domain (log of a negative number, 0/0) the value is NaN or ±inf as
/// in IEEE arithmetic; no exception is thrown. ImplicitProblem treats that as "outside F's domain".
class Expression {
 public:
  /// Parses `text` as a function of `variable_names` (in this order: x(0) is the first name).
  /// \param parameters  named constants the text may use; their values are fixed now.
  /// \pre  names are identifiers ([A-Za-z_][A-Za-z0-9_]*), distinct, and neither a function name
  ///       nor `pi`; no name is both a variable and a parameter; parameter values are finite.
  /// \throw ExpressionSyntaxError (an InvalidArgument) for a syntax error, naming the column,
  ///        what was expected and what was found.
  /// \throw InvalidArgument if a precondition on the names fails.
  Expression(std::string_view text, std::vector<std::string> variable_names,
             const std::map<std::string, double>& parameters = {});

  /// f(x). \pre x.size() == variable_count(). Allocates only if `workspace` is too small.
  double value(const Eigen::Ref<const Eigen::VectorXd>& x, ExpressionWorkspace& workspace) const;
  /// f(x), convenient form (allocates its scratch).
  double value(const Eigen::Ref<const Eigen::VectorXd>& x) const;

  /// f(x), and ∇f(x) written to `gradient` (exact up to rounding, no finite differences).
  /// \pre x.size() == gradient.size() == variable_count().
  /// Allocates only if `workspace` is too small.
  double value_and_gradient(const Eigen::Ref<const Eigen::VectorXd>& x,
                            Eigen::Ref<Eigen::VectorXd> gradient,
                            ExpressionWorkspace& workspace) const;
  /// f(x) and ∇f(x), convenient form (allocates its scratch).
  double value_and_gradient(const Eigen::Ref<const Eigen::VectorXd>& x,
                            Eigen::Ref<Eigen::VectorXd> gradient) const;

  /// True if variable `index` occurs in the folded tape (its partial derivative may be nonzero).
  /// Gives the sparsity pattern of a Jacobian built from expressions.
  bool depends_on(int index) const;

  int variable_count() const { return static_cast<int>(variable_names_.size()); }
  const std::vector<std::string>& variable_names() const { return variable_names_; }
  /// The source text as given.
  const std::string& text() const { return text_; }
  /// Number of instructions after constant folding (1 for a constant or a lone variable).
  int tape_length() const { return static_cast<int>(tape_.size()); }

  /// The function names the language knows, in a fixed order (for messages and documentation).
  static const std::vector<std::string>& function_names();
  /// True if `name` may name a variable or parameter: an identifier that is not reserved.
  /// \param why  if not null and the answer is false, receives the reason.
  static bool is_valid_name(const std::string& name, std::string* why = nullptr);

 private:
  // Exp … Abs are in the order of function_names(): the parser maps the function with index k
  // to Operation(Exp + k).
  enum class Operation : std::uint8_t {
    Constant,
    Variable,
    Add,
    Subtract,
    Multiply,
    Divide,
    Power,
    PowerConstant,
    Negate,
    Exp,
    Log,
    Sqrt,
    Sin,
    Cos,
    Tan,
    Tanh,
    Sinh,
    Cosh,
    Atan,
    Asin,
    Acos,
    Abs,
  };
  /// One tape entry. `first`/`second` index earlier instructions (operands); for Variable
  /// `first` is the variable index; `constant` holds the value of Constant or the exponent of
  /// PowerConstant.
  struct Instruction {
    Operation operation = Operation::Constant;
    int first = -1;
    int second = -1;
    double constant = 0.0;
  };
  class Parser;  // in expression_parser.cpp

  static double apply(Operation operation, double a, double b);
  void forward_sweep(const Eigen::Ref<const Eigen::VectorXd>& x,
                     ExpressionWorkspace& workspace) const;

  std::string text_;
  std::vector<std::string> variable_names_;
  std::vector<Instruction> tape_;
};

}  // namespace tessera
