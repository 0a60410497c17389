// SPDX-License-Identifier: MIT
#include "tessera/methods/folds/level_curves.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <sstream>

#include "tessera/core/error.h"
#include "tessera/core/linearization.h"
#include "tessera/core/metric_problem.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/methods/common/zero_set_curves.h"
#include "tessera/methods/folds/functional_gradient.h"

namespace tessera {

int LevelCurves::point_count() const {
  int count = 0;
  for (const LevelCurve& curve : curves) {
    count += static_cast<int>(curve.points.size());
  }
  return count;
}

std::string LevelSet::specification() const {
  std::ostringstream out;
  out.precision(17);
  out << functional.specification() << " = " << value;
  return out.str();
}

namespace {

std::string trimmed(const std::string& text) {
  std::size_t begin = 0;
  std::size_t end = text.size();
  while (begin < end && std::isspace(static_cast<unsigned char>(text[begin]))) {
    ++begin;
  }
  while (end > begin && std::isspace(static_cast<unsigned char>(text[end - 1]))) {
    --end;
  }
  return text.substr(begin, end - begin);
}

// A view item that is a plain name or a block functional ("x1", "max:u", "norm"), as opposed to
// an unnamed expression ("x^2 + y^2").
bool is_name_like(const std::string& item) {
  return std::all_of(item.begin(), item.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == ':' || c == ' ';
  });
}

}  // namespace

LevelSet parse_level_set(const std::string& specification, const ImplicitProblem& problem) {
  const std::size_t equals = specification.rfind('=');
  TESSERA_CHECK(equals != std::string::npos,
                "level set '" << specification
                              << "': no '='; write FUNCTIONAL=VALUE, e.g. x1=0.5 or mean:u=1.5");
  const std::string left = trimmed(specification.substr(0, equals));
  const std::string right = trimmed(specification.substr(equals + 1));
  TESSERA_CHECK(!left.empty(), "level set '" << specification
                                             << "': no functional before '='; write "
                                                "FUNCTIONAL=VALUE, e.g. x1=0.5");
  TESSERA_CHECK(!right.empty(), "level set '" << specification
                                              << "': no value after '='; write "
                                                 "FUNCTIONAL=VALUE, e.g. x1=0.5");
  char* end = nullptr;
  const double value = std::strtod(right.c_str(), &end);
  TESSERA_CHECK(end == right.c_str() + right.size(),
                "level set '" << specification << "': the value '" << right << "' is not a number");
  TESSERA_CHECK(std::isfinite(value),
                "level set '" << specification << "': the value '" << right << "' is not finite");
  LevelSet level;
  try {
    level.functional = parse_view(left, problem);
  } catch (const ViewSpecificationError&) {
    // "x^2 + y^2 = 1": an expression without a name is no view item; name it.
    if (left.find('=') != std::string::npos || is_name_like(left)) {
      throw;
    }
    try {
      level.functional = parse_view("level = " + left, problem);
    } catch (const ViewSpecificationError&) {
      parse_view(left, problem);  // the error of the functional as written
      throw;
    }
  }
  TESSERA_CHECK(level.functional.size() == 1,
                "level set '" << specification << "': '" << left << "' is "
                              << level.functional.size()
                              << " functionals; a level set needs one, e.g. x1=0.5");
  level.value = value;
  return level;
}

namespace {

// The level-set computation on the problem seen in its metric (ScaledProblem): lengths,
// tolerances and minimum-norm corrections are those of the metric, as for the covering and
// the fold curves.
class LevelSolver {
 public:
  LevelSolver(const ImplicitProblem& problem, const View& functional, double value,
              const LevelOptions& options)
      : functional_(functional),
        f_(functional.functionals().front()),
        value_(value),
        options_(options),
        metric_(problem),
        unit_weights_(metric_.weights().size() > 0
                          ? metric_.weights()
                          : Eigen::VectorXd(Eigen::VectorXd::Ones(problem.ambient_dimension()))) {
    values_.resize(1);
  }

  WorkCounts work() const { return metric_.work(); }
  Eigen::VectorXd to_metric(const Eigen::Ref<const Eigen::VectorXd>& x) const {
    return metric_.to_metric(x);
  }
  Eigen::VectorXd from_metric(const Eigen::Ref<const Eigen::VectorXd>& y) const {
    return metric_.from_metric(y);
  }

