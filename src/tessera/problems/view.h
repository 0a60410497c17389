// SPDX-License-Identifier: MIT
// Views: the few functionals of a point x in R^n (coordinates, the maximum or the norm of a block,
// expressions) in which a surface of large n is plotted, e.g. "lambda, epsilon, max:u".
#pragma once

#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tessera/core/ambient_space.h"
#include "tessera/core/error.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/problems/expression.h"

namespace tessera {

/// What a view functional computes from a point x in R^n. B is a coordinate block
/// (CoordinateBlock: coordinates first … first + size − 1, weight w).
enum class ViewFunctionalKind {
  Coordinate,       ///< x_i
  BlockMaximum,     ///< max_{i in B} x_i
  BlockMinimum,     ///< min_{i in B} x_i
  BlockMean,        ///< (1/|B|) Σ_{i in B} x_i, the arithmetic mean of the values
  BlockAbsMaximum,  ///< max_{i in B} |x_i|, the maximum norm of the block
  /// w·‖x_B‖₂ = (Σ_{i in B} (w x_i)²)^½, the block's norm in the problem's metric: with the weight
  /// √h of a grid of width h (h in two dimensions) the discrete L² norm, which approximates the
  /// continuous ‖u‖_L² of the function the block samples.
  BlockNorm,
  /// (Σ_i (w_i x_i)²)^½ over all n coordinates, the norm of the metric tessera measures M in
  /// (metric_weights; Euclidean without blocks).
  Norm,
  /// f(x) for an expression f of the coordinates (NAME = EXPRESSION; problems/expression.h).
  Expression,
};

/// One functional of a view, with the names it goes by.
struct ViewFunctional {
  ViewFunctionalKind kind = ViewFunctionalKind::Coordinate;
  /// As written in a view specification; parse_view(label) gives this functional back:
  /// "lambda", "max:u", "norm", "r = sqrt(x^2 + y^2)".
  std::string label;
  /// Column name in files (PLY property, VTK array): the coordinate's name, "max_u", "norm_u",
  /// "norm", or an expression's NAME. Unique within a view.
  std::string name;
  /// Coordinate: its index. Block functionals: the block's first coordinate. Norm: 0.
  int first = 0;
  /// Coordinate: 1. Block functionals: the block's size. Norm: n.
  int size = 1;
  /// BlockNorm: the block's weight w (CoordinateBlock::weight); 1 otherwise.
  double weight = 1.0;
  /// Expression only: f, a function of the coordinates `variables` (indices into 0 … n−1, in the
  /// order of f's variables): only the coordinates f names, so that f stays small at any n.
  std::optional<tessera::Expression> expression;
  std::vector<int> variables;
};

/// A bad view specification: which item, where, and what is available instead. Derives from
/// InvalidArgument; `column()` and `reason()` let a caller that embeds a specification in a larger
/// text (a problem file's `view` line, an option) point at the right place in its own source.
class ViewSpecificationError : public InvalidArgument {
 public:
  ViewSpecificationError(const std::string& specification, int column, std::string reason);
  /// 1-based column in the specification (its length + 1 for "at the end").
  int column() const { return column_; }
  /// What is wrong, naming the item, e.g. "'max:v': no block 'v' (blocks: u)".
  const std::string& reason() const { return reason_; }

 private:
  int column_;
  std::string reason_;
};

/// Scratch memory for View::evaluate; reusing one keeps evaluation free of allocations.
struct ViewWorkspace {
  ExpressionWorkspace expression;
  Eigen::VectorXd arguments;  ///< the coordinates an expression names, gathered from x
};

/// A view of the points of R^n: the map φ(x) = (f_1(x), …, f_k(x)) of k functionals, in which a
/// surface M ⊂ R^n of large n is plotted as φ(M) ⊂ R^k.
///
/// Made by parse_view, all_coordinates_view or default_view for one problem; it holds indices,
/// weights and expressions, not the problem, and evaluates points of that problem's R^n.
class View {
 public:
  View() = default;
  View(int ambient_dimension, std::vector<ViewFunctional> functionals,
       Eigen::VectorXd metric_weights);

  /// n, the dimension of the points the view takes.
  int ambient_dimension() const { return ambient_dimension_; }
  /// k, the number of functionals.
  int size() const { return static_cast<int>(functionals_.size()); }
  const std::vector<ViewFunctional>& functionals() const { return functionals_; }
  /// The column names (ViewFunctional::name), in order.
  std::vector<std::string> names() const;
  /// The labels joined by ", " ("all" for the view of every coordinate): a specification that
  /// parse_view reads back into this view.
  std::string specification() const;
  /// True if the view is x itself: the n coordinates in order (all_coordinates_view).
  bool is_all_coordinates() const;

