#include <gtest/gtest.h>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepLib.hxx>
#include <GCE2d_MakeSegment.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <cmath>
#include <gp_Circ.hxx>
#include <set>

#include "analysis/coverage.h"
#include "mesh/grid_clipping.h"
#include "mesh/panel_model.h"
#include "mesh/sliver_merge.h"
#include "tessella/errors.h"
#include "tessella/grid_methods.h"
#include "tessella/panel_metrics.h"
#include "test_faces.h"

using namespace tessella;
using namespace tessella::test;

namespace {
constexpr double kPi = 3.14159265358979323846;

IsoGridParams counts(int nu, int nv) {
  IsoGridParams p;
  p.u_count = nu;
  p.v_count = nv;
  return p;
}
}  // namespace

TEST(IsoGrid, ClosedCylinderIsAllQuadsWeldedAcrossTheSeam) {
  const SurfaceFace f = cylinder_face(5000, 8000);
  const PanelMesh m = iso_grid(f, counts(24, 8));
  ASSERT_EQ(m.panels.size(), 24u * 8u);
  for (const auto& p : m.panels) EXPECT_EQ(p.size(), 4u);
  EXPECT_EQ(m.vertex_count(), 24u * 9u);          // seam welded: no duplicate column
  EXPECT_EQ(m.rods.size(), 24u * 9u + 24u * 8u);  // rings + verticals
  for (const Vec3& x : m.xyz) EXPECT_NEAR(std::hypot(x.x(), x.y()), 5000.0, 1e-9);
}

TEST(IsoGrid, CylinderDeviationIsTheSagittaOfTheChord) {
  const double r = 5000;
  const SurfaceFace f = cylinder_face(r, 2000);
  for (int n : {6, 12, 31}) {
    const PanelMesh m = iso_grid(f, counts(n, 2));
    const PanelMetrics metrics = measure_panels(f, m);
    // Flat rectangles on a circle: the largest gap is at mid-chord.
    const double sagitta = r * (1 - std::cos(kPi / n));
    for (double d : metrics.deviation) EXPECT_NEAR(d, sagitta, 1e-6 * r) << n;
    for (double p : metrics.planarity) EXPECT_NEAR(p, 0.0, 1e-9);
    for (double a : metrics.min_angle) EXPECT_NEAR(a, 90.0, 1e-6);
    // Panel edge along the circle: chord 2 r sin(pi/n); along the axis 1000.
    for (double len : metrics.rod_length) {
      const bool chord = std::abs(len - 2 * r * std::sin(kPi / n)) < 1e-6;
      const bool axial = std::abs(len - 1000.0) < 1e-6;
      EXPECT_TRUE(chord || axial) << len;
    }
  }
}

TEST(IsoGrid, SpherePolesBecomeTrianglesAndEveryNodeIsOnTheSphere) {
  const SurfaceFace f = sphere_face(3000);
  const PanelMesh m = iso_grid(f, counts(12, 6));
  int triangles = 0;
  for (const auto& p : m.panels) triangles += p.size() == 3;
  EXPECT_EQ(triangles, 24);  // one ring of 12 at each pole
  EXPECT_EQ(m.panels.size(), 72u);
  EXPECT_EQ(m.vertex_count(), 12u * 5u + 2u);
  for (const Vec3& x : m.xyz) EXPECT_NEAR(x.norm(), 3000.0, 1e-9);
  const PanelMetrics metrics = measure_panels(f, m);
  for (double d : metrics.deviation) {
    EXPECT_GT(d, 0.0);
    EXPECT_LT(d, 3000.0 * (1 - std::cos(kPi / 6)) * 1.5);  // panels span at most 30 deg
  }
}

