// Cells between crossing curve families (2G2VM, GSM diamonds; seed 004
// sections 5.2.1 and 6), checked in closed form on flat plates.
#include <gtest/gtest.h>

#include <cmath>

#include "mesh/curve_family_mesh.h"
#include "tessella/errors.h"
#include "tessella/guide_line_diamond.h"
#include "methods/guide_lines/chord_division.h"
#include "methods/guide_lines/right_angle_rule.h"
#include "tessella/guide_line_scaling.h"
#include "tessella/two_guide_lines.h"
#include "tessella/surface_face.h"
#include "test_faces.h"

using namespace tessella;
using namespace tessella::test;

namespace {

SurfaceFace rectangle(double w, double h) {
  return SurfaceFace::from_brep_string(
      brep(BRepBuilderAPI_MakeFace(gp_Pln(), rect_wire(0, 0, w, h, false)).Face()));
}

// A straight curve on the plane z = 0 (u = x, v = y), 101 points.
SurfaceCurve straight(const Vec2& a, const Vec2& b) {
  SurfaceCurve c;
  for (int i = 0; i <= 100; ++i) {
    const Vec2 p = a + (b - a) * (i / 100.0);
    c.uv.push_back(p);
    c.xyz.emplace_back(p.x(), p.y(), 0.0);
  }
  return c;
}

double polygon_area(const PanelMesh& m, const std::vector<int>& p) {
  Vec3 a = Vec3::Zero();
  for (std::size_t i = 0; i < p.size(); ++i) a += m.xyz[p[i]].cross(m.xyz[p[(i + 1) % p.size()]]);
  return 0.5 * a.norm();
}

}  // namespace

TEST(CurveFamilyMesh, CellsAroundAHoleAreClosedByTheTrim) {
  // 10 m plate with a 3 m square hole [3.5, 6.5]^2; lines x = i and y = j (m)
  // running past the outline. 100 cells of 1 m^2, of which the hole swallows
  // the 4 inner ones and cuts 12 into L-shapes and bars: 96 cells whose area
  // adds up to exactly 100 - 9 = 91 m^2 (flat cells, straight trims).
  const SurfaceFace f = plate_with_square_hole(10000, 3500, 6500);
  std::vector<SurfaceCurve> xs, ys;
  for (int i = 1; i <= 9; ++i) {
    xs.push_back(straight(Vec2(1000.0 * i, -500), Vec2(1000.0 * i, 10500)));
    ys.push_back(straight(Vec2(-500, 1000.0 * i), Vec2(10500, 1000.0 * i)));
  }
  CurveFamilyMeshParams p;
  p.rod_length = 1000;
  const PanelMesh m = mesh_curve_families(f, {xs, ys}, p);
  EXPECT_EQ(m.panels.size(), 96u);
  double area = 0;
  int quads = 0;
  for (const auto& panel : m.panels) area += polygon_area(m, panel), quads += panel.size() == 4;
  EXPECT_NEAR(area, 91e6, 1e-3);
  EXPECT_EQ(quads, 84 + 8);  // 84 whole cells + the 8 bars beside the hole's sides
  for (const Vec3& x : m.xyz) {
    const bool in_hole =
        x.x() > 3500 + 1e-6 && x.x() < 6500 - 1e-6 && x.y() > 3500 + 1e-6 && x.y() < 6500 - 1e-6;
    EXPECT_FALSE(in_hole);
  }
  for (const auto& r : m.rods) {
    const double len = (m.xyz[r[0]] - m.xyz[r[1]]).norm();
    EXPECT_TRUE(std::abs(len - 1000) < 1e-6 || std::abs(len - 500) < 1e-6) << len;
  }
  // Triangulated: a cell of n corners becomes n - 2 triangles.
  p.triangulate = true;
  const PanelMesh t = mesh_curve_families(f, {xs, ys}, p);
  std::size_t expected = 0;
  for (const auto& panel : m.panels) expected += panel.size() - 2;
  EXPECT_EQ(t.panels.size(), expected);
  // Curves that never cross make no grid.
  EXPECT_THROW(mesh_curve_families(f, {xs}, p), InvalidParameter);
}

TEST(GuideLineDiamond, PerpendicularGuidesOnAPlateGiveSquares) {
  // GSM from the left edge and from the bottom edge of a 10 m x 6 m plate,
  // 1000 mm apart: the lines x = i and y = j, so 60 squares with 1000 mm rods.
  const SurfaceFace f = rectangle(10000, 6000);
  GuideLineDiamondParams p;
  p.guide_a = {Vec3(0, 0, 0), Vec3(0, 6000, 0)};
  p.guide_b = {Vec3(0, 0, 0), Vec3(10000, 0, 0)};
  p.rod_length = 1000;
  const PanelMesh m = guide_line_diamond(f, p);
  EXPECT_EQ(m.panels.size(), 60u);
  for (const auto& panel : m.panels) EXPECT_EQ(panel.size(), 4u);
  for (const auto& r : m.rods) EXPECT_NEAR((m.xyz[r[0]] - m.xyz[r[1]]).norm(), 1000.0, 1e-4);
}

