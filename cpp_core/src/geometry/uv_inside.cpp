// Fast point-in-face test on cached (u,v) trim polylines for the guide-line
// methods (see guide_curves.h).
#include <algorithm>
#include <cmath>
#include <limits>

#include "methods/guide_lines/guide_curves.h"

namespace tessella::guide_detail {

namespace {
constexpr int kBands = 512;

double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}
}  // namespace

UvInside::UvInside(const SurfaceFace& face, const std::vector<TrimLoop>& loops) : face_(&face) {
  double vmin = std::numeric_limits<double>::infinity(), vmax = -vmin;
  for (const TrimLoop& loop : loops) {
    const std::size_t n = loop.uv.size();
    for (std::size_t k = 0; k < n; ++k) {
      const Vec2& a = loop.uv[k];
      const Vec2& b = loop.uv[(k + 1) % n];
      edges_.emplace_back(a, b);
      vmin = std::min({vmin, a[1], b[1]});
      vmax = std::max({vmax, a[1], b[1]});
    }
  }
  if (edges_.empty() || !(vmax > vmin)) return;  // fallback_ stays true
  // A point on the trim (within eps) is inside, as for OCCT's classifier (ON).
  const UvBounds box = face.bounds();
  eps_ = 1e-9 * std::hypot(box.u_max - box.u_min, box.v_max - box.v_min);
  v0_ = vmin;
  dv_ = (vmax - vmin) / kBands;
  bands_.assign(kBands, {});
  for (std::size_t e = 0; e < edges_.size(); ++e) {
    const double lo = std::min(edges_[e].first[1], edges_[e].second[1]);
    const double hi = std::max(edges_[e].first[1], edges_[e].second[1]);
    const int b0 = std::clamp(static_cast<int>((lo - v0_) / dv_), 0, kBands - 1);
    const int b1 = std::clamp(static_cast<int>((hi - v0_) / dv_), 0, kBands - 1);
    for (int b = b0; b <= b1; ++b) bands_[b].push_back(static_cast<int>(e));
  }
  // Validate against OCCT on probe points away from the polylines.
  const UvBounds bb = face.bounds();
  const double du = bb.u_max - bb.u_min, dvv = bb.v_max - bb.v_min;
  const double margin = 1e-3 * std::hypot(du, dvv);
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j) {
      const Vec2 p(bb.u_min + du * (i + 0.5) / 9.0, bb.v_min + dvv * (j + 0.5) / 9.0);
      double d = std::numeric_limits<double>::infinity();
      for (const auto& e : edges_) d = std::min(d, segment_distance(p, e.first, e.second));
      if (d < margin) continue;
      if (crossings_odd(p[0], p[1]) != face.is_inside(p[0], p[1])) return;  // fallback
    }
  fallback_ = false;
}

bool UvInside::crossings_odd(double u, double v) const {
  if (v < v0_ - eps_ || v > v0_ + kBands * dv_ + eps_) return false;
  const int b = std::clamp(static_cast<int>((v - v0_) / dv_), 0, kBands - 1);
  bool odd = false;
  const Vec2 p(u, v);
  for (int e : bands_[b]) {
    const Vec2& a = edges_[e].first;
    const Vec2& c = edges_[e].second;
    if (segment_distance(p, a, c) <= eps_) return true;
    if ((a[1] > v) == (c[1] > v)) continue;
    const double x = a[0] + (v - a[1]) / (c[1] - a[1]) * (c[0] - a[0]);
    if (x > u) odd = !odd;
  }
  return odd;
}

bool UvInside::operator()(double u, double v) const {
  if (fallback_) return face_ != nullptr && face_->is_inside(u, v);
  return crossings_odd(u, v);
}

}  // namespace tessella::guide_detail
