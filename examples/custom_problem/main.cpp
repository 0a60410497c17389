// SPDX-License-Identifier: MIT
// Example: cover an ellipsoid x²/a² + y²/b² + z²/c² = 1 defined here, not in tessera.
// Build against an installed tessera:  cmake -S . -B build -DCMAKE_PREFIX_PATH=<prefix>
#include <cmath>
#include <iostream>

#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/io/mesh_io.h"
#include "tessera/methods/front/advancing_front.h"

class Ellipsoid final : public tessera::ImplicitProblem {
 public:
  int ambient_dimension() const override { return 3; }  // F: R³ → R¹
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override {
    F(0) = x(0) * x(0) / 4.0 + x(1) * x(1) + x(2) * x(2) / 0.25 - 1.0;
  }
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override {  // J: 1×3
    J << x(0) / 2.0, 2.0 * x(1), 8.0 * x(2);
  }
  std::string name() const override { return "ellipsoid"; }
};

int main(int argc, char** argv) {
  Ellipsoid ellipsoid;
  tessera::FrontOptions options;
  options.step = 0.15;
  const Eigen::Vector3d start(0.0, 1.0, 0.0);
  const auto result = tessera::triangulate_by_front(ellipsoid, start, tessera::Domain(), options);
  const auto validation = tessera::validate(result.mesh);
  const auto quality = tessera::measure_quality(result.mesh, ellipsoid);
  std::cout << result.mesh.vertex_count() << " vertices, " << result.mesh.triangle_count()
            << " triangles, Euler characteristic " << validation.euler_characteristic
            << ", max |F| " << quality.vertex_residual.max << ", "
            << (validation.is_valid() ? "valid" : "INVALID") << "\n";
  if (argc > 1) {
    tessera::write_mesh(argv[1], result.mesh);
  }
  // A closed ellipsoid must close into a valid mesh with χ = 2, vertices on M.
  const bool ok = result.summary.is_complete() && validation.is_valid() &&
                  validation.euler_characteristic == 2 && quality.vertex_residual.max < 1e-8;
  return ok ? 0 : 1;
}
