#include "geometry/polygon_fold.h"

#include <algorithm>
#include <cmath>

namespace tessella {

namespace {

int orient(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 u = b - a, v = c - a;
  const double d = u.x() * v.y() - u.y() * v.x();
  return (d > 0) - (d < 0);
}

// Sides a-b and c-d on one line, overlapping over more than a rounding.
bool overlap_on_a_line(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  if (orient(a, b, c) != 0 || orient(a, b, d) != 0) return false;
  const int axis = std::abs(b.x() - a.x()) >= std::abs(b.y() - a.y()) ? 0 : 1;
  const double lo1 = std::min(a[axis], b[axis]), hi1 = std::max(a[axis], b[axis]);
  const double lo2 = std::min(c[axis], d[axis]), hi2 = std::max(c[axis], d[axis]);
  return std::min(hi1, hi2) - std::max(lo1, lo2) > 1e-12 * ((hi1 - lo1) + (hi2 - lo2));
}

}  // namespace

bool folds_back_on_itself(const std::vector<Vec2>& p) {
  const std::size_t n = p.size();
  if (n < 3) return false;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 &a = p[(i + n - 1) % n], &b = p[i], &c = p[(i + 1) % n];
    if (a != b && b != c && orient(a, b, c) == 0 && (a - b).dot(c - b) > 0) return true;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 &a = p[i], &b = p[(i + 1) % n];
    const Vec2 lo = a.cwiseMin(b), hi = a.cwiseMax(b);
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;
      const Vec2 &c = p[j], &d = p[(j + 1) % n];
      if (std::max(c.x(), d.x()) < lo.x() || std::min(c.x(), d.x()) > hi.x() ||
          std::max(c.y(), d.y()) < lo.y() || std::min(c.y(), d.y()) > hi.y())
        continue;
      if (overlap_on_a_line(a, b, c, d)) return true;
    }
  }
  return false;
}

}  // namespace tessella
