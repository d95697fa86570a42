// The surface points one panel's deviation probes have met, with the query
// the prober asks after every probe: which of them is nearer to x than the
// probe's answer (panel_metrics.cpp, Prober::tighten).
//
// A linear scan made that query quadratic in the probes of a panel: a
// boundary panel of a few hundred thin pieces spent 5-15 million
// instructions a panel there (two thirds of panelize on a trimmed dome).
// The points go into a uniform grid of at most 8 x 8 x 8 cells over a box
// given up front (a point outside it lands in the nearest border cell, so a
// query box still finds it); a query visits the cells its ball touches and
// applies the scan's own rule to the candidates in the order they were
// added, so the answer is the linear scan's, bit for bit.
#pragma once

#include <cstddef>
#include <vector>

#include "tessella/vec.h"

namespace tessella {

class KnownSurfacePoints {
 public:
  // A grid over [lo, hi] (the panel's corners and seed points): cubic cells
  // of an eighth of the box's largest side.
  void reset(const Vec3& lo, const Vec3& hi);

  void add(const Vec2& uv, const Vec3& xyz);

  std::size_t size() const { return xyz_.size(); }
  const Vec2& uv(std::size_t k) const { return uv_[k]; }
  const Vec3& xyz(std::size_t k) const { return xyz_[k]; }

  // The linear scan "for k = from, from + 1, ...: if |xyz_k - x| + tiny <
  // d_near, take k" started from d_near: the index it ends on (size() if
  // none) and d_near lowered to that point's distance.
  std::size_t nearer(const Vec3& x, double& d_near, double tiny, std::size_t from = 0) const;

 private:
  int cell_of(const Vec3& p) const;
  void cell_range(const Vec3& lo, const Vec3& hi, int first[3], int last[3]) const;

  Vec3 origin_ = Vec3::Zero();
  double inv_cell_ = 0;
  int n_[3] = {1, 1, 1};
  std::vector<int> head_;  // per cell: the last point added to it, -1 if none
  std::vector<int> next_;  // per point: the point added before it to its cell
  // Per cell the box of its points (valid where head_ >= 0): a query skips a
  // cell whose box lies outside its ball (the surface points under a probe
  // at distance d fill the cells of its query box, but the ball only
  // touches them: a coarse boundary panel scanned ~400 points a query).
  std::vector<Vec3> cell_lo_, cell_hi_;
  std::vector<Vec2> uv_;
  std::vector<Vec3> xyz_;
  mutable std::vector<int> candidates_;
};

}  // namespace tessella
