#include "geometry/surface_sample_grid.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <utility>

namespace tessella {

SurfaceSampleGrid::SurfaceSampleGrid(const UvBounds& range, int nu, int nv,
                                     const std::function<Vec3(double, double)>& point)
    : range_(range), nu_(std::max(1, nu)), nv_(std::max(1, nv)) {
  points_.resize(static_cast<std::size_t>(nu_ + 1) * (nv_ + 1));
  for (int j = 0; j <= nv_; ++j)
    for (int i = 0; i <= nu_; ++i) {
      const Vec2 uv = uv_of(i, j);
      points_[static_cast<std::size_t>(j) * (nu_ + 1) + i] = point(uv.x(), uv.y());
    }
  bu_ = (nu_ + kBlock) / kBlock;  // blocks of samples i in [b * kBlock, b * kBlock + kBlock)
  bv_ = (nv_ + kBlock) / kBlock;
  const double inf = std::numeric_limits<double>::infinity();
  box_lo_.assign(static_cast<std::size_t>(bu_) * bv_, Vec3(inf, inf, inf));
  box_hi_.assign(static_cast<std::size_t>(bu_) * bv_, Vec3(-inf, -inf, -inf));
  for (int j = 0; j <= nv_; ++j)
    for (int i = 0; i <= nu_; ++i) {
      const std::size_t b = static_cast<std::size_t>(j / kBlock) * bu_ + i / kBlock;
      const Vec3& q = points_[static_cast<std::size_t>(j) * (nu_ + 1) + i];
      box_lo_[b] = box_lo_[b].cwiseMin(q);
      box_hi_[b] = box_hi_[b].cwiseMax(q);
    }
  // The surface bends between samples; the half diagonal is the reach of
  // the cell's corners to first order, which the margin of candidates() takes
  // twice over.
  for (int j = 0; j < nv_; ++j)
    for (int i = 0; i < nu_; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * (nu_ + 1) + i;
      const double d1 = (points_[k + nu_ + 2] - points_[k]).norm();
      const double d2 = (points_[k + nu_ + 1] - points_[k + 1]).norm();
      reach_ = std::max(reach_, 0.5 * std::max(d1, d2));
    }
}

Vec2 SurfaceSampleGrid::uv_of(int i, int j) const {
  // The last sample sits exactly on the upper bound.
  const double u = i == nu_ ? range_.u_max : range_.u_min + step_u() * i;
  const double v = j == nv_ ? range_.v_max : range_.v_min + step_v() * j;
  return {u, v};
}

// The blocks in order of the squared distance from p to their box (then of
// their index), taken from a heap as far as a search goes: a search stops at
// the first block farther than its answer, a few dozen of the terrain's 4,225
// blocks, whose full sort was half of the time of a rough terrain's metrics.
// Blocks once taken are kept, so a second pass goes through the same order.
class SurfaceSampleGrid::BlocksByDistance {
 public:
  BlocksByDistance(const SurfaceSampleGrid& grid, const Vec3& p) {
    const std::size_t blocks = grid.box_lo_.size();
    heap_.resize(blocks);
    for (std::size_t b = 0; b < blocks; ++b) {
      // Squared distance from p to the block's box: no sample in it is nearer.
      const Vec3 d = (grid.box_lo_[b] - p).cwiseMax(p - grid.box_hi_[b]).cwiseMax(Vec3::Zero());
      heap_[b] = {d.squaredNorm(), b};
    }
    std::make_heap(heap_.begin(), heap_.end(), std::greater<>());
    taken_.reserve(64);
  }
  // The k-th block in order (k at most one past the last taken); false past
  // the last block.
  bool at(std::size_t k, std::pair<double, std::size_t>& out) {
    if (k == taken_.size()) {
      if (heap_.empty()) return false;
      std::pop_heap(heap_.begin(), heap_.end(), std::greater<>());
      taken_.push_back(heap_.back());
      heap_.pop_back();
    }
    out = taken_[k];
    return true;
  }

