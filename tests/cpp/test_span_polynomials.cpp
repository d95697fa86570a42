// SpanPolynomials against OCCT's own evaluation (Geom_Surface::D0/D1/D2):
// random points, every knot crossing, just beyond the range, in an order that
// makes spans evict each other from the cache.
#include <gtest/gtest.h>

#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_Plane.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_SphericalSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <vector>

#include "geometry/span_polynomials.h"

using namespace tessella;

namespace {

// Agreement with OCCT, relative to the model size (pole box diagonal);
// derivatives scaled by the parameter ranges to lengths.
constexpr double kTol = 1e-11;

struct Deviation {
  double point = 0, d1 = 0, d2 = 0;
};

double dist(const gp_XYZ& a, const double b[3]) {
  return std::sqrt((a.X() - b[0]) * (a.X() - b[0]) + (a.Y() - b[1]) * (a.Y() - b[1]) +
                   (a.Z() - b[2]) * (a.Z() - b[2]));
}

Handle(Geom_BSplineSurface) bspline(const Handle(Geom_Surface) & s) {
  Handle(Geom_Surface) b = s;
  if (b->IsKind(STANDARD_TYPE(Geom_RectangularTrimmedSurface)))
    b = Handle(Geom_RectangularTrimmedSurface)::DownCast(b)->BasisSurface();
  Handle(Geom_BSplineSurface) bs = Handle(Geom_BSplineSurface)::DownCast(b);
  return bs.IsNull() ? GeomConvert::SurfaceToBSplineSurface(s) : bs;
}

double pole_box_diagonal(const Handle(Geom_BSplineSurface) & bs) {
  gp_XYZ lo(1e300, 1e300, 1e300), hi(-1e300, -1e300, -1e300);
  const TColgp_Array2OfPnt& poles = bs->Poles();
  for (int i = poles.LowerRow(); i <= poles.UpperRow(); ++i) {
    for (int j = poles.LowerCol(); j <= poles.UpperCol(); ++j) {
      for (int k = 1; k <= 3; ++k) {
        lo.SetCoord(k, std::min(lo.Coord(k), poles(i, j).Coord(k)));
        hi.SetCoord(k, std::max(hi.Coord(k), poles(i, j).Coord(k)));
      }
    }
  }
  return (hi - lo).Modulus();
}

// Compares SpanPolynomials with the surface's own evaluation at the points;
// `check` may test the point against a closed form. Returns the largest deviations.
Deviation compare(const Handle(Geom_Surface) & surface, const std::vector<gp_Pnt2d>& uvs,
                  const std::function<void(const double*)>& check = {}) {
  const std::unique_ptr<SpanPolynomials> sp = SpanPolynomials::create(surface);
  EXPECT_TRUE(sp);
  if (!sp) return {};
  const Handle(Geom_BSplineSurface) bs = bspline(surface);
  const double size = pole_box_diagonal(bs);
  double u0, u1, v0, v1;
  bs->Bounds(u0, u1, v0, v1);
  // A derivative times the range (its power) is a length.
  const double ru = u1 - u0, rv = v1 - v0;
  Deviation dev;
  for (const gp_Pnt2d& uv : uvs) {
    const double u = uv.X(), v = uv.Y();
    gp_Pnt P;
    gp_Vec Su, Sv, Suu, Svv, Suv;
    surface->D2(u, v, P, Su, Sv, Suu, Svv, Suv);
    double p[3], du[3], dv[3], duu[3], dvv[3], duv[3];
    sp->d2(u, v, p, du, dv, duu, dvv, duv);
    dev.point = std::max(dev.point, dist(P.XYZ(), p) / size);
    dev.d1 = std::max({dev.d1, dist(Su.XYZ(), du) * ru / size, dist(Sv.XYZ(), dv) * rv / size});
    dev.d2 =
        std::max({dev.d2, dist(Suu.XYZ(), duu) * ru * ru / size,
                  dist(Svv.XYZ(), dvv) * rv * rv / size, dist(Suv.XYZ(), duv) * ru * rv / size});
    // The lower orders on their own, against OCCT's D0 / D1.
    double q[3], qu[3], qv[3];
    sp->d0(u, v, q);
    dev.point = std::max(dev.point, dist(P.XYZ(), q) / size);
    surface->D1(u, v, P, Su, Sv);
    sp->d1(u, v, q, qu, qv);
    dev.point = std::max(dev.point, dist(P.XYZ(), q) / size);
    dev.d1 = std::max({dev.d1, dist(Su.XYZ(), qu) * ru / size, dist(Sv.XYZ(), qv) * rv / size});
    if (check) check(p);
  }
  return dev;
}

// The surface's distinct knots in its parameter range.
std::vector<double> knots(const Handle(Geom_BSplineSurface) & bs, bool u) {
  std::vector<double> k;
  const int first = u ? bs->FirstUKnotIndex() : bs->FirstVKnotIndex();
  const int last = u ? bs->LastUKnotIndex() : bs->LastVKnotIndex();
  for (int i = first; i <= last; ++i) k.push_back(u ? bs->UKnot(i) : bs->VKnot(i));
  return k;
}

// Random points over the range grown by 2% each side, every pair of knots,
// and knots against random parameters, shuffled (deterministic seed).
std::vector<gp_Pnt2d> sample(const Handle(Geom_Surface) & surface, int n = 2000) {
  const Handle(Geom_BSplineSurface) bs = bspline(surface);
  double u0, u1, v0, v1;
  surface->Bounds(u0, u1, v0, v1);
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> fu(u0 - 0.02 * (u1 - u0), u1 + 0.02 * (u1 - u0));
  std::uniform_real_distribution<double> fv(v0 - 0.02 * (v1 - v0), v1 + 0.02 * (v1 - v0));
  std::vector<gp_Pnt2d> uvs;
  for (int i = 0; i < n; ++i) uvs.emplace_back(fu(rng), fv(rng));
  std::vector<double> ku = knots(bs, true), kv = knots(bs, false);
  // A trimmed surface: its own bounds, and the basis knots inside them.
  ku.erase(std::remove_if(ku.begin(), ku.end(), [&](double k) { return k < u0 || k > u1; }),
           ku.end());
  kv.erase(std::remove_if(kv.begin(), kv.end(), [&](double k) { return k < v0 || k > v1; }),
           kv.end());
  for (double a : {u0, u1}) ku.push_back(a);
  for (double b : {v0, v1}) kv.push_back(b);
  for (double a : ku) {
    for (double b : kv) uvs.emplace_back(a, b);
    for (int i = 0; i < 20; ++i) uvs.emplace_back(a, fv(rng));
  }
  for (double b : kv)
    for (int i = 0; i < 20; ++i) uvs.emplace_back(fu(rng), b);
  std::shuffle(uvs.begin(), uvs.end(), rng);
  return uvs;
}

void report(const char* name, const Deviation& d) {
  std::printf("[ deviation ] %-22s point %.2e  d1 %.2e  d2 %.2e\n", name, d.point, d.d1, d.d2);
  EXPECT_LE(d.point, kTol) << name;
  EXPECT_LE(d.d1, kTol) << name;
  EXPECT_LE(d.d2, kTol) << name;
}

// A wavy height field over a nu x nv grid of poles (x, y in [0, 1000] x [0, 800]).
TColgp_Array2OfPnt wavy_poles(int nu, int nv) {
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  for (int i = 1; i <= nu; ++i) {
    for (int j = 1; j <= nv; ++j) {
      const double x = 1000.0 * (i - 1) / (nu - 1), y = 800.0 * (j - 1) / (nv - 1);
      poles(i, j) = gp_Pnt(x + 30 * std::sin(0.7 * j), y + 25 * std::cos(1.3 * i),
                           120 * std::sin(0.9 * i) * std::cos(0.6 * j) + 0.05 * x);
    }
  }
  return poles;
}

// A non-periodic B-spline surface of degree (p, q) with the given knots and
// multiplicities (poles from the multiplicities).
Handle(Geom_BSplineSurface)
    make_bspline(int p, int q, const std::vector<double>& uk, const std::vector<int>& um,
                 const std::vector<double>& vk, const std::vector<int>& vm) {
  TColStd_Array1OfReal UK(1, static_cast<int>(uk.size())), VK(1, static_cast<int>(vk.size()));
  TColStd_Array1OfInteger UM(1, static_cast<int>(um.size())), VM(1, static_cast<int>(vm.size()));
  int nu = -p - 1, nv = -q - 1;
  for (std::size_t i = 0; i < uk.size(); ++i) {
    UK(static_cast<int>(i) + 1) = uk[i];
    UM(static_cast<int>(i) + 1) = um[i];
    nu += um[i];
  }
  for (std::size_t i = 0; i < vk.size(); ++i) {
    VK(static_cast<int>(i) + 1) = vk[i];
    VM(static_cast<int>(i) + 1) = vm[i];
    nv += vm[i];
  }
  return new Geom_BSplineSurface(wavy_poles(nu, nv), UK, VK, UM, VM, p, q);
}

// Uniform interior knots over [a, b]: n spans, clamped ends.
void uniform(int n, int degree, double a, double b, std::vector<double>& k, std::vector<int>& m) {
  for (int i = 0; i <= n; ++i) {
    k.push_back(a + (b - a) * i / n);
    m.push_back(i == 0 || i == n ? degree + 1 : 1);
  }
}

}  // namespace