  // f(x) − c (NaN where f is not finite).
  double level(const Eigen::Ref<const Eigen::VectorXd>& x) {
    functional_.evaluate(x, values_, workspace_);
    return std::isfinite(values_(0)) ? values_(0) - value_
                                     : std::numeric_limits<double>::quiet_NaN();
  }

  struct Refined {
    bool converged = false;
    int iterations = 0;
    double residual = std::numeric_limits<double>::quiet_NaN();
    double level_residual = std::numeric_limits<double>::quiet_NaN();
  };

  // Newton from y on F = 0, f = c; for an extremum of a block, with the coordinate extremal at
  // the estimate held at c, retried (at most twice) with the one extremal at the converged point
  // if that differs.
  Refined refine(Eigen::VectorXd& y, double max_displacement) {
    const Eigen::VectorXd start = y;
    const bool is_extremum = !is_differentiable(f_.kind);
    int active = is_extremum ? extremal_coordinate(f_, from_metric(y)) : -1;
    Refined total;
    if (is_extremum && active < 0) {
      return total;  // every coordinate of the block is NaN
    }
    for (int attempt = 0; attempt < (is_extremum ? 3 : 1); ++attempt) {
      y = start;
      const Refined refined = newton(y, max_displacement, active);
      total.iterations += refined.iterations;
      total.residual = refined.residual;
      total.level_residual = refined.level_residual;
      total.converged = refined.converged;
      if (refined.converged || !is_extremum || !y.allFinite()) {
        break;
      }
      const int now_active = extremal_coordinate(f_, from_metric(y));
      if (now_active == active || now_active < 0) {
        break;
      }
      active = now_active;
    }
    return total;
  }

 private:
  Refined newton(Eigen::VectorXd& y, double max_displacement, int active) {
    Refined result;
    const Eigen::VectorXd start = y;
    const int n = static_cast<int>(y.size());
    Eigen::VectorXd F(metric_.counted().equation_count());
    Eigen::VectorXd gradient(n);
    Eigen::VectorXd dy_p(n);
    Eigen::MatrixXd reference;
    for (int iteration = 1; iteration <= options_.max_iterations; ++iteration) {
      result.iterations = iteration;
      if (!linearization_.factor(metric_.counted(), y, reference.size() > 0 ? &reference : nullptr)) {
        return result;
      }
      const Eigen::MatrixXd& T = linearization_.tangent_basis();
      reference = T;
      metric_.counted().evaluate(y, F);
      const Eigen::VectorXd x = from_metric(y);
      // h = f − c with the held coordinate for an extremum (x_i − c, or |x_i| − c): the equation
      // Newton solves; its gradient with respect to y = W x is ∇f(x)/W.
      const double h =
          active >= 0
              ? (f_.kind == ViewFunctionalKind::BlockAbsMaximum ? std::abs(x(active)) : x(active)) -
                    value_
              : level(x);
      if (!F.allFinite() || !std::isfinite(h)) {
        return result;
      }
      functional_gradient(f_, unit_weights_, x, gradient, active);
      if (metric_.weights().size() > 0) {
        gradient = gradient.cwiseQuotient(metric_.weights());
      }
      // dy = dy_p + T a: dy_p = −DF⁺F (⟂ T) corrects F; a, of minimum norm, corrects f to first
      // order: ∇f·dy_p + q·a = −h with q = Tᵀ∇f, the gradient of f on M in tangent coordinates.
      // Together the minimum-norm solution of [DF; ∇fᵀ] dy = −[F; h].
      const Eigen::Vector2d q = T.transpose() * gradient;
      const double q_norm = q.norm();
      if (!(q_norm > 0.0) || !std::isfinite(q_norm)) {
        return result;  // f has no gradient on M here: a critical point of f on M
      }
      linearization_.solve_minimum_norm(-F, dy_p);
      const double rhs = -h - gradient.dot(dy_p);
      const Eigen::VectorXd dy = dy_p + T * ((rhs / (q_norm * q_norm)) * q);
      y += dy;
      if (!y.allFinite() || (y - start).norm() > max_displacement) {
        return result;
      }
      if (dy.norm() <= options_.tolerance * (1.0 + y.norm()) &&
          F.norm() <= options_.residual_tolerance) {
        metric_.counted().evaluate(y, F);
        result.residual = F.norm();
        result.level_residual = std::abs(level(from_metric(y)));
        result.converged =
            F.allFinite() && result.residual <= options_.residual_tolerance &&
            result.level_residual <= options_.residual_tolerance * (1.0 + std::abs(value_));
        return result;
      }
    }
    return result;
  }

