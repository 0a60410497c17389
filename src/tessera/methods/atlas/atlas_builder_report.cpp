// SPDX-License-Identifier: MIT
// The atlas build's counts and the notes that explain them (radius caps, factorisations made
// twice, singular crossings), for the covering's summary.
#include <sstream>

#include "tessera/methods/atlas/atlas_builder.h"

namespace tessera::detail {
namespace {

// The note on charts held below the tolerance's radius is made from this fraction of the charts
// on: below it they barely change the cost of the run (measured in the commit that made it).
constexpr double kRadiusCapNoteFraction = 0.1;

}  // namespace

// The counts and notes of the build.
void AtlasBuilder::report(CoveringSummary& summary) {
  summary.charts = chart_count();
  if (n_ >= kReleaseHeapDimension) {
    release_free_heap();  // what the last charts freed, before the build's final sample
  }
  summary.note_resident_memory(boundary_bytes());
  summary.boundary_peak_bytes = boundary_peak_bytes_;
  summary.borrowed_factorisations = borrowed_charts_;
  summary.singular_crossings = singular_crossings_;
  summary.sheet_rejections = sheet_rejections_;
  CoveringSummary::RadiusCaps& caps = summary.radius_caps;
  caps.curvature = capped_[static_cast<int>(RadiusCap::Curvature)];
  caps.not_a_graph = capped_[static_cast<int>(RadiusCap::NotAGraph)];
  caps.grading = capped_[static_cast<int>(RadiusCap::Grading)];
  caps.reach = capped_[static_cast<int>(RadiusCap::Reach)];
  caps.band = capped_[static_cast<int>(RadiusCap::Band)];
  caps.reduced_later = shrunk_charts_;
  const int capped = caps.total();
  // The counts are always in the summary (run.atlas.radius_caps). The note is for the few runs
  // where they change the cost: a few charts held small (a grading step, a corner) are in every
  // atlas and say nothing; issue 34 found the same 400 characters printed by every run.
  if (capped > 0 && capped >= kRadiusCapNoteFraction * chart_count()) {
    // The causes that held charts, those that did not left out.
    std::vector<std::string> causes;
    const auto cause = [&causes](int count, const std::string& why) {
      if (count > 0) {
        causes.push_back(std::to_string(count) + " " + why);
      }
    };
    std::ostringstream turning;
    turning << "capped by the curvature (radius <= " << options_.max_turning_angle
            << "/curvature: M turns within the disk)";
    cause(caps.curvature, turning.str());
    cause(caps.not_a_graph,
          "where M is no graph over the larger disk or the corrector does not reach it (a thin "
          "part or a turn of M nearby)");
    std::ostringstream grading;
    grading << "next to smaller charts (radii grow by at most " << options_.radius_growth - 1.0
            << " per unit length)";
    cause(caps.grading, grading.str());
    cause(caps.reach, "by the reach (another part of M within the disk)");
    cause(caps.band, "to half the width of a band of M ∩ S narrower than two radii");
    std::ostringstream note;
    note << capped << " of " << chart_count() << " charts ("
         << std::lround(100.0 * capped / chart_count())
         << "%) have a radius below the tolerance's sqrt(2*tolerance/curvature), so the mesh "
            "is finer than the tolerance asks: ";
    for (std::size_t i = 0; i < causes.size(); ++i) {
      note << (i == 0 ? "" : ", ") << causes[i];
    }
    if (shrunk_charts_ > 0) {
      note << "; " << shrunk_charts_
           << " radii were reduced later, where pointOnDisk failed on the disk or another part "
              "of M came near";
    }
    summary.notes.push_back(note.str());
  }
  if (refactored_charts_ > 0) {
    std::ostringstream note;
    note << refactored_charts_ << " of " << chart_count()
         << " charts were factored twice: the factorisations of the charts waiting on the "
            "boundary outgrew max_factorisation_bytes ("
         << options_.max_factorisation_bytes / (1024.0 * 1024.0) << " MB)";
    summary.notes.push_back(note.str());
  }
  if (singular_crossings_ > 0) {
    summary.notes.push_back("met a singular crossing of M (first near " + first_crossing_ +
                            "): the atlas continued along the sheet it was on, " +
                            std::to_string(sheet_rejections_) +
                            " overlaps with charts of other sheets were kept apart");
  }
}

}  // namespace tessera::detail
