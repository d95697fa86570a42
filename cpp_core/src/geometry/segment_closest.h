// The point of a segment closest to a point, as the fraction along it: the
// one formula the trim and edge searches share (2D in (u,v), 3D in space).
#pragma once

#include <algorithm>

namespace tessella {

// Fraction t in [0, 1] of the point a + t d closest to p (a zero-length
// segment: its start).
template <class V>
double closest_fraction(const V& a, const V& d, const V& p) {
  return std::clamp((p - a).dot(d) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
}

}  // namespace tessella
