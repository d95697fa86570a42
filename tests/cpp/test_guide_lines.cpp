// Guide-line building blocks and the GSM (seed 004 sections 4-5), checked in
// closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tessella/errors.h"
#include "methods/guide_lines/chord_division.h"
#include "methods/guide_lines/right_angle_rule.h"
#include "tessella/guide_line_scaling.h"
#include "tessella/two_guide_lines.h"
#include "tessella/surface_face.h"
#include "test_faces.h"

using namespace tessella;
using namespace tessella::test;

namespace {
constexpr double kPi = 3.14159265358979323846;

std::vector<Vec3> line(double length, int points) {
  std::vector<Vec3> p;
  for (int i = 0; i < points; ++i) p.emplace_back(length * i / (points - 1), 0, 0);
  return p;
}

std::vector<double> chords(const std::vector<Vec3>& pts, const std::vector<double>& t) {
  std::vector<double> c;
  for (std::size_t i = 1; i < t.size(); ++i)
    c.push_back((polyline_point(pts, t[i]) - polyline_point(pts, t[i - 1])).norm());
  return c;
}

SurfaceFace rectangle(double w, double h) {
  return SurfaceFace::from_brep_string(
      brep(BRepBuilderAPI_MakeFace(gp_Pln(), rect_wire(0, 0, w, h, false)).Face()));
}

double triangle_area(const PanelMesh& m, const std::vector<int>& p) {
  return 0.5 * (m.xyz[p[1]] - m.xyz[p[0]]).cross(m.xyz[p[2]] - m.xyz[p[0]]).norm();
}
}  // namespace

TEST(GuideLineProjection, CylinderFootPointInClosedForm) {
  const double r = 3000;
  const SurfaceFace f = cylinder_face(r, 5000);
  for (double phi : {0.3, 1.7, 4.0}) {
    for (double rho : {1000.0, 5000.0}) {
      const Vec3 p(rho * std::cos(phi), rho * std::sin(phi), 1234.0);
      const Projection pr = f.project(p, Vec2(phi + 0.2, 1000.0));
      EXPECT_NEAR((pr.point - Vec3(r * std::cos(phi), r * std::sin(phi), 1234.0)).norm(), 0.0,
                  1e-6);
      EXPECT_NEAR(pr.distance, std::abs(rho - r), 1e-6);
    }
  }
}

TEST(ChordDivision, SpreadsALargeLeftOverIntoEqualChords) {
  // Length 10, L1 = 3: three full chords leave 1 > 0.2 * 3; 3 chords of 10/3
  // are closer to L1 than 4 of 2.5.
  const auto pts = line(10, 11);
  const auto t = divide_by_chords(pts, {3.0, 0.2});
  ASSERT_EQ(t.size(), 4u);
  EXPECT_DOUBLE_EQ(t.front(), 0.0);
  EXPECT_DOUBLE_EQ(t.back(), 10.0);
  for (double c : chords(pts, t)) EXPECT_NEAR(c, 10.0 / 3.0, 1e-9);
  // Length 11, L1 = 3: the rest 2 -> 4 chords of 2.75 beat 3 of 3.667.
  const auto pts2 = line(11, 12);
  const auto t2 = divide_by_chords(pts2, {3.0, 0.2});
  ASSERT_EQ(t2.size(), 5u);
  for (double c : chords(pts2, t2)) EXPECT_NEAR(c, 2.75, 1e-9);
}

TEST(ChordDivision, MergesASmallLeftOverIntoTheLastChord) {
  // Length 9.5, L1 = 3: rest 0.5 < 0.6 joins the last chord (3, 3, 3.5).
  const auto pts = line(9.5, 20);
  const auto c = chords(pts, divide_by_chords(pts, {3.0, 0.2}));
  ASSERT_EQ(c.size(), 3u);
  EXPECT_NEAR(c[0], 3.0, 1e-9);
  EXPECT_NEAR(c[1], 3.0, 1e-9);
  EXPECT_NEAR(c[2], 3.5, 1e-9);
}

TEST(ChordDivision, EqualChordsOnACircularArcMatchTheClosedForm) {
  // Quarter circle R = 1000 as a dense polyline; L1 = 300 -> n chords with
  // chord 2 R sin(theta / 2n) where the arc's chords add up (iterated, not
  // measured along the curve).
  const double r = 1000.0;
  std::vector<Vec3> pts;
  for (int i = 0; i <= 4000; ++i) {
    const double a = 0.5 * kPi * i / 4000;
    pts.emplace_back(r * std::cos(a), r * std::sin(a), 0);
  }
  const auto c = chords(pts, divide_by_chords(pts, {300.0, 0.2}));
  const int n = static_cast<int>(c.size());
  // The polyline is inscribed in the circle: its chords match the circle's
  // to the polyline's sagitta (R (1 - cos(pi / 16000)) ~ 2e-5).
  const double expected = 2 * r * std::sin(0.25 * kPi / n);
  for (double x : c) EXPECT_NEAR(x, expected, 1e-3);
  EXPECT_TRUE(n == 5 || n == 6);  // arc chord total ~1570: 5 x 314 is closest to 300
  EXPECT_EQ(n, 5);
}

