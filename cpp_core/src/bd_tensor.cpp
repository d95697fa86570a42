#include "tessella/bd_tensor.h"

#include <cmath>

#include "tessella/errors.h"

namespace tessella {

Vec2 tangent_to_uv(const Vec3& du, const Vec3& dv, const Vec3& d) {
  const double a = du.dot(du), b = du.dot(dv), c = dv.dot(dv);
  const double det = a * c - b * b;
  if (!(std::abs(det) > 1e-300)) return Vec2::Zero();
  const double r1 = du.dot(d), r2 = dv.dot(d);
  return Vec2((c * r1 - b * r2) / det, (a * r2 - b * r1) / det);
}

BdTensor build_bd_tensor(const SurfaceFace& face, const std::vector<BdPolyline>& sources,
                         const BdTensorParams& params) {
  require_in_range("rho", params.rho, 0.5, 8.0);
  const double ms = face.model_size();
  require_in_range("tensor sample spacing (mm)", params.sample_spacing, 1e-6 * ms, ms);
  BdTensor t;
  t.rho = params.rho;
  for (const BdPolyline& line : sources) {
    const double len = line.length();
    const int n = std::max(line.closed ? 3 : 2,
                           static_cast<int>(std::ceil(len / params.sample_spacing)) + (line.closed ? 0 : 1));
    for (int k = 0; k < n; ++k) {
      double s = line.closed ? len * k / n : len * k / (n - 1);
      const int i = line.segment_at(s);
      // The tangent of the segment (its 3D chord), projected onto the tangent plane.
      const Vec3 chord = line.xyz[(i + 1) % line.xyz.size()] - line.xyz[i];
      const Vec2 uv = line.uv_at(s);
      const Vec3 n3 = face.normal(uv.x(), uv.y());
      Vec3 tan = chord - chord.dot(n3) * n3;
      if (tan.norm() <= 1e-12 * ms) continue;  // a pole or a degenerate edge
      BdTensorSample smp;
      smp.uv = uv;
      smp.point = face.point(uv.x(), uv.y());
      smp.tangent = tan.normalized();
      t.samples.push_back(smp);
    }
  }
  if (t.samples.empty()) throw InvalidGeometry("the source curves have no usable length");
  return t;
}

BdDirections eval_bd_tensor(const BdTensor& tensor, const SurfaceFace& face, const Vec2& uv) {
  const SurfacePoint sp = face.derivatives(uv.x(), uv.y());
  BdDirections out;
  out.normal = face.normal(uv.x(), uv.y());
  Vec3 e1 = sp.du - sp.du.dot(out.normal) * out.normal;
  if (e1.norm() < 1e-12 * (sp.dv.norm() + 1e-300)) e1 = sp.dv - sp.dv.dot(out.normal) * out.normal;
  e1.normalize();
  const Vec3 e2 = out.normal.cross(e1);
  double sc = 0, ss = 0, wsum = 0;
  for (const BdTensorSample& s : tensor.samples) {
    const double a = s.tangent.dot(e1), b = s.tangent.dot(e2);
    const double r2 = a * a + b * b;
    if (r2 < 1e-24) continue;
    // cos/sin of 4 theta without trigonometry.
    const double c2 = (a * a - b * b) / r2, s2 = 2 * a * b / r2;
    const double c4 = c2 * c2 - s2 * s2, s4 = 2 * c2 * s2;
    const double d = (s.point - sp.point).norm();
    if (d == 0.0) {  // eq. 1, second case: T(x) = T_i
      sc = c4, ss = s4, wsum = 1;
      break;
    }
    const double w = std::pow(d, -tensor.rho);
    sc += w * c4, ss += w * s4, wsum += w;
  }
  const double theta = (sc * sc + ss * ss) > 1e-30 * wsum * wsum ? std::atan2(ss, sc) / 4.0 : 0.0;
  out.d1 = std::cos(theta) * e1 + std::sin(theta) * e2;
  out.d2 = out.normal.cross(out.d1);
  out.uv1 = tangent_to_uv(sp.du, sp.dv, out.d1);
  out.uv2 = tangent_to_uv(sp.du, sp.dv, out.d2);
  return out;
}

}  // namespace tessella
