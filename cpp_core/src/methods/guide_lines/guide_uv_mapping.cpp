// The guide-line methods' curve mapping in the parameter plane (guide_curves.h).
#include <complex>

#include "methods/guide_lines/guide_curves.h"

namespace tessella::guide_detail {

SurfaceCurve map_curve_uv(const SurfaceFace& face, const SurfaceCurve& c, const Vec2& uv0,
                          const Vec2& uv1) {
  // The similarity z -> uv0 + m (z - c0) of the (u,v) plane, as a complex
  // product (rotation and scale in one factor), takes c's ends to uv0 / uv1.
  using C = std::complex<double>;
  const Vec2 c0 = c.uv.front(), c1 = c.uv.back();
  const C from(c1.x() - c0.x(), c1.y() - c0.y()), to(uv1.x() - uv0.x(), uv1.y() - uv0.y());
  const C m = std::abs(from) > 0 ? to / from : C(1.0, 0.0);
  SurfaceCurve out;
  out.uv.reserve(c.uv.size());
  out.xyz.reserve(c.uv.size());
  for (std::size_t i = 0; i < c.uv.size(); ++i) {
    const C z = m * C(c.uv[i].x() - c0.x(), c.uv[i].y() - c0.y());
    const Vec2 uv = i + 1 == c.uv.size() ? uv1 : Vec2(uv0.x() + z.real(), uv0.y() + z.imag());
    out.uv.push_back(uv);
    out.xyz.push_back(face.point(uv.x(), uv.y()));
  }
  return out;
}

}  // namespace tessella::guide_detail
