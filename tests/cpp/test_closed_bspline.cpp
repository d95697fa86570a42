// periodic_where_closed: a B-spline surface closed on itself is read as
// periodic only when that changes no point.
#include <gtest/gtest.h>

#include <BRepBuilderAPI_MakeFace.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <cmath>
#include <random>

#include "geometry/closed_bspline.h"
#include "tessella/surface_face.h"
#include "test_faces.h"

namespace tessella {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A bicubic band round the z axis, clamped in both directions, whose last
// row of poles along u repeats its first: closed on itself, not periodic.
// `gap` moves the last row off the first; `weight` (if not 1) makes the
// surface rational with that weight on the last row only.
Handle(Geom_BSplineSurface) band(double gap = 0.0, double weight = 1.0) {
  const int nu = 9, nv = 5, degree = 3;
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  TColStd_Array2OfReal weights(1, nu, 1, nv);
  for (int i = 1; i <= nu; ++i)
    for (int j = 1; j <= nv; ++j) {
      const double a = 2 * kPi * ((i - 1) % (nu - 1)) / (nu - 1);
      const double r = 1000.0 - 120.0 * j + 60.0 * std::sin(3 * a);
      poles(i, j) = gp_Pnt(r * std::cos(a) + (i == nu ? gap : 0.0), r * std::sin(a), 400.0 * j);
      weights(i, j) = i == nu ? weight : 1.0;
    }
  auto knots = [degree](TColStd_Array1OfReal& k, TColStd_Array1OfInteger& m) {
    for (int i = 1; i <= k.Length(); ++i) k(i) = i - 1, m(i) = 1;
    m(1) = m(k.Length()) = degree + 1;
  };
  TColStd_Array1OfReal ku(1, nu - degree + 1), kv(1, nv - degree + 1);
  TColStd_Array1OfInteger mu(1, nu - degree + 1), mv(1, nv - degree + 1);
  knots(ku, mu);
  knots(kv, mv);
  if (weight != 1.0) return new Geom_BSplineSurface(poles, weights, ku, kv, mu, mv, degree, degree);
  return new Geom_BSplineSurface(poles, ku, kv, mu, mv, degree, degree);
}

TEST(ClosedBSpline, ABandClosedOnItselfIsReadAsPeriodicWithTheSamePoints) {
  const Handle(Geom_BSplineSurface) s = band();
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

TEST(ClosedBSpline, SurfacesNotClosedOnThemselvesAreLeftAsTheyAre) {
  const Handle(Geom_BSplineSurface) apart = band(1e-3);  // the last row a micron off
  EXPECT_EQ(periodic_where_closed(apart).get(), apart.get());
  const Handle(Geom_BSplineSurface) weighted = band(0.0, 2.0);  // same poles, other weights
  EXPECT_EQ(periodic_where_closed(weighted).get(), weighted.get());
  Handle(Geom_BSplineSurface) periodic = band();
  periodic->SetUPeriodic();
  EXPECT_EQ(periodic_where_closed(periodic).get(), periodic.get());
  EXPECT_TRUE(periodic_where_closed(Handle(Geom_BSplineSurface)()).IsNull());
}

TEST(ClosedBSpline, AFaceOnABandClosedOnItselfIsPeriodic) {
  const Handle(Geom_BSplineSurface) s = band();
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
