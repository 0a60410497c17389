// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include <iostream>

#include "tessera/geometry/mesh_validation.h"
#include "tessera/methods/front/advancing_front.h"
#include "tessera/problems/catalogue.h"

TEST(FrontSmoke, Examples) {
  for (const char* name : {"sphere", "sphere_cut", "plane", "equipotential", "whitney_pleat", "trough", "cstr", "torus"}) {
    auto setup = tessera::make_catalogue_problem(name);
    tessera::FrontOptions options;
    options.step = setup.suggested_step;
    auto result = tessera::triangulate_by_front(*setup.problem, setup.start, setup.domain, options);
    auto validation = tessera::validate(result.mesh);
    std::cout << name << ": " << tessera::to_string(result.summary.termination) << " "
              << result.summary.message << "\n V=" << result.mesh.vertex_count()
              << " T=" << result.mesh.triangle_count() << " chi=" << validation.euler_characteristic
              << " merges=" << result.summary.merges << " valid=" << validation.is_valid() << "\n";
    if (!validation.is_valid()) std::cout << validation.report() << "\n";
  }
}
