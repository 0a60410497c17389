// SPDX-License-Identifier: MIT
#include "tessera/core/face_projection.h"

#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include "tessera/core/ambient_space.h"
#include "tessera/core/linearization.h"

namespace tessera {

void place_on_faces(const Domain& domain, const std::vector<int>& faces, Eigen::VectorXd& x) {
  // Two passes: a second face that is not orthogonal to the first moves x off it again, by
  // rounding only.
  for (int pass = 0; pass < 2; ++pass) {
    for (int f : faces) {
      const HalfSpace& h = domain.half_spaces()[f];
      int axis = -1;
      bool is_coordinate_face = true;
      for (Eigen::Index i = 0; i < h.normal.size(); ++i) {
        if (h.normal(i) != 0.0) {
          is_coordinate_face = axis < 0;
          axis = static_cast<int>(i);
          if (!is_coordinate_face) {
            break;
          }
        }
      }
      if (is_coordinate_face && axis >= 0) {
        x(axis) = h.point(axis);  // the bound itself: b·(x − p) is then exactly 0
      } else {
        x -= h.normal.dot(x - h.point) * h.normal;
      }
    }
  }
}

void place_on_faces(const Domain& domain, const std::vector<int>& faces, Eigen::VectorXd& x,
                    const AmbientSpace& space) {
  if (!space.is_distributed()) {
    place_on_faces(domain, faces, x);
    return;
  }
  // A coordinate face has one nonzero in its normal over all the ranks: counted at once. Its
  // bound is then set by the rank that holds the coordinate; the others move x along the
  // normal (one reduction for b·(x − p) each).
  const auto count = faces.size();
  std::vector<double> nonzeros(count, 0.0);
  std::vector<int> axis(count, -1);
  for (std::size_t f = 0; f < count; ++f) {
    const HalfSpace& h = domain.half_spaces()[faces[f]];
    for (Eigen::Index i = 0; i < h.normal.size(); ++i) {
      if (h.normal(i) != 0.0) {
        nonzeros[f] += 1.0;
        axis[f] = static_cast<int>(i);
      }
    }
  }
  if (count > 0) {
    space.sum(nonzeros.data(), static_cast<int>(count));
  }
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t f = 0; f < count; ++f) {
      const HalfSpace& h = domain.half_spaces()[faces[f]];
      if (nonzeros[f] == 1.0) {
        if (axis[f] >= 0) {
          x(axis[f]) = h.point(axis[f]);  // the bound itself: b·(x − p) is then exactly 0
        }
      } else {
        x -= domain.signed_distance(faces[f], x) * h.normal;
      }
    }
  }
}

