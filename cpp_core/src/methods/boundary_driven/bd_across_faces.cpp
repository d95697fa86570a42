#include "methods/boundary_driven/bd_across_faces.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/segment_closest.h"
#include "methods/boundary_driven/bd_geometry.h"

namespace tessella {

namespace {

// A point where a curve meets a trim loop: curve parameter (segment + t), the
// loop and its arc length there.
struct Crossing {
  double param;
  Vec2 uv;
  BdCurveEnd at;
};

// The point of `boundary` closest in (u,v) to `uv`, as a curve end, if it is
// within `on_trim`; else an interior end (loop -1).
BdCurveEnd end_on(const std::vector<BdPolyline>& boundary, const Vec2& uv, double on_trim) {
  BdCurveEnd best;
  double best_d = on_trim;
  for (std::size_t k = 0; k < boundary.size(); ++k) {
    const BdPolyline& line = boundary[k];
    for (int i = 0; i < line.segment_count(); ++i) {
      const Vec2 a = line.uv[i], d = line.seg_end_uv(i) - a;
      const double t = closest_fraction(a, d, uv);
      const double dist = (a + t * d - uv).norm();
      if (dist <= best_d) best_d = dist, best.loop = static_cast<int>(k), best.s = line.s_at(i, t);
    }
  }
  return best;
}

Vec2 at_param(const BdCurve& c, double p) {
  const int n = static_cast<int>(c.uv.size());
  const int i = std::clamp(static_cast<int>(std::floor(p)), 0, n - 1);
  const double t = p - i;
  return t <= 0 ? c.uv[i] : c.uv[i] + t * (c.uv[(i + 1) % n] - c.uv[i]);
}

}  // namespace

std::vector<BdCurve> clip_bd_curves(const SurfaceFace& face, const std::vector<BdCurve>& curves,
                                    const std::vector<BdPolyline>& boundary, double on_trim) {
  const UvBounds b = face.bounds();
  Vec2 lo(b.u_min, b.v_min), hi(b.u_max, b.v_max);
  std::size_t segs = 0;
  for (const BdPolyline& line : boundary) {
    segs += line.uv.size();
    for (const Vec2& p : line.uv) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  bd::SegmentGrid grid(lo, hi, std::clamp(static_cast<int>(std::sqrt(double(segs))), 4, 512));
  for (std::size_t k = 0; k < boundary.size(); ++k)
    for (int i = 0; i < boundary[k].segment_count(); ++i)
      grid.add(boundary[k].uv[i], boundary[k].seg_end_uv(i), static_cast<int>(k), i);
  const UvTrimClassifier inside = bd::make_classifier(boundary);

  std::vector<BdCurve> out;
  std::vector<std::array<int, 2>> cand;
  for (const BdCurve& c : curves) {
    const int n = static_cast<int>(c.uv.size());
    if (n < 2) continue;
    const int nseg = c.closed ? n : n - 1;
    std::vector<Crossing> cross;
    for (int i = 0; i < nseg; ++i) {
      const Vec2 a = c.uv[i], e = c.uv[(i + 1) % n];
      cand.clear();
      grid.query(a, e, [&](int loop, int seg) { cand.push_back({loop, seg}); });
      std::sort(cand.begin(), cand.end());
      cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
      for (const auto& [loop, seg] : cand) {
        const BdPolyline& line = boundary[static_cast<std::size_t>(loop)];
        double t, s;
        if (!bd::intersect_segments(a, e, line.uv[seg], line.seg_end_uv(seg), t, s)) continue;
        t = std::clamp(t, 0.0, 1.0), s = std::clamp(s, 0.0, 1.0);
        Crossing x;
        x.param = i + t;
        x.uv = line.uv[seg] + s * (line.seg_end_uv(seg) - line.uv[seg]);
        x.at.loop = loop;
        x.at.s = line.s_at(seg, s);
        cross.push_back(x);
      }
    }
    std::sort(cross.begin(), cross.end(),
              [](const Crossing& x, const Crossing& y) { return x.param < y.param; });
    // A crossing at a trim vertex is found on both segments beside it: once.
    std::vector<Crossing> unique;
    for (const Crossing& x : cross)
      if (unique.empty() || (x.uv - unique.back().uv).norm() > on_trim) unique.push_back(x);
    // The stretches between consecutive events (ends and crossings); a closed
    // curve with crossings is cut open at its first one.
    struct Event {
      double param;
      Vec2 uv;
      BdCurveEnd at;
      bool crossing;
    };
    std::vector<Event> events;
    if (c.closed) {
      if (unique.empty()) {
        if (inside.contains(c.uv[0])) out.push_back(c);
        continue;
      }
      for (const Crossing& x : unique) events.push_back({x.param, x.uv, x.at, true});
      events.push_back({unique[0].param + nseg, unique[0].uv, unique[0].at, true});
    } else {
      const BdCurveEnd start =
          c.start.loop >= 0 ? end_on(boundary, c.uv.front(), on_trim) : BdCurveEnd{};
      const BdCurveEnd end =
          c.end.loop >= 0 ? end_on(boundary, c.uv.back(), on_trim) : BdCurveEnd{};
      events.push_back({0.0, c.uv.front(), start, false});
      for (const Crossing& x : unique) {
        // A crossing at the curve's own end on the trim is that end.
        if ((x.uv - c.uv.front()).norm() <= on_trim || (x.uv - c.uv.back()).norm() <= on_trim)
          continue;
        events.push_back({x.param, x.uv, x.at, true});
      }
      events.push_back({double(nseg), c.uv.back(), end, false});
    }
    for (std::size_t k = 0; k + 1 < events.size(); ++k) {
      const Event& e0 = events[k];
      const Event& e1 = events[k + 1];
      if (!(e1.param > e0.param)) continue;
      const Vec2 mid = at_param(c, std::fmod(0.5 * (e0.param + e1.param), double(nseg)));
      if (!inside.contains(mid)) continue;
      BdCurve piece;
      piece.uv.push_back(e0.uv);
      for (double p = std::floor(e0.param) + 1; p < e1.param; p += 1.0)
        if (p > e0.param) piece.uv.push_back(c.uv[static_cast<std::size_t>(std::fmod(p, nseg))]);
      piece.uv.push_back(e1.uv);
      double length = 0;
      for (std::size_t i = 0; i + 1 < piece.uv.size(); ++i)
        length += (piece.uv[i + 1] - piece.uv[i]).norm();
      if (length <= on_trim) continue;
      for (const Vec2& p : piece.uv) piece.xyz.push_back(face.point(p.x(), p.y()));
      piece.start = e0.at;
      piece.end = e1.at;
      out.push_back(std::move(piece));
    }
  }
  return out;
}

}  // namespace tessella
