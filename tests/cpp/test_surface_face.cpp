#include <gtest/gtest.h>

#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepGProp.hxx>
#include <BRep_Builder.hxx>
#include <GCPnts_AbscissaPoint.hxx>
#include <GC_MakeSegment.hxx>
#include <GProp_GProps.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <GeomAdaptor_Curve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_Curve.hxx>
#include <Geom_SurfaceOfLinearExtrusion.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <cmath>
#include <gp_Circ.hxx>
#include <gp_Pln.hxx>

#include "geometry/face_area.h"
#include "tessella/errors.h"
#include "tessella/surface_face.h"
#include "test_faces.h"

using namespace tessella;
using namespace tessella::test;

namespace {
constexpr double kPi = 3.14159265358979323846;

double loop_area(const std::vector<Vec2>& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2& q = p[(i + 1) % p.size()];
    a += p[i].x() * q.y() - q.x() * p[i].y();
  }
  return 0.5 * a;
}
}  // namespace

TEST(SurfaceFace, RejectsGarbageAndEmptyShapes) {
  EXPECT_THROW(SurfaceFace::from_brep_string("not a brep"), InvalidGeometry);
  EXPECT_THROW(SurfaceFace::from_brep_string(""), InvalidGeometry);
  BRepBuilderAPI_MakePolygon p(gp_Pnt(0, 0, 0), gp_Pnt(1, 0, 0));
  EXPECT_THROW(SurfaceFace::from_brep_string(brep(p.Wire())), InvalidGeometry);  // no face
}

TEST(SurfaceFace, CylinderPointNormalAndPeriod) {
  const SurfaceFace f = cylinder_face(5000, 8000);
  EXPECT_TRUE(f.u_periodic());
  EXPECT_NEAR(f.u_period(), 2 * kPi, 1e-12);
  for (double u : {0.0, 1.0, 3.0, 6.0}) {
    const Vec3 p = f.point(u, 1234.0);
    EXPECT_NEAR(std::hypot(p.x(), p.y()), 5000.0, 1e-9);
    EXPECT_NEAR(p.z(), 1234.0, 1e-9);
    const Vec3 n = f.normal(u, 1234.0);
    // The lateral face of a solid cylinder points outwards.
    EXPECT_NEAR(n.dot(Vec3(p.x(), p.y(), 0).normalized()), 1.0, 1e-12);
  }
  EXPECT_NEAR(f.area(), 2 * kPi * 5000 * 8000, 1e-6 * 2 * kPi * 5000 * 8000);
}

TEST(SurfaceFace, InsideTestAndTrimLoopsOfAPlateWithAHole) {
  const SurfaceFace f = plate_with_square_hole(1000, 300, 700);
  const UvBounds b = f.bounds();
  // The plane's (u,v) are x,y here: check on the grid of the plate.
  EXPECT_NEAR(b.u_max - b.u_min, 1000, 1e-9);
  EXPECT_TRUE(f.is_inside(b.u_min + 100, b.v_min + 100));
  EXPECT_FALSE(f.is_inside(b.u_min + 500, b.v_min + 500));  // in the hole
  EXPECT_FALSE(f.is_inside(b.u_min - 10, b.v_min + 500));   // outside
  const auto loops = f.trim_loops(0.01);
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_TRUE(loops[0].outer);
  EXPECT_FALSE(loops[1].outer);
  EXPECT_NEAR(loop_area(loops[0].uv), 1000.0 * 1000.0, 1e-6);  // counter-clockwise
  EXPECT_NEAR(loop_area(loops[1].uv), -400.0 * 400.0, 1e-6);   // clockwise
  EXPECT_NEAR(f.area(), 1000.0 * 1000.0 - 400.0 * 400.0, 1e-6);
}

TEST(SurfaceFace, TrimLoopChordsStayWithinTheDeflection) {
  const SurfaceFace f = cylinder_face(1000, 500);
  for (double deflection : {1.0, 0.01}) {
    for (const TrimLoop& loop : f.trim_loops(deflection)) {
      for (std::size_t i = 0; i < loop.xyz.size(); ++i) {
        const Vec3 m = 0.5 * (loop.xyz[i] + loop.xyz[(i + 1) % loop.xyz.size()]);
        // Chord midpoint to the circle of radius 1000 (closed form).
        if (std::abs(m.z()) < 1e-9 || std::abs(m.z() - 500) < 1e-9) {
          EXPECT_LE(1000.0 - std::hypot(m.x(), m.y()), deflection * 1.0001);
        }
      }
    }
  }
}

