// SPDX-License-Identifier: MIT
// The camera direction that shows a surface's folds: the default view of continuation
// surfaces, where the sheets of steady states fold over each other and a fixed direction often
// shows them edge-on or hides the middle (unstable) sheet behind the others.
#pragma once

#include "tessera/picture/picture.h"

namespace tessera {

/// A camera direction, as PictureOptions takes it.
struct ViewDirection {
  double azimuth_degrees = -60.0;
  double elevation_degrees = 30.0;
};

/// The direction from which the folds of a surface show, as the picture of a cusp catastrophe
/// shows them: along the folds and from above the plane of the first two axes (the parameter
/// plane of a continuation view), so that the sheets' S shows at the near end.
///
/// The folds are where the tangent plane stands vertical (contains the third axis): there the
/// sheets over a point of the plane meet and turn back. The principal axis of the horizontal
/// normals of those triangles (weighted by area, the tangent plane within 14° of vertical) is
/// the direction across the folds; the camera looks along the folds, 30° aside (so that they do
/// not shrink to points), from one of the four such azimuths and an elevation of 20°, 30° or
/// 40°: the one from which a depth buffer of 160×160 pixels shows the most surface (each pixel
/// counting the area it stands for, up to 4 for grazing triangles), preferring azimuths where
/// both horizontal axes stay readable. Measured after `aspect`'s scaling, as drawn.
/// \pre scene.positions finite, its triangles' indices in range (as render_picture checks).
/// \return the default (−60°, 30°) where there are no folds, or where they face every way
///         alike (a sphere's equator); for a scene without triangles.
ViewDirection best_view_direction(const PictureScene& scene, PictureAspect aspect);

}  // namespace tessera
