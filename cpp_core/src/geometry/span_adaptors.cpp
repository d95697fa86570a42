#include "geometry/span_adaptors.h"

#include <Geom_BSplineSurface.hxx>
#include <algorithm>

namespace tessella {

SpanAdaptors::SpanAdaptors(const Handle(Geom_Surface) & surface) : surface_(surface) {
  const Handle(Geom_BSplineSurface) bs = Handle(Geom_BSplineSurface)::DownCast(surface);
  // Periodic knots would need wrapping: those surfaces keep one adaptor.
  if (!bs.IsNull() && !bs->IsUPeriodic() && !bs->IsVPeriodic() &&
      (bs->NbUKnots() > 2 || bs->NbVKnots() > 2)) {
    for (int i = 1; i <= bs->NbUKnots(); ++i) u_knots_.push_back(bs->UKnot(i));
    for (int i = 1; i <= bs->NbVKnots(); ++i) v_knots_.push_back(bs->VKnot(i));
  }
}

int SpanAdaptors::locate(const std::vector<double>& knots, double t, double& lo, double& hi) {
  const auto it = std::upper_bound(knots.begin(), knots.end(), t);
  const long i = std::clamp<long>(static_cast<long>(it - knots.begin()) - 1, 0,
                                  static_cast<long>(knots.size()) - 2);
  lo = knots[static_cast<std::size_t>(i)];
  hi = knots[static_cast<std::size_t>(i) + 1];
  return static_cast<int>(i);
}

GeomAdaptor_Surface& SpanAdaptors::at(double u, double v) {
  int slot = 0;
  if (!u_knots_.empty()) {
    if (u >= u_lo_ && u < u_hi_ && v >= v_lo_ && v < v_hi_) {
      slot = last_;
    } else {
      const int iu = locate(u_knots_, u, u_lo_, u_hi_);
      const int iv = locate(v_knots_, v, v_lo_, v_hi_);
      slot = (iu % kSide) * kSide + iv % kSide;
      last_ = slot;
    }
  }
  std::unique_ptr<GeomAdaptor_Surface>& a = slots_[static_cast<std::size_t>(slot)];
  if (!a) a = std::make_unique<GeomAdaptor_Surface>(surface_);
  return *a;
}

}  // namespace tessella