TEST(SpanPolynomials, BicubicWithADoubleKnotMatchesOcct) {
  // u: a C1 double knot at 4.5; the range starts away from 0.
  const Handle(Geom_BSplineSurface) s = make_bspline(
      3, 3, {2.0, 3.0, 4.25, 4.5, 6.0, 7.0}, {4, 1, 1, 2, 1, 4}, {0, 0.3, 0.6, 1}, {4, 1, 1, 4});
  ASSERT_EQ(s->NbUPoles(), 9);
  report("bicubic, C1 knot", compare(s, sample(s)));
  // The double knot: OCCT's second derivatives there (and an ulp below,
  // within its locating tolerance) are the upper span's, two ulps below the
  // lower span's. Each time from a point of the lower span (the span check).
  const std::unique_ptr<SpanPolynomials> sp = SpanPolynomials::create(s);
  ASSERT_TRUE(sp);
  const double k1 = std::nextafter(4.5, 0.0), k2 = std::nextafter(k1, 0.0);
  for (double v : {0.1, 0.45, 0.9}) {
    gp_Pnt P;
    gp_Vec Su, Sv, upper, lower, Svv, Suv;
    s->D2(4.5, v, P, Su, Sv, upper, Svv, Suv);
    s->D2(4.5 - 1e-9, v, P, Su, Sv, lower, Svv, Suv);
    ASSERT_GT((upper - lower).Magnitude(), 1e-3 * upper.Magnitude());  // the jump is there
    for (double u : {4.5, k1, k2}) {
      gp_Vec Suu;
      s->D2(u, v, P, Su, Sv, Suu, Svv, Suv);
      EXPECT_LE((Suu - (u == k2 ? lower : upper)).Magnitude(), 1e-6 * upper.Magnitude()) << u;
      double p[3], du[3], dv[3], duu[3], dvv[3], duv[3];
      sp->d2(4.4, v, p, du, dv, duu, dvv, duv);
      sp->d2(u, v, p, du, dv, duu, dvv, duv);
      EXPECT_LE(dist(Suu.XYZ(), duu), 1e-11 * Suu.Magnitude()) << u;
    }
  }
}

