#include "methods/grids/path_along_cuts.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "geometry/segment_closest.h"

namespace tessella {

namespace {

// A path within this share of the rod of a cut is meant to be the cut.
constexpr double kAlongShare = 0.01;
// Steps at most this share of the rod near a cut, so that between two
// points moved onto a curved cut the straight step stays on it.
constexpr double kStepShare = 1.0 / 16.0;
// Along a cut, not across it (a guide crossing a hole's rim stays).
const double kParallelCos = std::cos(20.0 * 3.14159265358979323846 / 180.0);

struct CutSegment {
  Vec2 a, d;  // (u,v): from a to a + d
  Vec3 p, q;  // its ends on the surface
};

// The cut segments in a uniform grid of (u,v) buckets, in segment order.
class Buckets {
 public:
  Buckets(const std::vector<CutSegment>& segs, const Vec2& lo, const Vec2& hi)
      : lo_(lo), size_((hi - lo).cwiseMax(Vec2(1e-300, 1e-300))) {
    n_ = std::clamp(static_cast<int>(std::sqrt(double(segs.size()))), 1, 512);
    cells_.resize(std::size_t(n_) * std::size_t(n_));
    for (std::size_t s = 0; s < segs.size(); ++s) {
      const Vec2 a = segs[s].a, b = segs[s].a + segs[s].d;
      for (int j = index(std::min(a.y(), b.y()), 1); j <= index(std::max(a.y(), b.y()), 1); ++j)
        for (int i = index(std::min(a.x(), b.x()), 0); i <= index(std::max(a.x(), b.x()), 0); ++i)
          cells_[std::size_t(j) * std::size_t(n_) + std::size_t(i)].push_back(int(s));
    }
  }
  // Segments whose bucket meets the box [lo, hi], each once, in order.
  std::vector<int> near(const Vec2& lo, const Vec2& hi) const {
    std::vector<int> out;
    for (int j = index(lo.y(), 1); j <= index(hi.y(), 1); ++j)
      for (int i = index(lo.x(), 0); i <= index(hi.x(), 0); ++i)
        for (int s : cells_[std::size_t(j) * std::size_t(n_) + std::size_t(i)]) out.push_back(s);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

 private:
  int index(double x, int axis) const {
    const double t = std::floor((x - lo_[axis]) / size_[axis] * n_);
    return static_cast<int>(std::clamp(t, 0.0, double(n_ - 1)));  // clamped before the cast
  }
  Vec2 lo_, size_;
  int n_ = 1;
  std::vector<std::vector<int>> cells_;
};

}  // namespace

std::vector<Vec2> path_along_cuts(const SurfaceFace& face, const std::vector<Vec2>& path,
                                  const std::vector<std::vector<Vec2>>& cuts, double size) {
  if (cuts.empty() || path.size() < 2 || !(size > 0)) return path;
  std::vector<CutSegment> segs;
  Vec2 lo = path.front(), hi = path.front();
  for (const auto& cut : cuts) {
    if (cut.size() < 2) continue;
    for (std::size_t k = 0; k < cut.size(); ++k) {  // closed: the last point joins the first
      const Vec2& a = cut[k];
      const Vec2& b = cut[(k + 1) % cut.size()];
      segs.push_back({a, b - a, face.point(a.x(), a.y()), face.point(b.x(), b.y())});
      lo = lo.cwiseMin(a.cwiseMin(b)), hi = hi.cwiseMax(a.cwiseMax(b));
    }
  }
  if (segs.empty()) return path;
  for (const Vec2& p : path) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const Buckets buckets(segs, lo, hi);
  const double reach = kAlongShare * size;

  // The nearest point of a cut segment running along direction `along`
  // (3D) within the reach of x = S(uv), if any.
  auto onto_cut = [&](const Vec2& uv, const Vec3& x, const Vec3& along) -> std::optional<Vec2> {
    const SurfacePoint d = face.derivatives(uv.x(), uv.y());
    // A (u,v) box holding every point within the reach (by the first
    // derivatives, with room for their change across the box).
    const double su = d.du.norm(), sv = d.dv.norm();
    const Vec2 r(su > 0 ? 4 * reach / su : hi.x() - lo.x(),
                 sv > 0 ? 4 * reach / sv : hi.y() - lo.y());
    double best = reach;
    std::optional<Vec2> out;
    for (int s : buckets.near(uv - r, uv + r)) {
      const CutSegment& e = segs[std::size_t(s)];
      const Vec3 chord = e.q - e.p;
      if (!(std::abs(along.dot(chord)) >= kParallelCos * along.norm() * chord.norm())) continue;
      const Vec2 foot = e.a + closest_fraction(e.a, e.d, uv) * e.d;
      const double dist = (face.point(foot.x(), foot.y()) - x).norm();
      if (dist < best) best = dist, out = foot;
    }
    return out;
  };

  // Resampled (points on the path's own (u,v) steps: its shape unchanged).
  std::vector<Vec3> at(path.size());
  for (std::size_t k = 0; k < path.size(); ++k) at[k] = face.point(path[k].x(), path[k].y());
  std::vector<Vec2> out{path.front()};
  for (std::size_t k = 1; k < path.size(); ++k) {
    const Vec2 a = path[k - 1], b = path[k];
    const double length = (at[k] - at[k - 1]).norm();
    const int pieces = std::max(1, static_cast<int>(std::ceil(length / (kStepShare * size))));
    for (int q = 1; q <= pieces; ++q) out.push_back(a + (b - a) * (double(q) / pieces));
  }
  // Each point moved onto the cut it runs along (directions from the
  // points as given, before any move).
  std::vector<Vec3> xyz(out.size());
  for (std::size_t k = 0; k < out.size(); ++k) xyz[k] = face.point(out[k].x(), out[k].y());
  std::vector<Vec2> moved = out;
  for (std::size_t k = 0; k < out.size(); ++k) {
    const Vec3 along = xyz[std::min(k + 1, out.size() - 1)] - xyz[k > 0 ? k - 1 : 0];
    if (const std::optional<Vec2> q = onto_cut(out[k], xyz[k], along)) moved[k] = *q;
  }
  return moved;
}

}  // namespace tessella
