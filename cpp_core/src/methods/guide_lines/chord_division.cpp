// Equal-chord division of a curve with the left-over rule (seed 004 section 5.1
// step 7).
#include "methods/guide_lines/chord_division.h"

#include <algorithm>
#include <cmath>

#include "methods/guide_lines/right_angle_rule.h"
#include "tessella/errors.h"
#include "tessella/guide_line_scaling.h"
#include "tessella/two_guide_lines.h"

namespace tessella {

Vec3 polyline_point(const std::vector<Vec3>& points, double t) {
  if (points.empty()) throw InvalidParameter("polyline_point: empty polyline");
  const double last = static_cast<double>(points.size() - 1);
  t = std::clamp(t, 0.0, last);
  const std::size_t s = std::min(static_cast<std::size_t>(t), points.size() - 1);
  if (s + 1 >= points.size()) return points.back();
  const double f = t - static_cast<double>(s);
  return points[s] + f * (points[s + 1] - points[s]);
}

namespace {

// Smallest t > t0 where the polyline is `chord` away from its point at t0
// (walking forward); -1 if the end comes first.
double next_at_chord(const std::vector<Vec3>& pts, double t0, double chord) {
  const Vec3 x = polyline_point(pts, t0);
  std::size_t s = static_cast<std::size_t>(t0);
  for (; s + 1 < pts.size(); ++s) {
    const double lo = std::max(0.0, t0 - static_cast<double>(s));
    const Vec3 a = pts[s], d = pts[s + 1] - pts[s];
    const double qa = d.squaredNorm();
    if (qa <= 0.0) continue;
    const double qb = 2.0 * (a - x).dot(d);
    const double qc = (a - x).squaredNorm() - chord * chord;
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc < 0.0) continue;
    const double tau = (-qb + std::sqrt(disc)) / (2.0 * qa);  // the larger root: leaving the sphere
    if (tau >= lo && tau <= 1.0) return static_cast<double>(s) + tau;
  }
  return -1.0;
}

// Chord length with which exactly n equal chords end at the polyline's end
// (bisection), and the nodes; the last node is set to the end.
double equal_chords(const std::vector<Vec3>& pts, int n, double guess, std::vector<double>& nodes) {
  const double end = static_cast<double>(pts.size() - 1);
  double lo = guess * 0.25, hi = guess * 4.0;
  for (int it = 0; it < 60; ++it) {
    const double c = 0.5 * (lo + hi);
    const std::vector<double> laid = lay_chords(pts, c, n);
    if (static_cast<int>(laid.size()) - 1 < n)
      hi = c;  // ran out of curve: chords too long
    else
      lo = c;  // all n laid before the end: too short
  }
  const double c = lo;
  nodes = lay_chords(pts, c, n);
  if (static_cast<int>(nodes.size()) - 1 == n)
    nodes.back() = end;
  else
    nodes.push_back(end);
  return c;
}

}  // namespace

std::vector<double> lay_chords(const std::vector<Vec3>& pts, double chord, int max_count) {
  std::vector<double> nodes{0.0};
  while (static_cast<int>(nodes.size()) - 1 < max_count) {
    const double t = next_at_chord(pts, nodes.back(), chord);
    if (t < 0.0) break;
    nodes.push_back(t);
  }
  return nodes;
}

std::vector<double> divide_by_chords(const std::vector<Vec3>& points,
                                     const ChordDivisionParams& params) {
  require_in_range("rod_length (mm)", params.chord, 1e-3, 1e9);
  require_in_range("merge_fraction", params.merge_fraction, 0.0, 0.999);
  if (points.size() < 2) throw InvalidParameter("divide_by_chords: the curve needs two points");
  const double end = static_cast<double>(points.size() - 1);
  const double l1 = params.chord;
  std::vector<double> nodes = lay_chords(points, l1, 1 << 24);
  const int full = static_cast<int>(nodes.size()) - 1;
  const double rest = (points.back() - polyline_point(points, nodes.back())).norm();
  if (full == 0) return {0.0, end};
  if (rest < params.merge_fraction * l1) {
    // Merge: the left-over joins the last chord (one slightly longer chord).
    nodes.back() = end;
    return nodes;
  }
  // Spread: n equal chords ending at the end, n = full or full + 1, whichever
  // chord is closer to L1.
  std::vector<double> a, b;
  const double ca = equal_chords(points, full, l1, a);
  const double cb = equal_chords(points, full + 1, l1, b);
  return std::abs(ca - l1) <= std::abs(cb - l1) ? a : b;
}

}  // namespace tessella
