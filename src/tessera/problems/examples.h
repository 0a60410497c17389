// SPDX-License-Identifier: MIT
// Example manifolds with exact analytic Jacobians: the papers' test cases and a sparse large-n BVP.
//
// Each class is an ImplicitProblem that users can construct directly, e.g.
//     tessera::Torus torus{1.0, 0.4};
// The catalogue (catalogue.h) pairs each of them with a start point, a domain and what is known
// about the manifold (Euler characteristic, area).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "tessera/core/implicit_problem.h"

namespace tessera {

/// The plane z = 0 in R³: F(x, y, z) = z. The simplest test case (flat, J constant).
class Plane final : public ImplicitProblem {
 public:
  int ambient_dimension() const override { return 3; }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override;
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override;
  std::string name() const override { return "plane"; }
  bool is_thread_safe() const override { return true; }  // a pure function of x
};

/// The sphere |x|² − r² = 0 in R³, centred at the origin.
class Sphere final : public ImplicitProblem {
 public:
  /// \throw InvalidArgument unless radius is finite and > 0.
  explicit Sphere(double radius = 1.0);

  int ambient_dimension() const override { return 3; }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override;
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override;
  std::string name() const override { return "sphere"; }
  bool is_thread_safe() const override { return true; }  // a pure function of x
  double radius() const { return radius_; }

 private:
  double radius_;
};

/// The torus about the first coordinate axis in Hohmann's polynomial form
///     F(y) = (|y|² + R² − r²)² − 4R²(y₂² + y₃²),
/// the points at distance r from the circle of radius R in the plane y₁ = 0.
/// \see Hohmann, "An adaptive continuation method for implicitly defined surfaces", ZIB report
///      SC 91-20 (1991), example 4 (after Allgower & Gnutzmann).
class Torus final : public ImplicitProblem {
 public:
  /// \throw InvalidArgument unless 0 < minor_radius < major_radius (finite); for r ≥ R the
  ///        surface has singular points on the axis.
  Torus(double major_radius = 1.0, double minor_radius = 0.4);

  int ambient_dimension() const override { return 3; }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override;
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override;
  std::string name() const override { return "torus"; }
  bool is_thread_safe() const override { return true; }  // a pure function of x
  double major_radius() const { return major_radius_; }
  double minor_radius() const { return minor_radius_; }

 private:
  double major_radius_;
  double minor_radius_;
};

/// Bloomenthal's equipotential surface of two point charges ("blobby" molecule):
///     F(y) = r_p²/|y − p|² + r_q²/|y − q|² − c,   p = (0, 0, 0),  q = (0, q_y, 0),  r_p = r_q = 1.
/// F is singular (+infinity) at p and q; both lie inside the surface.
/// \see Bloomenthal, "Polygonization of implicit surfaces", CAGD 5 (1988); Hohmann (1991),
///      example 2, with c = 1.7 and the start (0, −0.8, 0).
class Equipotential final : public ImplicitProblem {
 public:
  /// \throw InvalidArgument unless level > 0 and separation is finite.
  explicit Equipotential(double level = 1.7, double separation = 2.0);

  int ambient_dimension() const override { return 3; }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override;
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override;
  std::string name() const override { return "equipotential"; }
  bool is_thread_safe() const override { return true; }  // a pure function of x

