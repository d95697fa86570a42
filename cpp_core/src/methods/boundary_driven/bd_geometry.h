// Private helpers of the boundary-driven stages: segment intersection in (u,v),
// a uniform grid of segments in (u,v) and a hash of points in 3D.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

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

// Even-odd point-in-region test against closed (u,v) polylines (the trim
// loops), with the segments binned in bands of v: much faster than OCCT's
// classifier when called for every tracing step.
class UvClassifier {
 public:
  UvClassifier(const std::vector<std::vector<Vec2>>& loops, int bands) : n_(std::max(bands, 1)) {
    lo_ = 1e300, hi_ = -1e300;
    for (const auto& l : loops)
      for (const Vec2& p : l) lo_ = std::min(lo_, p.y()), hi_ = std::max(hi_, p.y());
    step_ = std::max((hi_ - lo_) / n_, 1e-300);
    bands_.resize(n_);
    for (const auto& l : loops)
      for (std::size_t i = 0; i < l.size(); ++i) {
        const Vec2& a = l[i];
        const Vec2& b = l[(i + 1) % l.size()];
        if (a.y() == b.y()) continue;
        for (int k = band(std::min(a.y(), b.y())); k <= band(std::max(a.y(), b.y())); ++k)
          bands_[k].push_back({a, b});
      }
  }
  bool inside(const Vec2& p) const {
    if (!(p.y() >= lo_ && p.y() <= hi_)) return false;
    bool in = false;
    for (const auto& s : bands_[band(p.y())]) {
      const Vec2 &a = s[0], &b = s[1];
      if ((a.y() > p.y()) != (b.y() > p.y())) {
        const double x = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
        if (x > p.x()) in = !in;
      }
    }
    return in;
  }

 private:
  int band(double v) const { return std::clamp(static_cast<int>((v - lo_) / step_), 0, n_ - 1); }
  int n_;
  double lo_, hi_, step_;
  std::vector<std::vector<std::array<Vec2, 2>>> bands_;
};

template <class Lines>
UvClassifier make_classifier(const Lines& boundary) {
  std::vector<std::vector<Vec2>> loops;
  std::size_t n = 0;
  for (const auto& l : boundary) loops.push_back(l.uv), n += l.uv.size();
  return UvClassifier(loops, static_cast<int>(std::clamp<std::size_t>(n / 4, 16, 4096)));
}

}  // namespace tessella::bd
