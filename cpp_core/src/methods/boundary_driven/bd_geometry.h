// Private helpers of the boundary-driven stages: segment intersection in (u,v),
// a uniform grid of segments in (u,v), a hash of points in 3D and the trim
// classifier of the boundary polylines.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "geometry/uv_trim_classifier.h"
#include "tessella/vec.h"

namespace tessella::bd {

inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Proper or touching intersection of segments [a,b] and [c,d]: t along ab, s along cd.
inline bool intersect_segments(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d,
                               double& t, double& s) {
  const Vec2 r = b - a, q = d - c;
  const double den = cross2(r, q);
  if (den == 0.0) return false;  // parallel (collinear overlap is not a crossing here)
  const Vec2 ac = c - a;
  t = cross2(ac, q) / den;
  s = cross2(ac, r) / den;
  const double eps = 1e-12;
  return t >= -eps && t <= 1 + eps && s >= -eps && s <= 1 + eps;
}

// Segments indexed by (line, segment) in a uniform grid over (u,v).
class SegmentGrid {
 public:
  SegmentGrid(const Vec2& lo, const Vec2& hi, int cells) : lo_(lo), n_(std::max(cells, 1)) {
    size_ = (hi - lo).cwiseMax(Vec2(1e-300, 1e-300)) / n_;
    cells_.resize(static_cast<std::size_t>(n_) * n_);
  }
  void add(const Vec2& a, const Vec2& b, int line, int seg) {
    int i0, j0, i1, j1;
    cell(a.cwiseMin(b), i0, j0);
    cell(a.cwiseMax(b), i1, j1);
    for (int i = i0; i <= i1; ++i)
      for (int j = j0; j <= j1; ++j) cells_[i * n_ + j].push_back({line, seg});
  }
  // Calls f(line, seg) for every stored segment whose cells meet the box of [a,b]
  // (a segment may be reported more than once).
  template <class F>
  void query(const Vec2& a, const Vec2& b, F f) const {
    int i0, j0, i1, j1;
    cell(a.cwiseMin(b), i0, j0);
    cell(a.cwiseMax(b), i1, j1);
    for (int i = i0; i <= i1; ++i)
      for (int j = j0; j <= j1; ++j)
        for (const auto& e : cells_[i * n_ + j]) f(e[0], e[1]);
  }

 private:
  void cell(const Vec2& p, int& i, int& j) const {
    i = std::clamp(static_cast<int>(std::floor((p.x() - lo_.x()) / size_.x())), 0, n_ - 1);
    j = std::clamp(static_cast<int>(std::floor((p.y() - lo_.y()) / size_.y())), 0, n_ - 1);
  }
  Vec2 lo_, size_;
  int n_;
  std::vector<std::vector<std::array<int, 2>>> cells_;
};

// Points in 3D hashed by cell, for "is there a point of another line near here".
struct HashedPoint {
  Vec3 p, dir;
  Vec2 uv;
  int line;
  double arc;
  int chart = 0;  // the face uv belongs to (curves traced across faces)
};

class PointHash {
 public:
  explicit PointHash(double cell) : cell_(cell) {}
  void add(const HashedPoint& hp) { map_[key(hp.p)].push_back(hp); }
  template <class F>
  void near(const Vec3& p, F f) const {
    const long long ix = coord(p.x()), iy = coord(p.y()), iz = coord(p.z());
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          auto it = map_.find(pack(ix + dx, iy + dy, iz + dz));
          if (it == map_.end()) continue;
          for (const HashedPoint& hp : it->second) f(hp);
        }
  }

 private:
  long long coord(double x) const { return static_cast<long long>(std::floor(x / cell_)); }
  static std::int64_t pack(long long x, long long y, long long z) {
    return ((x & 0x1FFFFF) << 42) | ((y & 0x1FFFFF) << 21) | (z & 0x1FFFFF);
  }
  std::int64_t key(const Vec3& p) const { return pack(coord(p.x()), coord(p.y()), coord(p.z())); }
  double cell_;
  std::unordered_map<std::int64_t, std::vector<HashedPoint>> map_;
};

}  // namespace tessella::bd

namespace tessella::bd {

// The one (u,v) point-in-trim classifier over the boundary polylines (the trim
// loops): default on-trim epsilon, a point on the trim counts as inside.
template <class Lines>
UvTrimClassifier make_classifier(const Lines& boundary) {
  std::vector<std::vector<Vec2>> loops;
  for (const auto& l : boundary) loops.push_back(l.uv);
  return UvTrimClassifier(loops);
}

}  // namespace tessella::bd