TEST(SurfaceFace, TrimLoopsAskedAgainAreTheSameAndFollowTheDeflection) {
  // The (u,v) loops are kept per deflection; a second call (and a call in a
  // span-cached scope) gives the loops a fresh face gives, bit for bit, and
  // another deflection its own loops.
  const SurfaceFace f = cylinder_face(1000, 500);
  const SurfaceFace fresh = cylinder_face(1000, 500);
  auto same = [](const std::vector<TrimLoop>& a, const std::vector<TrimLoop>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t l = 0; l < a.size(); ++l)
      if (a[l].uv != b[l].uv || a[l].xyz != b[l].xyz || a[l].corner != b[l].corner ||
          a[l].outer != b[l].outer)
        return false;
    return true;
  };
  const std::vector<TrimLoop> first = f.trim_loops(1.0);
  EXPECT_TRUE(same(first, f.trim_loops(1.0)));
  EXPECT_TRUE(same(first, fresh.trim_loops(1.0)));
  {
    const SurfaceFace::FastEvaluation fast(f);
    const SurfaceFace::FastEvaluation fast_fresh(fresh);
    EXPECT_TRUE(same(f.trim_loops(1.0), fresh.trim_loops(1.0)));
  }
  const std::vector<TrimLoop> finer = f.trim_loops(0.01);
  std::size_t coarse_points = 0, fine_points = 0;
  for (const TrimLoop& l : first) coarse_points += l.uv.size();
  for (const TrimLoop& l : finer) fine_points += l.uv.size();
  EXPECT_GT(fine_points, 5 * coarse_points);
  EXPECT_TRUE(same(finer, fresh.trim_loops(0.01)));
}

TEST(SurfaceFace, NewtonProjectionMatchesTheSphereInClosedForm) {
  const SurfaceFace f = sphere_face(3000);
  const Vec3 points[] = {
      {4000, 100, 200}, {-100, 2500, -1000}, {10, 20, 5000}, {0, 0, -3500}, {1000, -200, 300}};
  for (const Vec3& p : points) {
    const Projection r = f.project(p, Vec2(1.0, 0.2));
    EXPECT_NEAR(r.distance, std::abs(p.norm() - 3000.0), 1e-6) << p.transpose();
    EXPECT_NEAR(r.point.norm(), 3000.0, 1e-6);
    EXPECT_NEAR((r.point.normalized() - p.normalized()).norm(), 0.0, 1e-6);
  }
}

TEST(SurfaceFace, ProjectionAcrossTheSeamWraps) {
  const SurfaceFace f = cylinder_face(1000, 100);
  // A point just before the seam (angle -0.01) from a start just after it.
  const Vec3 p(1100 * std::cos(-0.01), 1100 * std::sin(-0.01), 50);
  const Projection r = f.project(p, Vec2(0.02, 50));
  EXPECT_NEAR(r.distance, 100.0, 1e-6);
  EXPECT_NEAR(std::atan2(r.point.y(), r.point.x()), -0.01, 1e-9);
  EXPECT_GE(r.uv.x(), 0.0);
  EXPECT_LE(r.uv.x(), 2 * kPi);
}

TEST(SurfaceFace, NormalIsDefinedAtAPole) {
  const SurfaceFace f = sphere_face(2000);
  const Vec3 n = f.normal(0.3, kPi / 2);
  EXPECT_NEAR(n.z(), 1.0, 1e-3);
}

TEST(SurfaceFace, ALoopOfOneClosedEdgeIsDiscretized) {
  // A disc: its outer wire is a single closed circle edge.
  BRepBuilderAPI_MakeEdge circle(gp_Circ(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 500.0));
  BRepBuilderAPI_MakeFace disc(gp_Pln(), BRepBuilderAPI_MakeWire(circle.Edge()).Wire());
  const SurfaceFace f = SurfaceFace::from_brep_string(brep(disc.Face()));
  const auto loops = f.trim_loops(0.01);
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_TRUE(loops[0].outer);
  EXPECT_GT(loops[0].uv.size(), 100u);
  // Inscribed polygon: its area is under the disc's by at most the chord sagittas.
  EXPECT_NEAR(loop_area(loops[0].uv), kPi * 500.0 * 500.0, 2 * kPi * 500.0 * 0.01);
}