 private:
  std::vector<std::pair<double, std::size_t>> heap_;   // not yet taken, a min-heap
  std::vector<std::pair<double, std::size_t>> taken_;  // taken, in order
};

SurfaceSampleGrid::Sample SurfaceSampleGrid::nearest(const Vec3& p) const {
  BlocksByDistance order(*this, p);
  return nearest_in(order, p);
}

SurfaceSampleGrid::Sample SurfaceSampleGrid::nearest_in(BlocksByDistance& order,
                                                        const Vec3& p) const {
  double best = std::numeric_limits<double>::infinity();
  std::size_t best_index = 0;
  std::pair<double, std::size_t> next;
  for (std::size_t k = 0; order.at(k, next); ++k) {
    const auto& [bound, b] = next;
    if (bound > best) break;
    const int bi = static_cast<int>(b % bu_), bj = static_cast<int>(b / bu_);
    for (int j = bj * kBlock; j < std::min(nv_ + 1, bj * kBlock + kBlock); ++j)
      for (int i = bi * kBlock; i < std::min(nu_ + 1, bi * kBlock + kBlock); ++i) {
        const std::size_t k = static_cast<std::size_t>(j) * (nu_ + 1) + i;
        const double d = (points_[k] - p).squaredNorm();
        // Ties go to the first in grid order, whatever order the blocks came in.
        if (d < best || (d == best && k < best_index)) best = d, best_index = k;
      }
  }
  Sample s;
  s.uv = uv_of(static_cast<int>(best_index % (nu_ + 1)), static_cast<int>(best_index / (nu_ + 1)));
  s.distance = std::sqrt(best);
  return s;
}

std::vector<SurfaceSampleGrid::Sample> SurfaceSampleGrid::candidates(const Vec3& p,
                                                                     int count) const {
  BlocksByDistance order(*this, p);  // one order for both passes
  const Sample first = nearest_in(order, p);
  const double limit = first.distance + 2.0 * reach_;
  const double limit_sq = limit * limit;
  auto dist_sq = [&](int i, int j) {
    return (points_[static_cast<std::size_t>(j) * (nu_ + 1) + i] - p).squaredNorm();
  };
  std::vector<std::pair<double, std::size_t>> found;  // (squared distance, sample index)
  std::pair<double, std::size_t> next;
  for (std::size_t k = 0; order.at(k, next); ++k) {
    const auto& [bound, b] = next;
    if (bound > limit_sq) break;
    const int bi = static_cast<int>(b % bu_), bj = static_cast<int>(b / bu_);
    for (int j = bj * kBlock; j < std::min(nv_ + 1, bj * kBlock + kBlock); ++j)
      for (int i = bi * kBlock; i < std::min(nu_ + 1, bi * kBlock + kBlock); ++i) {
        const double d = dist_sq(i, j);
        if (d > limit_sq) continue;
        bool minimum = true;
        for (int dj = -1; dj <= 1 && minimum; ++dj)
          for (int di = -1; di <= 1; ++di) {
            const int a = i + di, c = j + dj;
            if ((di == 0 && dj == 0) || a < 0 || c < 0 || a > nu_ || c > nv_) continue;
            if (dist_sq(a, c) < d) {
              minimum = false;
              break;
            }
          }
        if (minimum) found.emplace_back(d, static_cast<std::size_t>(j) * (nu_ + 1) + i);
      }
  }
  std::sort(found.begin(), found.end());  // by distance, then grid order: deterministic
  std::vector<Sample> out{first};
  for (const auto& [d, k] : found) {
    if (static_cast<int>(out.size()) >= count) break;
    const Vec2 uv = uv_of(static_cast<int>(k % (nu_ + 1)), static_cast<int>(k / (nu_ + 1)));
    if (uv == first.uv) continue;
    out.push_back({uv, std::sqrt(d)});
  }
  return out;
}

}  // namespace tessella
