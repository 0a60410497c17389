// SPDX-License-Identifier: MIT
// What the curves, marked points and categories of a picture are, and how each is drawn: the
// conventions of two-parameter continuation (fold curves solid, Hopf curves dashed, neutral
// saddle curves dotted; cusp, Bogdanov–Takens and zero-Hopf points as distinct shapes) and the
// stability colours of a surface of steady states (stable blue, index 1 orange, index >= 2 red,
// unknown grey). Shared by the surface pictures (picture.h) and the bifurcation diagram
// (bifurcation_diagram.h).
#pragma once

#include <array>
#include <string>
#include <vector>

namespace tessera {

/// How a curve is stroked.
enum class CurveDash {
  Solid,
  Dashed,  ///< dashes of 4 line widths, gaps of 2.5 (Hopf curves)
  Dotted,  ///< round dots 3 line widths apart (neutral saddle curves)
};

/// What a curve is, as the "kind" of its polylines file (io/polylines.h).
enum class CurveKind {
  Fold,           ///< "fold" (and files without a kind): saddle-node bifurcations
  Hopf,           ///< "hopf": a pair of eigenvalues ±iω crosses the imaginary axis
  NeutralSaddle,  ///< "neutral_saddle": real eigenvalues ±μ, not a bifurcation of equilibria
  Level,          ///< "level": a level curve of a functional
  Other,          ///< any other kind: drawn solid, in grey, labelled by its name
};

/// The kind named `name` in a polylines file: "" and "fold" are Fold, "hopf", "neutral_saddle",
/// "level" the others; any other name is Other.
CurveKind curve_kind_from_name(const std::string& name);

/// The style of a curve of one kind.
struct CurveStyle {
  std::array<double, 3> rgb = {0.8, 0.1, 0.1};  ///< components in [0, 1]
  double width = 2.5;                           ///< pixels
  CurveDash dash = CurveDash::Solid;
  std::string label;  ///< the legend's words, e.g. "Hopf"
};

/// Fold: red, solid; Hopf: blue, dashed; neutral saddle: grey, dotted; level: green, solid and
/// thinner; other: grey, solid, labelled `name`. On a surface coloured by stability these
/// colours would vanish into the regions the curves bound, so there the caller darkens them
/// (see dark_curve_style).
CurveStyle curve_style(CurveKind kind, const std::string& name = "");

/// curve_style in near-black, keeping the dash and width: curves over a surface coloured by
/// categories (blue, orange, red), where only the dash tells fold from Hopf.
CurveStyle dark_curve_style(CurveKind kind, const std::string& name = "");

/// What a marked point is, as the marker name of its polylines file.
enum class PointKind {
  Generic,         ///< any other marker name: a yellow dot
  Cusp,            ///< "cusp": an upward triangle
  BogdanovTakens,  ///< "bogdanov_takens" (also "bt"): a square
  ZeroHopf,        ///< "zero_hopf" (also "fold_hopf", "zh"): a diamond
};

/// The point kind of a marker name (case as written by tessera: lower case).
PointKind point_kind_from_marker_name(const std::string& marker_name);

/// The legend's words for a point kind: "cusp", "Bogdanov-Takens", "zero-Hopf", "marked point".
std::string point_kind_label(PointKind kind);

/// A category of a categorical colouring: its colour and its words in the legend.
struct PictureCategory {
  std::string label;
  std::array<double, 3> rgb = {0.5, 0.5, 0.5};
};

/// The stability categories of a steady state by its number of unstable eigenvalues (with
/// positive real part), in this order (the indices of stability_category):
///   0 "stable"     blue   (0.23, 0.45, 0.80)
///   1 "index 1"    orange (0.98, 0.60, 0.13)
///   2 "index >= 2" red    (0.80, 0.12, 0.12)
///   3 "unknown"    grey   (0.72, 0.72, 0.72)  where the eigensolver failed
/// Blue for stable and warm colours for growing instability are what continuation codes draw
/// (AUTO's and MatCont's stable/unstable branches); grey says "no data" and is no index.
std::vector<PictureCategory> stability_categories();

/// The category (index into stability_categories()) of a vertex with `unstable_count`
/// eigenvalues of positive real part: 0, 1, 2 (for 2 and more), or 3 (unknown) for a negative
/// value (the −1 of a failed eigensolver), NaN, infinity or a value that is not an integer.
int stability_category(double unstable_count);

}  // namespace tessera