 private:
  double level_;       // c
  double separation_;  // q_y, the second charge sits at (0, q_y, 0)
};

/// Whitney's pleat (the cusp catastrophe surface) F(x, λ, μ) = x³ − λx − μ in coordinates
/// (x, lambda, mu). It is the graph μ = x³ − λx over the (x, λ) plane; its projection to the
/// (λ, μ) plane folds along 3x² = λ and has a cusp at the origin. \see Hohmann (1991), example 3.
class WhitneyPleat final : public ImplicitProblem {
 public:
  int ambient_dimension() const override { return 3; }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override;
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override;
  std::string name() const override { return "whitney_pleat"; }
  bool is_thread_safe() const override { return true; }  // a pure function of x
  std::vector<std::string> coordinate_names() const override { return {"x", "lambda", "mu"}; }
  /// x' = −F = −V'(x) for the potential V = x⁴/4 − λx²/2 − μx: the outer sheets (3x² > λ) are
  /// stable, the middle one unstable; parameters (lambda, mu).
  std::optional<Dynamics> dynamics() const override;
};

/// Melville and Mackey's trough F(x, y, z) = z (a² z² (b² − z²) − x²) + ε, a cylinder in y over a
/// plane curve. For ε = 0 the curve is the line z = 0 together with the figure-eight
/// x² = a² z² (b² − z²) (lobes of half-width a b²/2 at z = ±b/√2); ε > 0 separates them into an
/// arch over the upper lobe (z > 0, reaching down to the line far from the lobe) and a loop
/// inside the lower lobe. The narrow gaps of width O(ε) make it a hard test of step control.
/// \see Melville & Mackey, "A new algorithm for two-dimensional numerical continuation" (1994),
///      as used by Brodzik & Rheinboldt, "On the computation of simplicial approximations of
///      implicitly defined two-dimensional manifolds", section 5, figure 5.4.
class Trough final : public ImplicitProblem {
 public:
  /// \throw InvalidArgument unless a, b > 0 and ε are finite.
  Trough(double a = 4.0, double b = 0.25, double epsilon = 5e-5);

  int ambient_dimension() const override { return 3; }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override;
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override;
  std::string name() const override { return "trough"; }
  bool is_thread_safe() const override { return true; }  // a pure function of x

 private:
  double a_;
  double b_;
  double epsilon_;
};

/// Steady states of a continuous stirred tank reactor with a first-order exothermic reaction,
/// in coordinates (x1, x2, Da, B): rescaled concentration x1, dimensionless temperature x2,
/// Damköhler number Da, adiabatic temperature rise B, and heat transfer coefficient β (the limit
/// of infinite activation energy and zero cooling temperature):
///     f₁ = −x₁ + Da (1 − x₁) exp(x₂),
///     f₂ = −(1 + β) x₂ + B Da (1 − x₁) exp(x₂).
/// The manifold is the graph x₂ = B x₁/(1 + β), Da = x₁ exp(−x₂)/(1 − x₁) over (x₁, B) with
/// x₁ < 1; see point_on_manifold. Seen as a function of Da it folds (ignition and extinction).
/// \see Hohmann (1991), example 5, after Uppal, Ray & Poore, Chem. Engng. Sci. 29 (1974).
class StirredTankReactor final : public ImplicitProblem {
 public:
  /// \throw InvalidArgument unless beta is finite and > −1.
  explicit StirredTankReactor(double beta = 0.5);

  int ambient_dimension() const override { return 4; }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override;
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override;
  std::string name() const override { return "cstr"; }
  bool is_thread_safe() const override { return true; }  // a pure function of x
  std::vector<std::string> coordinate_names() const override { return {"x1", "x2", "Da", "B"}; }
  /// (x₁, x₂)' = (f₁, f₂), parameters (Da, B). On M, with a = x₁/(1 − x₁), D_uF has trace
  /// B x₁ − (2 + β) − a and determinant (1 + β)/(1 − x₁) − B x₁: folds where the determinant
  /// vanishes, Hopf bifurcations where the trace does with a positive determinant (x₁ > 1/(1+β)),
  /// a Bogdanov–Takens point where both do (x₁ = 1/(1 + β)).
  std::optional<Dynamics> dynamics() const override;

  /// The point of M with concentration x1 and temperature rise B (exact parametrisation).
  /// \pre x1 < 1.
  Eigen::VectorXd point_on_manifold(double x1, double B) const;

