#include "geometry/edge_track.h"

#include <algorithm>

namespace tessella {

EdgeTrack::EdgeTrack(std::vector<Vec3> points) : points_(std::move(points)) {
  for (std::size_t first = 0; first + 1 < points_.size(); first += kRun) {
    const std::size_t last = std::min(first + kRun, points_.size() - 1);
    Vec3 lo = points_[first], hi = points_[first];
    for (std::size_t i = first + 1; i <= last; ++i)
      lo = lo.cwiseMin(points_[i]), hi = hi.cwiseMax(points_[i]);
    lo_.push_back(lo);
    hi_.push_back(hi);
  }
}

bool EdgeTrack::near(const Vec3& p, double d) const {
  if (points_.size() == 1) return (points_[0] - p).norm() <= d;
  std::size_t segment = 0;
  double t = 0;
  return nearest(p, d, segment, t);
}

bool EdgeTrack::nearest(const Vec3& p, double d, std::size_t& segment, double& t) const {
  double best = d * d;
  bool found = false;
  for (std::size_t r = 0; r < lo_.size(); ++r) {
    const Vec3 out = (lo_[r] - p).cwiseMax(p - hi_[r]).cwiseMax(0.0);
    if (out.squaredNorm() > best) continue;
    const std::size_t first = r * kRun, last = std::min(first + kRun, points_.size() - 1);
    for (std::size_t i = first; i < last; ++i) {
      const Vec3 a = points_[i], e = points_[i + 1] - a;
      const double f = std::clamp((p - a).dot(e) / std::max(e.squaredNorm(), 1e-300), 0.0, 1.0);
      const double d2 = (a + f * e - p).squaredNorm();
      if (d2 <= best) best = d2, segment = i, t = f, found = true;
    }
  }
  return found;
}

}  // namespace tessella
