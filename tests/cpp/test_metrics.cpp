#include <gtest/gtest.h>

#include <BRep_Builder.hxx>
#include <TopoDS_Iterator.hxx>
#include <algorithm>
#include <cmath>

#include "tessella/panel_metrics.h"
#include "mesh/panel_model.h"
#include "tessella/shape_export.h"
#include "test_faces.h"

using namespace tessella;
using namespace tessella::test;

namespace {
// One quad over the plate z = 0 with corner 2 lifted by h.
PanelMesh lifted_quad(double h) {
  PanelMesh m;
  m.xyz = {{0, 0, 0}, {1000, 0, 0}, {1000, 1000, h}, {0, 1000, 0}};
  m.uv = {{0, 0}, {1000, 0}, {1000, 1000}, {0, 1000}};
  m.panels = {{0, 1, 2, 3}};
  build_rods(m);
  return m;
}
}  // namespace

TEST(Metrics, PlanarityIsTheDiagonalGapOverTheMeanEdge) {
  const SurfaceFace plate = plate_with_square_hole(2000, 1500, 1900);
  for (double h : {0.0, 10.0, 100.0}) {
    const PanelMetrics m = measure_panels(plate, lifted_quad(h));
    // Diagonals (0,0,0)-(1000,1000,h) and (1000,0,0)-(0,1000,0): distance
    // 1000 h / sqrt(2 h^2 + 4e6) (cross product of the directions).
    const double gap = 1000.0 * h / std::sqrt(2 * h * h + 4e6);
    const double mean_edge = (2000.0 + 2 * std::sqrt(1e6 + h * h)) / 4;
    EXPECT_NEAR(m.planarity[0], gap / mean_edge, 1e-12);
    // The bilinear patch is farthest from z = 0 at the lifted corner.
    EXPECT_NEAR(m.deviation[0], h, 1e-9);
  }
}

TEST(Metrics, AreaAnglesAndRodLengthsOfAKnownQuad) {
  const SurfaceFace plate = plate_with_square_hole(2000, 1500, 1900);
  const PanelMetrics m = measure_panels(plate, lifted_quad(0));
  EXPECT_NEAR(m.area[0], 1e6, 1e-6);
  EXPECT_NEAR(m.min_angle[0], 90.0, 1e-9);
  EXPECT_NEAR(m.max_angle[0], 90.0, 1e-9);
  ASSERT_EQ(m.rod_length.size(), 4u);
  for (double len : m.rod_length) EXPECT_NEAR(len, 1000.0, 1e-9);
  // Bilinear area of the lifted quad against an independent fine midpoint sum.
  const double h = 300;
  const PanelMetrics lifted = measure_panels(plate, lifted_quad(h));
  double area = 0;
  const int n = 400;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double s = (i + 0.5) / n, t = (j + 0.5) / n;
      // X(s,t) = (1000 s, 1000 t, h s t): |X_s x X_t| = 1e3 sqrt(1e6 + h^2 (s^2 + t^2))
      area += 1e3 * std::sqrt(1e6 + h * h * (s * s + t * t)) / (n * n);
    }
  EXPECT_NEAR(lifted.area[0], area, 1e-5 * area);
}

TEST(Metrics, SummaryStatistics) {
  const SummaryStats s = summarize({1.0, 2.0, 3.0, 4.0});
  EXPECT_EQ(s.count, 4);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.variance, 1.25);
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 4.0);
  EXPECT_EQ(summarize({}).count, 0);
}

TEST(Metrics, IrregularFlagsFollowTheirThreeRules) {
  PanelMesh m = lifted_quad(0);
  m.xyz.push_back({500, -10, 0});
  m.uv.push_back({500, -10});
  m.panels.push_back({0, 4, 1});  // a thin triangle under the quad
  m.nominal_area = 1e6;
  build_rods(m);
  const SurfaceFace plate = plate_with_square_hole(2000, 1500, 1900);
  const PanelMetrics metrics = measure_panels(plate, m);
  const std::vector<bool> flags = irregular_panels(m, metrics);
  EXPECT_FALSE(flags[0]);
  EXPECT_TRUE(flags[1]);
  IrregularParams strict;
  strict.min_angle_deg = 90.5;  // every corner of the square is under it
  EXPECT_TRUE(irregular_panels(m, metrics, strict)[0]);
}

TEST(Model, EarClippingCoversANonConvexOutline) {
  // An L shape: area 3 (unit squares), a fan from the mean corner would not fit.
  const std::vector<Vec2> l = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const auto tris = triangulate_polygon(l);
  ASSERT_EQ(tris.size(), 4u);
  double area = 0;
  for (const auto& t : tris) {
    const Vec2 a = l[t[1]] - l[t[0]], b = l[t[2]] - l[t[0]];
    const double cross = a.x() * b.y() - a.y() * b.x();
    EXPECT_GT(cross, 0.0);
    area += 0.5 * cross;
  }
  EXPECT_NEAR(area, 3.0, 1e-12);
}

TEST(Model, EarClippingOfAClockwiseOutlineKeepsItsTurningSense) {
  std::vector<Vec2> l = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  std::reverse(l.begin(), l.end());  // clockwise L
  const auto tris = triangulate_polygon(l);
  ASSERT_EQ(tris.size(), 4u);
  double area = 0;
  for (const auto& t : tris) {
    const Vec2 a = l[t[1]] - l[t[0]], b = l[t[2]] - l[t[0]];
    const double cross = a.x() * b.y() - a.y() * b.x();
    EXPECT_LT(cross, 0.0);  // clockwise, like the outline
    area -= 0.5 * cross;
  }
  EXPECT_NEAR(area, 3.0, 1e-12);  // covers the L exactly (no overlap)
}

TEST(ShapeExport, OneSubShapePerPanelRodAndNode) {
  const PanelMesh m = lifted_quad(50);
  for (const std::string& s : {panels_to_brep(m, 1e-6), rods_to_brep(m), nodes_to_brep(m)}) {
    TopoDS_Shape shape;
    std::istringstream in(s);
    BRep_Builder b;
    BRepTools::Read(shape, in, b);
    ASSERT_FALSE(shape.IsNull());
    int n = 0;
    for (TopoDS_Iterator it(shape); it.More(); it.Next()) ++n;
    EXPECT_GE(n, 1);
  }
}