// A wire may close with a gap within its first vertex's tolerance (a STEP
// face, 3.8e-7 mm on a 0.5 mm face): the last edge's end is that vertex
// again, as every other edge's start is its previous one's end, and is not
// kept as a loop point of its own (a rod of the gap's length at the corner).
TEST(SurfaceFace, AWireClosingWithinItsVertexToleranceHasOnePointThere) {
  const double gap = 4e-4;  // on a 100 mm plate: 2.8e-6 of the model, over 1e-9
  BRep_Builder b;
  const TopoDS_Vertex v0 = BRepBuilderAPI_MakeVertex(gp_Pnt(0, 0, 0));
  b.UpdateVertex(v0, gap);
  const TopoDS_Vertex v1 = BRepBuilderAPI_MakeVertex(gp_Pnt(100, 0, 0));
  const TopoDS_Vertex v2 = BRepBuilderAPI_MakeVertex(gp_Pnt(100, 100, 0));
  const TopoDS_Vertex v3 = BRepBuilderAPI_MakeVertex(gp_Pnt(0, 100, 0));
  auto line = [](const gp_Pnt& a, const gp_Pnt& c) {
    return Handle(Geom_Curve)(GC_MakeSegment(a, c).Value());
  };
  // The last edge's curve ends gap short of the first vertex's point.
  BRepBuilderAPI_MakeWire wire;
  wire.Add(BRepBuilderAPI_MakeEdge(v0, v1).Edge());
  wire.Add(BRepBuilderAPI_MakeEdge(v1, v2).Edge());
  wire.Add(BRepBuilderAPI_MakeEdge(v2, v3).Edge());
  const Handle(Geom_Curve) last = line(gp_Pnt(0, 100, 0), gp_Pnt(0, gap, 0));
  wire.Add(BRepBuilderAPI_MakeEdge(last, v3, v0, 0.0, last->LastParameter()).Edge());
  ASSERT_TRUE(wire.IsDone());
  BRepBuilderAPI_MakeFace plate(gp_Pln(), wire.Wire());
  ASSERT_TRUE(plate.IsDone());
  const SurfaceFace f = SurfaceFace::from_brep_string(brep(plate.Face()));
  const auto loops = f.trim_loops(1e-3);
  ASSERT_EQ(loops.size(), 1u);
  const auto& xyz = loops[0].xyz;
  double shortest = 1e300;
  for (std::size_t i = 0; i < xyz.size(); ++i)
    shortest = std::min(shortest, (xyz[(i + 1) % xyz.size()] - xyz[i]).norm());
  EXPECT_GT(shortest, 1.0);  // the plate's sides, not the gap
  EXPECT_NEAR(std::abs(loop_area(loops[0].uv)), 100.0 * 100.0, 1.0);
  int corners = 0;
  for (char c : loops[0].corner) corners += c ? 1 : 0;
  EXPECT_EQ(corners, 4);
}

// FastEvaluation (OCCT's span cache) gives the closed-form surface, its
// derivatives and projections, counts every evaluation, and ends with its scope.
TEST(SurfaceFace, FastEvaluationMatchesTheClosedForm) {
  const SurfaceFace f = stretched_plate();  // x = 400u + 600u^2, y = 1000v, z = 0
  auto check = [&](double u, double v) {
    const Vec3 p = f.point(u, v);
    EXPECT_NEAR(p.x(), 400 * u + 600 * u * u, 1e-9);
    EXPECT_NEAR(p.y(), 1000 * v, 1e-9);
    EXPECT_NEAR(p.z(), 0, 1e-9);
    const SurfacePoint d = f.derivatives(u, v);
    EXPECT_NEAR(d.du.x(), 400 + 1200 * u, 1e-9);
    EXPECT_NEAR(d.dv.y(), 1000, 1e-9);
    const Projection pr = f.project(Vec3(p.x(), p.y(), 50.0), {0.5, 0.5});
    EXPECT_NEAR(pr.distance, 50.0, 1e-6);
    EXPECT_NEAR(pr.uv.x(), u, 1e-9);
    EXPECT_NEAR(pr.uv.y(), v, 1e-9);
  };
  f.reset_evaluations();
  {
    const SurfaceFace::FastEvaluation fast(f);
    for (double u : {0.0, 0.13, 0.5, 0.91, 1.0}) check(u, 0.37);
    {
      const SurfaceFace::FastEvaluation inner(f);  // scopes nest
      check(0.25, 0.75);
    }
    check(0.75, 0.25);
  }
  EXPECT_GE(f.evaluations(), 7u * 3u);  // point, derivatives, >= 1 Newton step each
  check(0.6, 0.6);                      // and without the scope
}

namespace {
// The faces of `shape` converted to NURBS (rational where they were conics).
std::vector<TopoDS_Face> nurbs_faces(const TopoDS_Shape& shape) {
  BRepBuilderAPI_NurbsConvert convert(shape, true);
  std::vector<TopoDS_Face> out;
  for (TopExp_Explorer e(convert.Shape(), TopAbs_FACE); e.More(); e.Next())
    out.push_back(TopoDS::Face(e.Current()));
  return out;
}
}  // namespace

