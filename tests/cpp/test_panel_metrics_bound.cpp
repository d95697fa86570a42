// panel_deviation is an upper bound of the true distance within 1%: checked
// against closed forms on a cylinder and a sphere.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tessella/panel_metrics.h"
#include "tessella/surface_face.h"
#include "test_faces.h"

using namespace tessella;
using namespace tessella::test;

namespace {

Vec3 on_cylinder(double r, double a, double z) { return {r * std::cos(a), r * std::sin(a), z}; }
}  // namespace

// A chord rectangle of the cylinder x^2 + y^2 = R^2 between angles a0 and a1:
// the gap is largest along its middle line, R - sqrt(R^2 - (c/2)^2) with c the
// chord. With an odd number of samples the grid has no point there (3
// samples: 8/9 of the true value); the refinement must find it.
TEST(PanelDeviationBound, ChordRectangleOverACylinder) {
  const double R = 1000, h = 800;
  const SurfaceFace cyl = cylinder_face(R, h);
  const double a0 = 0.3, a1 = 0.9;
  const double chord = 2 * R * std::sin((a1 - a0) / 2);
  const double truth = R - std::sqrt(R * R - chord * chord / 4);
  const std::vector<Vec3> p = {on_cylinder(R, a0, 100), on_cylinder(R, a1, 100),
                               on_cylinder(R, a1, 600), on_cylinder(R, a0, 600)};
  const std::vector<Vec2> uv = {{a0, 100}, {a1, 100}, {a1, 600}, {a0, 600}};
  for (int samples : {1, 2, 3, 5, 7, 8}) {
    const PanelDeviation d = measure_panel_deviation(cyl, p, uv, {}, samples);
    EXPECT_GE(d.value, truth * (1 - 1e-3)) << samples;
    EXPECT_LE(d.value, truth * 1.01) << samples;
    EXPECT_FALSE(d.unreliable);
  }
  // The same rectangle as two flat triangles (the flat-piece model).
  const std::vector<std::array<int, 3>> tris = {{{0, 1, 2}}, {{0, 2, 3}}};
  for (int samples : {1, 3, 8}) {
    const PanelDeviation d = measure_panel_deviation(cyl, p, uv, tris, samples);
    EXPECT_GE(d.value, truth * (1 - 1e-3)) << samples;
    EXPECT_LE(d.value, truth * 1.01) << samples;
  }
}

// A quad of four points of a sphere, not symmetric: the bilinear patch's gap
// to the sphere is R - |x| at every point (closed form), its maximum taken by
// a dense 400 x 400 sweep of the patch.
TEST(PanelDeviationBound, SkewQuadOverASphere) {
  const double R = 2000;
  const SurfaceFace sph = sphere_face(R);
  auto on_sphere = [&](double u, double v) {
    return Vec3{R * std::cos(v) * std::cos(u), R * std::cos(v) * std::sin(u), R * std::sin(v)};
  };
  const std::vector<Vec2> uv = {{0.2, 0.1}, {0.75, 0.05}, {0.9, 0.6}, {0.15, 0.45}};
  std::vector<Vec3> p;
  for (const Vec2& q : uv) p.push_back(on_sphere(q.x(), q.y()));
  double truth = 0;
  const int n = 400;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double s = double(i) / n, t = double(j) / n;
      const Vec3 x = (1 - s) * (1 - t) * p[0] + s * (1 - t) * p[1] + s * t * p[2] + (1 - s) * t * p[3];
      truth = std::max(truth, R - x.norm());
    }
  ASSERT_GT(truth, 10.0);
  for (int samples : {3, 8}) {
    const PanelDeviation d = measure_panel_deviation(sph, p, uv, {}, samples);
    EXPECT_GE(d.value, truth * (1 - 1e-3)) << samples;
    EXPECT_LE(d.value, truth * 1.01) << samples;
    EXPECT_FALSE(d.unreliable);
  }
}

// Through measure_panels: the flag vector has one entry per panel.
TEST(PanelDeviationBound, MeasurePanelsCarriesTheFlag) {
  const double R = 1000;
  const SurfaceFace cyl = cylinder_face(R, 800);
  PanelMesh m;
  m.xyz = {on_cylinder(R, 0.3, 100), on_cylinder(R, 0.9, 100), on_cylinder(R, 0.9, 600),
           on_cylinder(R, 0.3, 600)};
  m.uv = {{0.3, 100}, {0.9, 100}, {0.9, 600}, {0.3, 600}};
  m.panels = {{0, 1, 2, 3}};
  build_rods(m);
  MetricsParams mp;
  mp.samples = 3;
  const PanelMetrics pm = measure_panels(cyl, m, mp);
  ASSERT_EQ(pm.deviation_unreliable.size(), 1u);
  EXPECT_EQ(pm.deviation_unreliable[0], 0);
  const double chord = 2 * R * std::sin(0.3);
  EXPECT_NEAR(pm.deviation[0], R - std::sqrt(R * R - chord * chord / 4), 1e-3);
}
