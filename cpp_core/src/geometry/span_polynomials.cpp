#include "geometry/span_polynomials.h"

#include <BSplCLib.hxx>
#include <GeomConvert.hxx>
#include <Geom_BezierSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Standard_Real.hxx>
#include <algorithm>
#include <cmath>
#include <limits>
#include <math_Matrix.hxx>
#include <stdexcept>

namespace tessella {

namespace {

constexpr int kN = SpanPolynomials::kMaxDegree + 1;

// Horner in t then in s of c[i][j][d] (row-major, D doubles each), giving
// the value and derivatives up to Order. P, Q > 0 fix the degrees at compile
// time (fully unrolled); 0 takes them from p, q.
template <int P, int Q, int D, int Order>
void horner(const double* c, int p_rt, int q_rt, double s, double t, double (&out)[6][4]) {
  const int p = P > 0 ? P : p_rt, q = Q > 0 ? Q : q_rt;
  // f: S, Su, Suu/2; g: Sv, Suv; h: Svv/2 (simultaneous Horner in s).
  double f0[D] = {}, f1[D] = {}, f2[D] = {}, g0[D] = {}, g1[D] = {}, h0[D] = {};
  for (int i = p; i >= 0; --i) {
    const double* row = c + i * (q + 1) * D;
    // The row's polynomial in t: r0 = R_i, r1 = R_i', r2 = R_i''/2.
    double r0[D], r1[D] = {}, r2[D] = {};
    for (int d = 0; d < D; ++d) r0[d] = row[q * D + d];
    for (int j = q - 1; j >= 0; --j) {
      for (int d = 0; d < D; ++d) {
        if (Order >= 2) r2[d] = r2[d] * t + r1[d];
        if (Order >= 1) r1[d] = r1[d] * t + r0[d];
        r0[d] = r0[d] * t + row[j * D + d];
      }
    }
    for (int d = 0; d < D; ++d) {
      if (Order >= 2) {
        f2[d] = f2[d] * s + f1[d];
        g1[d] = g1[d] * s + g0[d];
        h0[d] = h0[d] * s + r2[d];
      }
      if (Order >= 1) {
        f1[d] = f1[d] * s + f0[d];
        g0[d] = g0[d] * s + r1[d];
      }
      f0[d] = f0[d] * s + r0[d];
    }
  }
  for (int d = 0; d < D; ++d) {
    out[0][d] = f0[d];
    if (Order >= 1) out[1][d] = f1[d], out[2][d] = g0[d];
    if (Order >= 2) out[3][d] = 2 * f2[d], out[4][d] = 2 * h0[d], out[5][d] = g1[d];
  }
}

// fill's sums, c[i][j] = sum_ab Nu_a^(i) Nv_b^(j) H_ab / (i! j!), separably
// (u first): bu[i][a] and bv[j][b] the basis derivatives ((p+1)^2 and
// (q+1)^2 doubles, row-major), h[a][b][d] the homogeneous poles (kN x kN x 4).
// P, Q > 0 fix the degrees at compile time; the same sums in the same order
// either way.
template <int P, int Q, int D>
void expand(int p_rt, int q_rt, const double* bu, const double* bv, const double* h, double* c) {
  const int p = P > 0 ? P : p_rt, q = Q > 0 ? Q : q_rt;
  auto H = [h](int a, int b, int d) { return h[(a * kN + b) * 4 + d]; };
  double t[kN][kN][4];
  double fact = 1;
  for (int i = 0; i <= p; ++i) {
    if (i > 0) fact *= i;
    for (int b = 0; b <= q; ++b) {
      for (int d = 0; d < D; ++d) {
        double sum = 0;
        for (int a = 0; a <= p; ++a) sum += bu[i * (p + 1) + a] * H(a, b, d);
        t[i][b][d] = sum / fact;
      }
    }
  }
  for (int i = 0; i <= p; ++i) {
    fact = 1;
    for (int j = 0; j <= q; ++j) {
      if (j > 0) fact *= j;
      for (int d = 0; d < D; ++d) {
        double sum = 0;
        for (int b = 0; b <= q; ++b) sum += bv[j * (q + 1) + b] * t[i][b][d];
        c[(i * (q + 1) + j) * D + d] = sum / fact;
      }
    }
  }
}

using ExpandFn = void (*)(int, int, const double*, const double*, const double*, double*);

template <int D>
ExpandFn expand_for(int p, int q) {
  if (p == 3 && q == 3) return expand<3, 3, D>;
  if (p == 2 && q == 2) return expand<2, 2, D>;
  return expand<0, 0, D>;
}

using Kernels = std::array<void (*)(const double*, int, int, double, double, double (&)[6][4]), 3>;

template <int P, int Q, int D>
Kernels kernels_of() {
  return {horner<P, Q, D, 0>, horner<P, Q, D, 1>, horner<P, Q, D, 2>};
}

// Unrolled kernels for the common degrees, the loops otherwise.
template <int D>
Kernels kernels_for(int p, int q) {
  if (p == 3 && q == 3) return kernels_of<3, 3, D>();
  if (p == 2 && q == 2) return kernels_of<2, 2, D>();
  return kernels_of<0, 0, D>();
}

}  // namespace

std::unique_ptr<SpanPolynomials> SpanPolynomials::create(const Handle(Geom_Surface) & surface) {
  Handle(Geom_Surface) s = surface;
  // A trimmed surface evaluates as its basis does.
  while (!s.IsNull() && s->IsKind(STANDARD_TYPE(Geom_RectangularTrimmedSurface)))
    s = Handle(Geom_RectangularTrimmedSurface)::DownCast(s)->BasisSurface();
  if (s.IsNull()) return nullptr;
  Handle(Geom_BSplineSurface) bs = Handle(Geom_BSplineSurface)::DownCast(s);
  if (bs.IsNull() && s->IsKind(STANDARD_TYPE(Geom_BezierSurface)))
    bs = GeomConvert::SurfaceToBSplineSurface(s);
  if (bs.IsNull() || bs->IsUPeriodic() || bs->IsVPeriodic()) return nullptr;
  if (bs->UDegree() > kMaxDegree || bs->VDegree() > kMaxDegree) return nullptr;
  return std::unique_ptr<SpanPolynomials>(new SpanPolynomials(bs));
}

SpanPolynomials::SpanPolynomials(const Handle(Geom_BSplineSurface) & bs)
    : surface_(bs),
      p_(bs->UDegree()),
      q_(bs->VDegree()),
      dim_(bs->IsURational() || bs->IsVRational() ? 4 : 3) {
  stride_ = (p_ + 1) * (q_ + 1) * dim_;
  kernels_ = dim_ == 4 ? kernels_for<4>(p_, q_) : kernels_for<3>(p_, q_);
  expand_ = dim_ == 4 ? expand_for<4>(p_, q_) : expand_for<3>(p_, q_);
  u_.init(bs, true);
  v_.init(bs, false);
  coeffs_.assign(static_cast<std::size_t>(stride_) * slots_.size(), 0.0);
}

void SpanPolynomials::Axis::init(const Handle(Geom_BSplineSurface) & bs, bool u) {
  // Unclamped ends: the range runs between the first and last knots where
  // the basis sums to one, not over all knots.
  const int first = u ? bs->FirstUKnotIndex() : bs->FirstVKnotIndex();
  const int end = u ? bs->LastUKnotIndex() : bs->LastVKnotIndex();
  for (int i = first; i <= end; ++i) knots.push_back(u ? bs->UKnot(i) : bs->VKnot(i));
  last = u ? bs->UKnot(bs->NbUKnots()) : bs->VKnot(bs->NbVKnots());
  degree = u ? bs->UDegree() : bs->VDegree();
  sequence = u ? &bs->UKnotSequence() : &bs->VKnotSequence();
  // The end spans extend to infinity. OCCT moves a parameter within its
  // Epsilon below a knot up to the next span (see step): a few ulps short of
  // the knot a span surely holds it; step decides the few in between.
  constexpr double inf = std::numeric_limits<double>::infinity();
  const std::size_t n = knots.size() - 1;
  for (std::size_t i = 0; i < n; ++i) {
    lo.push_back(i == 0 ? -inf : knots[i]);
    hi.push_back(i + 1 == n ? inf : knots[i + 1] - 4 * Epsilon(std::abs(knots[i + 1])));
  }
}

int SpanPolynomials::Axis::step(double t) const {
  // Along a walk the next span is mostly a neighbour.
  const int n = static_cast<int>(knots.size()) - 1;
  for (int i : {current + 1, current - 1}) {
    if (i < 0 || i >= n) continue;
    const auto k = static_cast<std::size_t>(i);
    if (t >= lo[k] && t < hi[k]) return i;
  }
  // As BSplCLib::LocateParameter: the span starting at t on a knot (or within
  // Epsilon below it), the last span at the last knot, the end spans beyond.
  int i = static_cast<int>(std::upper_bound(knots.begin(), knots.end(), t) - knots.begin()) - 1;
  i = std::clamp(i, 0, n - 1);
  if (i < n - 1 &&
      knots[static_cast<std::size_t>(i) + 1] - t <= Epsilon(std::min(std::abs(last), std::abs(t))))
    ++i;
  return i;
}

const double* SpanPolynomials::Axis::basis_of(int span, int& first_pole) {
  const auto i = static_cast<std::size_t>(span);
  const std::size_t n = static_cast<std::size_t>(degree + 1) * (degree + 1);
  if (first.empty()) {
    first.assign(knots.size() - 1, 0);
    basis.assign(first.size() * n, 0.0);
  }
  double* out = basis.data() + i * n;
  if (first[i] == 0) {
    const double middle = 0.5 * (knots[i] + knots[i + 1]);
    int f = 0;
    math_Matrix scratch(1, degree + 1, 1, degree + 1);
    if (BSplCLib::EvalBsplineBasis(degree, degree + 1, *sequence, middle, f, scratch))
      throw std::logic_error("SpanPolynomials: cannot evaluate the B-spline basis");
    for (int r = 0; r <= degree; ++r)
      for (int a = 0; a <= degree; ++a) out[r * (degree + 1) + a] = scratch(r + 1, a + 1);
    first[i] = f;
  }
  first_pole = first[i];
  return out;
}

void SpanPolynomials::fill(std::size_t k, int iu, int iv) {
  const auto ku = static_cast<std::size_t>(iu), kv = static_cast<std::size_t>(iv);
  Slot& s = slots_[k];
  s.iu = iu;
  s.iv = iv;
  s.um = 0.5 * (u_.knots[ku] + u_.knots[ku + 1]);
  s.vm = 0.5 * (v_.knots[kv] + v_.knots[kv + 1]);

  // Derivatives of the non-zero basis functions at the middle (1-based first pole).
  int fu = 0, fv = 0;
  const double* bu = u_.basis_of(iu, fu);
  const double* bv = v_.basis_of(iv, fv);
  // The homogeneous poles of the span, relative to their centre: the
  // derivative coefficients sum basis derivatives (of size 1/h^i) times
  // poles, so their rounding scales with the span's extent, not the model's.
  const TColgp_Array2OfPnt& poles = surface_->Poles();
  const TColStd_Array2OfReal* weights = dim_ == 4 ? surface_->Weights() : nullptr;
  const int r0 = poles.LowerRow() + fu - 1, c0 = poles.LowerCol() + fv - 1;
  // The span's poles and weights read once into plain arrays (OCCT's arrays
  // check every index: reading them in the sums was most of a span's 13,000
  // instructions, and OCCT's terrain fills 175,000 spans).
  double xyz[kN][kN][3], wt[kN][kN];
  for (int a = 0; a <= p_; ++a)
    for (int b = 0; b <= q_; ++b) {
      const gp_Pnt& P = poles(r0 + a, c0 + b);
      xyz[a][b][0] = P.X(), xyz[a][b][1] = P.Y(), xyz[a][b][2] = P.Z();
      wt[a][b] =
          weights ? (*weights)(weights->LowerRow() + fu - 1 + a, weights->LowerCol() + fv - 1 + b)
                  : 1.0;
    }
  for (int d = 0; d < 3; ++d) {
    double lo = xyz[0][0][d], hi = lo;
    for (int a = 0; a <= p_; ++a) {
      for (int b = 0; b <= q_; ++b) {
        lo = std::min(lo, xyz[a][b][d]);
        hi = std::max(hi, xyz[a][b][d]);
      }
    }
    s.origin[d] = 0.5 * (lo + hi);
  }
  double h[kN][kN][4];
  for (int a = 0; a <= p_; ++a) {
    for (int b = 0; b <= q_; ++b) {
      const double w = wt[a][b];
      for (int d = 0; d < 3; ++d) h[a][b][d] = w * (xyz[a][b][d] - s.origin[d]);
      h[a][b][3] = w;
    }
  }
  expand_(p_, q_, bu, bv, &h[0][0][0], coeffs_.data() + k * static_cast<std::size_t>(stride_));
}

const double* SpanPolynomials::eval(int order, double u, double v, Derivatives& out) {
  const std::size_t k = slot(u, v);
  const Slot& s = slots_[k];
  kernels_[static_cast<std::size_t>(order)](coeffs_.data() + k * static_cast<std::size_t>(stride_),
                                            p_, q_, u - s.um, v - s.vm, out);
  return s.origin;
}

void SpanPolynomials::finish(int order, Derivatives& h, const double origin[3],
                             double* out[6]) const {
  const int n = order == 0 ? 1 : order == 1 ? 3 : 6;
  if (dim_ == 4) {
    // Quotient rule on S = A / w, derivative by derivative (h[m][3]: w's).
    const double iw = 1 / h[0][3];
    for (int d = 0; d < 3; ++d) {
      const double S = h[0][d] * iw;
      h[0][d] = S;
      if (order < 1) continue;
      const double Su = (h[1][d] - h[1][3] * S) * iw, Sv = (h[2][d] - h[2][3] * S) * iw;
      h[1][d] = Su;
      h[2][d] = Sv;
      if (order < 2) continue;
      h[3][d] = (h[3][d] - 2 * h[1][3] * Su - h[3][3] * S) * iw;
      h[4][d] = (h[4][d] - 2 * h[2][3] * Sv - h[4][3] * S) * iw;
      h[5][d] = (h[5][d] - h[1][3] * Sv - h[2][3] * Su - h[5][3] * S) * iw;
    }
  }
  for (int d = 0; d < 3; ++d) out[0][d] = h[0][d] + origin[d];
  for (int m = 1; m < n; ++m)
    for (int d = 0; d < 3; ++d) out[m][d] = h[m][d];
}

void SpanPolynomials::d0(double u, double v, double p[3]) {
  Derivatives h;
  const double* origin = eval(0, u, v, h);
  double* out[6] = {p};
  finish(0, h, origin, out);
}

void SpanPolynomials::d1(double u, double v, double p[3], double du[3], double dv[3]) {
  Derivatives h;
  const double* origin = eval(1, u, v, h);
  double* out[6] = {p, du, dv};
  finish(1, h, origin, out);
}

void SpanPolynomials::d2(double u, double v, double p[3], double du[3], double dv[3], double duu[3],
                         double dvv[3], double duv[3]) {
  Derivatives h;
  const double* origin = eval(2, u, v, h);
  double* out[6] = {p, du, dv, duu, dvv, duv};
  finish(2, h, origin, out);
}

}  // namespace tessella