// OCCT's fixed-order rule is off by 0.16-0.37% on these rational faces (a
// NURBS disk, cylinder band and sphere); the face's area must be their closed
// form, or the coverage check refuses correct panels as overlapping.
TEST(SurfaceFace, TheAreaOfRationalFacesIsTheirClosedForm) {
  const double r = 1000, h = 1500;
  double band = 0, caps = 0;
  for (const TopoDS_Face& f : nurbs_faces(BRepPrimAPI_MakeCylinder(r, h).Shape())) {
    EXPECT_TRUE(face_has_rational_geometry(f));
    const double a = SurfaceFace::from_brep_string(brep(f)).area();
    (BRepAdaptor_Surface(f).IsUPeriodic() ? band : caps) += a;
  }
  EXPECT_NEAR(band, 2 * kPi * r * h, 1e-6 * band);
  EXPECT_NEAR(caps, 2 * kPi * r * r, 1e-6 * caps);
  const std::vector<TopoDS_Face> sphere = nurbs_faces(BRepPrimAPI_MakeSphere(r).Shape());
  ASSERT_EQ(sphere.size(), 1u);
  EXPECT_NEAR(face_area(sphere[0]), 4 * kPi * r * r, 1e-6 * 4 * kPi * r * r);
  // The fixed rule's error on the same face, so this test shows what it guards.
  GProp_GProps gauss;
  BRepGProp::SurfaceProperties(sphere[0], gauss);
  EXPECT_GT(std::abs(gauss.Mass() / (4 * kPi * r * r) - 1), 1e-3);
}

TEST(SurfaceFace, TheAreaOfAnExtrudedClosedCurveIsItsLengthTimesItsHeight) {
  // A closed B-spline curve extruded along its plane's normal: the area is
  // the curve's length (OCCT's arc length, an independent integral) times
  // the height.
  const int n = 7;
  const double radius[n] = {3000, 2400, 3500, 2800, 3300, 2600, 3100};
  Handle(TColgp_HArray1OfPnt) points = new TColgp_HArray1OfPnt(1, n);
  for (int k = 0; k < n; ++k) {
    const double a = 2 * kPi * k / n;
    points->SetValue(k + 1, gp_Pnt(radius[k] * std::cos(a), radius[k] * std::sin(a), 0));
  }
  GeomAPI_Interpolate interpolate(points, Standard_True, 1e-9);
  interpolate.Perform();
  const Handle(Geom_BSplineCurve) curve = interpolate.Curve();
  const double height = 4000;
  const TopoDS_Face face =
      BRepBuilderAPI_MakeFace(new Geom_SurfaceOfLinearExtrusion(curve, gp_Dir(0, 0, 1)),
                              curve->FirstParameter(), curve->LastParameter(), 0, height, 1e-7);
  GeomAdaptor_Curve adaptor(curve);
  const double exact = GCPnts_AbscissaPoint::Length(adaptor, 1e-12) * height;
  EXPECT_NEAR(SurfaceFace::from_brep_string(brep(face)).area(), exact, 1e-6 * exact);
  // OCCT's adaptive rule on the face as it is, so this test shows what it guards.
  GProp_GProps adaptive;
  BRepGProp::SurfaceProperties(face, adaptive, 1e-9);
  EXPECT_GT(std::abs(adaptive.Mass() / exact - 1), 1e-3);
}

TEST(SurfaceFace, PolynomialFacesKeepTheFixedOrderRule) {
  // A plate with a hole and a Bezier patch: the same area as OCCT's fixed
  // rule, bit for bit (their figures do not move).
  TopoDS_Face plate = BRepBuilderAPI_MakeFace(gp_Pln(), rect_wire(0, 0, 800, 600, false)).Face();
  TColgp_Array2OfPnt poles(1, 3, 1, 3);
  for (int i = 1; i <= 3; ++i)
    for (int j = 1; j <= 3; ++j)
      poles(i, j) = gp_Pnt(500.0 * i, 400.0 * j, (i == 2 && j == 2) ? 300.0 : 0.0);
  TopoDS_Face patch = BRepBuilderAPI_MakeFace(new Geom_BezierSurface(poles), 1e-7).Face();
  for (const TopoDS_Face& f : {plate, patch}) {
    EXPECT_FALSE(face_has_rational_geometry(f));
    GProp_GProps gauss;
    BRepGProp::SurfaceProperties(f, gauss);
    EXPECT_EQ(face_area(f), std::abs(gauss.Mass()));
  }
  EXPECT_NEAR(face_area(plate), 800.0 * 600.0, 1e-9 * 480000.0);
}
