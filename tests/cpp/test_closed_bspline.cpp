// periodic_where_closed: a B-spline surface closed on itself is read as
// periodic only when that changes no point.
#include <gtest/gtest.h>

#include <BRepBuilderAPI_MakeFace.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <cmath>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>
#include <random>

#include "geometry/closed_bspline.h"
#include "tessella/surface_face.h"
#include "test_faces.h"

namespace tessella {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A bicubic band round the z axis, periodic along u (8 poles round), made
// not periodic by OCCT: its last row of poles its first, smooth across the
// seam. Closed on itself, not periodic.
Handle(Geom_BSplineSurface) smooth_band() {
  const int nu = 8, nv = 5, degree = 3;
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  for (int i = 1; i <= nu; ++i)
    for (int j = 1; j <= nv; ++j) {
      const double a = 2 * kPi * (i - 1) / nu;
      const double r = 1000.0 - 120.0 * j + 60.0 * std::sin(3 * a);
      poles(i, j) = gp_Pnt(r * std::cos(a), r * std::sin(a), 400.0 * j);
    }
  TColStd_Array1OfReal ku(1, nu + 1), kv(1, nv - degree + 1);
  TColStd_Array1OfInteger mu(1, nu + 1), mv(1, nv - degree + 1);
  for (int i = 1; i <= nu + 1; ++i) ku(i) = i - 1, mu(i) = 1;
  for (int i = 1; i <= kv.Length(); ++i) kv(i) = i - 1, mv(i) = 1;
  mv(1) = mv(kv.Length()) = degree + 1;
  Handle(Geom_BSplineSurface) s =
      new Geom_BSplineSurface(poles, ku, kv, mu, mv, degree, degree, Standard_True);
  // A full knot at the seam first, so that the surface, made not periodic,
  // ends on a row of poles at each side of it (the same row).
  s->InsertUKnot(0.0, degree, 1e-9);
  s->SetUNotPeriodic();
  return s;
}

// The same poles clamped at the seam as they are: the last row repeats the
// first, but the two sides meet at a crease (the tangents at a clamped end
// run along its first and last legs of poles).
Handle(Geom_BSplineSurface) creased_band() {
  const int nu = 9, nv = 5, degree = 3;
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  for (int i = 1; i <= nu; ++i)
    for (int j = 1; j <= nv; ++j) {
      const double a = 2 * kPi * ((i - 1) % (nu - 1)) / (nu - 1);
      const double r = 1000.0 - 120.0 * j + 60.0 * std::sin(3 * a);
      poles(i, j) = gp_Pnt(r * std::cos(a), r * std::sin(a), 400.0 * j);
    }
  TColStd_Array1OfReal ku(1, nu - degree + 1), kv(1, nv - degree + 1);
  TColStd_Array1OfInteger mu(1, nu - degree + 1), mv(1, nv - degree + 1);
  for (int i = 1; i <= ku.Length(); ++i) ku(i) = i - 1, mu(i) = 1;
  for (int i = 1; i <= kv.Length(); ++i) kv(i) = i - 1, mv(i) = 1;
  mu(1) = mu(ku.Length()) = mv(1) = mv(kv.Length()) = degree + 1;
  return new Geom_BSplineSurface(poles, ku, kv, mu, mv, degree, degree);
}

TEST(ClosedBSpline, ABandClosedOnItselfIsReadAsPeriodicWithTheSamePoints) {
  // Smooth across its seam, or creased there (read as periodic all the
  // same: the crease then lies inside panels, as any other crease of a
  // surface does, and the measure sees it).
  for (const Handle(Geom_BSplineSurface) & s : {smooth_band(), creased_band()}) {
    ASSERT_FALSE(s->IsUPeriodic());
    const Handle(Geom_BSplineSurface) p = periodic_where_closed(s);
    ASSERT_NE(p.get(), s.get());
    EXPECT_TRUE(p->IsUPeriodic());
    EXPECT_FALSE(p->IsVPeriodic());
    EXPECT_FALSE(s->IsUPeriodic());  // the original is left alone
    double a0, a1, b0, b1, c0, c1, d0, d1;
    s->Bounds(a0, a1, b0, b1);
    p->Bounds(c0, c1, d0, d1);
    EXPECT_EQ(a0, c0);
    EXPECT_EQ(a1, c1);
    EXPECT_EQ(b0, d0);
    EXPECT_EQ(b1, d1);
    // Independent of the function's own 17 x 17 check: random points.
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(a0, a1), v(b0, b1);
    for (int k = 0; k < 500; ++k) {
      const double x = u(rng), y = v(rng);
      EXPECT_LT(s->Value(x, y).Distance(p->Value(x, y)), 1e-9) << x << " " << y;
    }
    // And round the seam, u wraps.
    EXPECT_LT(p->Value(a1 + 0.25, 1.0).Distance(s->Value(a0 + 0.25, 1.0)), 1e-9);
  }
  // The creased band's premise: its sides meet at an angle.
  const Handle(Geom_BSplineSurface) creased = creased_band();
  gp_Pnt p;
  gp_Vec du0, dv0, du1, dv1;
  creased->D1(0.0, 1.0, p, du0, dv0);
  creased->D1(6.0, 1.0, p, du1, dv1);
  EXPECT_GT(du0.Crossed(dv0).Angle(du1.Crossed(dv1)), 0.1);
}

TEST(ClosedBSpline, SurfacesNotClosedOnThemselvesAreLeftAsTheyAre) {
  // The last row a micron off.
  Handle(Geom_BSplineSurface) apart = smooth_band();
  for (int j = 1; j <= apart->NbVPoles(); ++j)
    apart->SetPole(apart->NbUPoles(), j,
                   apart->Pole(apart->NbUPoles(), j).Translated(gp_Vec(1e-3, 0, 0)));
  EXPECT_EQ(periodic_where_closed(apart).get(), apart.get());
  // The same poles, other weights on the last row.
  Handle(Geom_BSplineSurface) weighted = smooth_band();
  for (int j = 1; j <= weighted->NbVPoles(); ++j) weighted->SetWeight(weighted->NbUPoles(), j, 2.0);
  EXPECT_EQ(periodic_where_closed(weighted).get(), weighted.get());
  Handle(Geom_BSplineSurface) periodic = smooth_band();
  periodic->SetUPeriodic();
  EXPECT_EQ(periodic_where_closed(periodic).get(), periodic.get());
  EXPECT_TRUE(periodic_where_closed(Handle(Geom_BSplineSurface)()).IsNull());
}

TEST(ClosedBSpline, AFaceOnABandClosedOnItselfIsPeriodic) {
  const Handle(Geom_BSplineSurface) s = smooth_band();
  const SurfaceFace face =
      SurfaceFace::from_brep_string(test::brep(BRepBuilderAPI_MakeFace(s, 1e-7).Face()));
  EXPECT_TRUE(face.u_periodic());
  EXPECT_FALSE(face.v_periodic());
  double a0, a1, b0, b1;
  s->Bounds(a0, a1, b0, b1);
  EXPECT_DOUBLE_EQ(face.u_period(), a1 - a0);
  const gp_Pnt q = s->Value(2.5, 1.5);
  EXPECT_LT((face.point(2.5, 1.5) - Vec3(q.X(), q.Y(), q.Z())).norm(), 1e-9);
}

}  // namespace
}  // namespace tessella
