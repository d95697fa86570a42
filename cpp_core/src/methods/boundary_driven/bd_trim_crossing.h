// Whether a straight network edge in (u,v) crosses a trim loop: the test that
// keeps the refinement's node moves from pulling a rod across an opening.
//
// A node moved next to a convex opening can still be inside the face while
// its edge to a node on the opening's trim cuts across the opening's bulge;
// the panel between them then follows the trim (follow_trims) on one side and
// the rod on the other, and its outline crosses itself (cone_facade at
// 900 mm: a 336-corner panel folded over a hole's rim, zero area in (u,v)).
// Only an edge's own ends may touch the trim, where it starts on a trim node.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "methods/boundary_driven/bd_geometry.h"
#include "tessella/boundary_driven.h"

namespace tessella::bd {

class TrimCrossingTest {
 public:
  explicit TrimCrossingTest(const std::vector<BdPolyline>& boundary) : boundary_(boundary) {
    Vec2 lo(1e300, 1e300), hi(-1e300, -1e300);
    std::size_t segs = 0;
    for (const auto& l : boundary)
      for (const Vec2& p : l.uv) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p), ++segs;
    if (segs == 0) return;
    grid_.emplace_back(lo, hi, std::clamp(static_cast<int>(std::sqrt(double(segs)) / 2), 4, 512));
    for (std::size_t li = 0; li < boundary.size(); ++li) {
      const BdPolyline& l = boundary[li];
      for (int i = 0; i < l.segment_count(); ++i)
        grid_[0].add(l.uv[static_cast<std::size_t>(i)], l.seg_end_uv(i), static_cast<int>(li), i);
    }
  }

  // Whether the straight edge between nodes a and b meets a trim polyline
  // anywhere but at its ends. A trim node snapped onto its trim's own curve
  // lies off the polyline by up to the trim deflection, so its edges may
  // graze the polyline segments around it: those (the one at its arc length
  // and either neighbour) do not count for that end.
  bool crosses(const BdNode& a, const BdNode& b) const {
    if (grid_.empty()) return false;
    Near na, nb;  // found at the first intersection (most edges have none)
    bool looked = false, hit = false;
    grid_[0].query(a.uv, b.uv, [&](int li, int si) {
      if (hit) return;
      const BdPolyline& l = boundary_[static_cast<std::size_t>(li)];
      double t, s;
      if (!intersect_segments(a.uv, b.uv, l.uv[static_cast<std::size_t>(si)], l.seg_end_uv(si), t,
                              s) ||
          !(t > kEndShare && t < 1.0 - kEndShare))
        return;
      if (!looked) na = near(a), nb = near(b), looked = true;
      hit = !na.holds(li, si) && !nb.holds(li, si);
    });
    return hit;
  }

 private:
  static constexpr double kEndShare = 1e-6;  // an end on the trim touches it
  // The polyline segments at a trim node (none for an interior node).
  struct Near {
    int loop = -1, seg = 0, count = 1;
    bool holds(int li, int si) const {
      if (li != loop) return false;
      const int d = ((si - seg) % count + count) % count;
      return d <= 1 || d == count - 1;
    }
  };
  Near near(const BdNode& n) const {
    Near r;
    if (n.loop < 0) return r;
    const BdPolyline& l = boundary_[static_cast<std::size_t>(n.loop)];
    double s = n.s;
    r.loop = n.loop, r.seg = l.segment_at(s), r.count = std::max(l.segment_count(), 1);
    return r;
  }
  const std::vector<BdPolyline>& boundary_;
  std::vector<SegmentGrid> grid_;  // empty when there is no trim
};

}  // namespace tessella::bd