TEST(GuideLineDiamond, GuidesCrossingAt60DegreesGiveRhombi) {
  // Guides through the centre of a 20 m plate at +-30 degrees to x: each GSM
  // set is straight lines 1000 mm apart near the guide (GSM turns them once
  // an end reaches a corner of the plate), so the cells within 4.5 m of the
  // centre are rhombi of side 1000 / sin(60 deg) = 1154.70 mm with 60 / 120
  // degree corners.
  const double w = 20000, c = 10000, t = std::tan(30.0 * 3.14159265358979323846 / 180.0);
  const SurfaceFace f = rectangle(w, w);
  GuideLineDiamondParams p;
  p.guide_a = {Vec3(0, c - c * t, 0), Vec3(w, c + c * t, 0)};
  p.guide_b = {Vec3(0, c + c * t, 0), Vec3(w, c - c * t, 0)};
  p.rod_length = 1000;
  const PanelMesh m = guide_line_diamond(f, p);
  const double side = 1000.0 / std::sin(60.0 * 3.14159265358979323846 / 180.0);
  int interior = 0;
  for (const auto& panel : m.panels) {
    bool outside = false;
    for (int v : panel)
      outside = outside || std::abs(m.xyz[v].x() - c) > 4500 || std::abs(m.xyz[v].y() - c) > 4500;
    if (outside) continue;
    ++interior;
    ASSERT_EQ(panel.size(), 4u);
    for (int k = 0; k < 4; ++k) {
      const Vec3 a = m.xyz[panel[k]], b = m.xyz[panel[(k + 1) % 4]], n = m.xyz[panel[(k + 3) % 4]];
      EXPECT_NEAR((b - a).norm(), side, 1e-3);
      const double angle = std::acos((b - a).normalized().dot((n - a).normalized())) * 180.0 /
                           3.14159265358979323846;
      EXPECT_TRUE(std::abs(angle - 60) < 1e-3 || std::abs(angle - 120) < 1e-3) << angle;
    }
  }
  // 81 m^2 / (1154.7 * 1000 mm^2) = 70 cells, less those cut by the square.
  EXPECT_GT(interior, 45);
}

TEST(GuideLineDiamond, RejectsBadInput) {
  const SurfaceFace f = rectangle(10000, 6000);
  GuideLineDiamondParams p;
  p.guide_a = {Vec3(0, 0, 0), Vec3(0, 6000, 0)};
  p.guide_b = {Vec3(0, 0, 0), Vec3(10000, 0, 0)};
  p.rod_length = 0;
  EXPECT_THROW(guide_line_diamond(f, p), InvalidParameter);
  p.rod_length = 1000;
  p.advance = -1;
  EXPECT_THROW(guide_line_diamond(f, p), InvalidParameter);
  p.advance = 0;
  p.guide_b = {Vec3(10000, 0, 0), Vec3(10000, 6000, 0)};  // parallel to guide_a
  EXPECT_THROW(guide_line_diamond(f, p), InvalidParameter);
}

TEST(TwoGuideLines, BoundaryDivisionsSplitEachBoundaryCurveEqually) {
  // 10 m x 6 m plate, guides = the left and the bottom edge, 5 divisions: the
  // bottom and top edges get chords of 2000 mm, the left and right edges of
  // 1200 mm, so 5 x 5 cells of 2000 x 1200 mm.
  const SurfaceFace f = rectangle(10000, 6000);
  TwoGuideLinesParams p;
  p.guide_a = {Vec3(0, 0, 0), Vec3(0, 6000, 0)};
  p.guide_b = {Vec3(0, 0, 0), Vec3(10000, 0, 0)};
  p.rod_length = 1000;
  p.boundary_divisions = 5;
  const PanelMesh m = two_guide_lines(f, p);
  EXPECT_EQ(m.panels.size(), 25u);
  for (const auto& r : m.rods) {
    const double len = (m.xyz[r[0]] - m.xyz[r[1]]).norm();
    EXPECT_TRUE(std::abs(len - 2000) < 1e-6 || std::abs(len - 1200) < 1e-6) << len;
  }
  p.boundary_divisions = -1;
  EXPECT_THROW(two_guide_lines(f, p), InvalidParameter);
}