 private:
  double beta_;
};

/// The Gelfand–Bratu problem with Arrhenius nonlinearity, a two-parameter boundary value problem
///     u'' + λ exp(u / (1 + ε u)) = 0 on (0, 1),  u(0) = u(1) = 0,
/// discretised by central differences on N interior points x_i = i h, h = 1/(N + 1).
/// Coordinates (u1 … uN, lambda, epsilon), n = N + 2. Equation i, multiplied by h² so that J has
/// O(1) entries and |F| is not amplified by 1/h² rounding:
///     F_i = u_{i−1} − 2 u_i + u_{i+1} + h² λ exp(u_i / (1 + ε u_i)),   u_0 = u_{N+1} = 0.
/// For ε below about 0.2457 the branch λ ↦ u is S-shaped (ignition and extinction folds); the
/// two fold curves meet in a cusp near ε ≈ 0.2457, max u ≈ 4.9, λ ≈ 5.22 (N = 100), so M is a
/// genuine fold surface over the (λ, ε) plane.
///
/// Scale: the u-block dominates Euclidean distances in R^n. Moving along M changes the discrete
/// profile u by a vector of norm ≈ 0.7–0.8 √N times the change of its maximum, while λ and ε
/// move by O(1) and O(0.1): seen in the (λ, ε) plane, a mesh with uniform edges in R^n is dense
/// along the branches and coarse across them, and near u = 0 (where ε hardly matters) M is a
/// strip only ≈ 0.3 wide.
///
/// J is tridiagonal in the u-block plus two dense columns: has_sparse_jacobian() is true.
/// \see Brown, Ibrahim & Shivaji, "S-shaped bifurcation curves", Nonlinear Anal. 5 (1981).
class ArrheniusBratu final : public ImplicitProblem {
 public:
  /// \throw InvalidArgument unless point_count >= 1.
  explicit ArrheniusBratu(int point_count = 100);

  int ambient_dimension() const override { return point_count_ + 2; }
  int point_count() const { return point_count_; }

  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override;
  /// Dense N×(N+2) form; fine for small N, O(N²) memory.
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override;
  bool has_sparse_jacobian() const override { return true; }
  /// 5N − 2 nonzeros in compressed column storage. When J already has this problem's shape the
  /// storage is reused, so repeated calls do not allocate.
  void sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                       Eigen::SparseMatrix<double>& J) const override;
  std::string name() const override { return "bvp"; }
  bool is_thread_safe() const override { return true; }  // a pure function of x
  /// The heat equation u_t = u'' + λ exp(u/(1 + εu)) discretised like F: h²·u' = F, so B = h²·I
  /// and the eigenvalues are those of the discrete operator; parameters (lambda, epsilon).
  std::optional<Dynamics> dynamics() const override;
  std::vector<std::string> coordinate_names() const override;
  /// One block "u" (the N grid values) of weight √h, h = 1/(N + 1): the metric's norm of u is
  /// the discrete L² norm, so lengths on M do not grow with N.
  std::vector<CoordinateBlock> coordinate_blocks() const override;

  /// The point of M whose profile has maximum value `amplitude` (taken at the middle grid point
  /// ⌊(N+1)/2⌋), at the given ε. Positive solutions are symmetric and determined by (u_max, ε),
  /// so this reaches every branch, folds included. Computed by continuation in the amplitude
  /// from u = 0, with Newton's method on F together with u_mid = amplitude.
  /// \pre amplitude >= 0, epsilon >= 0.
  /// \throw ComputationFailed if Newton's method does not converge (the message says where).
  Eigen::VectorXd point_with_amplitude(double amplitude, double epsilon) const;

 private:
  int point_count_;
};

