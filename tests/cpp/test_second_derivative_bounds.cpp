// SecondDerivativeBounds against OCCT's own second derivatives
// (Geom_Surface::D2) sampled densely inside random boxes: a bound below a
// sampled value is a defect (the metric's check of what lies between its
// samples rests on it); a bound far above the sampled values makes that
// check slow, so how loose they are is asserted as well.
#include <gtest/gtest.h>

#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierSurface.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_OffsetSurface.hxx>
#include <Geom_Plane.hxx>
#include <Geom_SphericalSurface.hxx>
#include <Geom_ToroidalSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <algorithm>
#include <random>

#include "geometry/second_derivative_bounds.h"

using namespace tessella;

namespace {

// The largest |S_uu|, |S_uv|, |S_vv| of a 41 x 41 sampling of the box.
SecondDerivativeBound sampled(const Handle(Geom_Surface) & s, const UvBounds& box) {
  SecondDerivativeBound out;
  const int n = 40;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double u = box.u_min + (box.u_max - box.u_min) * i / n;
      const double v = box.v_min + (box.v_max - box.v_min) * j / n;
      gp_Pnt p;
      gp_Vec su, sv, suu, svv, suv;
      s->D2(u, v, p, su, sv, suu, svv, suv);
      out.uu = std::max(out.uu, suu.Magnitude());
      out.uv = std::max(out.uv, suv.Magnitude());
      out.vv = std::max(out.vv, svv.Magnitude());
    }
  return out;
}

// Random boxes inside [u0,u1] x [v0,v1]: each bound at least the sampled
// largest (to rounding). Returns how loose the bounds are over the whole
// range: the largest ratio bound / sampled of the three.
double check_boxes(const Handle(Geom_Surface) & s, double u0, double u1, double v0, double v1,
                   int boxes, unsigned seed) {
  const auto bounds = SecondDerivativeBounds::create(s);
  EXPECT_TRUE(bounds);
  if (!bounds) return 0;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0, 1);
  for (int b = 0; b < boxes; ++b) {
    double a = u0 + (u1 - u0) * U(rng), c = u0 + (u1 - u0) * U(rng);
    double e = v0 + (v1 - v0) * U(rng), f = v0 + (v1 - v0) * U(rng);
    if (b % 3 == 0) c = a + 0.02 * (u1 - u0) * U(rng), f = e + 0.02 * (v1 - v0) * U(rng);
    const UvBounds box{std::min(a, c), std::min(std::max(a, c), u1), std::min(e, f),
                       std::min(std::max(e, f), v1)};
    const SecondDerivativeBound got = bounds->over(box), seen = sampled(s, box);
    const double tiny = 1e-9 * (1 + seen.uu + seen.uv + seen.vv);
    EXPECT_GE(got.uu + tiny, seen.uu) << "box " << b;
    EXPECT_GE(got.uv + tiny, seen.uv) << "box " << b;
    EXPECT_GE(got.vv + tiny, seen.vv) << "box " << b;
  }
  const UvBounds whole{u0, u1, v0, v1};
  const SecondDerivativeBound got = bounds->over(whole), seen = sampled(s, whole);
  double loosest = 0;
  for (auto [g, x] : {std::pair{got.uu, seen.uu}, {got.uv, seen.uv}, {got.vv, seen.vv}})
    if (x > 1e-9 * (seen.uu + seen.uv + seen.vv)) loosest = std::max(loosest, g / x);
  return loosest;
}

// A bicubic (or other degree) B-spline over random poles, non-uniform knots,
// optionally rational with weights in [0.8, 1.25] (those of real NURBS
// stay near 1; wilder weights make the quotient rule's bound looser still).
Handle(Geom_BSplineSurface)
    random_bspline(int p, int q, int nu, int nv, bool rational, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0, 1);
  auto knots = [&](int poles, int degree, TColStd_Array1OfReal& k, TColStd_Array1OfInteger& m) {
    const int n = poles - degree + 1;  // distinct knots
    k.Resize(1, n, false);
    m.Resize(1, n, false);
    double t = 0;
    for (int i = 1; i <= n; ++i) {
      k(i) = t;
      t += 0.3 + U(rng);  // uneven spans
      m(i) = (i == 1 || i == n) ? degree + 1 : 1;
    }
  };
  TColStd_Array1OfReal ku(1, 2), kv(1, 2);
  TColStd_Array1OfInteger mu(1, 2), mv(1, 2);
  knots(nu, p, ku, mu);
  knots(nv, q, kv, mv);
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  TColStd_Array2OfReal weights(1, nu, 1, nv);
  for (int i = 1; i <= nu; ++i)
    for (int j = 1; j <= nv; ++j) {
      poles(i, j) = gp_Pnt(100.0 * i, 100.0 * j, 80.0 * (U(rng) - 0.5));
      weights(i, j) = 0.8 + 0.45 * U(rng);
    }
  if (rational) return new Geom_BSplineSurface(poles, weights, ku, kv, mu, mv, p, q);
  return new Geom_BSplineSurface(poles, ku, kv, mu, mv, p, q);
}

}  // namespace