TEST(SpanPolynomials, ManySpansEvictingEachOtherMatchOcct) {
  std::vector<double> uk, vk;
  std::vector<int> um, vm;
  uniform(21, 3, 0, 1, uk, um);
  uniform(19, 3, 0, 1, vk, vm);
  const Handle(Geom_BSplineSurface) s = make_bspline(3, 3, uk, um, vk, vm);
  report("bicubic 21 x 19 spans", compare(s, sample(s, 5000)));
  // The result does not depend on what the cache held before.
  const std::unique_ptr<SpanPolynomials> sp = SpanPolynomials::create(s);
  ASSERT_TRUE(sp);
  double a[3], b[3], c[3];
  sp->d0(0.123, 0.456, a);
  for (double u = 0; u <= 1; u += 0.05) sp->d0(u, 1 - u, c);
  sp->d0(0.123, 0.456, b);
  EXPECT_EQ(a[0], b[0]);
  EXPECT_EQ(a[1], b[1]);
  EXPECT_EQ(a[2], b[2]);
}

TEST(SpanPolynomials, UnclampedEndsMatchOcct) {
  // End multiplicity 1: the range is [knot 4, knot 7] in u, not all knots.
  const Handle(Geom_BSplineSurface) s =
      make_bspline(3, 2, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1},
                   {0, 0.5, 1}, {3, 1, 3});
  report("unclamped (3,2)", compare(s, sample(s)));
}

TEST(SpanPolynomials, RationalCylinderPortionMatchesOcctAndTheRadius) {
  const double r = 750;
  Handle(Geom_Surface) cyl = new Geom_CylindricalSurface(gp_Ax3(gp::XOY()), r);
  const Handle(Geom_BSplineSurface) s = GeomConvert::SurfaceToBSplineSurface(
      new Geom_RectangularTrimmedSurface(cyl, 0.2, 4.9, -100.0, 400.0));
  ASSERT_TRUE(s->IsURational() || s->IsVRational());  // OCCT: weights vary in v
  ASSERT_FALSE(s->IsUPeriodic());
  double worst = 0;
  report("cylinder (rational)", compare(s, sample(s), [&](const double* p) {
           worst = std::max(worst, std::abs(std::hypot(p[0], p[1]) - r));
         }));
  // Inside and just beyond the range (the end spans' extension) alike.
  EXPECT_LE(worst, 1e-12 * r);
}

