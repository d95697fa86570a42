// The pairs of non-adjacent sides of a closed polygon whose bounding boxes
// meet, in order (side i with each later side j), for tests of how a
// polygon's sides meet each other (crossing, touching, overlapping on a line).
#pragma once

#include <algorithm>
#include <vector>

#include "tessella/vec.h"

namespace tessella {

// Whether `meet`(a, b, c, d) holds for some pair of non-adjacent sides a-b
// and c-d whose boxes meet; stops at the first.
template <class Meet>
bool any_non_adjacent_sides(const std::vector<Vec2>& p, Meet&& meet) {
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 &a = p[i], &b = p[(i + 1) % n];
    const Vec2 lo = a.cwiseMin(b), hi = a.cwiseMax(b);
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;
      const Vec2 &c = p[j], &d = p[(j + 1) % n];
      if (std::max(c.x(), d.x()) < lo.x() || std::min(c.x(), d.x()) > hi.x() ||
          std::max(c.y(), d.y()) < lo.y() || std::min(c.y(), d.y()) > hi.y())
        continue;
      if (meet(a, b, c, d)) return true;
    }
  }
  return false;
}

}  // namespace tessella
