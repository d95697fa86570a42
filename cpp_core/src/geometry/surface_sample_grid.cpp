#include "geometry/surface_sample_grid.h"

#include <algorithm>
#include <cmath>
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
  gu_ = (bu_ + kGroup - 1) / kGroup;
  gv_ = (bv_ + kGroup - 1) / kGroup;
  group_lo_.assign(static_cast<std::size_t>(gu_) * gv_, Vec3(inf, inf, inf));
  group_hi_.assign(static_cast<std::size_t>(gu_) * gv_, Vec3(-inf, -inf, -inf));
  for (int j = 0; j < bv_; ++j)
    for (int i = 0; i < bu_; ++i) {
      const std::size_t g = static_cast<std::size_t>(j / kGroup) * gu_ + i / kGroup;
      const std::size_t b = static_cast<std::size_t>(j) * bu_ + i;
      group_lo_[g] = group_lo_[g].cwiseMin(box_lo_[b]);
      group_hi_[g] = group_hi_[g].cwiseMax(box_hi_[b]);
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

namespace {
// Squared distance from p to the box [lo, hi]: no point in it is nearer.
double box_distance_sq(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  return (lo - p).cwiseMax(p - hi).cwiseMax(Vec3::Zero()).squaredNorm();
}
}  // namespace

void SurfaceSampleGrid::group_bounds(const Vec3& p, std::vector<double>& out) const {
  out.resize(group_lo_.size());
  for (std::size_t g = 0; g < out.size(); ++g)
    out[g] = box_distance_sq(p, group_lo_[g], group_hi_[g]);
}

// Two levels, so a search looks at the boxes near p only: the terrain's grid
// has 4,225 blocks, and sorting all of them on every call was half of the
// time of its metrics. Which blocks are visited does not depend on the
// order beyond what the limit excludes: a block is skipped only when its box
// is farther than the limit, and the limit only shrinks, so every sample
// within the final limit is visited (the answers are the same as visiting
// all blocks in sorted order).
// The nearest group first (after it the limit is small), then every other
// group in grid order that the limit still lets in: neither a sort nor a
// heap of all groups (420 on OCCT's terrain: sorting them twice a search was
// 7% of its time, a heap still 2.5%). In a group, the nearest blocks first.
template <class Limit, class Visit>
void SurfaceSampleGrid::blocks_within(const Vec3& p, const std::vector<double>& group_bound,
                                      const Limit& limit, const Visit& visit) const {
  std::size_t first = 0;
  for (std::size_t g = 1; g < group_bound.size(); ++g)
    if (group_bound[g] < group_bound[first]) first = g;
  std::vector<std::pair<double, std::size_t>> blocks;
  blocks.reserve(static_cast<std::size_t>(kGroup) * kGroup);
  auto visit_group = [&](std::size_t g) {
    if (group_bound[g] > limit()) return;  // every block in it is at least as far
    const int gi = static_cast<int>(g % static_cast<std::size_t>(gu_));
    const int gj = static_cast<int>(g / static_cast<std::size_t>(gu_));
    blocks.clear();
    for (int j = gj * kGroup; j < std::min(bv_, gj * kGroup + kGroup); ++j)
      for (int i = gi * kGroup; i < std::min(bu_, gi * kGroup + kGroup); ++i) {
        const std::size_t b = static_cast<std::size_t>(j) * bu_ + i;
        blocks.push_back({box_distance_sq(p, box_lo_[b], box_hi_[b]), b});
      }
    std::sort(blocks.begin(), blocks.end());
    for (const auto& [bound, b] : blocks) {
      if (bound > limit()) break;
      visit(b);
    }
  };
  if (group_bound.empty()) return;
  visit_group(first);
  for (std::size_t g = 0; g < group_bound.size(); ++g)
    if (g != first) visit_group(g);
}

template <class Visit>
void SurfaceSampleGrid::blocks_within_fixed(const Vec3& p, const std::vector<double>& group_bound,
                                            double limit_sq, const Visit& visit) const {
  for (std::size_t g = 0; g < group_bound.size(); ++g) {
    if (group_bound[g] > limit_sq) continue;
    const int gi = static_cast<int>(g % static_cast<std::size_t>(gu_));
    const int gj = static_cast<int>(g / static_cast<std::size_t>(gu_));
    for (int j = gj * kGroup; j < std::min(bv_, gj * kGroup + kGroup); ++j)
      for (int i = gi * kGroup; i < std::min(bu_, gi * kGroup + kGroup); ++i) {
        const std::size_t b = static_cast<std::size_t>(j) * bu_ + i;
        if (box_distance_sq(p, box_lo_[b], box_hi_[b]) <= limit_sq) visit(b);
      }
  }
}

template <class Visit>
void SurfaceSampleGrid::samples_of(std::size_t b, const Visit& visit) const {
  const int bi = static_cast<int>(b % static_cast<std::size_t>(bu_));
  const int bj = static_cast<int>(b / static_cast<std::size_t>(bu_));
  for (int j = bj * kBlock; j < std::min(nv_ + 1, bj * kBlock + kBlock); ++j)
    for (int i = bi * kBlock; i < std::min(nu_ + 1, bi * kBlock + kBlock); ++i) visit(i, j);
}

SurfaceSampleGrid::Sample SurfaceSampleGrid::nearest(const Vec3& p) const {
  std::vector<double> group_bound;
  group_bounds(p, group_bound);
  return nearest(p, group_bound);
}

SurfaceSampleGrid::Sample SurfaceSampleGrid::nearest(const Vec3& p,
                                                     const std::vector<double>& group_bound) const {
  double best = std::numeric_limits<double>::infinity();
  std::size_t best_index = 0;
  blocks_within(
      p, group_bound, [&] { return best; },
      [&](std::size_t b) {
        samples_of(b, [&](int i, int j) {
          const std::size_t k = static_cast<std::size_t>(j) * (nu_ + 1) + i;
          const double d = (points_[k] - p).squaredNorm();
          // Ties go to the first in grid order, whatever order the blocks came in.
          if (d < best || (d == best && k < best_index)) best = d, best_index = k;
        });
      });
  Sample s;
  s.uv = uv_of(static_cast<int>(best_index % (nu_ + 1)), static_cast<int>(best_index / (nu_ + 1)));
  s.distance = std::sqrt(best);
  return s;
}

std::vector<SurfaceSampleGrid::Sample> SurfaceSampleGrid::candidates(const Vec3& p,
                                                                     int count) const {
  std::vector<double> group_bound;
  group_bounds(p, group_bound);
  const Sample first = nearest(p, group_bound);
  const double limit = first.distance + 2.0 * reach_;
  const double limit_sq = limit * limit;
  auto dist_sq = [&](int i, int j) {
    return (points_[static_cast<std::size_t>(j) * (nu_ + 1) + i] - p).squaredNorm();
  };
  std::vector<std::pair<double, std::size_t>> found;  // (squared distance, sample index)
  blocks_within_fixed(p, group_bound, limit_sq, [&](std::size_t b) {
    samples_of(b, [&](int i, int j) {
      const double d = dist_sq(i, j);
      if (d > limit_sq) return;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int a = i + di, c = j + dj;
          if ((di == 0 && dj == 0) || a < 0 || c < 0 || a > nu_ || c > nv_) continue;
          if (dist_sq(a, c) < d) return;  // not a local minimum
        }
      found.emplace_back(d, static_cast<std::size_t>(j) * (nu_ + 1) + i);
    });
  });
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