  const View& functional_;
  const ViewFunctional& f_;
  double value_;
  LevelOptions options_;
  MetricProblem metric_;
  Eigen::VectorXd unit_weights_;  // the metric's weights, all 1 when the problem has none (`norm`)
  Linearization linearization_;
  ViewWorkspace workspace_;
  Eigen::VectorXd values_;
};

}  // namespace

LevelCurves find_level_curves(const ImplicitProblem& problem, const TriangleMesh& mesh,
                              const View& functional, double value, const LevelOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  const int n = problem.ambient_dimension();
  TESSERA_CHECK(mesh.ambient_dimension() == n, "level curves: the mesh lies in R^"
                                                   << mesh.ambient_dimension() << ", problem '"
                                                   << problem.name() << "' in R^" << n);
  TESSERA_CHECK(functional.ambient_dimension() == n,
                "level curves: the functional takes points of R^" << functional.ambient_dimension()
                                                                  << ", problem '" << problem.name()
                                                                  << "' has n = " << n);
  TESSERA_CHECK(functional.size() == 1, "level curves need one functional, got "
                                            << functional.size() << " ('"
                                            << functional.specification() << "')");
  TESSERA_CHECK(std::isfinite(value), "level curves: the value " << value << " is not finite");
  TESSERA_CHECK(options.tolerance > 0 && options.residual_tolerance > 0 &&
                    options.max_iterations > 0 && options.max_displacement_in_edges > 0,
                "LevelOptions: tolerance = "
                    << options.tolerance << ", residual_tolerance = " << options.residual_tolerance
                    << ", max_iterations = " << options.max_iterations
                    << " and max_displacement_in_edges = " << options.max_displacement_in_edges
                    << " must all be > 0");
  LevelCurves result;
  if (mesh.triangle_count() == 0) {
    return result;
  }
  const MeshTopology topology(mesh);
  LevelSolver solver(problem, functional, value, options);

  // f − c at every vertex (cheap next to a factorisation): the marching starts everywhere.
  const ZeroSetCurves zero_set = find_zero_set_curves(mesh, topology, [&](int v) {
    const double level = solver.level(mesh.point(v));
    if (std::isnan(level)) {
      ++result.undefined_vertex_count;
    }
    return level;
  });
  result.crossing_count = zero_set.crossing_count;

  for (const ZeroSetChain& chain : zero_set.chains) {
    LevelCurve curve;
    curve.is_closed = chain.is_closed;
    for (const int c : chain.crossings) {
      const ZeroSetCrossing& crossing = zero_set.crossings[static_cast<std::size_t>(c)];
      const Eigen::VectorXd ya = solver.to_metric(mesh.point(crossing.vertices[0]));
      const Eigen::VectorXd yb = solver.to_metric(mesh.point(crossing.vertices[1]));
      const Eigen::VectorXd estimate = ya + crossing.fraction * (yb - ya);
      Eigen::VectorXd y = estimate;
      const auto refined = solver.refine(y, options.max_displacement_in_edges * (yb - ya).norm());
      result.newton_iterations += refined.iterations;
      result.max_point_iterations = std::max(result.max_point_iterations, refined.iterations);
      LevelPoint point;
      point.iterations = refined.iterations;
      if (refined.converged) {
        point.is_refined = true;
        point.residual = refined.residual;
        point.level_residual = refined.level_residual;
        result.max_residual = std::max(result.max_residual, refined.residual);
        result.max_level_residual = std::max(result.max_level_residual, refined.level_residual);
      } else {
        y = estimate;
        ++result.unrefined_count;
      }
      point.x = solver.from_metric(y);
      curve.points.push_back(std::move(point));
    }
    result.curves.push_back(std::move(curve));
  }
  result.work = solver.work();
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

LevelCurves find_level_curves(const ImplicitProblem& problem, const TriangleMesh& mesh,
                              const LevelSet& level, const LevelOptions& options) {
  return find_level_curves(problem, mesh, level.functional, level.value, options);
}

}  // namespace tessera