TEST(IsoGrid, HoleStaysOpenAndAreaIsExactOnAPlate) {
  const SurfaceFace f = plate_with_square_hole(1000, 330, 670);
  const PanelMesh m = iso_grid(f, counts(10, 10));
  const PanelMetrics metrics = measure_panels(f, m);
  double area = 0;
  for (double a : metrics.area) area += a;
  EXPECT_NEAR(area, 1000.0 * 1000.0 - 340.0 * 340.0, 1e-6);
  for (const Vec3& x : m.xyz) {
    EXPECT_NEAR(x.z(), 0.0, 1e-12);
    const bool in_hole =
        x.x() > 330 + 1e-9 && x.x() < 670 - 1e-9 && x.y() > 330 + 1e-9 && x.y() < 670 - 1e-9;
    EXPECT_FALSE(in_hole) << x.transpose();
  }
  // Each panel's uv triangulation centroids lie inside the face.
  for (std::size_t p = 0; p < m.panels.size(); ++p) {
    const std::vector<Vec2> uv = panel_corner_uv(m, p);
    for (const auto& t : triangulate_polygon(uv)) {
      const Vec2 c = (uv[t[0]] + uv[t[1]] + uv[t[2]]) / 3.0;
      EXPECT_TRUE(f.is_inside(c.x(), c.y()));
    }
  }
}

TEST(IsoGrid, SliversNextToAHoleMergeIntoTheOuterRing) {
  // Hole [105,895]^2 in a 10 x 10 grid of 100 mm cells: the ring of cells
  // around it keeps 5 mm strips (28 slivers) that merge into the 36 outer cells.
  const SurfaceFace f = plate_with_square_hole(1000, 105, 895);
  const PanelMesh m = iso_grid(f, counts(10, 10));
  EXPECT_EQ(m.merged_slivers, 28);
  EXPECT_EQ(m.panels.size(), 36u);
  IsoGridParams keep = counts(10, 10);
  keep.clip.sliver_fraction = 0.0;
  const PanelMesh unmerged = iso_grid(f, keep);
  EXPECT_EQ(unmerged.merged_slivers, 0);
  EXPECT_EQ(unmerged.panels.size(), 64u);
  double a1 = 0, a2 = 0;
  for (double a : measure_panels(f, m).area) a1 += a;
  for (double a : measure_panels(f, unmerged).area) a2 += a;
  EXPECT_NEAR(a1, 1e6 - 790.0 * 790.0, 1e-6);
  EXPECT_NEAR(a2, a1, 1e-6);
}

