// SPDX-License-Identifier: MIT
// Internal to the picture module: makes cairo's SVG of a picture small. cairo writes every
// shape as a <path> with a long style (colours as percentages to six decimals, defaults spelled
// out) and coordinates to six decimals: about 330 bytes per triangle, 1.6 MB for 5000.
#pragma once

#include <string>

namespace tessera::picture_detail {

/// The same picture in fewer bytes. Each self-closing <path> after the <defs> (glyph outlines
/// stay as they are) is rewritten:
/// - its style becomes presentation attributes, colours #rrggbb, SVG's defaults left out
///   (fill-opacity 1, fill-rule nonzero, stroke-linecap butt, stroke-miterlimit where the join
///   is not a miter, …);
/// - its coordinates are rounded to 0.1 (pixels: within what antialiasing shows), and cairo's
///   move-to after a final close-path is dropped;
/// - consecutive paths that are filled alike with the nonzero rule and not stroked merge into
///   one path (the surface's triangles are drawn in one orientation, so that the union of
///   overlapping ones is filled).
/// Anything else, and any path it does not understand, is kept as it is.
std::string compact_svg(const std::string& svg);

}  // namespace tessera::picture_detail