TEST(ChordDivision, RejectsAZeroChord) {
  EXPECT_THROW(divide_by_chords(line(10, 3), {0.0, 0.2}), InvalidParameter);
  EXPECT_THROW(divide_by_chords({Vec3(0, 0, 0)}, {1.0, 0.2}), InvalidParameter);
}

TEST(RightAngleRule, FollowsFigure14OnARowWithOnePointAhead) {
  // P_0..P_5 on y = 0, Q_0 = (2.4, 1), Q_1 = (6, 1). Q_0 is connected to P_0..P_3
  // (angle Q_0 P_3 P_4 > 90), then Q_1, then the residual P_4, P_5 fan to Q_1.
  std::vector<Vec3> p, q{Vec3(2.4, 1, 0), Vec3(6, 1, 0)};
  for (int i = 0; i < 6; ++i) p.emplace_back(i, 0, 0);
  const auto t = connect_rows_right_angle(p, q);
  const std::vector<std::array<int, 3>> expected{{0, 1, 6}, {1, 2, 6}, {2, 3, 6},
                                                 {3, 7, 6}, {3, 4, 7}, {4, 5, 7}};
  EXPECT_EQ(t, expected);
}

TEST(RightAngleRule, StaggeredRowsGiveTrianglesWithoutObtuseAngles) {
  std::vector<Vec3> p, q;
  for (int i = 0; i < 8; ++i) p.emplace_back(i, 0, 0), q.emplace_back(i + 0.5, std::sqrt(0.75), 0);
  const auto t = connect_rows_right_angle(p, q);
  ASSERT_EQ(t.size(), 14u);  // n + m - 2
  std::vector<Vec3> all = p;
  all.insert(all.end(), q.begin(), q.end());
  for (const auto& tri : t) {
    const Vec3 a = all[tri[0]], b = all[tri[1]], c = all[tri[2]];
    EXPECT_GT((b - a).cross(c - a).z(), 0.0);  // counter-clockwise
    for (int k = 0; k < 3; ++k) {
      const Vec3 x = all[tri[k]], y = all[tri[(k + 1) % 3]], z = all[tri[(k + 2) % 3]];
      EXPECT_GE((y - x).dot(z - x), -1e-12);  // no angle over 90 degrees
    }
  }
}

TEST(GuideLineScaling, FlatRectangleIsCoveredByParallelCurvesAndEqualRods) {
  // 10 m x 6 m plate, guide = the left edge: curves are translated copies
  // (scale 1, no rotation) every 866 mm; each is divided into 6 rods of 1000 mm.
  const SurfaceFace f = rectangle(10000, 6000);
  GuideLineScalingParams p;
  p.guide = {Vec3(0, 0, 0), Vec3(0, 6000, 0)};
  p.rod_length = 1000;
  p.advance = 866;
  p.stagger = false;  // the paper's equal chords on every curve
  const GuideLineResult r = guide_line_scaling_curves(f, p);
  // Straight curves at x = k * 866, k = 0..11, and the last on the right edge
  // (the step beyond is clamped there); listed in sweep order.
  ASSERT_EQ(r.curves.size(), 13u);
  std::vector<double> xs;
  for (const SurfaceCurve& c : r.curves) {
    for (const Vec3& x : c.xyz) EXPECT_NEAR(x.x(), c.xyz.front().x(), 1e-4);
    xs.push_back(c.xyz.front().x());
  }
  std::sort(xs.begin(), xs.end());
  for (std::size_t k = 0; k < xs.size(); ++k)
    EXPECT_NEAR(xs[k], std::min(10000.0, 866.0 * k), 1e-4);
  const PanelMesh& m = r.mesh;
  double area = 0;
  for (const auto& panel : m.panels) {
    ASSERT_EQ(panel.size(), 3u);
    area += triangle_area(m, panel);
  }
  EXPECT_NEAR(area, 10000.0 * 6000.0, 1e-6 * 6e7);  // covered, no overlaps
  for (const Vec3& x : m.xyz) EXPECT_NEAR(x.z(), 0.0, 1e-9);
  int along = 0;
  for (const auto& rod : m.rods) {
    const Vec3 a = m.xyz[rod[0]], b = m.xyz[rod[1]];
    if (std::abs(a.x() - b.x()) < 1e-6) {
      EXPECT_NEAR((a - b).norm(), 1000.0, 1e-4);  // projection tolerance 1e-9 x model size
      ++along;
    }
  }
  EXPECT_EQ(along, 6 * static_cast<int>(r.curves.size()));
}

