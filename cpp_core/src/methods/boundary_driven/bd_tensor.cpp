#include "methods/boundary_driven/bd_tensor.h"

#include <cmath>

#include "geometry/parallel_in_scopes.h"
#include "mesh/seam_sides.h"
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
    const int n =
        std::max(line.closed ? 3 : 2,
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
      // The seam of a face closed round its period is no edge of the
      // surface: as a source it would turn the field along it (the rows
      // beside it bent into long thin quads).
      if (runs_along_seam(face, line.uv[i], line.seg_end_uv(i))) continue;
      BdTensorSample smp;
      smp.uv = uv;
      smp.point = face.point(uv.x(), uv.y());
      smp.tangent = tan.normalized();
      t.samples.push_back(smp);
    }
  }
  if (t.samples.empty())
    throw InvalidGeometry(
        "the source curves have no usable length (a face whose only trims are its seam and "
        "poles, a whole sphere or torus, has no edge to follow: use iso_grid or "
        "equal_size_grid)");
  return t;
}

namespace {

struct Frame {
  SurfacePoint sp;
  Vec3 normal, e1, e2;
};

Frame frame_at(const SurfaceFace& face, const Vec2& uv) {
  Frame f;
  f.sp = face.derivatives(uv.x(), uv.y());
  f.normal = face.normal(uv.x(), uv.y());
  f.e1 = f.sp.du - f.sp.du.dot(f.normal) * f.normal;
  if (f.e1.norm() < 1e-12 * (f.sp.dv.norm() + 1e-300))
    f.e1 = f.sp.dv - f.sp.dv.dot(f.normal) * f.normal;
  f.e1.normalize();
  f.e2 = f.normal.cross(f.e1);
  return f;
}

// Eq. 1-2 on (cos 4 theta_i, sin 4 theta_i): the weighted mean (not normalized).
Vec2 idw_c4s4(const BdTensor& tensor, const Frame& f) {
  double sc = 0, ss = 0, wsum = 0;
  for (const BdTensorSample& s : tensor.samples) {
    const double a = s.tangent.dot(f.e1), b = s.tangent.dot(f.e2);
    const double r2 = a * a + b * b;
    if (r2 < 1e-24) continue;
    // cos/sin of 4 theta without trigonometry.
    const double c2 = (a * a - b * b) / r2, s2 = 2 * a * b / r2;
    const double c4 = c2 * c2 - s2 * s2, s4 = 2 * c2 * s2;
    const double d2 = (s.point - f.sp.point).squaredNorm();
    if (d2 == 0.0) return Vec2(c4, s4);  // eq. 1, second case: T(x) = T_i
    const double w = tensor.rho == 2.0 ? 1.0 / d2 : std::pow(d2, -0.5 * tensor.rho);
    sc += w * c4, ss += w * s4, wsum += w;
  }
  return wsum > 0 ? Vec2(sc / wsum, ss / wsum) : Vec2(1, 0);
}

BdDirections directions(const Frame& f, const Vec2& c4s4) {
  BdDirections out;
  out.normal = f.normal;
  const double theta = c4s4.squaredNorm() > 1e-30 ? std::atan2(c4s4.y(), c4s4.x()) / 4.0 : 0.0;
  out.d1 = std::cos(theta) * f.e1 + std::sin(theta) * f.e2;
  out.d2 = out.normal.cross(out.d1);
  out.uv1 = tangent_to_uv(f.sp.du, f.sp.dv, out.d1);
  out.uv2 = tangent_to_uv(f.sp.du, f.sp.dv, out.d2);
  return out;
}

}  // namespace

BdDirections eval_bd_tensor(const BdTensor& tensor, const SurfaceFace& face, const Vec2& uv) {
  const Frame f = frame_at(face, uv);
  return directions(f, idw_c4s4(tensor, f));
}

BdTensorGrid sample_bd_tensor(const BdTensor& tensor, const SurfaceFace& face, int nu, int nv) {
  require_in_range("tensor grid size u", nu, 2, 4096);
  require_in_range("tensor grid size v", nv, 2, 4096);
  const UvBounds b = face.bounds();
  BdTensorGrid g;
  g.nu = nu, g.nv = nv;
  g.lo = Vec2(b.u_min, b.v_min);
  g.step = Vec2((b.u_max - b.u_min) / (nu - 1), (b.v_max - b.v_min) / (nv - 1));
  g.c4s4.resize(static_cast<std::size_t>(nu) * nv);
  // Rows on every core (each grid point costs a pass over all boundary
  // samples).
  for_each_in_scopes(face, static_cast<std::size_t>(nu), 4, [&](std::size_t i) {
    for (int j = 0; j < nv; ++j) {
      const Vec2 uv = g.lo + Vec2(static_cast<int>(i) * g.step.x(), j * g.step.y());
      g.c4s4[i * nv + j] = idw_c4s4(tensor, frame_at(face, uv));
    }
  });
  return g;
}

BdDirections eval_bd_tensor(const BdTensorGrid& g, const SurfaceFace& face, const Vec2& uv) {
  const double x = std::clamp((uv.x() - g.lo.x()) / g.step.x(), 0.0, g.nu - 1.0);
  const double y = std::clamp((uv.y() - g.lo.y()) / g.step.y(), 0.0, g.nv - 1.0);
  const int i = std::min(static_cast<int>(x), g.nu - 2),
            j = std::min(static_cast<int>(y), g.nv - 2);
  const double fx = x - i, fy = y - j;
  auto at = [&](int a, int b) { return g.c4s4[static_cast<std::size_t>(a) * g.nv + b]; };
  const Vec2 c = (1 - fx) * ((1 - fy) * at(i, j) + fy * at(i, j + 1)) +
                 fx * ((1 - fy) * at(i + 1, j) + fy * at(i + 1, j + 1));
  return directions(frame_at(face, uv), c);
}

}  // namespace tessella
