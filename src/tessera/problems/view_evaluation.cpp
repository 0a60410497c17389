// SPDX-License-Identifier: MIT
// A View's functionals evaluated at points (one point, or many at once, on one process or on a
// split mesh); view.cpp reads the specifications that make them.
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "tessera/core/describe.h"
#include "tessera/problems/view.h"

namespace tessera {
namespace {

using Kind = ViewFunctionalKind;

// Whether a split mesh's values of this kind come from a maximum over the ranks (else a sum).
bool is_reduced_by_maximum(Kind kind) {
  return kind == Kind::BlockMaximum || kind == Kind::BlockMinimum ||
         kind == Kind::BlockAbsMaximum;
}

}  // namespace

View::View(int ambient_dimension, std::vector<ViewFunctional> functionals,
           Eigen::VectorXd metric_weights)
    : ambient_dimension_(ambient_dimension),
      functionals_(std::move(functionals)),
      weights_(std::move(metric_weights)) {
  TESSERA_CHECK(ambient_dimension_ >= 1,
                "View: ambient dimension " << ambient_dimension_ << " must be >= 1");
  TESSERA_CHECK(weights_.size() == 0 || weights_.size() == ambient_dimension_,
                "View: " << weights_.size() << " metric weights for n = " << ambient_dimension_);
  for (const ViewFunctional& f : functionals_) {
    TESSERA_CHECK(f.first >= 0 && f.size >= 1 && f.first <= ambient_dimension_ - f.size,
                  "View: functional '" << f.label << "' covers coordinates " << f.first << " … "
                                       << f.first + f.size - 1 << ", outside 0 … "
                                       << ambient_dimension_ - 1);
    TESSERA_CHECK(f.kind != Kind::Expression ||
                      (f.expression &&
                       f.expression->variable_count() == static_cast<int>(f.variables.size())),
                  "View: expression functional '" << f.label << "' needs an expression with one "
                                                  << "variable per index in `variables`");
    for (const int i : f.variables) {
      TESSERA_CHECK(i >= 0 && i < ambient_dimension_,
                    "View: functional '" << f.label << "' uses coordinate " << i << ", outside 0 … "
                                         << ambient_dimension_ - 1);
    }
  }
}

std::vector<std::string> View::names() const {
  std::vector<std::string> names;
  names.reserve(functionals_.size());
  for (const ViewFunctional& functional : functionals_) {
    names.push_back(functional.name);
  }
  return names;
}

std::string View::specification() const {
  if (is_all_coordinates()) {
    return "all";
  }
  std::vector<std::string> labels;
  for (const ViewFunctional& functional : functionals_) {
    labels.push_back(functional.label);
  }
  return join_words(labels);
}

bool View::is_all_coordinates() const {
  if (size() != ambient_dimension_) {
    return false;
  }
  for (int i = 0; i < size(); ++i) {
    const ViewFunctional& functional = functionals_[static_cast<std::size_t>(i)];
    if (functional.kind != Kind::Coordinate || functional.first != i) {
      return false;
    }
  }
  return true;
}

void View::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> values,
                    ViewWorkspace& workspace) const {
  TESSERA_CHECK(x.size() == ambient_dimension_ && values.size() == size(),
                "View::evaluate: x has " << x.size() << " entries (n = " << ambient_dimension_
                                         << "), values " << values.size() << " (k = " << size()
                                         << ")");
  for (int i = 0; i < size(); ++i) {
    const ViewFunctional& f = functionals_[static_cast<std::size_t>(i)];
    const auto block = x.segment(f.first, f.size);
    double value = 0.0;
    switch (f.kind) {
      case Kind::Coordinate:
        value = x(f.first);
        break;
      case Kind::BlockMaximum:
        value = block.maxCoeff();
        break;
      case Kind::BlockMinimum:
        value = block.minCoeff();
        break;
      case Kind::BlockMean:
        value = block.mean();
        break;
      case Kind::BlockAbsMaximum:
        value = block.cwiseAbs().maxCoeff();
        break;
      case Kind::BlockNorm:
        value = f.weight * block.norm();
        break;
      case Kind::Norm: {
        double sum = 0.0;
        for (Eigen::Index j = 0; j < x.size(); ++j) {
          const double w = weights_.size() == 0 ? 1.0 : weights_(j);
          sum += (w * x(j)) * (w * x(j));
        }
        value = std::sqrt(sum);
        break;
      }
      case Kind::Expression: {
        workspace.arguments.resize(static_cast<Eigen::Index>(f.variables.size()));
        for (std::size_t j = 0; j < f.variables.size(); ++j) {
          workspace.arguments(static_cast<Eigen::Index>(j)) = x(f.variables[j]);
        }
        value = f.expression->value(workspace.arguments, workspace.expression);
        break;
      }
    }
    values(i) = value;
  }
}

