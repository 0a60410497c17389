// SPDX-License-Identifier: MIT
// The peer at n = 3 (issue 35): CGAL's surface mesher (Boissonnat–Oudot, CGAL::make_surface_mesh)
// on a catalogue surface, F taken from tessera's own problem so that both mesh the same M.
// Writes the mesh as OBJ for `tessera check` (which measures it against M as it measures
// tessera's) and prints the mesher's own time. bench/vs_cgal.sh runs it beside `tessera mesh`.
//
// Usage: tessera_cgal_surface_mesher SURFACE DISTANCE_BOUND OUT.obj [RADIUS_BOUND]
//   DISTANCE_BOUND: CGAL's bound on the distance between a facet's circumcentre and the centre
//   of its surface Delaunay ball (about the facet's distance to M); RADIUS_BOUND defaults to
//   what the accuracy allows on a unit sphere, sqrt(8·bound), i.e. no constraint of its own.
#include <CGAL/Complex_2_in_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/facets_in_complex_2_to_triangle_mesh.h>
#include <CGAL/Implicit_surface_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_default_triangulation_3.h>
#include <CGAL/make_surface_mesh.h>

#include <Eigen/Core>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "tessera/problems/catalogue.h"

namespace {

using Tr = CGAL::Surface_mesh_default_triangulation_3;
using C2t3 = CGAL::Complex_2_in_triangulation_3<Tr>;
using GT = Tr::Geom_traits;
using Sphere_3 = GT::Sphere_3;
using Point_3 = GT::Point_3;
using FT = GT::FT;

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s SURFACE DISTANCE_BOUND OUT.obj [RADIUS_BOUND]\n", argv[0]);
    return 2;
  }
  const tessera::ProblemSetup setup = tessera::make_catalogue_problem(argv[1]);
  const tessera::ImplicitProblem& problem = *setup.problem;
  if (problem.ambient_dimension() != 3) {
    std::fprintf(stderr, "%s: not a surface in R^3\n", argv[1]);
    return 2;
  }
  const double distance_bound = std::atof(argv[2]);
  const double radius_bound = argc > 4 ? std::atof(argv[4]) : std::sqrt(8.0 * distance_bound);
  Eigen::VectorXd x(3), value(1);
  const auto F = [&](double a, double b, double c) {
    x << a, b, c;
    problem.evaluate(x, value);
    return value(0);
  };
  // CGAL wants F < 0 at the bounding sphere's centre: a point just inside M from the start (on
  // the side where F has the opposite sign to far away), and a sphere around all of M.
  const double far_sign = F(100.0, 100.0, 100.0) > 0 ? 1.0 : -1.0;
  Eigen::VectorXd start = setup.start;
  Eigen::Vector3d gradient;
  for (int k = 0; k < 3; ++k) {
    const double h = 1e-6;
    Eigen::Vector3d e = Eigen::Vector3d::Zero();
    e(k) = h;
    gradient(k) = (F(start(0) + e(0), start(1) + e(1), start(2) + e(2)) -
                   F(start(0) - e(0), start(1) - e(1), start(2) - e(2))) /
                  (2 * h);
  }
  const Eigen::Vector3d inside = start.head<3>() - 0.02 * far_sign * gradient.normalized();
  const double sign = far_sign;  // s·F < 0 inside, > 0 far away
  if (!(sign * F(inside(0), inside(1), inside(2)) < 0)) {
    std::fprintf(stderr, "%s: no point inside found next to the start\n", argv[1]);
    return 1;
  }
  const double bounding_radius = 5.0;  // the catalogue's closed surfaces lie within 3 of 0
  const auto function = [&](const Point_3& p) {
    return FT(sign * F(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())));
  };
  using Surface = CGAL::Implicit_surface_3<GT, decltype(function)>;
  const auto began = std::chrono::steady_clock::now();
  Tr tr;
  C2t3 c2t3(tr);
  Surface surface(function,
                  Sphere_3(Point_3(inside(0), inside(1), inside(2)),
                           bounding_radius * bounding_radius),
                  1e-10);
  CGAL::Surface_mesh_default_criteria_3<Tr> criteria(30.0, radius_bound, distance_bound);
  CGAL::make_surface_mesh(c2t3, surface, criteria, CGAL::Manifold_tag());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  CGAL::Surface_mesh<Point_3> mesh;
  CGAL::facets_in_complex_2_to_triangle_mesh(c2t3, mesh);
  std::ofstream out(argv[3]);
  out.precision(17);
  for (const auto v : mesh.vertices()) {
    const Point_3& p = mesh.point(v);
    out << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  }
  for (const auto f : mesh.faces()) {
    out << 'f';
    for (const auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
      out << ' ' << static_cast<std::size_t>(v) + 1;
    }
    out << '\n';
  }
  std::printf("cgal %s distance_bound %g radius_bound %g vertices %zu triangles %zu seconds %.4f\n",
              argv[1], distance_bound, radius_bound, static_cast<std::size_t>(mesh.number_of_vertices()),
              static_cast<std::size_t>(mesh.number_of_faces()), seconds);
  return out ? 0 : 1;
}
