// SPDX-License-Identifier: MIT
#include "tessera/picture/picture_styles.h"

#include <cmath>

namespace tessera {

CurveKind curve_kind_from_name(const std::string& name) {
  if (name.empty() || name == "fold") {
    return CurveKind::Fold;
  }
  if (name == "hopf") {
    return CurveKind::Hopf;
  }
  if (name == "neutral_saddle") {
    return CurveKind::NeutralSaddle;
  }
  if (name == "level") {
    return CurveKind::Level;
  }
  return CurveKind::Other;
}

CurveStyle curve_style(CurveKind kind, const std::string& name) {
  switch (kind) {
    case CurveKind::Fold:
      return {{0.85, 0.1, 0.1}, 2.5, CurveDash::Solid, "fold"};
    case CurveKind::Hopf:
      return {{0.1, 0.3, 0.85}, 2.5, CurveDash::Dashed, "Hopf"};
    case CurveKind::NeutralSaddle:
      return {{0.4, 0.4, 0.4}, 2.5, CurveDash::Dotted, "neutral saddle"};
    case CurveKind::Level:
      return {{0.15, 0.55, 0.2}, 1.5, CurveDash::Solid, "level"};
    case CurveKind::Other:
      break;
  }
  return {{0.35, 0.35, 0.35}, 2.0, CurveDash::Solid, name.empty() ? "curve" : name};
}

CurveStyle dark_curve_style(CurveKind kind, const std::string& name) {
  CurveStyle style = curve_style(kind, name);
  style.rgb = kind == CurveKind::NeutralSaddle || kind == CurveKind::Other
                  ? std::array<double, 3>{0.3, 0.3, 0.3}
                  : std::array<double, 3>{0.05, 0.05, 0.05};
  return style;
}

PointKind point_kind_from_marker_name(const std::string& marker_name) {
  if (marker_name == "cusp") {
    return PointKind::Cusp;
  }
  if (marker_name == "bogdanov_takens" || marker_name == "bt") {
    return PointKind::BogdanovTakens;
  }
  if (marker_name == "zero_hopf" || marker_name == "fold_hopf" || marker_name == "zh") {
    return PointKind::ZeroHopf;
  }
  return PointKind::Generic;
}

std::string point_kind_label(PointKind kind) {
  switch (kind) {
    case PointKind::Cusp:
      return "cusp";
    case PointKind::BogdanovTakens:
      return "Bogdanov-Takens";
    case PointKind::ZeroHopf:
      return "zero-Hopf";
    case PointKind::Generic:
      break;
  }
  return "marked point";
}

std::vector<PictureCategory> stability_categories() {
  return {{"stable", {0.23, 0.45, 0.80}},
          {"index 1", {0.98, 0.60, 0.13}},
          {"index >= 2", {0.80, 0.12, 0.12}},
          {"unknown", {0.72, 0.72, 0.72}}};
}

int stability_category(double unstable_count) {
  if (!std::isfinite(unstable_count) || unstable_count < 0 ||
      unstable_count != std::floor(unstable_count)) {
    return 3;
  }
  return unstable_count >= 2 ? 2 : static_cast<int>(unstable_count);
}

}  // namespace tessera