namespace {

// Rows of BᵀT whose sines of angle are below this are parallel (the faces coincide on M to
// first order); rows of twin coordinates of a symmetric solution differ by rounding only.
constexpr double kParallelRows = 1e-8;
// A row this much shorter than another is a face nearly tangent to M, not a coincident one:
// it is kept (and the step fails as for any tangent face).
constexpr double kMinCoincidentRowRatio = 1e-3;

// SlowChord: the chord still contracted, but by less than options' max_contraction per step;
// x is left at the last iterate, nearer M ∩ faces than where it started.
enum class FaceProjection { Converged, FirstStepTooFar, SlowChord, Failed };

// Minimum-norm Gauss–Newton on F(x) = 0 together with the linear constraints of the faces in
// `faces` (g_f(x) = b_f·(x − p_f) = 0). The step reuses the linearisation of F alone: write
// dx = J⁺(−F) + T z with T the tangent basis; then J dx = −F for every z, the faces require
// (BᵀT) z = −g − Bᵀ J⁺(−F), and since J⁺(−F) ⟂ T z, the minimum-norm dx of the whole bordered
// system has the minimum-norm z of that c×2 system (Hohmann's example 3 solves the same system
// densely).
//
// The iteration of project_onto_faces. With `frozen` (a factorisation at a nearby point of M)
// it is the chord iteration: every step reuses J⁺ and T of that point and no factorisation is
// made; without, each step factors DF at the iterate (Gauss–Newton).
FaceProjection iterate_onto_faces(const ImplicitProblem& problem, const Domain& domain,
                        const std::vector<int>& faces, Eigen::VectorXd& x, double max_move,
                        const CorrectorOptions& options, double* first_contraction,
                        const Linearization* frozen) {
  // Local rows and global reductions (AmbientSpace): in one process Eigen's own norms.
  const std::shared_ptr<const AmbientSpace> shared_space = problem.space();
  const AmbientSpace& space = *shared_space;
  const bool split = space.is_distributed();
  const int c = static_cast<int>(faces.size());
  if (first_contraction != nullptr) {
    *first_contraction = 0.0;
  }
  // b·(x − p) of each face, and ‖x‖ last (one reduction on a split point).
  const auto offsets_and_norm = [&](const Eigen::VectorXd& at) {
    std::vector<double> parts(static_cast<std::size_t>(c) + 1);
    for (int f = 0; f < c; ++f) {
      const HalfSpace& h = domain.half_spaces()[faces[f]];
      parts[f] = h.normal.dot(at - h.point);
    }
    parts[c] = at.squaredNorm();
    if (split) {
      space.sum(parts.data(), c + 1);
    }
    parts[c] = std::sqrt(parts[c]);
    return parts;
  };
  const auto is_on_face = [](double offset, double norm) {
    return std::abs(offset) <= kOnFaceTolerance * (1.0 + norm);
  };
  // Only a face that x lies on from the start may be left out of the steps: a coincident face
  // the iteration reaches on its way (a chart centre snapped towards an edge of S where two
  // faces meet M in a curve) stays in, and the projection fails as it did before coincident
  // faces were recognised.
  std::vector<bool> is_on_at_start(static_cast<std::size_t>(c), false);
  if (c > 1) {
    const std::vector<double> at_start = offsets_and_norm(x);
    int on = 0;
    for (int f = 0; f < c; ++f) {
      is_on_at_start[f] = is_on_face(at_start[f], at_start[c]);
      on += is_on_at_start[f] ? 1 : 0;
    }
    if (c > 2 && on < c - 2) {
      // More faces than the surface has dimensions: no such point in general, unless all but
      // two are faces that x already lies on.
      return FaceProjection::Failed;
    }
  }
  const Eigen::VectorXd start = x;
  Eigen::VectorXd F(space.local_equations());
  Eigen::VectorXd dx(space.local_rows());
  Linearization own;
  const Linearization& linearization = frozen != nullptr ? *frozen : own;
  // The chord converges linearly: it gets more steps, and must contract by a factor 2 per step.
  const int max_steps = frozen != nullptr ? 3 * options.max_iterations : 2 * options.max_iterations;
  const double max_contraction = frozen != nullptr ? options.max_contraction : 0.9;
  // Gauss–Newton on a sparse problem may keep its factorisation while the steps contract well
  // (CorrectorOptions::reuse_factorisation; project_onto_faces retries without it).
  const bool reuse =
      frozen == nullptr && options.reuse_factorisation && problem.has_sparse_jacobian();
  int factorisations = 0;
  const auto factor_here = [&] {
    const Eigen::MatrixXd reference = own.is_factored() ? own.tangent_basis() : Eigen::MatrixXd();
    ++factorisations;
    return own.factor(problem, x, reference.size() ? &reference : nullptr);
  };
  // The faces the last step left out: x lies on them, and must still at the end.
  std::vector<int> left_out;
  // The step from x: J⁺(−F), completed by the tangential part that reaches the faces.
  const auto step = [&] {
    linearization.solve_minimum_norm(-F, dx);
    const Eigen::MatrixXd& T = linearization.tangent_basis();
    Eigen::MatrixXd BT(c, 2);
    // Per face: BᵀT's row, b·(x − p), b·dx; then ‖x‖ (one reduction on a split point).
    std::vector<double> parts(4 * static_cast<std::size_t>(c) + 1);
    for (int f = 0; f < c; ++f) {
      const HalfSpace& h = domain.half_spaces()[faces[f]];
      const Eigen::RowVector2d row = h.normal.transpose() * T;
      parts[4 * f] = row(0);
      parts[4 * f + 1] = row(1);
      parts[4 * f + 2] = h.normal.dot(x - h.point);
      parts[4 * f + 3] = h.normal.dot(dx);
    }
    parts[4 * c] = x.squaredNorm();
    if (split) {
      space.sum(parts.data(), 4 * c + 1);
    }
    const double norm = std::sqrt(parts[4 * c]);
    // The faces that constrain the step: a face whose row is a nonzero multiple of a kept
    // face's row, or comes after two kept rows (which span the tangent plane), coincides with
    // them on M to first order; where x lies on it, it is left out (with it the system would be
    // singular, or have more rows than the plane has dimensions).
    std::vector<int> kept;
    left_out.clear();
    for (int f = 0; f < c; ++f) {
      BT(f, 0) = parts[4 * f];
      BT(f, 1) = parts[4 * f + 1];
      bool is_dependent = kept.size() == 2;
      if (kept.size() == 1) {
        const Eigen::RowVector2d other = BT.row(kept[0]);
        const double size = BT.row(f).norm();
        const double cross = other(0) * BT(f, 1) - other(1) * BT(f, 0);
        is_dependent = size >= kMinCoincidentRowRatio * other.norm() &&
                       std::abs(cross) <= kParallelRows * size * other.norm();
      }
      if (is_dependent && is_on_at_start[f] && is_on_face(parts[4 * f + 2], norm)) {
        left_out.push_back(f);
      } else {
        kept.push_back(f);
      }
    }
    const int rows = static_cast<int>(kept.size());
    if (rows > 2) {
      return false;  // three independent faces: no point of the surface on all of them
    }
    Eigen::MatrixXd BT_kept(rows, 2);
    Eigen::VectorXd rhs(rows);
    for (int r = 0; r < rows; ++r) {
      const int f = kept[r];
      BT_kept.row(r) = BT.row(f);
      rhs(r) = -parts[4 * f + 2] - parts[4 * f + 3];
    }
    Eigen::VectorXd z(2);
    if (!solve_minimum_norm_dense(BT_kept, rhs, z)) {
      return false;  // a face tangent to M: the point is not isolated
    }
    dx += T * z;
    return true;
  };
  double previous = 0.0;
  for (int k = 0; k < (reuse ? 3 * max_steps : max_steps); ++k) {
    problem.evaluate(x, F);
    if (!space.all_finite(F)) {
      return FaceProjection::Failed;
    }
    if (frozen == nullptr && (!reuse || k == 0) && !factor_here()) {
      return FaceProjection::Failed;
    }
    if (!step()) {
      return FaceProjection::Failed;
    }
    if (reuse && k > 0) {
      // ‖dx‖ and ‖x‖ (one reduction on a split point).
      std::array<double, 2> norms{};
      if (split) {
        norms = {dx.squaredNorm(), x.squaredNorm()};
        space.sum(norms.data(), 2);
        norms = {std::sqrt(norms[0]), std::sqrt(norms[1])};
      } else {
        norms = {dx.norm(), x.norm()};
      }
      if (norms[0] > kReuseContraction * previous &&
          norms[0] > options.tolerance * (1.0 + norms[1])) {
        // The kept factorisation does not contract well here: the step with a new one.
        if (factorisations >= max_steps || !factor_here() || !step()) {
          return FaceProjection::Failed;
        }
      }
    }
    x += dx;
    // ‖x − start‖, ‖dx‖ and ‖x‖ (one reduction on a split point).
    std::array<double, 3> norms{};
    if (split) {
      norms = {(x - start).squaredNorm(), dx.squaredNorm(), x.squaredNorm()};
      space.sum(norms.data(), 3);
      norms = {std::sqrt(norms[0]), std::sqrt(norms[1]), std::sqrt(norms[2])};
    } else {
      norms = {(x - start).norm(), dx.norm(), x.norm()};
    }
    if (norms[0] > max_move) {
      return k == 0 ? FaceProjection::FirstStepTooFar : FaceProjection::Failed;
    }
    const double norm = norms[1];
    const bool small = norm <= options.tolerance * (1.0 + norms[2]);
    if (k == 1 && previous > 0 && first_contraction != nullptr) {
      *first_contraction = norm / previous;
    }
    if (k > 0 && previous > 0 && norm > max_contraction * previous && !small) {
      // Not contracting enough: outside the chord's (or Newton's) region of fast convergence.
      return frozen != nullptr && norm < previous && space.all_finite(x)
                 ? FaceProjection::SlowChord
                 : FaceProjection::Failed;
    }
    previous = norm;
    if (small) {
      if (!left_out.empty()) {
        // A face left out of the steps must still hold where they ended (coincident with a
        // kept one on M, not merely parallel to it there).
        const std::vector<double> at_end = offsets_and_norm(x);
        for (int f : left_out) {
          if (!is_on_face(at_end[f], at_end[c])) {
            return FaceProjection::Failed;
          }
        }
      }
      // The iteration leaves b·(x − p) at the size of the last step; a boundary vertex must lie
      // on its faces exactly (never outside S), so the last rounding-sized move puts it there.
      place_on_faces(domain, faces, x, space);
      problem.evaluate(x, F);
      return space.all_finite(F) && space.norm(F) <= options.residual_tolerance
                 ? FaceProjection::Converged
                 : FaceProjection::Failed;
    }
  }
  return FaceProjection::Failed;
}

}  // namespace

