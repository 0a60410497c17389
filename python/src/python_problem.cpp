// SPDX-License-Identifier: MIT
#include "python_problem.h"

#include <pybind11/numpy.h>

#include "tessera/core/error.h"

namespace tessera::python {

namespace {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using DenseArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
using IndexArray = py::array_t<int, py::array::c_style | py::array::forcecast>;

// A fresh NumPy copy of x: the callable may keep it, and x's memory belongs to the solver.
py::array_t<double> to_numpy(const Eigen::Ref<const Eigen::VectorXd>& x) {
  py::array_t<double> array(x.size());
  std::copy(x.data(), x.data() + x.size(), array.mutable_data());
  return array;
}

std::string shape_of(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t i = 0; i < array.ndim(); ++i) {
    text += (i ? ", " : "") + std::to_string(array.shape(i));
  }
  return text + (array.ndim() == 1 ? ",)" : ")");
}

bool is_scipy_sparse(const py::handle& value) {
  return py::hasattr(value, "tocsc") && py::hasattr(value, "nnz");
}

}  // namespace

PythonProblem::PythonProblem(int n, py::object F, py::object J, bool has_sparse_jacobian,
                             std::string name, std::vector<std::string> coordinate_names,
                             std::vector<CoordinateBlock> blocks, std::optional<Dynamics> dynamics)
    : n_(n),
      F_(std::move(F)),
      J_(std::move(J)),
      has_sparse_jacobian_(has_sparse_jacobian),
      name_(std::move(name)),
      coordinate_names_(std::move(coordinate_names)),
      blocks_(std::move(blocks)),
      dynamics_(std::move(dynamics)) {
  TESSERA_CHECK(n_ >= 3, "Problem: n = " << n_ << " must be at least 3 (F maps R^n to R^(n-2))");
  TESSERA_CHECK(coordinate_names_.empty() || static_cast<int>(coordinate_names_.size()) == n_,
                "Problem: " << coordinate_names_.size() << " coordinate names for n = " << n_);
  if (dynamics_) {
    check_dynamics(*dynamics_, n_, name_);
  }
}

PythonProblem::~PythonProblem() {
  // The last reference may go from a thread that does not hold the GIL.
  py::gil_scoped_acquire gil;
  F_ = py::object();
  J_ = py::object();
}

std::vector<std::string> PythonProblem::coordinate_names() const {
  return coordinate_names_.empty() ? default_coordinate_names(n_) : coordinate_names_;
}

void PythonProblem::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                             Eigen::Ref<Eigen::VectorXd> F) const {
  py::gil_scoped_acquire gil;
  const py::object value = F_(to_numpy(x));
  const auto array = DenseArray::ensure(value);
  if (!array) {
    throw InvalidArgument("Problem.F(x) returned a " +
                          py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>() +
                          ", not an array of numbers");
  }
  TESSERA_CHECK(array.ndim() <= 1 && array.size() == n_ - 2,
                "Problem.F(x) returned shape " << shape_of(array) << ", expected (" << n_ - 2
                                               << ",) = (n-2,) for n = " << n_);
  std::copy(array.data(), array.data() + (n_ - 2), F.data());
}

py::object PythonProblem::call_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  py::object value = J_(to_numpy(x));
  if (is_scipy_sparse(value)) {
    const auto shape = value.attr("shape").cast<std::pair<long, long>>();
    TESSERA_CHECK(shape.first == n_ - 2 && shape.second == n_,
                  "Problem.J(x) returned a sparse matrix of shape ("
                      << shape.first << ", " << shape.second << "), expected (" << n_ - 2 << ", "
                      << n_ << ") = (n-2, n)");
    return value;
  }
  auto array = DenseArray::ensure(value);
  if (!array) {
    throw InvalidArgument("Problem.J(x) returned a " +
                          py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>() +
                          ", not an array of numbers or a scipy.sparse matrix");
  }
  const bool is_gradient = n_ == 3 && array.ndim() == 1 && array.size() == 3;
  TESSERA_CHECK(is_gradient || (array.ndim() == 2 && array.shape(0) == n_ - 2 &&
                                array.shape(1) == n_),
                "Problem.J(x) returned shape " << shape_of(array) << ", expected (" << n_ - 2
                                               << ", " << n_ << ") = (n-2, n)");
  return array;
}

void PythonProblem::jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                             Eigen::Ref<Eigen::MatrixXd> J) const {
  py::gil_scoped_acquire gil;
  py::object value = call_jacobian(x);
  if (is_scipy_sparse(value)) {
    value = value.attr("toarray")();
  }
  const auto array = DenseArray::ensure(value);
  J = Eigen::Map<const RowMajorMatrix>(array.data(), n_ - 2, n_);
}

void PythonProblem::sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                                    Eigen::SparseMatrix<double>& J) const {
  py::gil_scoped_acquire gil;
  const py::object value = call_jacobian(x);
  if (!is_scipy_sparse(value)) {
    const auto array = DenseArray::ensure(value);
    J = Eigen::Map<const RowMajorMatrix>(array.data(), n_ - 2, n_).sparseView();
    return;
  }
  // Compressed columns with sorted, unique row indices: the layout of Eigen's SparseMatrix, so
  // the arrays are read in place; tocsc() of a CSC matrix is the caller's own object, which a
  // canonicalisation must not change.
  py::object csc = value.attr("tocsc")();
  if (!csc.attr("has_canonical_format").cast<bool>()) {
    csc = csc.attr("copy")();
    csc.attr("sum_duplicates")();
  }
  const auto column_starts = IndexArray::ensure(csc.attr("indptr"));
  const auto row_indices = IndexArray::ensure(csc.attr("indices"));
  const auto values = DenseArray::ensure(csc.attr("data"));
  TESSERA_ASSERT(column_starts && row_indices && values && column_starts.size() == n_ + 1);
  const int nonzeros = column_starts.data()[n_];
  J = Eigen::Map<const Eigen::SparseMatrix<double>>(n_ - 2, n_, nonzeros, column_starts.data(),
                                                    row_indices.data(), values.data());
}

}  // namespace tessera::python
