#include "geometry/second_derivative_bounds.h"

#include <GeomAdaptor_Surface.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace tessella {

namespace {

// A homogeneous control point (w (P - C), w).
using Homogeneous = std::array<double, 4>;

double norm3(const Homogeneous& h) { return std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]); }

// The distinct knots of a flat knot sequence (its first `degree` and last
// `degree` knots are outside the range) and, per span, the flat index k of
// its lower knot (t_k < t_{k+1}).
void spans_of(const TColStd_Array1OfReal& flat, int degree, int poles, std::vector<double>& knots,
              std::vector<int>& first_flat) {
  const int lo = flat.Lower();
  for (int k = degree; k < poles; ++k) {
    const double a = flat(lo + k), b = flat(lo + k + 1);
    if (!(b > a)) continue;
    if (knots.empty()) knots.push_back(a);
    knots.push_back(b);
    first_flat.push_back(k);
  }
}

// Control points of the derivative of a B-spline of `degree` over the
// flat knots t: D_i = degree (Q_{i+1} - Q_i) / (t_{i+degree+1} - t_{i+1}),
// for the `count` points Q[0..count) starting at flat index `first`.
// Within one span the denominators are at least the span's width. Into `d`
// (a buffer the caller keeps: a surface of 100,000 spans asked for a million
// small vectors).
void derivative(const std::vector<Homogeneous>& q, const TColStd_Array1OfReal& t, int first,
                int degree, std::vector<Homogeneous>& d) {
  d.clear();
  if (degree < 1 || q.size() < 2) return;
  const int lo = t.Lower();
  for (std::size_t i = 0; i + 1 < q.size(); ++i) {
    const int f = first + int(i);
    const double width = t(lo + f + degree + 1) - t(lo + f + 1);
    Homogeneous h;
    for (int c = 0; c < 4; ++c) h[c] = degree * (q[i + 1][c] - q[i][c]) / width;
    d.push_back(h);
  }
}

// A span's control net bounds its derivatives the more loosely the more the
// surface bends within it: a surface of few spans (a 10 x 10-pole face, a
// Bezier patch) got bounds several times its curvature, and the metric's
// check split nearly every cell near a panel's top (the 10 x 10-pole face
// of bench/no_cliff.py took 4.6 times as long as before the check, twice
// as long as the same shape with its knots inserted to 312 x 323 poles).
// The bounds are taken over at least kMinSpans spans a direction: knots
// inserted (on a copy; the same surface) evenly within each span.
constexpr int kMinSpans = 32;

void subdivide_spans(Handle(Geom_BSplineSurface) & b) {
  bool copied = false;
  for (int direction = 0; direction < 2; ++direction) {
    const bool u = direction == 0;
    const int first = u ? b->FirstUKnotIndex() : b->FirstVKnotIndex();
    const int last = u ? b->LastUKnotIndex() : b->LastVKnotIndex();
    const int spans = last - first;
    if (spans <= 0 || spans >= kMinSpans) continue;
    const int parts = (kMinSpans + spans - 1) / spans;
    std::vector<double> added;
    for (int i = first; i < last; ++i) {
      const double a = u ? b->UKnot(i) : b->VKnot(i), c = u ? b->UKnot(i + 1) : b->VKnot(i + 1);
      for (int k = 1; k < parts; ++k) added.push_back(a + (c - a) * k / parts);
    }
    if (added.empty()) continue;
    if (!copied) b = Handle(Geom_BSplineSurface)::DownCast(b->Copy()), copied = true;
    TColStd_Array1OfReal knots(1, int(added.size()));
    TColStd_Array1OfInteger mults(1, int(added.size()));
    for (std::size_t k = 0; k < added.size(); ++k)
      knots(int(k) + 1) = added[k], mults(int(k) + 1) = 1;
    if (u)
      b->InsertUKnots(knots, mults, 0.0);
    else
      b->InsertVKnots(knots, mults, 0.0);
  }
}

struct Largest {
  double xyz = 0, w = 0;
  void offer(const Homogeneous& h) {
    xyz = std::max(xyz, norm3(h));
    w = std::max(w, std::abs(h[3]));
  }
};

}  // namespace