bool project_onto_faces(const ImplicitProblem& problem, const Domain& domain,
                        const std::vector<int>& faces, Eigen::VectorXd& x, double max_move,
                        const CorrectorOptions& options, double* first_contraction,
                        const Linearization* near) {
  if (near != nullptr && near->is_factored()) {
    const Eigen::VectorXd start = x;
    const FaceProjection chord = iterate_onto_faces(problem, domain, faces, x, max_move, options,
                                                    first_contraction, near);
    if (chord == FaceProjection::Converged) {
      return true;
    }
    if (chord == FaceProjection::FirstStepTooFar) {
      // To first order the point of M on the faces is farther than max_move (a face at a
      // shallow angle to M): Gauss–Newton's first step would say the same, at a price.
      return false;
    }
    if (chord == FaceProjection::SlowChord) {
      // The chord contracted, slowly: J at `near` is too far from J here. One factorisation
      // at the last iterate, already close to the solution, and the chord from it converges
      // fast (seen on bratu2d: θ = 0.5–0.9 from the neighbour's factorisation, one step in 25
      // of clipping); Gauss–Newton from the start would factor at every step.
      const double moved = problem.space()->distance(x, start);
      Linearization here;
      const Eigen::MatrixXd& reference = near->tangent_basis();
      if (moved < max_move && here.factor(problem, x, &reference) &&
          iterate_onto_faces(problem, domain, faces, x, max_move - moved, options, nullptr,
                             &here) == FaceProjection::Converged) {
        return true;
      }
    }
    x = start;
  }
  const Eigen::VectorXd start = x;
  if (iterate_onto_faces(problem, domain, faces, x, max_move, options, first_contraction,
                         nullptr) == FaceProjection::Converged) {
    return true;
  }
  if (!options.reuse_factorisation || !problem.has_sparse_jacobian()) {
    return false;
  }
  // With a kept factorisation the steps do not stay normal to M ∩ faces: on one face, where
  // that is a curve, they can drift along it past max_move (seen in clipping bratu2d). Full
  // Gauss–Newton then decides.
  x = start;
  CorrectorOptions full = options;
  full.reuse_factorisation = false;
  return iterate_onto_faces(problem, domain, faces, x, max_move, full, first_contraction,
                            nullptr) == FaceProjection::Converged;
}

}  // namespace tessera
