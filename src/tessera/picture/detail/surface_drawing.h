// SPDX-License-Identifier: MIT
// Internal to the picture module: the triangles of a surface picture painted far to near, each
// in its colour and light: Gouraud-shaded through cairo mesh patterns on raster surfaces, flat
// (the mean of its corners) on vector ones; categories split per corner; edges by density.
#pragma once

#include <cairo.h>

#include "tessera/picture/detail/camera.h"
#include "tessera/picture/picture.h"

namespace tessera::picture_detail {

/// How strongly the triangles' edges are drawn, in [0, 1]: 0 none, 1 full. PictureEdges::On is
/// 1 and Off 0; Automatic grows from 0 at a median edge of 6 pixels on the screen (a denser mesh
/// would be darkened by its edges) to 1 at 14 pixels.
double edge_strength(const PictureScene& scene, const Camera& camera, PictureEdges edges);

/// The range of the scene's finite values (vertex or triangle values); [0, 1] without any.
std::array<double, 2> value_range(const PictureScene& scene);

/// Paints the triangles of `scene` far to near by the depth of their centroids (the painter's
/// algorithm), lit by Lambert's law with the light at the eye (0.35 ambient + 0.65 |cos|, both
/// sides; none with options.flat_shading), coloured by values in [low, high], categories or
/// options.surface_rgb, with edges of `edge_strength` (0: none). `is_raster`: interpolate the
/// colours and the light of the corners across each triangle (cairo mesh patterns), else fill
/// each flat, enlarged by half a pixel to close the seams viewers leave between neighbours.
void draw_surface(cairo_t* cr, const PictureScene& scene, const Camera& camera,
                  const PictureOptions& options, double low, double high, double edge_strength,
                  bool is_raster);

}  // namespace tessera::picture_detail
