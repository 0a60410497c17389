// SPDX-License-Identifier: MIT
// Internal to geometry/mesh_validation*.cpp: what the combinatorial pass (mesh_validation.cpp)
// hands to the geometric checks (mesh_validation_geometric.cpp: orientation and domain;
// mesh_validation_overlaps.cpp: overlaps).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "tessera/core/ambient_space.h"
#include "tessera/core/domain.h"
#include "tessera/core/implicit_problem.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/geometry/triangle_mesh.h"

namespace tessera::detail {

/// An angle in degrees, for messages.
inline double degrees(double radians) { return radians * 180.0 / std::numbers::pi; }

constexpr int kDefectKindCount = static_cast<int>(MeshDefectKind::VertexOutsideDomain) + 1;

// Counts every occurrence and keeps the first `max_examples` descriptions of each kind. The
// description is built lazily so that a mesh with a million defects costs no strings.
class DefectRecorder {
 public:
  explicit DefectRecorder(int max_examples) : max_examples_(max_examples) {
    for (int i = 0; i < kDefectKindCount; ++i) {
      defects_[i].kind = static_cast<MeshDefectKind>(i);
    }
  }
  template <class Describe>
  void record(MeshDefectKind kind, const Describe& describe) {
    MeshDefect& defect = defects_[static_cast<int>(kind)];
    ++defect.count;
    if (static_cast<int>(defect.examples.size()) < max_examples_) {
      defect.examples.push_back(describe());
    }
  }
  int count(MeshDefectKind kind) const { return defects_[static_cast<int>(kind)].count; }
  std::vector<MeshDefect> take_present() {
    std::vector<MeshDefect> present;
    for (MeshDefect& defect : defects_) {
      if (defect.count > 0) {
        present.push_back(std::move(defect));
      }
    }
    return present;
  }

 private:
  int max_examples_;
  std::array<MeshDefect, kDefectKindCount> defects_;
};

// ValidationOptions::stop_requested as the geometric checks poll it: once it has said stop it
// stays stopped, and on a split mesh the ranks decide together (one reduction per poll), so
// that every rank leaves its loop at the same place as the collective projections require.
class CheckStop {
 public:
  CheckStop(const std::function<bool()>& request, const AmbientSpace& space)
      : request_(request), space_(space) {}
  bool is_stopped() {
    if (!stopped_ && request_) {
      const bool local = request_();
      stopped_ = space_.is_distributed() ? space_.maximum(local ? 1.0 : 0.0) > 0.0 : local;
    }
    return stopped_;
  }

 private:
  const std::function<bool()>& request_;
  const AmbientSpace& space_;
  bool stopped_ = false;
};

struct GeometricInput {
  const ImplicitProblem& problem;
  const Domain& domain;
};

// Per topology triangle: what the combinatorial pass measured, and what the orientation pass
// finds for the overlap pass.
struct TriangleShapes {
  explicit TriangleShapes(int count)
      : area(count, 0.0),
        longest_edge(count, 0.0),
        is_finite(count, 0),
        is_degenerate(count, 0),
        oriented_cosine(count, std::numeric_limits<double>::quiet_NaN()) {}
  std::vector<double> area;
  std::vector<double> longest_edge;
  std::vector<std::uint8_t> is_finite;      // all three vertices finite
  std::vector<std::uint8_t> is_degenerate;  // a DegenerateTriangle defect
  // s_t against M's orientation as the mesh's piece sees it (σ applied, mean over the
  // corners); NaN if not judged.
  std::vector<double> oriented_cosine;
};

struct MeshView {
  const TriangleMesh& mesh;
  const MeshTopology& topology;
  const std::vector<int>& original;  // topology triangle -> mesh triangle
  TriangleShapes& shapes;
  const std::vector<std::uint8_t>& is_finite_vertex;
};

// The geometric checks (validate with a problem and a domain), in the order validate runs them.
// The mathematics is in docs/validation.md.
void check_orientation(const MeshView& view, const GeometricInput& geometry,
                       const ValidationOptions& options, CheckStop& stop, DefectRecorder& recorder,
                       MeshValidation& result);
void check_overlaps(const MeshView& view, const GeometricInput& geometry,
                    const ValidationOptions& options, CheckStop& stop, DefectRecorder& recorder,
                    MeshValidation& result);
// Thin triangles (an angle below 10° or above 150°) sampled on M against their nearby
// triangles `pairs` (mesh_validation_thin.cpp); called by check_overlaps.
void check_thin_triangles(const MeshView& view, const GeometricInput& geometry,
                          const std::vector<std::pair<int, int>>& pairs, CheckStop& stop,
                          DefectRecorder& recorder, MeshValidation& result);
// Fans whose corners' arcs in M's tangent plane at their vertex overlap (mesh_validation_fans.cpp),
// from check_orientation's oriented cosines and arcs (start, signed sweep) per corner.
void check_fan_arcs(const MeshView& view,
                    const std::vector<std::array<double, 3>>& corner_cosine,
                    const std::vector<std::array<std::array<double, 2>, 3>>& corner_arcs,
                    const ValidationOptions& options, DefectRecorder& recorder,
                    MeshValidation& result);
// "triangle 17 (vertices 3, 8, 9)"
std::string triangle_name(int t, const Triangle& tri);
void check_domain(const MeshView& view, const GeometricInput& geometry,
                  const ValidationOptions& options, DefectRecorder& recorder,
                  MeshValidation& result);

}  // namespace tessera::detail