/// The two-dimensional Gelfand–Bratu problem with Arrhenius nonlinearity on the unit square,
///     Δu + λ exp(u / (1 + ε u)) = 0 on (0, 1)²,  u = 0 on the boundary,
/// discretised by the five-point Laplacian on the N×N interior grid (i h, j h), h = 1/(N + 1).
/// Coordinates (u_1_1, u_1_2, … u_N_N, lambda, epsilon), row-major (u_i_j at index (i−1)N + j−1,
/// i the row, y = i h; j the column, x = j h), n = N² + 2. Equation (i, j), multiplied by h² as in
/// the one-dimensional ArrheniusBratu, with φ(u) = u / (1 + ε u):
///     F_ij = u_{i−1,j} + u_{i+1,j} + u_{i,j−1} + u_{i,j+1} − 4 u_ij + h² λ exp(φ(u_ij)),
/// with u = 0 on the boundary (i or j = 0 or N + 1).
///
/// The fold surface, from scans of λ along the centre value u_c at fixed ε with
/// point_with_amplitude (bench/bratu2d_folds.cpp; N = 32, with N = 15 in brackets where it differs
/// by more than the last digit shown):
/// - ε = 0 (Gelfand's problem): one fold, λ* = 6.807 (6.802) at u_c = 1.39; λ → 0 as u_c → ∞.
///   The continuous problem's λ* ≈ 6.808.
/// - 0 < ε < ε_c: S-shaped branches, an ignition fold (largest λ) and, at larger u_c, an
///   extinction fold (smallest λ): ε = 0.1: ignition at u_c = 1.81, λ = 7.698 (no extinction
///   fold below u_c = 20); ε = 0.2: u_c = 2.88, λ = 9.133 and u_c = 18.2, λ = 7.097;
///   ε = 0.22: u_c = 3.44, λ = 9.574 and u_c = 12.5, λ = 8.795; ε = 0.24: u_c = 5.01,
///   λ = 10.163 and u_c = 7.21, λ = 10.145.
/// - The two fold curves meet in a cusp at ε_c = 0.2418 (0.2420), u_c = 5.96, λ = 10.236
///   (10.224), close to the 1-D problem's ε_c ≈ 0.2457; for ε > ε_c, λ increases with u_c
///   (ε = 0.3: λ = 18.93 at u_c = 20).
///
/// J is the five-point stencil in the u-block plus two dense columns: has_sparse_jacobian() is
/// true and `jacobian` (dense (N²)×(N²+2)) is for small N only.
/// \see Bebernes & Eberly, "Mathematical Problems from Combustion Theory" (1989).
class ArrheniusBratu2D final : public ImplicitProblem {
 public:
  /// Grids up to 1000×1000 (n ≈ 10⁶). The sparse LU of the bordered Jacobian grows like
  /// n log n in memory (10⁷ nonzeros at N = 316, bench/history/RESULTS-log.md section 9), so the
  /// largest grids need gigabytes and seconds per factorisation.
  static constexpr int kMaxGridSize = 1000;

  /// \throw InvalidArgument unless 1 <= grid_size <= kMaxGridSize.
  explicit ArrheniusBratu2D(int grid_size = 32);

  int ambient_dimension() const override { return grid_size_ * grid_size_ + 2; }
  /// N, the number of interior grid points per side.
  int grid_size() const { return grid_size_; }
  /// Index of the centre value u_c, the grid point (⌊(N+1)/2⌋, ⌊(N+1)/2⌋) where u is largest.
  int centre_index() const;

  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override;
  /// Dense N²×(N²+2) form; O(N⁴) memory, for small N only.
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override;
  bool has_sparse_jacobian() const override { return true; }
  /// 7N² − 4N nonzeros in compressed column storage (the five-point stencil, 5N² − 4N, and two
  /// dense columns). When J already has this problem's shape the storage is reused, so repeated
  /// calls do not allocate.
  void sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                       Eigen::SparseMatrix<double>& J) const override;
  std::string name() const override { return "bratu2d"; }
  /// u_t = Δu + λ exp(u/(1 + εu)) discretised like F: h²·u' = F, B = h²·I; parameters
  /// (lambda, epsilon).
  std::optional<Dynamics> dynamics() const override;
  /// u_1_1 … u_N_N (row, column), lambda, epsilon.
  std::vector<std::string> coordinate_names() const override;
  /// One block "u" (the N² grid values) of weight h = 1/(N + 1): the metric's norm of u,
  /// h·‖u‖ = (h² Σ u_ij²)^½, approximates the L² norm on the unit square, so lengths on M do not
  /// grow with N.
  std::vector<CoordinateBlock> coordinate_blocks() const override;

  /// The point of M whose centre value is u_c = `amplitude`, at the given ε. Positive solutions
  /// are symmetric and, on the branches tessera meets, determined by (u_c, ε), so this reaches
  /// the folds too. Computed by continuation in the amplitude from u = 0 (tangent predictor),
  /// with Newton's method on F together with u_c = amplitude (a sparse LU of the bordered
  /// (N²+1)×(N²+1) system per iteration, regular through the folds of λ ↦ u).
  /// \pre amplitude >= 0, epsilon >= 0.
  /// \throw ComputationFailed if Newton's method does not converge (the message says where).
  Eigen::VectorXd point_with_amplitude(double amplitude, double epsilon) const;

 private:
  int grid_size_;
};

}  // namespace tessera
