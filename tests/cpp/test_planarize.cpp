// Planarization (tessella/planarize.h) against closed forms: a sphere's
// latitude/longitude grid is planar already (left as it is); the same grid
// with its free nodes pushed off by up to 3 mm comes back to planarity within
// the tolerance, its nodes within max_deviation of the sphere (distance to
// the centre minus the radius), its boundary nodes untouched.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tessella/errors.h"
#include "tessella/grid_methods.h"
#include "tessella/planarize.h"
#include "test_faces.h"

namespace tessella {
namespace {

PanelMesh sphere_grid(const SurfaceFace& f) {
  IsoGridParams p;
  p.u_count = 24;
  p.v_count = 12;
  return iso_grid(f, p);
}

TEST(Planarize, SphereLatitudeLongitudeGridIsLeftAsItIs) {
  const SurfaceFace f = test::sphere_face(5000);
  const PanelMesh m = sphere_grid(f);
  PlanarizeReport rep;
  const PanelMesh out = planarize(f, m, PlanarizeParams{}, &rep);
  EXPECT_GT(rep.quads, 200);
  EXPECT_EQ(rep.planar_before, rep.quads);
  EXPECT_TRUE(rep.converged);
  for (std::size_t v = 0; v < m.vertex_count(); ++v)
    EXPECT_LE((out.xyz[v] - m.xyz[v]).norm(), 1e-9);
}

TEST(Planarize, PerturbedPlanarGridReturnsToPlanarity) {
  const double r = 5000;
  const SurfaceFace f = test::sphere_face(r);
  const PanelMesh m = sphere_grid(f);
  PanelMesh pushed = m;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> d(-3.0, 3.0);
  // Every vertex off the poles' rows (the boundary: seam and poles stay).
  for (Vec3& x : pushed.xyz)
    if (std::abs(x.z()) < 0.99 * r) x += Vec3(d(rng), d(rng), d(rng));
  PlanarizeParams p;
  p.planarity_tolerance = 0.1;
  p.max_deviation = 20.0;
  PlanarizeReport rep;
  const PanelMesh out = planarize(f, pushed, p, &rep);
  EXPECT_LT(rep.planar_before, rep.quads / 2);
  EXPECT_EQ(rep.planar_after, rep.quads) << rep.max_planarity_after;
  EXPECT_TRUE(rep.converged);
  for (const auto& panel : out.panels) {
    if (panel.size() != 4) continue;
    std::vector<Vec3> x;
    for (int v : panel) x.push_back(out.xyz[static_cast<std::size_t>(v)]);
    EXPECT_LE(diagonal_distance(x), 0.1);
  }
  for (const Vec3& x : out.xyz) EXPECT_LE(std::abs(x.norm() - r), 20.0 + 1e-9);
}

TEST(Planarize, BoundaryNodesStayAndBadParametersAreRefused) {
  const SurfaceFace f = test::plate_with_square_hole(4000, 1500, 2500);
  IsoGridParams g;
  g.u_count = 8;
  g.v_count = 8;
  const PanelMesh m = iso_grid(f, g);
  const PanelMesh out = planarize(f, m, PlanarizeParams{});
  // A plate: planar already, nothing moves; the trim's vertices in particular.
  for (std::size_t v = 0; v < m.vertex_count(); ++v) EXPECT_EQ(out.xyz[v], m.xyz[v]);
  PlanarizeParams bad;
  bad.planarity_tolerance = 0;
  EXPECT_THROW(planarize(f, m, bad), InvalidParameter);
  bad = PlanarizeParams{};
  bad.max_deviation = -1;
  EXPECT_THROW(planarize(f, m, bad), InvalidParameter);
  bad = PlanarizeParams{};
  bad.closeness = -1;
  EXPECT_THROW(planarize(f, m, bad), InvalidParameter);
}

}  // namespace
}  // namespace tessella
