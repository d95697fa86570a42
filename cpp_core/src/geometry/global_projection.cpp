#include "geometry/global_projection.h"

#include <Standard_Failure.hxx>

namespace tessella {

GlobalProjection::GlobalProjection(const Handle(Geom_Surface) & surface, const UvBounds& range) {
  // Same set-up as the point constructor GeomAPI_ProjectPointOnSurf(P, S, bounds),
  // so the answers match it exactly; Perform() reuses the sample grid.
  projector_.Init(surface, range.u_min, range.u_max, range.v_min, range.v_max);
}

bool GlobalProjection::nearest(const Vec3& p, Vec2& uv) {
  try {
    projector_.Perform(gp_Pnt(p.x(), p.y(), p.z()));
    if (projector_.NbPoints() == 0) return false;
    double u = 0, v = 0;
    projector_.LowerDistanceParameters(u, v);
    uv = {u, v};
    return true;
  } catch (const Standard_Failure&) {
    return false;
  }
}

}  // namespace tessella
