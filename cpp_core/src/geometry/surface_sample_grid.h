// The global closest-point search behind SurfaceFace::project when Newton
// fails: a fixed grid of surface samples over the search range, grouped in
// blocks with bounding boxes, answers "which sample is nearest" by visiting
// blocks in order of their box distance. It replaces OCCT's Extrema search,
// which recomputes the distance to every grid point on every call (55 ms a
// call on OCCT's 312 x 323-pole terrain; this takes tens of microseconds).
// Read-only once built, so threads share it.
#pragma once

#include <functional>
#include <utility>
#include <vector>

#include "tessella/surface_face.h"

namespace tessella {

class SurfaceSampleGrid {
 public:
  // (nu + 1) x (nv + 1) samples of `point` over `range`, evenly in (u,v).
  SurfaceSampleGrid(const UvBounds& range, int nu, int nv,
                    const std::function<Vec3(double, double)>& point);

  struct Sample {
    Vec2 uv;
    double distance = 0;
  };
  // The sample nearest to p (the first in grid order among equals).
  Sample nearest(const Vec3& p) const;
  // Where a foot point search should start: the samples that are local
  // minima of the distance to p among their grid neighbours and no farther
  // than the nearest sample plus the grid's reach (every surface point has a
  // sample within it, so the global foot point's nearest sample is among
  // them), nearest first, at most `count`. The nearest sample comes first.
  std::vector<Sample> candidates(const Vec3& p, int count) const;
  // Grid step in u and v.
  double step_u() const { return (range_.u_max - range_.u_min) / nu_; }
  double step_v() const { return (range_.v_max - range_.v_min) / nv_; }

 private:
  static constexpr int kBlock = 8;  // samples per block side
  static constexpr int kGroup = 8;  // blocks per group side
  UvBounds range_;
  int nu_, nv_;
  int bu_, bv_;                            // blocks along u and v
  int gu_, gv_;                            // groups of blocks along u and v
  std::vector<Vec3> points_;               // (nu + 1) x (nv + 1), u fastest
  std::vector<Vec3> box_lo_, box_hi_;      // per block
  std::vector<Vec3> group_lo_, group_hi_;  // per group
  double reach_ = 0;                       // largest half diagonal of a grid cell in 3D
  Vec2 uv_of(int i, int j) const;
  // visit(b) for every block whose box is within limit() (a squared
  // distance, read again before each block: it may shrink as the visits go)
  // of p, the nearest group first and in a group the nearest blocks first.
  // group_bound: every group's squared box distance from p (group_bounds).
  template <class Limit, class Visit>
  void blocks_within(const Vec3& p, const std::vector<double>& group_bound, const Limit& limit,
                     const Visit& visit) const;
  // visit(b) for every block whose box is within limit_sq of p, in grid
  // order (a fixed limit: no order can let one be skipped).
  template <class Visit>
  void blocks_within_fixed(const Vec3& p, const std::vector<double>& group_bound, double limit_sq,
                           const Visit& visit) const;
  // The squared distance from p to each group's box, into out (reused: a
  // search computes them once for both of its passes).
  void group_bounds(const Vec3& p, std::vector<double>& out) const;
  Sample nearest(const Vec3& p, const std::vector<double>& group_bound) const;
  // Every sample of block b.
  template <class Visit>
  void samples_of(std::size_t b, const Visit& visit) const;
};

}  // namespace tessella
