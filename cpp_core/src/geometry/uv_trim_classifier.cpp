#include "geometry/uv_trim_classifier.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tessella {

namespace {

double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

std::vector<std::vector<Vec2>> loop_points(const std::vector<TrimLoop>& loops) {
  std::vector<std::vector<Vec2>> out;
  out.reserve(loops.size());
  for (const TrimLoop& loop : loops) out.push_back(loop.uv);
  return out;
}

}  // namespace

int UvTrimClassifier::Bands::index(double x) const {
  const int n = static_cast<int>(edges.size());
  const double k = std::floor((x - lo) / step);
  if (!(k >= 0)) return 0;
  return k >= n - 1 ? n - 1 : static_cast<int>(k);
}

UvTrimClassifier::UvTrimClassifier(const std::vector<TrimLoop>& loops, const Options& options)
    : UvTrimClassifier(loop_points(loops), options) {}

UvTrimClassifier::UvTrimClassifier(const std::vector<std::vector<Vec2>>& loops,
                                   const Options& options) {
  for (const auto& loop : loops) {
    const std::size_t n = loop.size();
    for (std::size_t k = 0; k < n; ++k) edges_.push_back({loop[k], loop[(k + 1) % n]});
  }
  build(options);
}

void UvTrimClassifier::build(const Options& options) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  lo_ = Vec2(inf, inf);
  hi_ = Vec2(-inf, -inf);
  for (const auto& e : edges_)
    lo_ = lo_.cwiseMin(e[0]).cwiseMin(e[1]), hi_ = hi_.cwiseMax(e[0]).cwiseMax(e[1]);
  const bool usable = !edges_.empty() && hi_.x() > lo_.x() && hi_.y() > lo_.y() &&
                      std::isfinite(lo_.x() + lo_.y() + hi_.x() + hi_.y());
  if (!usable) {
    edges_.clear();
    lo_ = hi_ = Vec2::Zero();
    if (options.check_with != nullptr) occt_ = options.check_with;
    return;
  }
  on_trim_ = options.on_trim >= 0 ? options.on_trim : 1e-9 * (hi_ - lo_).norm();
  const int count = static_cast<int>(std::clamp<std::size_t>(edges_.size() / 2, 16, 8192));
  for (int d = 0; d < 2; ++d) {
    Bands& b = bands_[d];
    b.lo = lo_[d];
    b.step = (hi_[d] - lo_[d]) / count;
    b.edges.assign(count, {});
    for (std::size_t e = 0; e < edges_.size(); ++e) {
      // Widened by on_trim so the band of a point holds every edge it can be on.
      const double a = std::min(edges_[e][0][d], edges_[e][1][d]) - on_trim_;
      const double c = std::max(edges_[e][0][d], edges_[e][1][d]) + on_trim_;
      for (int k = b.index(a), k1 = b.index(c); k <= k1; ++k)
        b.edges[k].push_back(static_cast<int>(e));
    }
  }
  if (options.check_with == nullptr) return;
  // Cross-check against OCCT on probe points well away from the polylines.
  const SurfaceFace& face = *options.check_with;
  const UvBounds bb = face.bounds();
  const double du = bb.u_max - bb.u_min, dv = bb.v_max - bb.v_min;
  const double margin = 1e-3 * std::hypot(du, dv);
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j) {
      const Vec2 p(bb.u_min + du * (i + 0.5) / 9.0, bb.v_min + dv * (j + 0.5) / 9.0);
      double dist = inf;
      for (const auto& e : edges_) dist = std::min(dist, segment_distance(p, e[0], e[1]));
      if (dist < margin) continue;
      if ((classify_polylines(p) != TrimSide::Outside) != face.is_inside(p.x(), p.y())) {
        occt_ = &face;
        return;
      }
    }
}

TrimSide UvTrimClassifier::classify(const Vec2& p) const {
  if (occt_ != nullptr)
    return occt_->is_inside(p.x(), p.y()) ? TrimSide::Inside : TrimSide::Outside;
  return classify_polylines(p);
}

TrimSide UvTrimClassifier::classify_polylines(const Vec2& p) const {
  const double eps = on_trim_;
  if (edges_.empty() || !(p.x() >= lo_.x() - eps && p.x() <= hi_.x() + eps &&
                          p.y() >= lo_.y() - eps && p.y() <= hi_.y() + eps))
    return TrimSide::Outside;
  bool odd = false;
  for (int e : bands_[1].edges[bands_[1].index(p.y())]) {
    const Vec2& a = edges_[e][0];
    const Vec2& b = edges_[e][1];
    if (p.x() >= std::min(a.x(), b.x()) - eps && p.x() <= std::max(a.x(), b.x()) + eps &&
        p.y() >= std::min(a.y(), b.y()) - eps && p.y() <= std::max(a.y(), b.y()) + eps &&
        segment_distance(p, a, b) <= eps)
      return TrimSide::OnTrim;
    if ((a.y() > p.y()) == (b.y() > p.y())) continue;
    const double x = a.x() + (p.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x());
    if (x > p.x()) odd = !odd;
  }
  return odd ? TrimSide::Inside : TrimSide::Outside;
}

std::vector<double> UvTrimClassifier::crossings(int free_dir, double c) const {
  std::vector<double> out;
  const int fixed = free_dir == 0 ? 1 : 0, free = 1 - fixed;
  if (edges_.empty() || !(c >= lo_[fixed] && c <= hi_[fixed])) return out;
  const Bands& b = bands_[fixed];
  for (int e : b.edges[b.index(c)]) {
    const Vec2& p = edges_[e][0];
    const Vec2& q = edges_[e][1];
    if ((p[fixed] > c) == (q[fixed] > c)) continue;
    out.push_back(p[free] + (c - p[fixed]) / (q[fixed] - p[fixed]) * (q[free] - p[free]));
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace tessella