Eigen::VectorXd View::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  Eigen::VectorXd values(size());
  ViewWorkspace workspace;
  evaluate(x, values, workspace);
  return values;
}

Eigen::MatrixXd View::evaluate_columns(const Eigen::Ref<const Eigen::MatrixXd>& points) const {
  TESSERA_CHECK(points.rows() == ambient_dimension_,
                "View::evaluate_columns: points have " << points.rows() << " rows, the view takes "
                                                       << "points of R^" << ambient_dimension_);
  Eigen::MatrixXd values(size(), points.cols());
  ViewWorkspace workspace;
  for (Eigen::Index j = 0; j < points.cols(); ++j) {
    evaluate(points.col(j), values.col(j), workspace);
  }
  return values;
}

Eigen::MatrixXd View::evaluate_columns(const Eigen::Ref<const Eigen::MatrixXd>& points,
                                       const AmbientSpace& space) const {
  if (!space.is_distributed()) {
    return evaluate_columns(points);
  }
  TESSERA_CHECK(space.dimension() == ambient_dimension_ && points.rows() == space.local_rows(),
                "View::evaluate_columns: points of R^" << space.dimension() << " ("
                    << points.rows() << " rows here, " << space.local_rows()
                    << " expected), the view takes points of R^" << ambient_dimension_);
  // Each functional's partial values go to slots of a sum or of a maximum: slot[i] is the
  // first of functional i's, in the table its kind reduces in.
  int sum_slots = 0;
  int maximum_slots = 0;
  std::vector<int> slot(functionals_.size());
  for (std::size_t i = 0; i < functionals_.size(); ++i) {
    const ViewFunctional& f = functionals_[i];
    if (is_reduced_by_maximum(f.kind)) {
      slot[i] = maximum_slots++;
    } else {
      slot[i] = sum_slots;
      sum_slots += f.kind == Kind::Expression ? static_cast<int>(f.variables.size()) : 1;
    }
  }
  const int first_row = space.first_row();
  const int local_rows = space.local_rows();
  // This rank's part [begin, end) of coordinates [first, first + size), in local rows.
  const auto local_part = [&](int first, int size) {
    const int begin = std::max(first, first_row) - first_row;
    const int end = std::min(first + size, first_row + local_rows) - first_row;
    return std::pair<int, int>(begin, std::max(begin, end));
  };
  // −0.0 is the identity of the sum (DistributedSpace::sum), −∞ that of the maximum: a rank
  // holding none of a block changes nothing, and a coordinate comes back bit for bit.
  constexpr double kNoSum = -0.0;
  constexpr double kNoMaximum = -std::numeric_limits<double>::infinity();
  // Writes f's partial values of x (this rank's rows) to `out`, its slots.
  const auto partial_value = [&](const ViewFunctional& f, const auto& x, double* out) {
    const auto [begin, end] = local_part(f.first, f.size);
    const auto part = x.segment(begin, end - begin);
    const bool is_empty = end == begin;
    switch (f.kind) {
      case Kind::Coordinate:
        *out = space.holds_row(f.first) ? x(f.first - first_row) : kNoSum;
        break;
      case Kind::BlockMaximum:
        *out = is_empty ? kNoMaximum : part.maxCoeff();
        break;
      case Kind::BlockMinimum:  // min = −max(−x): negation is exact
        *out = is_empty ? kNoMaximum : -part.minCoeff();
        break;
      case Kind::BlockAbsMaximum:
        *out = is_empty ? kNoMaximum : part.cwiseAbs().maxCoeff();
        break;
      case Kind::BlockMean:
        *out = is_empty ? kNoSum : part.sum();
        break;
      case Kind::BlockNorm:
        *out = is_empty ? kNoSum : part.squaredNorm();
        break;
      case Kind::Norm: {
        double sum = 0.0;
        for (int j = 0; j < local_rows; ++j) {
          const double w = weights_.size() == 0 ? 1.0 : weights_(first_row + j);
          sum += (w * x(j)) * (w * x(j));
        }
        *out = local_rows == 0 ? kNoSum : sum;
        break;
      }
      case Kind::Expression:
        for (std::size_t v = 0; v < f.variables.size(); ++v) {
          const int i = f.variables[v];
          out[v] = space.holds_row(i) ? x(i - first_row) : kNoSum;
        }
        break;
    }
  };
  const auto count = points.cols();
  Eigen::MatrixXd values(size(), count);
  // Bounded reductions: DistributedSpace::sum gathers every rank's values on every rank.
  constexpr Eigen::Index kValuesPerReduction = Eigen::Index{1} << 15;
  const Eigen::Index columns_per_reduction =
      std::max<Eigen::Index>(1, kValuesPerReduction / std::max(1, std::max(sum_slots,
                                                                           maximum_slots)));
  Eigen::MatrixXd sums(sum_slots, std::min(count, columns_per_reduction));
  Eigen::MatrixXd maxima(maximum_slots, std::min(count, columns_per_reduction));
  ViewWorkspace workspace;
  for (Eigen::Index begin = 0; begin < count; begin += columns_per_reduction) {
    const Eigen::Index columns = std::min(columns_per_reduction, count - begin);
    for (Eigen::Index j = 0; j < columns; ++j) {
      const auto x = points.col(begin + j);
      for (std::size_t i = 0; i < functionals_.size(); ++i) {
        const ViewFunctional& f = functionals_[i];
        Eigen::MatrixXd& table = is_reduced_by_maximum(f.kind) ? maxima : sums;
        partial_value(f, x, table.col(j).data() + slot[i]);
      }
    }
    if (sum_slots > 0) {
      space.sum(sums.data(), static_cast<int>(sum_slots * columns));
    }
    if (maximum_slots > 0) {
      space.maximum(maxima.data(), static_cast<int>(maximum_slots * columns));
    }
    for (Eigen::Index j = 0; j < columns; ++j) {
      for (std::size_t i = 0; i < functionals_.size(); ++i) {
        const ViewFunctional& f = functionals_[i];
        const double total =
            is_reduced_by_maximum(f.kind) ? maxima(slot[i], j) : sums(slot[i], j);
        double value = total;
        switch (f.kind) {
          case Kind::BlockMinimum:
            value = -total;
            break;
          case Kind::BlockMean:
            value = total / static_cast<double>(f.size);
            break;
          case Kind::BlockNorm:
            value = f.weight * std::sqrt(total);
            break;
          case Kind::Norm:
            value = std::sqrt(total);
            break;
          case Kind::Expression:
            workspace.arguments =
                sums.col(j).segment(slot[i], static_cast<Eigen::Index>(f.variables.size()));
            value = f.expression->value(workspace.arguments, workspace.expression);
            break;
          default:
            break;
        }
        values(static_cast<Eigen::Index>(i), begin + j) = value;
      }
    }
  }
  return values;
}

}  // namespace tessera