void SecondDerivativeBounds::Axis::range(double lo, double hi, std::size_t& first,
                                         std::size_t& last) const {
  const std::size_t spans = knots.size() - 1;
  first = 0, last = spans - 1;
  if (periodic && (lo < knots.front() || hi > knots.back())) return;  // the whole period
  auto span_of = [&](double t) {
    const auto it = std::upper_bound(knots.begin(), knots.end(), t);
    const std::size_t k = it == knots.begin() ? 0 : std::size_t(it - knots.begin()) - 1;
    return std::min(k, spans - 1);
  };
  first = span_of(lo);
  last = span_of(hi);
  // A parameter on a knot belongs to both spans beside it.
  if (first > 0 && lo <= knots[first]) --first;
  if (last + 1 < spans && hi >= knots[last + 1]) ++last;
}

std::unique_ptr<SecondDerivativeBounds> SecondDerivativeBounds::create(const Handle(Geom_Surface) &
                                                                       surface) {
  Handle(Geom_Surface) s = surface;
  while (auto t = Handle(Geom_RectangularTrimmedSurface)::DownCast(s)) s = t->BasisSurface();
  try {
    if (!Handle(Geom_BSplineSurface)::DownCast(s).IsNull() ||
        !Handle(Geom_BezierSurface)::DownCast(s).IsNull())
      return from_bspline(s);
    GeomAdaptor_Surface a(s);
    std::unique_ptr<SecondDerivativeBounds> out(new SecondDerivativeBounds());
    out->analytic_ = true;
    switch (a.GetType()) {
      case GeomAbs_Plane:
        break;
      case GeomAbs_Cylinder:
        out->radius_a_ = a.Cylinder().Radius();
        break;
      case GeomAbs_Cone: {
        const gp_Cone c = a.Cone();
        out->radius_a_ = c.RefRadius();
        out->radius_b_ = std::sin(c.SemiAngle());
        out->mixed_ = std::abs(std::sin(c.SemiAngle()));
        break;
      }
      case GeomAbs_Sphere:
        out->radius_a_ = out->mixed_ = out->along_v_ = a.Sphere().Radius();
        break;
      case GeomAbs_Torus:
        out->radius_a_ = a.Torus().MajorRadius() + a.Torus().MinorRadius();
        out->mixed_ = out->along_v_ = a.Torus().MinorRadius();
        break;
      default:
        return nullptr;
    }
    return out;
  } catch (const Standard_Failure&) {
    return nullptr;
  }
}

