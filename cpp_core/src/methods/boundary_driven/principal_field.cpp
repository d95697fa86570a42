#include "methods/boundary_driven/principal_field.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "methods/boundary_driven/bd_geometry.h"
#include "tessella/errors.h"

namespace tessella {

Vec2 principal_cross(const SurfaceFace& face, const Vec2& uv, double& anisotropy) {
  const UvBounds b = face.bounds();
  const double u = uv.x(), v = uv.y();
  const SurfacePoint sp = face.derivatives(u, v);
  const Vec3 n = face.normal(u, v);
  // Derivatives of du and dv along u (along_u) or v, by central differences
  // kept inside the face's bounds.
  auto rate = [&](bool along_u, Vec3& d_du, Vec3& d_dv) {
    const double x = along_u ? u : v;
    const double lo_bound = along_u ? b.u_min : b.v_min, hi_bound = along_u ? b.u_max : b.v_max;
    const double h = 1e-4 * (hi_bound - lo_bound);
    const double lo = std::max(x - h, lo_bound), hi = std::min(x + h, hi_bound);
    if (!(hi > lo)) {
      d_du = d_dv = Vec3::Zero();
      return;
    }
    const SurfacePoint a = along_u ? face.derivatives(lo, v) : face.derivatives(u, lo);
    const SurfacePoint c = along_u ? face.derivatives(hi, v) : face.derivatives(u, hi);
    d_du = (c.du - a.du) / (hi - lo);
    d_dv = (c.dv - a.dv) / (hi - lo);
  };
  Vec3 duu, dvu, duv, dvv;
  rate(true, duu, dvu);
  rate(false, duv, dvv);
  const double e = duu.dot(n), f = 0.5 * (dvu.dot(n) + duv.dot(n)), g = dvv.dot(n);
  // The BDTensor's frame: e1 = du in the tangent plane (dv at a degenerate du).
  Vec3 e1 = sp.du - sp.du.dot(n) * n;
  if (e1.norm() < 1e-12 * (sp.dv.norm() + 1e-300)) e1 = sp.dv - sp.dv.dot(n) * n;
  e1.normalize();
  const Vec3 e2 = n.cross(e1);
  const Vec2 w1 = tangent_to_uv(sp.du, sp.dv, e1), w2 = tangent_to_uv(sp.du, sp.dv, e2);
  auto second = [&](const Vec2& a, const Vec2& c) {
    return a.x() * c.x() * e + (a.x() * c.y() + a.y() * c.x()) * f + a.y() * c.y() * g;
  };
  // The second fundamental form in the orthonormal frame: [[A, B], [B, C]];
  // its eigenvectors are the principal directions, at 2 theta = atan2(2B, A - C).
  const double A = second(w1, w1), B = second(w1, w2), C = second(w2, w2);
  anisotropy = std::hypot(A - C, 2 * B);
  if (!(anisotropy > 0) || !std::isfinite(anisotropy)) {
    anisotropy = 0;
    return Vec2::Zero();
  }
  const double c2 = (A - C) / anisotropy, s2 = 2 * B / anisotropy;
  return Vec2(c2 * c2 - s2 * s2, 2 * s2 * c2);
}

BdTensorGrid principal_curvature_field(const SurfaceFace& face, const BdTensor& trims, int nu,
                                       int nv, const PrincipalFieldParams& params) {
  require_in_range("blend distance (mm)", params.blend_distance, 0.0, 1e12);
  require_in_range("field smoothness", params.smoothness, 1e-6, 1e6);
  require_in_range("field sweeps", params.sweeps, 0, 100000);
  BdTensorGrid g = sample_bd_tensor(trims, face, nu, nv);
  const std::size_t count = g.c4s4.size();
  std::vector<Vec2> trim_dir(count), principal(count);
  std::vector<double> aniso(count), beta(count);
  for (std::size_t k = 0; k < count; ++k) {
    const Vec2 t = g.c4s4[k];
    trim_dir[k] = t.norm() > 1e-12 ? Vec2(t / t.norm()) : Vec2(1, 0);
  }
  // Distance of each node from the trims' samples, where it matters (within
  // three blend distances; farther, the blend weight is below 1e-4).
  const double reach = 3.0 * params.blend_distance;
  bd::PointHash near(reach > 0 ? reach : 1.0);
  for (const BdTensorSample& s : trims.samples) near.add({s.point, s.tangent, s.uv, 0, 0.0});
  constexpr double kTrimFloor = 1e-3;  // the trims' say where no principal direction exists
  for (int i = 0; i < g.nu; ++i)
    for (int j = 0; j < g.nv; ++j) {
      const std::size_t k = static_cast<std::size_t>(i) * g.nv + j;
      const Vec2 uv = g.lo + Vec2(i * g.step.x(), j * g.step.y());
      principal[k] = principal_cross(face, uv, aniso[k]);
      double d = std::numeric_limits<double>::infinity();
      if (reach > 0) {
        const Vec3 p = face.point(uv.x(), uv.y());
        near.near(p, [&](const bd::HashedPoint& hp) { d = std::min(d, (hp.p - p).norm()); });
      }
      const double r = params.blend_distance > 0 ? d / params.blend_distance
                                                 : std::numeric_limits<double>::infinity();
      beta[k] = kTrimFloor + (r < 3.0 ? std::exp(-r * r) : 0.0);
    }
  // Weights of the principal directions: D / (D + D_ref), D_ref a tenth of
  // the face's high anisotropy (90th percentile), so a direction counts fully
  // where the surface clearly bends more one way than the other.
  std::vector<double> sorted = aniso;
  std::sort(sorted.begin(), sorted.end());
  const double high = sorted.empty() ? 0.0 : sorted[(sorted.size() * 9) / 10];
  const double ref = std::max(0.1 * high, 1e-12 / face.model_size());
  std::vector<double> w(count);
  for (std::size_t k = 0; k < count; ++k) w[k] = aniso[k] / (aniso[k] + ref);
  std::vector<Vec2> x(count), next(count);
  for (std::size_t k = 0; k < count; ++k)
    x[k] = (w[k] * principal[k] + beta[k] * trim_dir[k]) / (w[k] + beta[k]);
  const double lambda = params.smoothness;
  for (int sweep = 0; sweep < params.sweeps; ++sweep) {
    for (int i = 0; i < g.nu; ++i)
      for (int j = 0; j < g.nv; ++j) {
        const std::size_t k = static_cast<std::size_t>(i) * g.nv + j;
        Vec2 sum = w[k] * principal[k] + beta[k] * trim_dir[k];
        double weight = w[k] + beta[k];
        auto add = [&](int a, int c) {
          if (a < 0 || c < 0 || a >= g.nu || c >= g.nv) return;
          sum += lambda * x[static_cast<std::size_t>(a) * g.nv + c];
          weight += lambda;
        };
        add(i - 1, j), add(i + 1, j), add(i, j - 1), add(i, j + 1);
        next[k] = sum / weight;
      }
    x.swap(next);
  }
  g.c4s4 = std::move(x);
  return g;
}

}  // namespace tessella
