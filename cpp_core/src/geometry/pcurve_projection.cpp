#include "geometry/pcurve_projection.h"

#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_BezierCurve.hxx>
#include <Geom2d_Line.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <algorithm>
#include <cmath>

namespace tessella {

PcurveProjection::PcurveProjection(const Handle(Geom2d_Curve) & curve, double first, double last)
    : curve_(curve), first_(first), last_(last), adaptor_(curve, first, last) {
  extrema_.Initialize(adaptor_, first, last);
  // A box holding every point of the curve between first and last: a
  // B-spline's or Bezier's control points (the convex hull), a line's
  // segment. Grown by 1e-9 of its size so a rounded curve point never
  // falls outside it.
  Handle(Geom2d_Curve) basis = curve;
  while (auto t = Handle(Geom2d_TrimmedCurve)::DownCast(basis)) basis = t->BasisCurve();
  std::vector<gp_Pnt2d> hull;
  if (auto b = Handle(Geom2d_BSplineCurve)::DownCast(basis)) {
    for (int i = 1; i <= b->NbPoles(); ++i) hull.push_back(b->Pole(i));
  } else if (auto z = Handle(Geom2d_BezierCurve)::DownCast(basis)) {
    for (int i = 1; i <= z->NbPoles(); ++i) hull.push_back(z->Pole(i));
  } else if (!Handle(Geom2d_Line)::DownCast(basis).IsNull() && std::isfinite(first) &&
             std::isfinite(last)) {
    hull = {curve->Value(first), curve->Value(last)};
  }
  if (hull.empty()) return;
  box_[0] = box_[1] = hull[0].X();
  box_[2] = box_[3] = hull[0].Y();
  for (const gp_Pnt2d& q : hull) {
    box_[0] = std::min(box_[0], q.X()), box_[1] = std::max(box_[1], q.X());
    box_[2] = std::min(box_[2], q.Y()), box_[3] = std::max(box_[3], q.Y());
  }
  const double grow = 1e-9 * (std::abs(box_[0]) + std::abs(box_[1]) + std::abs(box_[2]) +
                              std::abs(box_[3]) + (box_[1] - box_[0]) + (box_[3] - box_[2]));
  box_[0] -= grow, box_[1] += grow, box_[2] -= grow, box_[3] += grow;
  has_box_ = std::isfinite(grow);
}

double PcurveProjection::lower_bound(const gp_Pnt2d& p) const {
  if (!has_box_) return 0.0;
  const double dx = std::max({box_[0] - p.X(), 0.0, p.X() - box_[1]});
  const double dy = std::max({box_[2] - p.Y(), 0.0, p.Y() - box_[3]});
  return std::sqrt(dx * dx + dy * dy);
}

void PcurveProjection::candidates(const gp_Pnt2d& p, std::vector<gp_Pnt2d>& out) {
  out.clear();
  out.push_back(curve_->Value(first_));
  out.push_back(curve_->Value(last_));
  extrema_.Perform(p);
  if (!extrema_.IsDone()) return;
  for (int i = 1; i <= extrema_.NbExt(); ++i) out.push_back(extrema_.Point(i).Value());
}

}  // namespace tessella