TEST(SecondDerivativeBounds, HoldOnRandomBSplines) {
  const int degrees[][2] = {{3, 3}, {2, 5}, {1, 3}, {5, 2}};
  unsigned seed = 1;
  for (const auto& d : degrees) {
    for (bool rational : {false, true}) {
      const auto s = random_bspline(d[0], d[1], 9, 8, rational, seed++);
      double u0, u1, v0, v1;
      s->Bounds(u0, u1, v0, v1);
      const double loosest = check_boxes(s, u0, u1, v0, v1, 60, seed);
      // Non-rational: the derivatives' control points lie close to their
      // values; rational: the quotient rule's bound is looser.
      EXPECT_LT(loosest, rational ? 20.0 : 3.0)
          << d[0] << " x " << d[1] << " rational " << rational;
    }
  }
}

TEST(SecondDerivativeBounds, HoldOnABezierPatch) {
  TColgp_Array2OfPnt poles(1, 4, 1, 3);
  for (int i = 1; i <= 4; ++i)
    for (int j = 1; j <= 3; ++j)
      poles(i, j) = gp_Pnt(i * 10.0, j * 10.0, ((i * 7 + j * 3) % 5) * 4.0);
  const Handle(Geom_BezierSurface) s = new Geom_BezierSurface(poles);
  EXPECT_LT(check_boxes(s, 0, 1, 0, 1, 40, 3), 3.0);
}

TEST(SecondDerivativeBounds, PeriodicBSplineBoundedOverItsPeriod) {
  auto s = random_bspline(3, 3, 10, 7, false, 11);
  s->SetUPeriodic();
  ASSERT_TRUE(s->IsUPeriodic());
  double u0, u1, v0, v1;
  s->Bounds(u0, u1, v0, v1);
  check_boxes(s, u0, u1, v0, v1, 40, 5);
  // A box across the seam (beyond the first period) is bounded by the whole period.
  const auto bounds = SecondDerivativeBounds::create(s);
  ASSERT_TRUE(bounds);
  const double p = u1 - u0;
  const UvBounds across{u1 - 0.1 * p, u1 + 0.1 * p, v0, v1};
  const SecondDerivativeBound got = bounds->over(across);
  const SecondDerivativeBound seen = sampled(s, across);
  EXPECT_GE(got.uu, seen.uu);
  EXPECT_GE(got.uv, seen.uv);
  EXPECT_GE(got.vv, seen.vv);
}

TEST(SecondDerivativeBounds, ClosedFormsOfAnalyticSurfaces) {
  const gp_Ax3 axis(gp_Pnt(1, 2, 3), gp_Dir(0.2, 0.3, 1), gp_Dir(1, 0, -0.2));
  const double pi = 3.14159265358979323846;
  check_boxes(new Geom_Plane(axis), -50, 50, -50, 50, 20, 1);
  check_boxes(new Geom_CylindricalSurface(axis, 7.5), 0, 2 * pi, -20, 20, 20, 2);
  check_boxes(new Geom_ConicalSurface(axis, 0.4, 5.0), 0, 2 * pi, -10, 30, 20, 3);
  check_boxes(new Geom_SphericalSurface(axis, 12.0), 0, 2 * pi, -pi / 2, pi / 2, 20, 4);
  check_boxes(new Geom_ToroidalSurface(axis, 20.0, 4.0), 0, 2 * pi, 0, 2 * pi, 20, 5);
  // A plane's bounds are zero: no slack for a flat panel to fail on.
  const auto plane = SecondDerivativeBounds::create(new Geom_Plane(axis));
  const SecondDerivativeBound z = plane->over({0, 1, 0, 1});
  EXPECT_EQ(z.uu + z.uv + z.vv, 0.0);
}

TEST(SecondDerivativeBounds, NoneForSurfacesItCannotBound) {
  const Handle(Geom_Surface) offset =
      new Geom_OffsetSurface(random_bspline(3, 3, 6, 6, false, 2), 5.0);
  EXPECT_FALSE(SecondDerivativeBounds::create(offset));
}
