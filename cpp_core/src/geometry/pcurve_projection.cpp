#include "geometry/pcurve_projection.h"

namespace tessella {

PcurveProjection::PcurveProjection(const Handle(Geom2d_Curve) & curve, double first, double last)
    : curve_(curve), first_(first), last_(last), adaptor_(curve, first, last) {
  extrema_.Initialize(adaptor_, first, last);
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
