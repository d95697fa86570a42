#include "geometry/edge_track.h"

#include <algorithm>

#include "geometry/segment_closest.h"

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
      const double f = closest_fraction(a, e, p);
      const double d2 = (a + f * e - p).squaredNorm();
      if (d2 <= best) best = d2, segment = i, t = f, found = true;
    }
  }
  return found;
}

int first_track_near(const std::vector<EdgeTrack>& tracks, const Vec3& p, double d) {
  for (std::size_t i = 0; i < tracks.size(); ++i)
    if (tracks[i].near(p, d)) return static_cast<int>(i);
  return -1;
}

std::vector<Vec3> sample_curve(const std::function<Vec3(double)>& at, double first, double last,
                               double max_sag, int max_chords, double& sag) {
  const double span = last - first;
  int n = 64;
  std::vector<Vec3> line;
  for (int k = 0; k <= n; ++k) line.push_back(at(first + span * k / n));
  for (;;) {
    // span * (k + 0.5) / n is bit for bit the parameter of point 2k + 1 of
    // the doubled polyline (scaling by two is exact), so the midpoints are
    // its points.
    std::vector<Vec3> mid(static_cast<std::size_t>(n));
    sag = 0;
    for (int k = 0; k < n; ++k) {
      mid[k] = at(first + span * (k + 0.5) / n);
      sag = std::max(sag, (mid[k] - 0.5 * (line[k] + line[k + 1])).norm());
    }
    if (sag <= max_sag || 2 * n > max_chords) return line;
    std::vector<Vec3> finer;
    finer.reserve(2 * static_cast<std::size_t>(n) + 1);
    for (int k = 0; k < n; ++k) {
      finer.push_back(line[k]);
      finer.push_back(mid[k]);
    }
    finer.push_back(line[n]);
    line.swap(finer);
    n *= 2;
  }
}

}  // namespace tessella