  /// values(i) = f_i(x).
  /// \pre x.size() == ambient_dimension(), values.size() == size() (else InvalidArgument).
  /// Allocates only if `workspace` (for expressions) is too small.
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> values,
                ViewWorkspace& workspace) const;
  /// f(x), convenient form.
  Eigen::VectorXd evaluate(const Eigen::Ref<const Eigen::VectorXd>& x) const;

  /// The view of N points at once.
  /// \param points  n×N, one point per column (as TriangleMesh::points()).
  /// \return k×N, column j = φ(points.col(j)), row i the values of functional i: the same memory
  ///         as a NumPy (N, k) array whose columns are names().
  /// \throw InvalidArgument if points.rows() != ambient_dimension().
  Eigen::MatrixXd evaluate_columns(const Eigen::Ref<const Eigen::MatrixXd>& points) const;
  /// The view of N points split over the ranks of `space` (SPMD, docs/cluster.md): `points`
  /// holds this rank's rows of each (space.local_rows() × N, as TriangleMesh::points() of a
  /// split mesh). Collective: every rank computes its partial values of every functional for
  /// every point, then one sum (coordinates, means, norms, an expression's coordinates) and one
  /// maximum (max, min, absmax) per 2^15 values make the same k×N on every rank.
  /// Coordinates, max, min, absmax and expressions are one process's values to the bit; means
  /// and norms to rounding (the ranks' partial sums are added in rank order).
  /// In one process (space not distributed): evaluate_columns(points), bit for bit.
  /// \throw InvalidArgument if space.dimension() != ambient_dimension() or points.rows() !=
  ///        space.local_rows() (the same on every rank: nothing is reduced then).
  Eigen::MatrixXd evaluate_columns(const Eigen::Ref<const Eigen::MatrixXd>& points,
                                   const AmbientSpace& space) const;

 private:
  int ambient_dimension_ = 0;
  std::vector<ViewFunctional> functionals_;
  Eigen::VectorXd weights_;  ///< metric weights for Norm; empty: all 1
};

/// Parses a view specification: items separated by commas, each one of
///
///     NAME           a coordinate of the problem (coordinate_names), e.g. lambda or u17;
///                    a block's name B: every coordinate of the block, in order;
///     max:B  min:B  mean:B  absmax:B  norm:B    a functional of block B (ViewFunctionalKind);
///     norm           the metric's norm of x (all n coordinates);
///     all            every coordinate, in order (the whole state);
///     NAME = EXPR    an expression of the coordinates (and of `parameters`) named NAME, in the
///                    language of problems/expression.h (one-argument functions, so no commas).
///
/// Spaces around items and around ':' and '=' are ignored. A coordinate or block name takes
/// precedence over the words norm and all. Column names must be unique: an item given twice, or
/// an expression named like a coordinate or like another column, is an error.
///
/// \param parameters  named constants that expressions may use (a problem file's parameters).
/// \throw ViewSpecificationError (an InvalidArgument) for an empty specification or item, an
///        unknown name, block or functional, a malformed expression or a repeated column. The
///        message names the item and lists what is available: the coordinates that belong to no
///        block and the blocks with their ranges ("u1 … u1000 (block u)"), never every one of
///        10⁴ names.
View parse_view(std::string_view specification, const ImplicitProblem& problem,
                const std::map<std::string, double>& parameters = {});

/// The view of every coordinate, in order (specification "all").
View all_coordinates_view(const ImplicitProblem& problem);

/// Problems whose n exceeds this are written in default_view unless a view is asked for.
constexpr int kLargeAmbientDimension = 50;

/// The view a surface of large n is shown in when none is asked for: the coordinates that
/// belong to no block, then max:B for every block B, then, while fewer than three functionals,
/// norm:B and min:B of the largest block. For bvp:points=N: lambda, epsilon, max:u.
/// \return the view, or all_coordinates_view when n ≤ kLargeAmbientDimension or the problem has
///         no blocks (nothing to summarise).
View default_view(const ImplicitProblem& problem);

/// "u1 … u1000 (block u), lambda, epsilon": the coordinates of `problem` in order, a block as the
/// range of its names; for error messages and reports at any n.
std::string describe_coordinates(const ImplicitProblem& problem);

}  // namespace tessera
