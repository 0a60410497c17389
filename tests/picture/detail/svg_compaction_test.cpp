// SPDX-License-Identifier: MIT
// compact_svg (detail/svg_compaction.h) on the SVG cairo writes: styles become short attributes,
// coordinates tenths, relative after the first point; shapes filled alike merge, shapes stroked
// in their fill's colour name it once; what it does not read is kept as it is.
#include "tessera/picture/detail/svg_compaction.h"

#include <gtest/gtest.h>

#include <string>

namespace tessera::picture_detail {
namespace {

const std::string kHead =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg width=\"600pt\" height=\"450pt\">\n"
    "<defs>\n<symbol id=\"glyph0-1\"><path style=\"stroke:none;\" d=\"M 1.125 -9.125 L 2.203125 "
    "-9.125 Z\"/></symbol>\n</defs>\n<g id=\"surface1\">\n";

std::string fill(const std::string& colour, const std::string& d) {
  return "<path style=\"fill-rule:nonzero;fill:" + colour + ";fill-opacity:1;\" d=\"" + d +
         "\"/>\n";
}

TEST(SvgCompaction, ColoursCoordinatesAndDefaultsShrink) {
  const std::string svg =
      kHead +
      "<path style=\"fill:none;stroke-width:1.2;stroke-linecap:butt;stroke-linejoin:round;"
      "stroke:rgb(80%,10%,10%);stroke-opacity:1;stroke-miterlimit:10;\" d=\"M 106.789062 "
      "325.035156 L 91.023438 333.566406 C 90 334 89 335 88.5 336.04 \"/>\n</g>\n</svg>\n";
  const std::string out = compact_svg(svg);
  // The glyphs in <defs> are as they were.
  EXPECT_NE(out.find("d=\"M 1.125 -9.125 L 2.203125 -9.125 Z\""), std::string::npos) << out;
  EXPECT_NE(out.find("<path fill=\"none\" stroke-width=\"1.2\" stroke-linejoin=\"round\" "
                     "stroke=\"#cc1a1a\" d=\"M106.8 325l-15.8 8.6c-1 .4-2 1.4-2.5 2.4\"/>"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("</g>\n</svg>"), std::string::npos);
}

TEST(SvgCompaction, ConsecutiveFillsOfOneColourMergeAndOthersDoNot) {
  const std::string svg = kHead + fill("rgb(50%,50%,50%)", "M 0 0 L 10 0 L 0 10 Z M 0 0") +
                          fill("rgb(50%,50%,50%)", "M 10 0 L 10 10 L 0 10 Z M 10 0") +
                          fill("rgb(0%,0%,100%)", "M 20 0 L 30 0 L 20 10 Z") +
                          "<path style=\"fill-rule:evenodd;fill:rgb(0%,0%,100%);\" d=\"M 0 0 L 1 "
                          "0 L 0 1 Z\"/>\n"
                          "<path style=\"fill-rule:evenodd;fill:rgb(0%,0%,100%);\" d=\"M 0 0 L 1 "
                          "0 L 0 1 Z\"/>\n</g>\n</svg>\n";
  const std::string out = compact_svg(svg);
  EXPECT_NE(out.find("<path fill=\"#808080\" d=\"M0 0l10 0-10 10zM10 0l0 10-10 0z\"/>"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("<path fill=\"#0000ff\" d=\"M20 0l10 0-10 10z\"/>"), std::string::npos) << out;
  // Even-odd fills would cancel where they overlap: never merged.
  std::size_t count = 0;
  for (auto at = out.find("evenodd"); at != std::string::npos; at = out.find("evenodd", at + 1)) {
    ++count;
  }
  EXPECT_EQ(count, 2u) << out;
}

// Triangles stroked in their own colour (the seams closed) name it once, and a run of them
// shares its stroke in a group.
TEST(SvgCompaction, ARunOfTrianglesStrokedInTheirColourSharesAGroup) {
  std::string svg = kHead;
  for (int i = 0; i < 5; ++i) {
    const std::string colour = "rgb(" + std::to_string(10 * i) + "%,20%,30%)";
    svg += "<path style=\"fill-rule:nonzero;fill:" + colour +
           ";fill-opacity:1;stroke-width:0.8;stroke-linecap:butt;stroke-linejoin:round;stroke:" +
           colour + ";stroke-opacity:1;stroke-miterlimit:10;\" d=\"M " + std::to_string(i) +
           " 0 L 5 5 L 0 5 Z M 0 0\"/>\n";
  }
  svg += "<rect x=\"0\" y=\"0\" width=\"3\" height=\"3\"/>\n</g>\n</svg>\n";
  const std::string out = compact_svg(svg);
  EXPECT_NE(out.find("<g fill=\"currentColor\" stroke-width=\"0.8\" stroke-linejoin=\"round\" "
                     "stroke=\"currentColor\">\n<path color=\"#00334d\" d=\"M0 0l5 5-5 0z\"/>\n"
                     "<path color=\"#1a334d\" d=\"M1 0l4 5-5 0z\"/>"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("</g>\n<rect x=\"0\" y=\"0\" width=\"3\" height=\"3\"/>"), std::string::npos)
      << out;
  EXPECT_LT(out.size(), svg.size() / 2);
}

TEST(SvgCompaction, WhatItDoesNotReadStaysAsItIs) {
  const std::string odd =
      "<path d=\"M 0 0 A 5 5 0 0 1 10 10\" style=\"fill:none;\"/>\n"
      "<path style=\"fill:red\" d=\"M 0 0 L 1 1\"></path>\n";
  const std::string svg = kHead + odd + "</g>\n</svg>\n";
  EXPECT_EQ(compact_svg(svg), svg);
  EXPECT_EQ(compact_svg("not an svg"), "not an svg");
}

}  // namespace
}  // namespace tessera::picture_detail