TEST(IsoGrid, NoTJunctionsEveryEdgeHasAtMostTwoPanels) {
  const SurfaceFace f = plate_with_square_hole(1000, 333, 667);
  const PanelMesh m = iso_grid(f, counts(7, 9));
  std::map<std::array<int, 2>, int> uses;
  for (const auto& p : m.panels)
    for (std::size_t k = 0; k < p.size(); ++k) {
      const int a = p[k], b = p[(k + 1) % p.size()];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  // Boundary edges: used once; their total length is the two perimeters.
  double boundary = 0;
  for (const auto& [e, n] : uses) {
    EXPECT_LE(n, 2);
    if (n == 1) boundary += (m.xyz[e[0]] - m.xyz[e[1]]).norm();
  }
  EXPECT_NEAR(boundary, 4000.0 + 4 * 334.0, 1e-6);
}

TEST(IsoGrid, BySizeGivesEdgesNearTheSize) {
  const SurfaceFace f = cylinder_face(5000, 8000);
  IsoGridParams p;
  p.size = 1000;
  const PanelMesh m = iso_grid(f, p);
  const PanelMetrics metrics = measure_panels(f, m);
  for (double len : metrics.rod_length) EXPECT_NEAR(len, 1000.0, 20.0);
}

TEST(IsoGrid, BadParametersAreRejectedWithTheirName) {
  const SurfaceFace f = cylinder_face(5000, 8000);
  IsoGridParams p;
  p.size = -1;
  try {
    iso_grid(f, p);
    FAIL();
  } catch (const InvalidParameter& e) {
    EXPECT_NE(std::string(e.what()).find("size"), std::string::npos);
  }
  EXPECT_THROW(iso_grid(f, IsoGridParams{}), InvalidParameter);  // nothing given
  IsoGridParams both = counts(3, 3);
  both.size = 100;
  EXPECT_THROW(iso_grid(f, both), InvalidParameter);
  IsoGridParams tiny;
  tiny.size = 1.0;  // 31 416 x 8 000 panels
  EXPECT_THROW(iso_grid(f, tiny), LimitExceeded);
  IsoGridParams capped = counts(100, 100);
  capped.clip.max_panels = 9999;
  EXPECT_THROW(iso_grid(f, capped), LimitExceeded);
  IsoGridParams nan_size;
  nan_size.size = std::nan("");
  EXPECT_THROW(iso_grid(f, nan_size), InvalidParameter);
}

TEST(IsoGrid, IsDeterministic) {
  const SurfaceFace f = plate_with_square_hole(1000, 123, 456);
  const PanelMesh a = iso_grid(f, counts(13, 11));
  const PanelMesh b = iso_grid(f, counts(13, 11));
  ASSERT_EQ(a.xyz.size(), b.xyz.size());
  for (std::size_t i = 0; i < a.xyz.size(); ++i) EXPECT_EQ(a.xyz[i], b.xyz[i]);
  EXPECT_EQ(a.panels, b.panels);
}

TEST(EqualSizeGrid, EvensOutAnUnevenParameterization) {
  const SurfaceFace f = stretched_plate();
  IsoGridParams iso;
  iso.size = 100;
  EqualSizeGridParams eq;
  eq.size = 100;
  auto x_edges = [&](const PanelMesh& m) {
    std::vector<double> out;
    for (const auto& rod : m.rods) {
      const Vec3 d = m.xyz[rod[1]] - m.xyz[rod[0]];
      if (std::abs(d.y()) < 1e-9) out.push_back(std::abs(d.x()));
    }
    return out;
  };
  const std::vector<double> iso_x = x_edges(iso_grid(f, iso));
  const std::vector<double> eq_x = x_edges(equal_size_grid(f, eq));
  ASSERT_FALSE(eq_x.empty());
  // x(u) = 400u + 600u^2 with 10 columns: uniform u gives widths 46..154 mm.
  EXPECT_LT(*std::min_element(iso_x.begin(), iso_x.end()), 50.0);
  EXPECT_GT(*std::max_element(iso_x.begin(), iso_x.end()), 150.0);
  for (double w : eq_x) EXPECT_NEAR(w, 100.0, 0.5);
  EqualSizeGridParams missing;
  EXPECT_THROW(equal_size_grid(f, missing), InvalidParameter);
}

TEST(IsoGrid, OnlyCrossingsAndCornersOfACurvedTrimAreNodes) {
  // Disc of radius 500 (one closed circle edge, its B-rep vertex at (500,0))
  // with a 4 x 4 grid over [-500,500]^2: nodes are the 9 inner grid nodes and
  // the 12 points where grid lines meet the circle; the circle's many outline
  // points only shape the boundary panels. Rods: 4 segments on each of the 6
  // inner lines, and 12 chords between neighbouring boundary nodes.
  BRepBuilderAPI_MakeEdge circle(gp_Circ(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 500.0));
  BRepBuilderAPI_MakeFace disc(gp_Pln(), BRepBuilderAPI_MakeWire(circle.Edge()).Wire());
  const SurfaceFace f = SurfaceFace::from_brep_string(brep(disc.Face()));
  IsoGridParams p = counts(4, 4);
  p.clip.sliver_fraction = 0.0;
  const PanelMesh m = iso_grid(f, p);
  int nodes = 0;
  for (std::size_t v = 0; v < m.vertex_count(); ++v) nodes += is_node(m, int(v));
  EXPECT_EQ(nodes, 21);
  EXPECT_GT(m.vertex_count(), 100u);  // the outline follows the circle
  EXPECT_EQ(m.rods.size(), 36u);
  for (const auto& rod : m.rods) {
    EXPECT_TRUE(is_node(m, rod[0]) && is_node(m, rod[1]));
    // A rod ends on the circle, on a grid line, or both.
    for (int v : rod) {
      const Vec3& x = m.xyz[v];
      const bool on_line = std::abs(std::fmod(x.x() + 1000.0, 250.0)) < 1e-9 ||
                           std::abs(std::fmod(x.y() + 1000.0, 250.0)) < 1e-9;
      EXPECT_TRUE(on_line || std::abs(x.norm() - 500.0) < 1e-6);
    }
  }
}

namespace {
// Signed (u,v) area of a polygon (counter-clockwise > 0).
double signed_area(const std::vector<Vec2>& q) {
  double a = 0;
  for (std::size_t k = 0; k < q.size(); ++k) {
    const Vec2& p = q[k];
    const Vec2& r = q[(k + 1) % q.size()];
    a += p.x() * r.y() - p.y() * r.x();
  }
  return 0.5 * a;
}

// Strictly inside a simple polygon (even-odd), at least `margin` from its edges.
bool strictly_inside(const std::vector<Vec2>& q, const Vec2& x, double margin) {
  bool in = false;
  for (std::size_t k = 0; k < q.size(); ++k) {
    const Vec2& a = q[k];
    const Vec2& b = q[(k + 1) % q.size()];
    const Vec2 d = b - a;
    const double t = std::clamp((x - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    if ((a + t * d - x).norm() < margin) return false;
    if ((a.y() > x.y()) != (b.y() > x.y()) &&
        x.x() < a.x() + (x.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x()))
      in = !in;
  }
  return in;
}
}  // namespace

// A whole opening inside one grid cell: the cell is split through the hole,
// and the split line's ends on the cell's grid lines are no trim crossings.
// They used to be snapped onto the nearest trim (here the plate's edge x = 0,
// across the neighbouring cell), so panels wrapped around their neighbours.
TEST(IsoGrid, AHoleInsideOneCellIsSplitWithoutOverlap) {
  BRepBuilderAPI_MakeFace mk(gp_Pln(), rect_wire(0, 0, 1000, 1000, false));
  mk.Add(rect_wire(400, 300, 600, 700, true));
  const SurfaceFace f = SurfaceFace::from_brep_string(brep(mk.Face()));
  const double hole_free = 1000.0 * 1000.0 - 200.0 * 400.0;
  // The tall cell [100,700] x [100,900] holds the hole and is split at y = 500,
  // whose ends (100,500) and (700,500) are nearer the plate's edges than the hole.
  for (double sliver : {0.0, 0.25}) {
    GridClipParams params;
    params.sliver_fraction = sliver;
    const PanelMesh m = clip_grid(f, {0, 100, 700, 1000}, {0, 100, 900, 1000}, params);
    // Independent of the coverage scan: on a plane the panels' (u,v) areas
    // (u,v = x,y) tile the face only if they add up to it and no panel holds
    // another's vertex.
    double area = 0;
    std::vector<std::vector<Vec2>> polys;
    for (std::size_t p = 0; p < m.panels.size(); ++p) {
      polys.push_back(panel_corner_uv(m, p));
      const double a = signed_area(polys.back());
      EXPECT_GT(a, 0.0) << "panel " << p;
      area += a;
    }
    EXPECT_NEAR(area, hole_free, 1e-6 * hole_free);
    for (std::size_t p = 0; p < polys.size(); ++p)
      for (std::size_t v = 0; v < m.uv.size(); ++v)
        EXPECT_FALSE(strictly_inside(polys[p], m.uv[v], 1e-6))
            << "panel " << p << " holds vertex " << m.uv[v].transpose();
    // The split line's ends stay where the split put them.
    for (const Vec2& end : {Vec2(100, 500), Vec2(700, 500)}) {
      bool found = false;
      for (const Vec2& q : m.uv) found = found || (q - end).norm() < 1e-9;
      EXPECT_TRUE(found) << end.transpose();
    }
    const Coverage c = measure_coverage(f, m, measure_panels(f, m).area);
    EXPECT_LT(c.gap_fraction(), 1e-9);
    EXPECT_LT(c.overlap_fraction(), 1e-9);
    EXPECT_NO_THROW(check_coverage(c, 0.0, "test"));
  }
}

TEST(IsoGrid, AHoleInTheMiddleCellOfAThreeByThreeGridLeavesNoGap) {
  // Square hole in the middle cell: the split's ends (500, 333) and
  // (500, 667) used to be pulled onto the hole's edges, into the rows of
  // cells below and above (a spike in each).
  const SurfaceFace f = plate_with_square_hole(1000, 400, 600);
  const PanelMesh m = iso_grid(f, counts(3, 3));
  for (const Vec2& end : {Vec2(500, 1000.0 / 3), Vec2(500, 2000.0 / 3)}) {
    bool found = false;
    for (const Vec2& q : m.uv) found = found || (q - end).norm() < 1e-9;
    EXPECT_TRUE(found) << end.transpose();
  }
  const Coverage c = measure_coverage(f, m, measure_panels(f, m).area);
  EXPECT_NEAR(c.face_area, 1e6 - 200.0 * 200.0, 1e-6 * 1e6);
  EXPECT_LT(c.gap_fraction(), 1e-9);
  EXPECT_LT(c.overlap_fraction(), 1e-9);
  double area = 0;
  for (double a : measure_panels(f, m).area) area += a;
  EXPECT_NEAR(area, 1e6 - 200.0 * 200.0, 1e-6);
}

TEST(PanelModel, ADentedQuadOfFourNodesIsFlatPiecesNotAFoldedBilinearPatch) {
  // Half of a cell split around an opening, split again by a new rod, can be
  // a quad dented at one node; its bilinear patch folds over itself and
  // counted the dent twice (the vault's and the plate's model_area refused).
  PanelMesh m;
  for (const Vec2& q : {Vec2(0, 0), Vec2(300, 100), Vec2(100, 100), Vec2(0, 300)}) {
    m.uv.push_back(q);
    m.xyz.push_back(Vec3(q.x(), q.y(), 0));
  }
  m.panels.push_back({0, 1, 2, 3});
  EXPECT_TRUE(modelled_as_pieces(m, 0));
  EXPECT_NEAR(panel_area(m, 0), signed_area(panel_corner_uv(m, 0)), 1e-9);
  EXPECT_NEAR(panel_area(m, 0), 25000.0, 1e-9);
  // A convex quad stays a bilinear patch.
  m.uv[2] = Vec2(200, 200), m.xyz[2] = Vec3(200, 200, 0);
  EXPECT_FALSE(modelled_as_pieces(m, 0));
}

namespace {
// A closed polygon of straight (u,v) segments on `surface`.
TopoDS_Wire uv_polygon(const Handle(Geom_Surface) & surface, const std::vector<gp_Pnt2d>& pts) {
  BRepBuilderAPI_MakeWire wire;
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const gp_Pnt2d& a = pts[k];
    const gp_Pnt2d& b = pts[(k + 1) % pts.size()];
    wire.Add(BRepBuilderAPI_MakeEdge(GCE2d_MakeSegment(a, b).Value(), surface).Edge());
  }
  return wire.Wire();
}
}  // namespace

TEST(IsoGrid, AHoleInOneCellOfAStretchedParameterizationDoesNotWrapTheNeighbour) {
  // The plate [0,1000]^2 with u = x / 1000 and v = y (as vault_openings: u
  // spans 1, v thousands), an opening u in [0.4, 0.6], v in [200, 400] inside
  // the cell [0.1, 0.7] x [100, 500], split at u = 0.5. In (u,v) the split's
  // ends (0.5, 100) and (0.5, 500) are nearest the edge u = 0, at the grid
  // nodes (0, 100) and (0, 500): snapped there, they welded onto them and the
  // half-cells wrapped around the full cells of the first column.
  TColgp_Array2OfPnt poles(1, 3, 1, 2);
  for (int i = 1; i <= 3; ++i) {
    poles(i, 1) = gp_Pnt(500.0 * (i - 1), 0, 0);
    poles(i, 2) = gp_Pnt(500.0 * (i - 1), 1000, 0);
  }
  TColStd_Array1OfReal uk(1, 3), vk(1, 2);
  uk(1) = 0, uk(2) = 0.5, uk(3) = 1, vk(1) = 0, vk(2) = 1000;
  TColStd_Array1OfInteger umult(1, 3), vmult(1, 2);
  umult(1) = 2, umult(2) = 1, umult(3) = 2, vmult(1) = vmult(2) = 2;
  Handle(Geom_BSplineSurface) surface = new Geom_BSplineSurface(poles, uk, vk, umult, vmult, 1, 1);
  BRepBuilderAPI_MakeFace mk(surface, uv_polygon(surface, {{0, 0}, {1, 0}, {1, 1000}, {0, 1000}}),
                             true);
  mk.Add(uv_polygon(surface, {{0.4, 200}, {0.4, 400}, {0.6, 400}, {0.6, 200}}));
  TopoDS_Face face = mk.Face();
  BRepLib::BuildCurves3d(face);
  const SurfaceFace f = SurfaceFace::from_brep_string(brep(face));
  GridClipParams params;
  params.sliver_fraction = 0.0;
  const PanelMesh m = clip_grid(f, {0, 0.1, 0.7, 1}, {0, 100, 500, 1000}, params);
  const Coverage c = measure_coverage(f, m, measure_panels(f, m).area);
  EXPECT_NEAR(c.face_area, 1e6 - 200.0 * 200.0, 1e-6 * 1e6);
  EXPECT_LT(c.gap_fraction(), 1e-9);
  EXPECT_LT(c.overlap_fraction(), 1e-9);
  double area = 0;
  for (double a : measure_panels(f, m).area) area += a;
  EXPECT_NEAR(area, 1e6 - 200.0 * 200.0, 1e-6);
  // No panel repeats a vertex (wrapping around a neighbour welds its corners in).
  for (const auto& p : m.panels) EXPECT_EQ(std::set<int>(p.begin(), p.end()).size(), p.size());
}

// A trim that runs along a grid line a hair's breadth off it (here a plate's
// bottom edge wiggling +-2e-7 mm about y = 0, as an approximated pcurve of a
// face cut along an iso-line does) leaves the cells beside it whole: four
// nodes each, no trim point on their side (before, the bottom row's outlines
// carried the edge's points, some of them nodes, and were bent pieces).
TEST(IsoGrid, ATrimAHairsBreadthOffAGridLineLeavesTheCellsBesideItWhole) {
  TColgp_Array1OfPnt pts(1, 5);
  for (int k = 0; k < 5; ++k)
    pts.SetValue(k + 1, gp_Pnt(250.0 * k, k % 2 ? (k == 1 || k == 3 ? 2e-7 : -2e-7) : 0.0, 0));
  pts.SetValue(3, gp_Pnt(500, -2e-7, 0));
  GeomAPI_PointsToBSpline fit(pts, 3, 3, GeomAbs_C2, 1e-12);
  BRepBuilderAPI_MakeWire wire;
  wire.Add(BRepBuilderAPI_MakeEdge(fit.Curve()).Edge());
  wire.Add(BRepBuilderAPI_MakeEdge(gp_Pnt(1000, 0, 0), gp_Pnt(1000, 1000, 0)).Edge());
  wire.Add(BRepBuilderAPI_MakeEdge(gp_Pnt(1000, 1000, 0), gp_Pnt(0, 1000, 0)).Edge());
  wire.Add(BRepBuilderAPI_MakeEdge(gp_Pnt(0, 1000, 0), gp_Pnt(0, 0, 0)).Edge());
  ASSERT_TRUE(wire.IsDone());
  BRepBuilderAPI_MakeFace mk(gp_Pln(), wire.Wire());
  ASSERT_TRUE(mk.IsDone());
  const SurfaceFace f = SurfaceFace::from_brep_string(brep(mk.Face()));
  const UvBounds b = f.bounds();
  ASSERT_LT(b.v_min, -1e-7);  // the wiggle is off the bottom line
  const PanelMesh m = iso_grid(f, counts(10, 10));
  ASSERT_EQ(m.panels.size(), 100u);
  for (std::size_t p = 0; p < m.panels.size(); ++p) {
    EXPECT_EQ(m.panels[p].size(), 4u) << p;
    for (int v : m.panels[p]) EXPECT_TRUE(is_node(m, v)) << p;
  }
  // The outline still follows the trim within the deflection.
  for (std::size_t v = 0; v < m.vertex_count(); ++v) EXPECT_GE(m.xyz[v].y(), b.v_min - 1e-12);
}

// A panel tapering to a knife edge where a rod meets the trim nearly along
// it (iso_grid on trimmed_bspline_holes at 1200 mm: 0.03 deg) goes into the
// neighbour across that rod; the rod goes, the trim point stays.
TEST(SpikeMerge, AKnifeEdgePanelJoinsItsNeighbourAcrossTheRod) {
  PanelMesh m;
  // Nodes A(0,0), B(10,0), C(0,5); the trim runs from B back left through
  // T1(5,0.2) and T2(2,1.5) to C: a corner of 2.3 deg at B between the rod
  // B-A and the trim. The quad below shares the rod A-B.
  m.xyz = {Vec3(0, 0, 0), Vec3(10, 0, 0),  Vec3(5, 0.2, 0), Vec3(2, 1.5, 0),
           Vec3(0, 5, 0), Vec3(0, -10, 0), Vec3(10, -10, 0)};
  for (const Vec3& x : m.xyz) m.uv.emplace_back(x.x(), x.y());
  m.is_node = {1, 1, 0, 0, 1, 1, 1};
  const int A = 0, B = 1, T1 = 2, T2 = 3, C = 4, E = 5, F = 6;
  m.panels = {{A, B, T1, T2, C}, {B, A, E, F}};
  build_rods(m);
  const PanelMesh before = m;
  // a union of more nodes than allowed: kept
  EXPECT_EQ(merge_spikes(m, kSpikeCornerDeg, 3), 0);
  EXPECT_EQ(m.panels, before.panels);
  // a limit under the spike's corner: kept
  EXPECT_EQ(merge_spikes(m, 2.0, 5), 0);

  EXPECT_EQ(merge_spikes(m, kSpikeCornerDeg, 5), 1);
  ASSERT_EQ(m.panels.size(), 1u);
  const std::vector<int>& p = m.panels[0];
  EXPECT_EQ(std::set<int>(p.begin(), p.end()), (std::set<int>{A, B, T1, T2, C, E, F}));
  // every corner of the union blunter than 5 deg; no rod A-B any more
  for (std::size_t k = 0; k < p.size(); ++k) {
    const Vec3 a = m.xyz[p[(k + p.size() - 1) % p.size()]] - m.xyz[p[k]];
    const Vec3 b = m.xyz[p[(k + 1) % p.size()]] - m.xyz[p[k]];
    EXPECT_GT(std::acos(a.dot(b) / (a.norm() * b.norm())) * 180 / 3.14159265358979323846, 5.0);
  }
  for (const auto& r : m.rods) EXPECT_FALSE(r[0] == A && r[1] == B);
  EXPECT_EQ(m.rods.size(), before.rods.size() - 1);
  // nothing left to merge
  EXPECT_EQ(merge_spikes(m, kSpikeCornerDeg, 5), 0);
  EXPECT_THROW(merge_spikes(m, -1.0, 5), InvalidParameter);
}
