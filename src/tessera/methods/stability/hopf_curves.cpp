// SPDX-License-Identifier: MIT
#include "tessera/methods/stability/hopf_curves.h"

#include <chrono>
#include <cmath>
#include <complex>

#include "tessera/core/error.h"
#include "tessera/core/metric_problem.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/methods/common/zero_set_curves.h"
#include "tessera/methods/stability/lyapunov.h"
#include "tessera/methods/stability/state_jacobian.h"

namespace tessera {

int HopfCurves::point_count() const {
  int count = 0;
  for (const HopfCurve& curve : curves) {
    count += static_cast<int>(curve.points.size());
  }
  return count;
}

namespace {

// What the marching and the first Newton guess need of a vertex's spectrum.
struct VertexSpectrum {
  double value = std::numeric_limits<double>::quiet_NaN();  // the bialternate product's stand-in
  bool is_complex = false;  // the pair with the smallest |μᵢ + μⱼ| is a complex one
  double omega = 0.0;       // its Im μ (complex)
  double kappa = 0.0;       // half the distance of the real pair (real)
  bool is_partial = false;  // only the eigenvalues nearest 0 were computed (sparse problems)
  int real_unstable = 0;    // computed real eigenvalues with Re > 0
};

VertexSpectrum spectrum_of(const VertexStability& vertex, double threshold) {
  VertexSpectrum spectrum;
  if (vertex.has_failed()) {
    return spectrum;
  }
  std::vector<double> reals;
  std::vector<std::complex<double>> pairs;  // Im > 0 representatives
  // Where only the eigenvalues nearest 0 were computed, the set changes from vertex to vertex:
  // an eigenvalue entering it at the rim, or a stable pair turning real, would flip the
  // product's sign with no bifurcation between. There the value's sign is the parity of the
  // complex pairs with positive real part well inside the examined disk (Hopf points only: the
  // neutral saddles, sums of two real eigenvalues, are not looked for), and a crossing where a
  // real eigenvalue changes sign too is left out (find_hopf_curves).
  spectrum.is_partial = std::isfinite(vertex.examined_radius);
  if (spectrum.is_partial) {
    int unstable_pairs = 0;
    double nearest = std::numeric_limits<double>::infinity();
    for (const std::complex<double>& mu : vertex.eigenvalues) {
      const bool is_real = std::abs(mu.imag()) <= threshold * std::max(1.0, std::abs(mu));
      if (is_real) {
        spectrum.real_unstable += mu.real() > 0.0;
      } else if (mu.imag() > 0.0 && std::abs(mu) <= 0.9 * vertex.examined_radius) {
        unstable_pairs += mu.real() > 0.0;
        if (2 * std::abs(mu.real()) < nearest) {
          nearest = 2 * std::abs(mu.real());
          spectrum.is_complex = true;
          spectrum.omega = mu.imag();
        }
      }
    }
    const double magnitude =
        std::max(std::isfinite(nearest) ? nearest : 1.0, std::numeric_limits<double>::min());
    spectrum.value = unstable_pairs % 2 == 0 ? magnitude : -magnitude;
    return spectrum;
  }
  for (const std::complex<double>& mu : vertex.eigenvalues) {
    const bool is_real = std::abs(mu.imag()) <= threshold * std::max(1.0, std::abs(mu));
    if (is_real) {
      reals.push_back(mu.real());
    } else if (mu.imag() > 0.0) {
      pairs.push_back(mu);
    }
  }
  bool negative = false;
  double smallest = std::numeric_limits<double>::infinity();
  for (const auto& mu : pairs) {
    negative ^= mu.real() < 0.0;
    if (2 * std::abs(mu.real()) < smallest) {
      smallest = 2 * std::abs(mu.real());
      spectrum.is_complex = true;
      spectrum.omega = mu.imag();
    }
  }
  for (std::size_t i = 0; i < reals.size(); ++i) {
    for (std::size_t j = i + 1; j < reals.size(); ++j) {
      const double sum = reals[i] + reals[j];
      negative ^= sum < 0.0;
      if (std::abs(sum) < smallest) {
        smallest = std::abs(sum);
        spectrum.is_complex = false;
        spectrum.kappa = std::abs(reals[i] - reals[j]) / 2;
      }
    }
  }
  if (!std::isfinite(smallest)) {
    smallest = 1.0;  // fewer than two eigenvalues: no crossing can involve this vertex
  }
  // 0 counts as positive in the marching: keep the sign on a zero magnitude.
  smallest = std::max(smallest, std::numeric_limits<double>::min());
  spectrum.value = negative ? -smallest : smallest;
  return spectrum;
}

}  // namespace

HopfCurves find_hopf_curves(const ImplicitProblem& problem, const TriangleMesh& mesh,
                            const StabilityResult& stability, const HopfCurveOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  required_dynamics(problem, "Hopf curves");
  TESSERA_CHECK(static_cast<int>(stability.vertices.size()) == mesh.vertex_count(),
                "Hopf curves: the stability has " << stability.vertices.size()
                                                  << " vertices, the mesh "
                                                  << mesh.vertex_count());
  TESSERA_CHECK(mesh.ambient_dimension() == problem.ambient_dimension(),
                "Hopf curves: the mesh lies in R^" << mesh.ambient_dimension() << ", problem '"
                                                   << problem.name() << "' in R^"
                                                   << problem.ambient_dimension());
  HopfCurves result;
  if (mesh.triangle_count() == 0) {
    return result;
  }
  const int vertex_count = mesh.vertex_count();
  std::vector<VertexSpectrum> spectra(static_cast<std::size_t>(vertex_count));
  std::vector<double> values(static_cast<std::size_t>(vertex_count));
  for (int v = 0; v < vertex_count; ++v) {
    spectra[static_cast<std::size_t>(v)] =
        spectrum_of(stability.vertices[static_cast<std::size_t>(v)], options.complex_threshold);
    values[static_cast<std::size_t>(v)] = spectra[static_cast<std::size_t>(v)].value;
  }
  const MeshTopology topology(mesh);
  const ZeroSetCurves zero_set = find_zero_set_curves(mesh, topology, values);
  result.crossing_count = zero_set.crossing_count;
  const MetricProblem metric(problem);
  auto metric_length = [&](const Eigen::VectorXd& d) { return metric.length(d); };
  auto edge_length = [&](int c) {
    const auto& crossing = zero_set.crossings[static_cast<std::size_t>(c)];
    return metric_length(mesh.point(crossing.vertices[1]) - mesh.point(crossing.vertices[0]));
  };

  // Each crossing refined: a Hopf point or a neutral saddle, whichever its vertices suggest
  // first; nothing when Newton converges to neither.
  auto refine = [&](int c) -> std::optional<HopfPoint> {
    const ZeroSetCrossing& crossing = zero_set.crossings[static_cast<std::size_t>(c)];
    const Eigen::VectorXd estimate = crossing_point(crossing, mesh.points());
    const VertexSpectrum& a = spectra[static_cast<std::size_t>(crossing.vertices[0])];
    const VertexSpectrum& b = spectra[static_cast<std::size_t>(crossing.vertices[1])];
    const double reach = options.max_displacement_in_edges * edge_length(c);
    const double omega = a.is_complex && b.is_complex ? a.omega + crossing.fraction * (b.omega - a.omega)
                         : a.is_complex                ? a.omega
                         : b.is_complex                ? b.omega
                                                       : 0.0;
    const double kappa = !a.is_complex && !b.is_complex ? a.kappa + crossing.fraction * (b.kappa - a.kappa)
                         : !a.is_complex                 ? a.kappa
                         : !b.is_complex                 ? b.kappa
                                                         : 0.0;
    const bool hopf_first = a.is_complex || b.is_complex;
    const bool is_partial = a.is_partial || b.is_partial;
    if (is_partial && a.real_unstable != b.real_unstable) {
      ++result.mixed_crossing_count;  // a pair turned real, or a fold: no Hopf point to find
      return std::nullopt;
    }
    const int attempts = is_partial ? 1 : 2;  // no neutral saddles where the set is partial
    for (int attempt = 0; attempt < attempts; ++attempt) {
      const bool try_hopf = (attempt == 0) == hopf_first;
      HopfPoint point =
          try_hopf ? refine_hopf_point(problem, estimate, omega, reach, options.newton, result.work)
                   : refine_neutral_saddle_point(problem, estimate, kappa, reach, options.newton,
                                                 result.work);
      result.newton_iterations += point.iterations;
      // A Hopf point with ω = 0 or a neutral saddle with κ = 0 is a fold point, not one of them.
      const double parameter = try_hopf ? point.omega : point.kappa;
      if (point.is_refined && parameter > options.complex_threshold) {
        return point;
      }
    }
    ++result.unrefined_count;
    return std::nullopt;
  };

  // The sign of the product of the real eigenvalues at a point of M (0 if they fail there).
  const int state_count = problem.ambient_dimension() - 2;
  auto real_eigenvalue_sign = [&](const Eigen::VectorXd& x) {
    const VertexStability s = stability_at(problem, x);
    if (s.has_failed()) {
      return 0;
    }
    int sign = 1;
    for (const std::complex<double>& mu : s.eigenvalues) {
      if (std::abs(mu.imag()) <= options.complex_threshold * std::max(1.0, std::abs(mu)) &&
          mu.real() < 0.0) {
        sign = -sign;
      }
    }
    return sign;
  };

  // Regula falsi (Illinois) on l₁ over the chord from a to b, each trial point refined onto the
  // Hopf curve; stops when the bracket is below 10⁻⁸ of the chord or after 40 trials.
  auto locate_bautin = [&](const HopfPoint& a, const HopfPoint& b) -> std::optional<HopfPoint> {
    const Eigen::VectorXd chord = b.x - a.x;
    const double reach = (options.max_displacement_in_edges + 1.0) * metric.length(chord);
    double s_lo = 0.0, s_hi = 1.0;
    double l_lo = a.first_lyapunov_coefficient, l_hi = b.first_lyapunov_coefficient;
    int side = 0;
    std::optional<HopfPoint> best;
    for (int trial = 0; trial < 40 && (s_hi - s_lo) > 1e-8; ++trial) {
      const double s = (s_lo * l_hi - s_hi * l_lo) / (l_hi - l_lo);
      const double omega = a.omega + s * (b.omega - a.omega);
      HopfPoint point = refine_hopf_point(problem, a.x + s * chord, omega, reach, options.newton,
                                          result.work);
      result.newton_iterations += point.iterations;
      if (!point.is_refined) {
        break;
      }
      const double l = first_lyapunov_coefficient(problem, point.x, point.omega);
      if (!std::isfinite(l)) {
        break;
      }
      point.first_lyapunov_coefficient = l;
      best = point;
      if (l == 0.0) {
        break;
      }
      if ((l > 0.0) == (l_lo > 0.0)) {
        s_lo = s;
        l_lo = l;
        if (side == 1) {
          l_hi /= 2;
        }
        side = 1;
      } else {
        s_hi = s;
        l_hi = l;
        if (side == -1) {
          l_lo /= 2;
        }
        side = -1;
      }
    }
    if (best) {
      best->is_bautin = true;
    }
    return best;
  };

  std::vector<Eigen::VectorXd> bogdanov_takens_points;
  auto try_bogdanov_takens = [&](const Eigen::VectorXd& from, double reach) -> std::optional<HopfPoint> {
    HopfPoint bt = refine_bogdanov_takens_point(problem, from, reach, options.newton, result.work);
    result.newton_iterations += bt.iterations;
    if (!bt.is_refined) {
      return std::nullopt;
    }
    bt.is_bogdanov_takens = true;
    result.max_residual = std::max(result.max_residual, bt.residual);
    bool is_known = false;
    for (const Eigen::VectorXd& known : bogdanov_takens_points) {
      is_known = is_known || metric_length(known - bt.x) <= 1e-6 * (1.0 + metric_length(known));
    }
    if (!is_known) {
      bogdanov_takens_points.push_back(bt.x);
      ++result.bogdanov_takens_count;
    }
    return bt;
  };

  for (const ZeroSetChain& chain : zero_set.chains) {
    const std::vector<int>& crossings = chain.crossings;
    const int m = static_cast<int>(crossings.size());
    std::vector<std::optional<HopfPoint>> points(static_cast<std::size_t>(m));
    for (int i = 0; i < m; ++i) {
      points[static_cast<std::size_t>(i)] = refine(crossings[static_cast<std::size_t>(i)]);
    }
    // Pieces: maximal runs of refined points of one kind. A closed chain is walked from a cut (a
    // point that failed or a change of kind) when it has one.
    auto kind_of = [&](int i) {
      const auto& p = points[static_cast<std::size_t>((i % m + m) % m)];
      return p ? (p->is_neutral_saddle ? 1 : 0) : -1;
    };
    int first = 0;
    bool is_closed = chain.is_closed;
    if (is_closed) {
      for (int i = 0; i < m; ++i) {
        if (kind_of(i) != kind_of(i - 1) || kind_of(i) < 0) {
          first = i;
          is_closed = false;
          break;
        }
      }
    }
    std::vector<HopfCurve> pieces;
    std::vector<std::pair<int, int>> piece_ends;  // chain indices of each piece's first and last
    for (int k = 0; k < m; ++k) {
      const int i = (first + k) % m;
      const int kind = kind_of(i);
      if (kind < 0) {
        continue;
      }
      if (pieces.empty() || k == 0 || kind_of(i - 1) != kind || piece_ends.back().second != (i - 1 + m) % m) {
        pieces.emplace_back();
        pieces.back().is_neutral_saddle = kind == 1;
        piece_ends.emplace_back(i, i);
      }
      pieces.back().points.push_back(*points[static_cast<std::size_t>(i)]);
      piece_ends.back().second = i;
    }
    if (pieces.size() == 1 && is_closed) {
      pieces.front().is_closed = true;
    }
    // Bogdanov–Takens points: between neighbouring pieces of different kinds, and at the ends of
    // Hopf pieces inside the mesh (where the neutral saddles were not seen).
    for (std::size_t p = 0; p < pieces.size(); ++p) {
      HopfCurve& piece = pieces[p];
      if (piece.is_closed) {
        continue;
      }
      for (const bool at_front : {true, false}) {
        const int c_index = at_front ? piece_ends[p].first : piece_ends[p].second;
        const int c = crossings[static_cast<std::size_t>(c_index)];
        const int neighbour_index = at_front ? c_index - 1 : c_index + 1;
        const bool has_neighbour = chain.is_closed || (neighbour_index >= 0 && neighbour_index < m);
        const int neighbour_kind = has_neighbour ? kind_of(neighbour_index) : -1;
        const bool kind_changes = neighbour_kind >= 0 && neighbour_kind != (piece.is_neutral_saddle ? 1 : 0);
        const bool interior_end = !has_neighbour && !piece.is_neutral_saddle &&
                                  topology.edge_triangles(zero_set.crossings[static_cast<std::size_t>(c)].edge).size() == 2;
        if (!kind_changes && !interior_end) {
          continue;
        }
        if (kind_changes && piece.is_neutral_saddle) {
          continue;  // found from the Hopf side, which starts nearer (ω → 0 there)
        }
        const HopfPoint& end = at_front ? piece.points.front() : piece.points.back();
        const auto bt = try_bogdanov_takens(end.x, (options.max_displacement_in_edges + 1.0) * edge_length(c));
        if (!bt) {
          continue;
        }
        if (at_front) {
          piece.points.insert(piece.points.begin(), *bt);
        } else {
          piece.points.push_back(*bt);
        }
        if (kind_changes) {  // the neutral saddle piece beside it ends there too
          const std::size_t other = at_front ? p - 1 : p + 1;
          if (other < pieces.size()) {
            auto& neighbour = pieces[other].points;
            if (at_front) {
              neighbour.push_back(*bt);
            } else {
              neighbour.insert(neighbour.begin(), *bt);
            }
          }
        }
        if (piece.points.size() == 2 && piece_ends[p].first == piece_ends[p].second) {
          break;  // one crossing: its two ends are the same point
        }
      }
    }
    // Fold–Hopf points: along a Hopf curve, a real eigenvalue crosses 0 where the sign of the
    // product of the real eigenvalues changes between neighbouring points (n − 2 ≥ 3).
    if (state_count >= 3) {
      for (HopfCurve& piece : pieces) {
        if (piece.is_neutral_saddle) {
          continue;
        }
        std::vector<int> signs;
        for (const HopfPoint& point : piece.points) {
          signs.push_back(point.is_bogdanov_takens ? 0 : real_eigenvalue_sign(point.x));
        }
        for (std::size_t i = piece.points.size(); i-- > 1;) {
          if (signs[i] == 0 || signs[i - 1] == 0 || signs[i] == signs[i - 1]) {
            continue;
          }
          const HopfPoint& a = piece.points[i - 1];
          const HopfPoint& b = piece.points[i];
          HopfPoint zero_hopf = refine_zero_hopf_point(
              problem, 0.5 * (a.x + b.x), 0.5 * (a.omega + b.omega),
              (options.max_displacement_in_edges + 1.0) * metric_length(b.x - a.x), options.newton,
              result.work);
          result.newton_iterations += zero_hopf.iterations;
          if (zero_hopf.is_refined && zero_hopf.omega > options.complex_threshold) {
            ++result.zero_hopf_count;
            piece.points.insert(piece.points.begin() + static_cast<std::ptrdiff_t>(i), std::move(zero_hopf));
          }
        }
      }
    }
    // The first Lyapunov coefficient at the Hopf points, and Bautin points where it changes
    // sign (dense problems; NaN elsewhere).
    for (HopfCurve& piece : pieces) {
      if (piece.is_neutral_saddle) {
        continue;
      }
      for (HopfPoint& point : piece.points) {
        if (!point.is_bogdanov_takens && !point.is_zero_hopf) {
          point.first_lyapunov_coefficient = first_lyapunov_coefficient(problem, point.x, point.omega);
        }
      }
      for (std::size_t i = piece.points.size(); i-- > 1;) {
        const HopfPoint& a = piece.points[i - 1];
        const HopfPoint& b = piece.points[i];
        const double la = a.first_lyapunov_coefficient;
        const double lb = b.first_lyapunov_coefficient;
        if (!(la * lb < 0.0)) {
          continue;  // same sign, or not computed (NaN)
        }
        if (auto bautin = locate_bautin(a, b)) {
          ++result.bautin_count;
          piece.points.insert(piece.points.begin() + static_cast<std::ptrdiff_t>(i), std::move(*bautin));
        }
      }
    }
    for (HopfCurve& piece : pieces) {
      for (const HopfPoint& point : piece.points) {
        if (point.is_bogdanov_takens || point.is_zero_hopf || point.is_bautin) {
          continue;
        }
        (point.is_neutral_saddle ? result.neutral_saddle_point_count : result.hopf_point_count) += 1;
        result.max_residual = std::max(result.max_residual, point.residual);
        result.max_condition_residual =
            std::max(result.max_condition_residual, point.condition_residual);
      }
      result.curves.push_back(std::move(piece));
    }
  }
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

}  // namespace tessera
