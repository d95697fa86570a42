#include "geometry/closed_bspline.h"

#include <Standard_Failure.hxx>
#include <algorithm>
#include <cmath>
#include <gp_Pnt.hxx>

namespace tessella {

namespace {

// The largest distance between corresponding poles of the first and last
// rows along u (axis 0) or v (1), or infinity where their weights differ.
double end_rows_apart(const Geom_BSplineSurface& s, int axis) {
  const int n_along = axis == 0 ? s.NbUPoles() : s.NbVPoles();
  const int n_across = axis == 0 ? s.NbVPoles() : s.NbUPoles();
  double apart = 0;
  for (int k = 1; k <= n_across; ++k) {
    const int i0 = axis == 0 ? 1 : k, j0 = axis == 0 ? k : 1;
    const int i1 = axis == 0 ? n_along : k, j1 = axis == 0 ? k : n_along;
    if (s.Weight(i0, j0) != s.Weight(i1, j1)) return HUGE_VAL;
    apart = std::max(apart, s.Pole(i0, j0).Distance(s.Pole(i1, j1)));
  }
  return apart;
}

double poles_extent(const Geom_BSplineSurface& s) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (int i = 1; i <= s.NbUPoles(); ++i)
    for (int j = 1; j <= s.NbVPoles(); ++j) {
      const gp_Pnt p = s.Pole(i, j);
      const double c[3] = {p.X(), p.Y(), p.Z()};
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
    }
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                   (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

bool same_points(const Geom_BSplineSurface& a, const Geom_BSplineSurface& b, double tol) {
  double u0, u1, v0, v1;
  a.Bounds(u0, u1, v0, v1);
  const int n = 16;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double u = u0 + (u1 - u0) * i / n, v = v0 + (v1 - v0) * j / n;
      if (!(a.Value(u, v).Distance(b.Value(u, v)) <= tol)) return false;
    }
  return true;
}

}  // namespace

Handle(Geom_BSplineSurface) periodic_where_closed(const Handle(Geom_BSplineSurface) & surface) {
  if (surface.IsNull()) return surface;
  const double extent = poles_extent(*surface);
  if (!(extent > 0) || !std::isfinite(extent)) return surface;
  const double tol = 1e-12 * extent;
  const bool close_u = !surface->IsUPeriodic() && end_rows_apart(*surface, 0) <= tol;
  const bool close_v = !surface->IsVPeriodic() && end_rows_apart(*surface, 1) <= tol;
  if (!close_u && !close_v) return surface;
  try {
    Handle(Geom_BSplineSurface) copy = Handle(Geom_BSplineSurface)::DownCast(surface->Copy());
    if (close_u) copy->SetUPeriodic();
    if (close_v) copy->SetVPeriodic();
    double a0, a1, b0, b1, c0, c1, d0, d1;
    surface->Bounds(a0, a1, b0, b1);
    copy->Bounds(c0, c1, d0, d1);
    if (a0 != c0 || a1 != c1 || b0 != d0 || b1 != d1) return surface;
    if (!same_points(*surface, *copy, tol)) return surface;
    return copy;
  } catch (const Standard_Failure&) {
    return surface;
  }
}

}  // namespace tessella