TEST(SpanPolynomials, RationalSpherePortionMatchesOcctAndTheRadius) {
  const double r = 420;
  const gp_Pnt centre(100, -50, 30);
  Handle(Geom_Surface) sph = new Geom_SphericalSurface(gp_Ax3(centre, gp::DZ()), r);
  const Handle(Geom_BSplineSurface) s = GeomConvert::SurfaceToBSplineSurface(
      new Geom_RectangularTrimmedSurface(sph, 0.3, 5.0, -1.2, 1.3));
  ASSERT_TRUE(s->IsURational() && s->IsVRational());
  double worst = 0;
  report("sphere (rational)", compare(s, sample(s), [&](const double* p) {
           worst = std::max(worst, std::sqrt((p[0] - centre.X()) * (p[0] - centre.X()) +
                                             (p[1] - centre.Y()) * (p[1] - centre.Y()) +
                                             (p[2] - centre.Z()) * (p[2] - centre.Z())) -
                                       r);
         }));
  EXPECT_LE(std::abs(worst), 1e-12 * r);
}

TEST(SpanPolynomials, BezierPatchMatchesOcct) {
  Handle(Geom_BezierSurface) s = new Geom_BezierSurface(wavy_poles(4, 5));  // degree (3, 4)
  report("Bezier (3,4)", compare(s, sample(s)));
  // Rational, and trimmed as BRep_Tool may hand it over.
  TColStd_Array2OfReal w(1, 4, 1, 5);
  for (int i = 1; i <= 4; ++i)
    for (int j = 1; j <= 5; ++j) w(i, j) = 1 + 0.3 * std::sin(i + 2.0 * j);
  Handle(Geom_BezierSurface) rs = new Geom_BezierSurface(wavy_poles(4, 5), w);
  Handle(Geom_Surface) trimmed = new Geom_RectangularTrimmedSurface(rs, 0.1, 0.8, 0.2, 0.9);
  report("rational Bezier, trim", compare(trimmed, sample(trimmed)));
}

TEST(SpanPolynomials, BiquadraticMatchesOcct) {
  const Handle(Geom_BSplineSurface) s = make_bspline(
      2, 2, {0, 0.1, 0.35, 0.5, 0.9, 1.0}, {3, 1, 2, 1, 1, 3}, {-5, -1, 2, 5}, {3, 1, 1, 3});
  report("biquadratic", compare(s, sample(s)));
}

TEST(SpanPolynomials, MixedDegreeMatchesOcct) {
  const Handle(Geom_BSplineSurface) s =
      make_bspline(3, 2, {0, 0.2, 0.4, 0.7, 1.0}, {4, 1, 2, 1, 4}, {0, 10, 25, 40}, {3, 1, 2, 3});
  report("mixed (3,2)", compare(s, sample(s)));
  // And a weighted one: the general rational kernel.
  Handle(Geom_BSplineSurface) w = Handle(Geom_BSplineSurface)::DownCast(s->Copy());
  for (int i = 1; i <= w->NbUPoles(); ++i)
    for (int j = 1; j <= w->NbVPoles(); ++j) w->SetWeight(i, j, 1 + 0.4 * std::cos(i * j + 0.5));
  ASSERT_TRUE(w->IsURational() && w->IsVRational());
  report("mixed (3,2) rational", compare(w, sample(w)));
}

TEST(SpanPolynomials, RefusesPeriodicAndNonSplineSurfaces) {
  // Periodic in u (4 poles, degree 3), then in v.
  TColStd_Array1OfReal pk(1, 5), ck(1, 2);
  TColStd_Array1OfInteger pm(1, 5), cm(1, 2);
  for (int i = 1; i <= 5; ++i) pk(i) = i, pm(i) = 1;
  ck(1) = 0, ck(2) = 1, cm(1) = cm(2) = 4;
  Handle(Geom_BSplineSurface) up =
      new Geom_BSplineSurface(wavy_poles(4, 4), pk, ck, pm, cm, 3, 3, true, false);
  ASSERT_TRUE(up->IsUPeriodic());
  EXPECT_FALSE(SpanPolynomials::create(up));
  Handle(Geom_BSplineSurface) vp =
      new Geom_BSplineSurface(wavy_poles(4, 4), ck, pk, cm, pm, 3, 3, false, true);
  ASSERT_TRUE(vp->IsVPeriodic());
  EXPECT_FALSE(SpanPolynomials::create(vp));
  EXPECT_FALSE(SpanPolynomials::create(new Geom_Plane(gp::XOY())));
  EXPECT_FALSE(SpanPolynomials::create(Handle(Geom_Surface)()));
  // The same, non-periodic: accepted.
  EXPECT_TRUE(SpanPolynomials::create(make_bspline(3, 3, {0, 1}, {4, 4}, {0, 1}, {4, 4})));
}