std::unique_ptr<SecondDerivativeBounds> SecondDerivativeBounds::from_bspline(
    const Handle(Geom_Surface) & surface) {
  // A Bezier patch is a B-spline of one span, parametrized the same.
  Handle(Geom_BSplineSurface) b = Handle(Geom_BSplineSurface)::DownCast(surface);
  if (b.IsNull()) b = GeomConvert::SurfaceToBSplineSurface(surface);
  if (b.IsNull()) return nullptr;
  std::unique_ptr<SecondDerivativeBounds> out(new SecondDerivativeBounds());
  out->u_.periodic = b->IsUPeriodic();
  out->v_.periodic = b->IsVPeriodic();
  if (b->IsUPeriodic() || b->IsVPeriodic()) {
    // The same surface, parametrized the same over its first period, with
    // clamped knots (poles no longer wrap around).
    b = Handle(Geom_BSplineSurface)::DownCast(b->Copy());
    if (b->IsUPeriodic()) b->SetUNotPeriodic();
    if (b->IsVPeriodic()) b->SetVNotPeriodic();
  }
  subdivide_spans(b);
  const int p = b->UDegree(), q = b->VDegree();
  const int nu = b->NbUPoles(), nv = b->NbVPoles();
  TColStd_Array1OfReal tu(1, nu + p + 1), tv(1, nv + q + 1);
  b->UKnotSequence(tu);
  b->VKnotSequence(tv);
  std::vector<int> ku, kv;
  spans_of(tu, p, nu, out->u_.knots, ku);
  spans_of(tv, q, nv, out->v_.knots, kv);
  if (ku.empty() || kv.empty()) return nullptr;
  const TColgp_Array2OfPnt& poles = b->Poles();
  const TColStd_Array2OfReal* weights = b->Weights();
  out->spans_.resize(ku.size() * kv.size());
  // Buffers kept across the spans.
  std::vector<Homogeneous> column, d1, d2;
  std::vector<std::vector<Homogeneous>> net(p + 1, std::vector<Homogeneous>(q + 1));
  std::vector<std::vector<Homogeneous>> du_net(p);  // the u-derivative's net, per i
  for (std::size_t a = 0; a < ku.size(); ++a) {
    for (std::size_t c = 0; c < kv.size(); ++c) {
      // The span's poles: flat indices k - degree .. k in each direction.
      const int i0 = ku[a] - p, j0 = kv[c] - q;
      gp_XYZ centre(0, 0, 0);
      double w_min = std::numeric_limits<double>::infinity();
      for (int i = 0; i <= p; ++i)
        for (int j = 0; j <= q; ++j) {
          centre += poles(poles.LowerRow() + i0 + i, poles.LowerCol() + j0 + j).XYZ();
          if (weights)
            w_min = std::min(
                w_min, (*weights)(weights->LowerRow() + i0 + i, weights->LowerCol() + j0 + j));
        }
      if (!weights) w_min = 1;
      centre /= double((p + 1) * (q + 1));
      // net[i][j] = (w (P - C), w); the span lies within `radius` of C (the
      // convex hull of its poles, the weights being positive).
      double radius = 0;
      for (int i = 0; i <= p; ++i)
        for (int j = 0; j <= q; ++j) {
          const gp_XYZ d =
              poles(poles.LowerRow() + i0 + i, poles.LowerCol() + j0 + j).XYZ() - centre;
          const double w =
              weights ? (*weights)(weights->LowerRow() + i0 + i, weights->LowerCol() + j0 + j)
                      : 1.0;
          radius = std::max(radius, d.Modulus());
          net[i][j] = {w * d.X(), w * d.Y(), w * d.Z(), w};
        }
      // Derivatives of the homogeneous net H = w (S - C) and of w.
      Largest hu, huu, hv, hvv, huv;
      for (auto& row : du_net) row.clear();
      for (int j = 0; j <= q; ++j) {
        column.clear();
        for (int i = 0; i <= p; ++i) column.push_back(net[i][j]);
        derivative(column, tu, i0, p, d1);
        for (std::size_t i = 0; i < d1.size(); ++i) hu.offer(d1[i]), du_net[i].push_back(d1[i]);
        derivative(d1, tu, i0 + 1, p - 1, d2);
        for (const auto& h : d2) huu.offer(h);
      }
      for (int i = 0; i <= p; ++i) {
        derivative(net[i], tv, j0, q, d1);
        for (const auto& h : d1) hv.offer(h);
        derivative(d1, tv, j0 + 1, q - 1, d2);
        for (const auto& h : d2) hvv.offer(h);
      }
      for (int i = 0; i < p; ++i) {
        derivative(du_net[i], tv, j0, q, d1);
        for (const auto& h : d1) huv.offer(h);
      }
      // S - C = H / w, so S_u = (H_u - (S - C) w_u) / w and
      // S_uu = (H_uu - 2 S_u w_u - (S - C) w_uu) / w,
      // S_uv = (H_uv - S_u w_v - S_v w_u - (S - C) w_uv) / w.
      const double su = (hu.xyz + radius * hu.w) / w_min;
      const double sv = (hv.xyz + radius * hv.w) / w_min;
      SecondDerivativeBound& s = out->spans_[a * kv.size() + c];
      s.uu = (huu.xyz + 2 * su * hu.w + radius * huu.w) / w_min;
      s.vv = (hvv.xyz + 2 * sv * hv.w + radius * hvv.w) / w_min;
      s.uv = (huv.xyz + su * hv.w + sv * hu.w + radius * huv.w) / w_min;
    }
  }
  return out;
}

SecondDerivativeBound SecondDerivativeBounds::over(const UvBounds& box) const {
  SecondDerivativeBound out;
  if (analytic_) {
    out.uu = std::max(std::abs(radius_a_ + radius_b_ * box.v_min),
                      std::abs(radius_a_ + radius_b_ * box.v_max));
    out.uv = mixed_;
    out.vv = along_v_;
    return out;
  }
  std::size_t a0, a1, c0, c1;
  u_.range(box.u_min, box.u_max, a0, a1);
  v_.range(box.v_min, box.v_max, c0, c1);
  const std::size_t nv = v_.knots.size() - 1;
  for (std::size_t a = a0; a <= a1; ++a)
    for (std::size_t c = c0; c <= c1; ++c) {
      const SecondDerivativeBound& s = spans_[a * nv + c];
      out.uu = std::max(out.uu, s.uu);
      out.uv = std::max(out.uv, s.uv);
      out.vv = std::max(out.vv, s.vv);
    }
  return out;
}

}  // namespace tessella
