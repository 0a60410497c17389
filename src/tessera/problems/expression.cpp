// SPDX-License-Identifier: MIT
// Evaluation of Expression: the forward sweep for values, the reverse sweep for gradients.
#include "tessera/problems/expression.h"

#include <algorithm>
#include <cmath>

namespace tessera {

double Expression::apply(Operation operation, double a, double b) {
  switch (operation) {
    case Operation::Add:
      return a + b;
    case Operation::Subtract:
      return a - b;
    case Operation::Multiply:
      return a * b;
    case Operation::Divide:
      return a / b;
    case Operation::Power:
      return std::pow(a, b);
    case Operation::Negate:
      return -a;
    case Operation::Exp:
      return std::exp(a);
    case Operation::Log:
      return std::log(a);
    case Operation::Sqrt:
      return std::sqrt(a);
    case Operation::Sin:
      return std::sin(a);
    case Operation::Cos:
      return std::cos(a);
    case Operation::Tan:
      return std::tan(a);
    case Operation::Tanh:
      return std::tanh(a);
    case Operation::Sinh:
      return std::sinh(a);
    case Operation::Cosh:
      return std::cosh(a);
    case Operation::Atan:
      return std::atan(a);
    case Operation::Asin:
      return std::asin(a);
    case Operation::Acos:
      return std::acos(a);
    case Operation::Abs:
      return std::abs(a);
    case Operation::Constant:
    case Operation::Variable:
    case Operation::PowerConstant:
      break;
  }
  TESSERA_ASSERT(false && "apply() called for an operation without a fixed arity");
  return 0.0;
}

void Expression::forward_sweep(const Eigen::Ref<const Eigen::VectorXd>& x,
                               ExpressionWorkspace& workspace) const {
  TESSERA_CHECK(x.size() == variable_count(), "expression '"
                                                  << text_ << "' has " << variable_count()
                                                  << " variables, x has size " << x.size());
  if (workspace.values.size() < tape_.size()) {
    workspace.values.resize(tape_.size());
  }
  double* values = workspace.values.data();
  for (std::size_t i = 0; i < tape_.size(); ++i) {
    const Instruction& instruction = tape_[i];
    switch (instruction.operation) {
      case Operation::Constant:
        values[i] = instruction.constant;
        break;
      case Operation::Variable:
        values[i] = x(instruction.first);
        break;
      case Operation::PowerConstant: {
        const double base = values[instruction.first];
        values[i] =
            instruction.constant == 2.0 ? base * base : std::pow(base, instruction.constant);
        break;
      }
      default:
        values[i] = apply(instruction.operation, values[instruction.first],
                          instruction.second >= 0 ? values[instruction.second] : 0.0);
    }
  }
}

double Expression::value(const Eigen::Ref<const Eigen::VectorXd>& x,
                         ExpressionWorkspace& workspace) const {
  forward_sweep(x, workspace);
  return workspace.values[tape_.size() - 1];
}

double Expression::value(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  ExpressionWorkspace workspace;
  return value(x, workspace);
}

double Expression::value_and_gradient(const Eigen::Ref<const Eigen::VectorXd>& x,
                                      Eigen::Ref<Eigen::VectorXd> gradient,
                                      ExpressionWorkspace& workspace) const {
  TESSERA_CHECK(gradient.size() == variable_count(), "expression '" << text_ << "' has "
                                                                    << variable_count()
                                                                    << " variables, gradient has "
                                                                       "size "
                                                                    << gradient.size());
  forward_sweep(x, workspace);
  const std::size_t length = tape_.size();
  if (workspace.adjoints.size() < length) {
    workspace.adjoints.resize(length);
  }
  const double* v = workspace.values.data();
  double* adjoint = workspace.adjoints.data();
  std::fill(adjoint, adjoint + length, 0.0);
  adjoint[length - 1] = 1.0;
  gradient.setZero();
  // Reverse sweep: adjoint[i] = ∂f/∂v[i] is complete when instruction i is reached, because
  // every use of v[i] comes later on the tape.
  for (std::size_t i = length; i-- > 0;) {
    const double g = adjoint[i];
    if (g == 0.0) {
      continue;  // also keeps 0·inf = NaN of an irrelevant branch out of the gradient
    }
    const Instruction& instruction = tape_[i];
    const int a = instruction.first;
    const int b = instruction.second;
    switch (instruction.operation) {
      case Operation::Constant:
        break;
      case Operation::Variable:
        gradient(a) += g;
        break;
      case Operation::Add:
        adjoint[a] += g;
        adjoint[b] += g;
        break;
      case Operation::Subtract:
        adjoint[a] += g;
        adjoint[b] -= g;
        break;
      case Operation::Multiply:
        adjoint[a] += g * v[b];
        adjoint[b] += g * v[a];
        break;
      case Operation::Divide:
        adjoint[a] += g / v[b];
        adjoint[b] -= g * v[i] / v[b];
        break;
      case Operation::Power:
        adjoint[a] += g * v[b] * std::pow(v[a], v[b] - 1.0);
        // d(a^b)/db = a^b log a; its limit is 0 where a^b = 0 (a = 0, b > 0), not 0·(−inf).
        adjoint[b] += v[i] == 0.0 ? 0.0 : g * v[i] * std::log(v[a]);
        break;
      case Operation::PowerConstant: {
        const double p = instruction.constant;
        adjoint[a] += p == 0.0 ? 0.0 : g * p * (p == 2.0 ? v[a] : std::pow(v[a], p - 1.0));
        break;
      }
      case Operation::Negate:
        adjoint[a] -= g;
        break;
      case Operation::Exp:
        adjoint[a] += g * v[i];
        break;
      case Operation::Log:
        adjoint[a] += g / v[a];
        break;
      case Operation::Sqrt:
        adjoint[a] += g * 0.5 / v[i];
        break;
      case Operation::Sin:
        adjoint[a] += g * std::cos(v[a]);
        break;
      case Operation::Cos:
        adjoint[a] -= g * std::sin(v[a]);
        break;
      case Operation::Tan:
        adjoint[a] += g * (1.0 + v[i] * v[i]);
        break;
      case Operation::Tanh:
        adjoint[a] += g * (1.0 - v[i] * v[i]);
        break;
      case Operation::Sinh:
        adjoint[a] += g * std::cosh(v[a]);
        break;
      case Operation::Cosh:
        adjoint[a] += g * std::sinh(v[a]);
        break;
      case Operation::Atan:
        adjoint[a] += g / (1.0 + v[a] * v[a]);
        break;
      case Operation::Asin:
        adjoint[a] += g / std::sqrt(1.0 - v[a] * v[a]);
        break;
      case Operation::Acos:
        adjoint[a] -= g / std::sqrt(1.0 - v[a] * v[a]);
        break;
      case Operation::Abs:
        adjoint[a] += v[a] > 0.0 ? g : (v[a] < 0.0 ? -g : 0.0);
        break;
    }
  }
  return v[length - 1];
}

double Expression::value_and_gradient(const Eigen::Ref<const Eigen::VectorXd>& x,
                                      Eigen::Ref<Eigen::VectorXd> gradient) const {
  ExpressionWorkspace workspace;
  return value_and_gradient(x, gradient, workspace);
}

bool Expression::depends_on(int index) const {
  return std::any_of(tape_.begin(), tape_.end(), [index](const Instruction& instruction) {
    return instruction.operation == Operation::Variable && instruction.first == index;
  });
}

}  // namespace tessera
