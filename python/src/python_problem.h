// SPDX-License-Identifier: MIT
// ImplicitProblems for the bindings: one whose F and J are Python callables (NumPy arrays or
// SciPy sparse matrices), and one that forwards to a shared problem so that every run can own
// its own ProblemSetup (start and box may differ per run) while the problem is made once.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tessera/core/implicit_problem.h"

namespace tessera::python {

namespace py = pybind11;

/// F and J written in Python. Every evaluation takes the GIL (the run itself holds it not), so a
/// Python problem runs through the same solvers as a C++ one at the cost of one Python call per
/// evaluation (bench/RESULTS.md, "Python callbacks"). A Python exception raised by F or J
/// propagates out of the run as that exception.
class PythonProblem final : public ImplicitProblem {
 public:
  /// \param F  x ↦ F(x): an (n−2)-vector (any array-like of n−2 numbers; a number for n = 3).
  /// \param J  x ↦ DF(x): an (n−2)×n array-like, or a scipy.sparse matrix of that shape; for
  ///           n = 3 an n-vector (the gradient) is accepted too.
  /// \param has_sparse_jacobian  true: the solvers ask for J as a sparse matrix (dense results
  ///           are converted), false: as a dense one (sparse results are densified).
  /// \param dynamics  what F is the right-hand side of (tessera.Dynamics); none: nothing.
  /// \throw InvalidArgument for n < 3, names of the wrong count or invalid dynamics.
  PythonProblem(int n, py::object F, py::object J, bool has_sparse_jacobian, std::string name,
                std::vector<std::string> coordinate_names, std::vector<CoordinateBlock> blocks,
                std::optional<Dynamics> dynamics);
  ~PythonProblem() override;

  int ambient_dimension() const override { return n_; }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override;
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override;
  bool has_sparse_jacobian() const override { return has_sparse_jacobian_; }
  void sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                       Eigen::SparseMatrix<double>& J) const override;
  std::string name() const override { return name_; }
  std::vector<std::string> coordinate_names() const override;
  std::vector<CoordinateBlock> coordinate_blocks() const override { return blocks_; }
  std::optional<Dynamics> dynamics() const override { return dynamics_; }

 private:
  // Calls J(x) with the GIL held; the result is a dense array or a scipy.sparse matrix.
  py::object call_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x) const;

  int n_;
  py::object F_;
  py::object J_;
  bool has_sparse_jacobian_;
  std::string name_;
  std::vector<std::string> coordinate_names_;
  std::vector<CoordinateBlock> blocks_;
  std::optional<Dynamics> dynamics_;
};

/// Forwards every call to a shared problem (ProblemSetup owns its problem; a Python Problem is
/// meshed many times).
class SharedProblem final : public ImplicitProblem {
 public:
  explicit SharedProblem(std::shared_ptr<const ImplicitProblem> problem)
      : problem_(std::move(problem)) {}
  int ambient_dimension() const override { return problem_->ambient_dimension(); }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override {
    problem_->evaluate(x, F);
  }
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override {
    problem_->jacobian(x, J);
  }
  bool has_sparse_jacobian() const override { return problem_->has_sparse_jacobian(); }
  void sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                       Eigen::SparseMatrix<double>& J) const override {
    problem_->sparse_jacobian(x, J);
  }
  std::string name() const override { return problem_->name(); }
  bool is_thread_safe() const override { return problem_->is_thread_safe(); }
  std::vector<std::string> coordinate_names() const override {
    return problem_->coordinate_names();
  }
  std::vector<CoordinateBlock> coordinate_blocks() const override {
    return problem_->coordinate_blocks();
  }
  std::optional<Dynamics> dynamics() const override { return problem_->dynamics(); }

 private:
  std::shared_ptr<const ImplicitProblem> problem_;
};

}  // namespace tessera::python