TEST(GuideLineScaling, StaggeredRowsGiveNearEqualRodsBetweenCurves) {
  // Same plate: the guide x = 0 has nodes every 1000 mm; with stagger the next
  // curve (x = 866) takes its inner nodes near the feet of the guide rods'
  // midpoints (y = 1500 .. 4500), so the rods between the two curves in the
  // middle are near sqrt(866^2 + 500^2) = 1000 mm; without stagger the nodes
  // face each other and those rods are 866 and 1323 mm.
  const SurfaceFace f = rectangle(10000, 6000);
  GuideLineScalingParams p;
  p.guide = {Vec3(0, 0, 0), Vec3(0, 6000, 0)};
  p.rod_length = 1000;
  p.advance = 866;
  auto between = [&](bool stagger) {
    p.stagger = stagger;
    const PanelMesh m = guide_line_scaling(f, p);
    std::vector<double> len;
    for (const auto& rod : m.rods) {
      const Vec3 a = m.xyz[rod[0]], b = m.xyz[rod[1]];
      const bool first_gap =
          std::min(a.x(), b.x()) < 1e-6 && std::abs(std::max(a.x(), b.x()) - 866) < 1e-6;
      if (first_gap && std::min(a.y(), b.y()) > 1400 && std::max(a.y(), b.y()) < 4600)
        len.push_back((a - b).norm());
    }
    return len;
  };
  const std::vector<double> staggered = between(true), facing = between(false);
  ASSERT_GE(staggered.size(), 4u);
  // Within 10% (the spacing is smoothed towards L1 between the feet and the
  // boundary nodes, so the inner nodes move a little off the exact feet).
  for (double l : staggered) EXPECT_NEAR(l, 1000.0, 100.0);
  double worst_facing = 0;
  for (double l : facing) worst_facing = std::max(worst_facing, std::abs(l - 1000.0));
  EXPECT_GT(worst_facing, 130.0);
}

TEST(GuideLineScaling, RejectsBadInput) {
  const SurfaceFace f = rectangle(10000, 6000);
  GuideLineScalingParams p;
  p.guide = {Vec3(0, 0, 0), Vec3(0, 6000, 0)};
  p.rod_length = 0;
  EXPECT_THROW(guide_line_scaling(f, p), InvalidParameter);
  p.rod_length = 1000;
  p.advance = -5;
  EXPECT_THROW(guide_line_scaling(f, p), InvalidParameter);
  p.advance = 0;
  p.guide = {Vec3(0, 0, 50000), Vec3(0, 6000, 50000)};  // 50 m above a 12 m plate
  EXPECT_THROW(guide_line_scaling(f, p), InvalidParameter);
  p.guide = {Vec3(0, 0, 0)};
  EXPECT_THROW(guide_line_scaling(f, p), InvalidParameter);
}

TEST(TwoGuideLines, FlatRectangleGivesTheSquareGridAndItsDiagonals) {
  // 10 m x 6 m plate, guides = the left and the bottom edge, rods of 1000 mm:
  // the boundary vertices are every 1000 mm, the curves are the lines x = i and
  // y = j (m) (the last ones, on the far edges, are the outline itself and end
  // each family), and the cells between them and the outline are the 10 x 6
  // square quads on the 11 x 7 nodes.
  const SurfaceFace f = rectangle(10000, 6000);
  TwoGuideLinesParams p;
  p.guide_a = {Vec3(0, 0, 0), Vec3(0, 6000, 0)};
  p.guide_b = {Vec3(0, 0, 0), Vec3(10000, 0, 0)};
  p.rod_length = 1000;
  const TwoGuideLinesResult r = two_guide_lines_curves(f, p);
  EXPECT_EQ(r.curves_a.size(), 10u);
  EXPECT_EQ(r.curves_b.size(), 6u);
  const PanelMesh& m = r.mesh;
  EXPECT_EQ(m.panels.size(), 60u);
  EXPECT_EQ(m.xyz.size(), 77u);
  for (const Vec3& x : m.xyz) {
    EXPECT_NEAR(x.x() / 1000 - std::round(x.x() / 1000), 0.0, 1e-7);
    EXPECT_NEAR(x.y() / 1000 - std::round(x.y() / 1000), 0.0, 1e-7);
  }
  for (const auto& rod : m.rods) EXPECT_NEAR((m.xyz[rod[0]] - m.xyz[rod[1]]).norm(), 1000.0, 1e-4);
  p.triangulate = true;
  const PanelMesh t = two_guide_lines(f, p);
  EXPECT_EQ(t.panels.size(), 120u);
  EXPECT_EQ(t.rods.size(), m.rods.size() + 60u);  // one diagonal per quad
  for (const auto& panel : t.panels) EXPECT_EQ(panel.size(), 3u);
}

TEST(TwoGuideLines, RejectsBadInput) {
  const SurfaceFace f = rectangle(10000, 6000);
  TwoGuideLinesParams p;
  p.guide_a = {Vec3(0, 0, 0), Vec3(0, 6000, 0)};
  p.guide_b = {Vec3(0, 0, 0), Vec3(10000, 0, 0)};
  p.rod_length = 0;
  EXPECT_THROW(two_guide_lines(f, p), InvalidParameter);
  p.rod_length = 1000;
  p.guide_b = {Vec3(0, 0, 90000), Vec3(10000, 0, 90000)};
  EXPECT_THROW(two_guide_lines(f, p), InvalidParameter);
  p.guide_b = {};
  EXPECT_THROW(two_guide_lines(f, p), InvalidParameter);
}
