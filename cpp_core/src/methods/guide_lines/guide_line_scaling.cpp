// The Guide Line Scaling Method (seed 004 section 5): advance a guide curve over
// the face by scaling / translating / rotating it between new end points on the
// boundary and projecting it back, divide the curves into equal chords and
// connect neighbouring curves into triangles.
#include "tessella/guide_line_scaling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>

#include "geometry/trim_deflection.h"
#include "methods/guide_lines/chord_division.h"
#include "methods/guide_lines/guide_curves.h"
#include "methods/guide_lines/right_angle_rule.h"
#include "methods/guide_lines/trim_gap_fill.h"
#include "tessella/errors.h"
#include "tessella/surface_face.h"
#include "tessella/two_guide_lines.h"

namespace tessella {

namespace guide_detail {

double polyline_length(const std::vector<Vec3>& pts) {
  double len = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) len += (pts[i] - pts[i - 1]).norm();
  return len;
}

// The curve resampled to `count` points equally spaced in 3D arc length
// (interpolated linearly in (u,v), evaluated on the surface).
SurfaceCurve resample(const SurfaceFace& face, const SurfaceCurve& c, int count) {
  std::vector<double> s(c.xyz.size(), 0.0);
  for (std::size_t i = 1; i < c.xyz.size(); ++i) s[i] = s[i - 1] + (c.xyz[i] - c.xyz[i - 1]).norm();
  SurfaceCurve out;
  const double total = s.back();
  std::size_t seg = 0;
  for (int i = 0; i < count; ++i) {
    const double target = total * i / (count - 1);
    while (seg + 2 < s.size() && s[seg + 1] < target) ++seg;
    const double span = s[seg + 1] - s[seg];
    const double f = span > 0.0 ? std::clamp((target - s[seg]) / span, 0.0, 1.0) : 0.0;
    Vec2 uv = c.uv[seg] + f * (c.uv[seg + 1] - c.uv[seg]);
    if (i == 0) uv = c.uv.front();
    if (i == count - 1) uv = c.uv.back();
    out.uv.push_back(uv);
    out.xyz.push_back(face.point(uv[0], uv[1]));
  }
  return out;
}

// Boundary crossing between an inside and an outside (u,v) point (bisection).
// The fast test finds the crossing of the trim polyline; the last steps use
// OCCT's classifier in a small bracket around it, so the point lies on the true
// trim (the polyline is up to the trim deflection away from it).
Vec2 bisect_boundary(const Context& cx, Vec2 in, Vec2 out, bool exact) {
  const Vec2 in0 = in, out0 = out;
  for (int it = 0; it < 36; ++it) {
    const Vec2 mid = 0.5 * (in + out);
    if (cx.inside.contains(mid[0], mid[1]))
      in = mid;
    else
      out = mid;
  }
  if (!exact || cx.inside.uses_occt()) return in;
  const Vec2 dir = out0 - in0;
  const double len = dir.norm();
  if (!(len > 0.0)) return in;
  const double t = (in - in0).dot(dir) / (len * len);
  for (double w = 1e-3; w <= 1.0; w *= 4.0) {
    double lo = std::max(0.0, t - w), hi = std::min(1.0, t + w);
    if (!cx.face.is_inside(in0[0] + lo * dir[0], in0[1] + lo * dir[1])) continue;
    if (cx.face.is_inside(in0[0] + hi * dir[0], in0[1] + hi * dir[1])) continue;
    for (int it = 0; it < 30; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (cx.face.is_inside(in0[0] + mid * dir[0], in0[1] + mid * dir[1]))
        lo = mid;
      else
        hi = mid;
    }
    return in0 + lo * dir;
  }
  return in;
}

// The pieces of the curve inside the trimmed face, cut at the boundary.
std::vector<SurfaceCurve> inside_runs(const Context& cx, const SurfaceCurve& c, bool exact) {
  const SurfaceFace& face = cx.face;
  std::vector<SurfaceCurve> runs;
  SurfaceCurve cur;
  bool prev_in = false;
  for (std::size_t i = 0; i < c.uv.size(); ++i) {
    const bool in = cx.inside.contains(c.uv[i][0], c.uv[i][1]);
    if (i > 0 && in != prev_in) {
      const Vec2 b = in ? bisect_boundary(cx, c.uv[i], c.uv[i - 1], exact)
                        : bisect_boundary(cx, c.uv[i - 1], c.uv[i], exact);
      cur.uv.push_back(b);
      cur.xyz.push_back(face.point(b[0], b[1]));
      if (!in) {
        runs.push_back(std::move(cur));
        cur = SurfaceCurve();
      }
    }
    if (in) {
      cur.uv.push_back(c.uv[i]);
      cur.xyz.push_back(c.xyz[i]);
    }
    prev_in = in;
  }
  if (!cur.uv.empty()) runs.push_back(std::move(cur));
  runs.erase(std::remove_if(runs.begin(), runs.end(),
                            [](const SurfaceCurve& r) { return r.uv.size() < 2; }),
             runs.end());
  return runs;
}

// On the border of the surface's (u,v) box (a closed direction has none):
// where project_near leaves a point whose target lies beyond the surface.
bool on_uv_border(const SurfaceFace& face, const Vec2& uv) {
  const UvBounds b = face.bounds();
  return (!face.u_periodic() && (uv[0] <= b.u_min || uv[0] >= b.u_max)) ||
         (!face.v_periodic() && (uv[1] <= b.v_min || uv[1] >= b.v_max));
}

// Length of the curve on the face (sampled: the exact pieces come at the
// division).
double length_inside(const Context& cx, const SurfaceCurve& c) {
  double inside = 0.0;
  for (std::size_t i = 2; i < c.uv.size(); i += 2)
    if (cx.inside.contains(c.uv[i - 1][0], c.uv[i - 1][1]))
      inside += (c.xyz[i] - c.xyz[i - 2]).norm();
  return inside;
}

bool inside_bounds(const UvBounds& b, const Vec2& uv) {
  return uv[0] >= b.u_min && uv[0] <= b.u_max && uv[1] >= b.v_min && uv[1] <= b.v_max;
}

// Extends the curve end (index 0 or last) along its (u,v) tangent up to the
// boundary (doubling steps, then bisection).
Vec2 extend_to_boundary(const Context& cx, const Vec2& end, const Vec2& before) {
  const Vec2 dir = end - before;
  if (dir.norm() <= 0.0) return end;
  const UvBounds b = cx.face.bounds();
  Vec2 in = end;
  double h = 1.0;
  for (int it = 0; it < 60; ++it, h *= 2.0) {
    const Vec2 x = end + h * dir;
    if (!inside_bounds(b, x) || !cx.inside.contains(x[0], x[1])) return bisect_boundary(cx, in, x);
    in = x;
  }
  return in;
}

// Boundary point closest to the straight line through d along t (seed 004
// Fig. 10), preferring points near d: minimizes dist(X, line) + w |X - d| over
// the loop's segments (convex on each segment: golden-section search).
bool nearest_boundary_point(const Boundary& bd, const Vec3& d, const Vec3& t, double w, Vec3& out,
                            Vec2& out_uv) {
  const Vec3 tn = t.normalized();
  auto score = [&](const Vec3& x) { return (x - d).cross(tn).norm() + w * (x - d).norm(); };
  double best = std::numeric_limits<double>::infinity();
  const std::size_t n = bd.xyz.size();
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 a = bd.xyz[i], b = bd.xyz[(i + 1) % n];
    double lo = 0.0, hi = 1.0;
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    double f1 = score(a + x1 * (b - a)), f2 = score(a + x2 * (b - a));
    for (int it = 0; it < 40; ++it) {
      if (f1 < f2) {
        hi = x2, x2 = x1, f2 = f1;
        x1 = hi - g * (hi - lo);
        f1 = score(a + x1 * (b - a));
      } else {
        lo = x1, x1 = x2, f1 = f2;
        x2 = lo + g * (hi - lo);
        f2 = score(a + x2 * (b - a));
      }
    }
    const double tau = 0.5 * (lo + hi);
    const double f = score(a + tau * (b - a));
    if (f < best) {
      best = f;
      out = a + tau * (b - a);
      out_uv = bd.uv[i] + tau * (bd.uv[(i + 1) % n] - bd.uv[i]);
    }
  }
  return std::isfinite(best);
}

// Distance from x to the polyline.
double distance_to_polyline(const std::vector<Vec3>& pts, const Vec3& x) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    const Vec3 ab = pts[i + 1] - pts[i];
    const double l2 = ab.squaredNorm();
    const double t = l2 > 0.0 ? std::clamp((x - pts[i]).dot(ab) / l2, 0.0, 1.0) : 0.0;
    best = std::min(best, (pts[i] + t * ab - x).norm());
  }
  return best;
}

LoopPoint nearest_on_loop(const std::vector<Vec3>& loop, const Vec3& x) {
  LoopPoint best;
  best.distance = std::numeric_limits<double>::infinity();
  const std::size_t n = loop.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 a = loop[i], ab = loop[(i + 1) % n] - a;
    const double l2 = ab.squaredNorm();
    const double t = l2 > 0.0 ? std::clamp((x - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
    const double d = (a + t * ab - x).norm();
    if (d < best.distance) best = {i, t, d};
  }
  return best;
}

// The new end of a curve by distance (beyond seed 004): from the old end
// `from`, along the outer boundary in the direction that goes towards `d`
// (the side being advanced), the first boundary point `step` away from the
// curve c. Seed 004's rule (the boundary point nearest the line through D'
// parallel to the curve) is ill-conditioned where the face is steep across
// its edge: the line in 3D runs nearly along the slope and passes the flat
// edge at a glancing angle, so a small tilt of the curve's end tangent moves
// its closest point on the edge by several rod lengths; the tilt then grows
// from curve to curve (a roof from Williams' formula on a 120 x 160 grid:
// the south ends advanced 1.9, 2.2, 2.8, 3.9, 6.2, 11.5 m for L = 1.73 m,
// and a third of the roof was left uncovered). The distance from the curve
// is what the rows are to keep, and it is measured directly. False when no
// boundary point within 8 steps of walking gets that far (a boundary that
// turns back towards the curve): the caller then uses the paper's rule.
bool end_at_distance(const Boundary& bd, const std::vector<Vec3>& curve, bool at_start,
                     const Vec3& outward, const Vec3& d, double step, Vec3& out, Vec2& out_uv) {
  const std::size_t n = bd.xyz.size();
  if (n < 3) return false;
  const Vec3 from = at_start ? curve.front() : curve.back();
  // The curve carried on straight beyond this end (along its end tangent):
  // a boundary point's nearest point on the curve itself would often be the
  // end, where it is the offset of the curve's continuation that meets the
  // boundary (on a plate with an oblique guide the end that leans forward
  // then advanced step instead of step / cos(angle), and the curve turned).
  std::vector<Vec3> c;
  c.reserve(curve.size() + 1);
  if (at_start) c.push_back(from + 8.0 * step * outward);
  c.insert(c.end(), curve.begin(), curve.end());
  if (!at_start) c.push_back(from + 8.0 * step * outward);
  // Where `from` lies on the loop.
  const LoopPoint on = nearest_on_loop(bd.xyz, from);
  const std::size_t seg = on.seg;
  const double at = on.t;
  // The walk as a sequence of points: `from`'s foot, then loop vertices.
  auto vertex = [&](std::size_t k) { return bd.xyz[k % n]; };
  const Vec3 foot = bd.xyz[seg] + at * (vertex(seg + 1) - bd.xyz[seg]);
  const Vec2 foot_uv = bd.uv[seg] + at * (bd.uv[(seg + 1) % n] - bd.uv[seg]);
  const Vec3 forward = vertex(seg + 1) - foot, backward = bd.xyz[seg] - foot;
  // Direction: the one whose first stretch goes towards d (a foot on a
  // vertex looks one segment further).
  const Vec3 fwd = forward.norm() > 1e-12 * step ? forward : vertex(seg + 2) - foot;
  const Vec3 bwd = backward.norm() > 1e-12 * step ? backward : vertex(seg + n - 1) - foot;
  const double df = fwd.normalized().dot(d), db = bwd.normalized().dot(d);
  if (std::max(df, db) <= 0.0) return false;
  const bool ahead = df >= db;
  Vec3 prev = foot;
  Vec2 prev_uv = foot_uv;
  double walked = 0.0;
  for (std::size_t k = 1; k <= n && walked < 8.0 * step; ++k) {
    const std::size_t idx = ahead ? (seg + k) % n : (seg + 1 + n - k) % n;
    const Vec3 x = bd.xyz[idx];
    const Vec2 xuv = bd.uv[idx];
    const double dist = distance_to_polyline(c, x);
    if (dist >= step) {
      // Bisection on the stretch prev -> x (distance grows along it).
      double lo = 0.0, hi = 1.0;
      for (int it = 0; it < 40; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (distance_to_polyline(c, prev + mid * (x - prev)) >= step)
          hi = mid;
        else
          lo = mid;
      }
      out = prev + hi * (x - prev);
      out_uv = prev_uv + hi * (xuv - prev_uv);
      return true;
    }
    walked += (x - prev).norm();
    prev = x, prev_uv = xuv;
  }
  return false;
}

// Newton projection (seed 004 section 4) from the matching point of the
// previous curve (OCCT's global search only when Newton fails).
Projection project_near(const SurfaceFace& face, const Vec3& p, const Vec2& start) {
  // Seed 004 section 4 with the Gauss-Newton matrix (J = [Su Sv]^T [Su Sv]) and
  // the steps clamped to the face's (u,v) box, so a point beyond the border
  // lands on the border instead of sending SurfaceFace::project to OCCT's
  // global search (~50 ms each). Curve points always start from the matching
  // point of the previous curve, so the start is close.
  const UvBounds b = face.bounds();
  Vec2 uv = start;
  auto clamp_uv = [&](Vec2 x) {
    if (!face.u_periodic()) x[0] = std::clamp(x[0], b.u_min, b.u_max);
    if (!face.v_periodic()) x[1] = std::clamp(x[1], b.v_min, b.v_max);
    return x;
  };
  uv = clamp_uv(uv);
  const double eps = 1e-9 * face.model_size();
  for (int it = 0; it < 30; ++it) {
    const SurfacePoint sp = face.derivatives(uv[0], uv[1]);
    const Vec3 r = sp.point - p;
    Eigen::Matrix2d j;
    j << sp.du.dot(sp.du), sp.du.dot(sp.dv), sp.du.dot(sp.dv), sp.dv.dot(sp.dv);
    const Vec2 g(sp.du.dot(r), sp.dv.dot(r));
    if (!(std::abs(j.determinant()) > 1e-300)) break;
    const Vec2 next = clamp_uv(uv - j.inverse() * g);
    const double step = (sp.du * (next[0] - uv[0]) + sp.dv * (next[1] - uv[1])).norm();
    uv = next;
    if (step <= eps) break;
  }
  Projection pr;
  pr.uv = uv;
  pr.point = face.point(uv[0], uv[1]);
  pr.distance = (pr.point - p).norm();
  return pr;
}

// Steps 4-6 of seed 004 section 5.1: the curve c scaled, translated and rotated
// so that its ends land on end0 / end1 (eq. 21-24), projected point by point
// (Newton from the matching point of c) and resampled.
SurfaceCurve map_curve(const Context& cx, const SurfaceCurve& c, const Vec3& end0, const Vec2& uv0,
                       const Vec3& end1, const Vec2& uv1, const SurfaceCurve* near) {
  const SurfaceFace& face = cx.face;
  const std::size_t last = c.xyz.size() - 1;
  const Vec3 new_end[2] = {end0, end1};
  const Vec2 new_uv[2] = {uv0, uv1};
  const Vec3 p0 = c.xyz.front(), pn = c.xyz.back();
  const double l1 = std::max((p0 - pn).norm(), cx.tol), l2 = (new_end[0] - new_end[1]).norm();
  // Scale about Pn and translate Pn to Pn'' (eq. 21-22), then rotate about Pn''
  // so that P0 lands on P0'' (eq. 23-24).
  const double scale = l2 / l1;
  const Vec3 a = (p0 - pn) * scale, b = new_end[0] - new_end[1];
  Eigen::Matrix3d rot = Eigen::Matrix3d::Identity();
  const Vec3 axis = a.cross(b);
  if (axis.norm() > 1e-12 * a.norm() * b.norm())
    rot =
        Eigen::AngleAxisd(std::atan2(axis.norm(), a.dot(b)), axis.normalized()).toRotationMatrix();
  const SurfaceCurve& start = near != nullptr ? *near : c;
  SurfaceCurve moved;
  for (std::size_t i = 0; i <= last; ++i) {
    const Vec3 y = new_end[1] + rot * ((c.xyz[i] - pn) * scale);
    Vec2 uv;
    if (i == 0)
      uv = new_uv[0];
    else if (i == last)
      uv = new_uv[1];
    else
      uv = project_near(face, y, start.uv[i]).uv;  // step 5: Newton projection
    moved.uv.push_back(uv);
    moved.xyz.push_back(face.point(uv[0], uv[1]));
  }
  // Step 6: the curve lives in (u,v) and is evaluated on the surface.
  return resample(face, moved, cx.samples);
}

// Where the curve crosses a hole (or a notch of the outline), the samples off
// the face are replaced by the straight (u,v) bridge between the face points
// on either side. Beyond seed 004: the paper's faces have no holes. Projected
// onto whatever the surface does inside the hole (on the British Museum roof,
// a plateau over the Reading Room), those samples lag behind, and since each
// curve is scaled from the previous one, the lag grows into a V that
// bunches the rows north of the drum (south guide: rods over 1.5 L1 gave 59%
// of the rod-length variance).
void bridge_holes(const Context& cx, SurfaceCurve& c) {
  const std::size_t n = c.uv.size();
  std::vector<char> in(n);
  for (std::size_t i = 0; i < n; ++i) in[i] = cx.inside.contains(c.uv[i][0], c.uv[i][1]) ? 1 : 0;
  std::size_t i = 0;
  while (i < n && !in[i]) ++i;
  while (i < n) {
    std::size_t j = i + 1;
    while (j < n && in[j]) ++j;  // j: first sample off the face after i's run
    if (j >= n) break;
    std::size_t k = j;
    while (k < n && !in[k]) ++k;  // k: next sample back on the face
    if (k >= n) break;            // off the face up to the end: no bridge
    const std::size_t a = j - 1;
    for (std::size_t m = j; m < k; ++m) {
      const double f = static_cast<double>(m - a) / static_cast<double>(k - a);
      c.uv[m] = c.uv[a] + f * (c.uv[k] - c.uv[a]);
      c.xyz[m] = cx.face.point(c.uv[m][0], c.uv[m][1]);
    }
    i = k;
  }
}

// One GSM step (seed 004 section 5.1 steps 3-6): the next curve on the side
// `side` (+1 / -1 along N x tangent), or false when the face is covered.
bool advance_curve_by(const Context& cx, const SurfaceCurve& c, double side, double step,
                      SurfaceCurve& next, double& median_progress) {
  const SurfaceFace& face = cx.face;
  const std::size_t last = c.xyz.size() - 1;
  Vec3 new_end[2];
  Vec2 new_uv[2];
  for (int e = 0; e < 2; ++e) {
    const std::size_t i = e == 0 ? 0 : last;
    // End tangent over ~one rod length (robust to a kink in the last sample).
    const std::size_t m = std::clamp<std::size_t>(
        static_cast<std::size_t>(cx.l1 / std::max(polyline_length(c.xyz) / last, cx.tol)), 1,
        last / 4 + 1);
    const Vec3 tau = (e == 0 ? c.xyz[m] - c.xyz[0] : c.xyz[last] - c.xyz[last - m]).normalized();
    const Vec3 n = face.normal(c.uv[i][0], c.uv[i][1]);
    Vec3 d = n.cross(tau);
    if (d.norm() < 1e-12) return false;
    d = side * d.normalized();  // eq. 19
    const Vec3 target = c.xyz[i] + step * d;
    const Projection dp = project_near(face, target, c.uv[i]);
    const Vec3 n2 = face.normal(dp.uv[0], dp.uv[1]);
    const Vec3 t = d.cross(n2);  // eq. 20
    if (t.norm() < 1e-12) return false;
    // D' beyond the surface's border lands on the border (project_near clamps),
    // which would put the new end where the border meets the line through the
    // clamped point: on a plate with an oblique guide the end then advances
    // L instead of L / cos(angle), and the curves turn and crowd into the
    // corners. The line then goes through D itself (on the surface's
    // continuation), which is where the offset curve meets the border.
    const Vec3 anchor = dp.distance > 0.1 * step ? target : dp.point;
    if (cx.ends_by_distance && end_at_distance(cx.boundary, c.xyz, e == 0, e == 0 ? -tau : tau, d,
                                               step, new_end[e], new_uv[e]))
      continue;
    if (!nearest_boundary_point(cx.boundary, anchor, t, 0.05, new_end[e], new_uv[e])) return false;
  }
  const Vec3 p0 = c.xyz.front(), pn = c.xyz.back();
  // Stalled (both ends stayed): the face is covered on this side.
  if ((new_end[0] - p0).norm() < 0.05 * cx.advance && (new_end[1] - pn).norm() < 0.05 * cx.advance)
    return false;
  const double l1 = (p0 - pn).norm(), l2 = (new_end[0] - new_end[1]).norm();
  if (l1 < cx.tol || l2 < 0.5 * cx.l1) return false;
  // The new ends swapped sides (a short curve in a corner or on a bulge of
  // the border, whose ends found each other's boundary points): the scaled
  // curve would turn over and fold back across the ones before it.
  if ((new_end[1] - new_end[0]).dot(pn - p0) <= 0.0) return false;
  next = map_curve(cx, c, new_end[0], new_uv[0], new_end[1], new_uv[1]);
  bridge_holes(cx, next);
  // No progress across the curve (it fell back onto the previous one, or slid
  // along the boundary): covered.
  {
    // Median over the curve: one point stuck (e.g. over a hole) does not stop it.
    // The step's scale follows each point's move along N x tangent (rows kept
    // L apart on the surface); whether the curve moved at all is judged by
    // the move square to the curve's tangent, signed by the side it went to:
    // where the face is steep across the curve the first fell to a tenth (a
    // roof built from Williams' formula on a finer grid, 120 x 160 samples,
    // steep towards the court's edges), and a guide on such an edge never
    // advanced ("no panels").
    std::vector<double> progress, moved;
    for (std::size_t k = 1; k < last; ++k) {
      const Vec3 tau = (c.xyz[k + 1] - c.xyz[k - 1]).normalized();
      const Vec3 across = side * face.normal(c.uv[k][0], c.uv[k][1]).cross(tau);
      const Vec3 move = next.xyz[k] - c.xyz[k];
      progress.push_back(move.dot(across));
      const Vec3 square = move - move.dot(tau) * tau;
      moved.push_back(move.dot(across) < 0 ? -square.norm() : square.norm());
    }
    std::nth_element(progress.begin(), progress.begin() + progress.size() / 2, progress.end());
    median_progress = progress[progress.size() / 2];
    std::nth_element(moved.begin(), moved.begin() + moved.size() / 2, moved.end());
    if (moved[moved.size() / 2] < 0.2 * cx.advance) return false;
  }
  // Enough of it on the face.
  return length_inside(cx, next) >= 0.5 * cx.l1;
}

// One GSM step with the rows kept L apart: the ends advance by L, but where
// the face rises or falls across the curve the projection pulls its middle
// back (British Museum roof: rows 1,500-1,700 mm apart at L = 1,732, so the
// rods came out 5-6% short on average). The step of the ends is scaled by
// L / (median progress) and the step redone, twice at most, the step within
// [L, 1.5 L]. Beyond seed 004, which advances the ends by L.
bool advance_curve(const Context& cx, const SurfaceCurve& c, double side, SurfaceCurve& next) {
  double progress = 0.0, step = cx.advance;
  if (!advance_curve_by(cx, c, side, step, next, progress)) return false;
  for (int it = 0; it < 2 && progress < 0.98 * cx.advance; ++it) {
    step = std::clamp(step * cx.advance / progress, cx.advance, 1.5 * cx.advance);
    SurfaceCurve again;
    double p = 0.0;
    if (!advance_curve_by(cx, c, side, step, again, p) || p > 1.1 * cx.advance) break;
    next = std::move(again);
    progress = p;
  }
  return true;
}

// Finishing the sweep (beyond seed 004): where the face rises between its
// edges, the projection pulls the middle of each scaled curve back, so the
// ends reach the far corners while a strip in the middle is still open and
// the GSM step stalls. Then every point of the curve is moved by `advance`
// across the curve (N x tangent, tangent over about one rod length so the
// offset is smooth) and projected onto the surface; points whose target lies
// beyond the surface's border are dropped, the longest remaining run is kept
// and its ends are extended to the trim. False when less than L1/2 of the new
// curve lies on the face.
// The side of the last curve of the GSM sweep, in (u,v): positive ahead of it
// (where the finishing curves go), negative behind it (covered already).
struct SweepFront {
  std::vector<Vec2> uv;
  double sign = 1.0;
  double ahead(const Vec2& p) const {
    double best = std::numeric_limits<double>::infinity(), value = 0.0;
    for (std::size_t i = 0; i + 1 < uv.size(); ++i) {
      const Vec2 ab = uv[i + 1] - uv[i];
      const double len2 = ab.squaredNorm();
      if (len2 <= 0.0) continue;
      const double t = std::clamp((p - uv[i]).dot(ab) / len2, 0.0, 1.0);
      const Vec2 q = uv[i] + t * ab;
      const double d = (p - q).norm();
      if (d < best) best = d, value = sign * (p - q).dot(Vec2(-ab[1], ab[0]));
    }
    return value;
  }
};

SweepFront sweep_front(const Context& cx, const SurfaceCurve& c, double side) {
  SweepFront f;
  f.uv = c.uv;
  const std::size_t k = c.uv.size() / 2;
  const Vec3 tau = (c.xyz[k + 1] - c.xyz[k - 1]).normalized();
  const SurfacePoint sp = cx.face.derivatives(c.uv[k][0], c.uv[k][1]);
  const Vec3 d = side * cx.face.normal(c.uv[k][0], c.uv[k][1]).cross(tau);
  Eigen::Matrix<double, 3, 2> j;
  j << sp.du, sp.dv;
  const Vec2 duv = (j.transpose() * j).ldlt().solve(j.transpose() * d);
  const Vec2 ab = c.uv[k + 1] - c.uv[k - 1];
  f.sign = Vec2(-ab[1], ab[0]).dot(duv) >= 0.0 ? 1.0 : -1.0;
  return f;
}

// Where a concave part of an offset curve folds over itself (two arms of a V
// crossing), the loop between the first and the last crossing segment is cut
// out, as for offset curves in the plane (in (u,v)).
std::vector<Vec2> cut_self_crossings(std::vector<Vec2> pts) {
  auto cross2 = [](const Vec2& a, const Vec2& b) { return a[0] * b[1] - a[1] * b[0]; };
  for (std::size_t i = 0; i + 3 < pts.size(); ++i) {
    const Vec2 a = pts[i], r = pts[i + 1] - pts[i];
    for (std::size_t j = pts.size() - 2; j >= i + 2; --j) {
      const Vec2 c = pts[j], q = pts[j + 1] - pts[j];
      const double den = cross2(r, q);
      if (den == 0.0) continue;
      const double t = cross2(c - a, q) / den, u = cross2(c - a, r) / den;
      if (t < 0.0 || t > 1.0 || u < 0.0 || u > 1.0) continue;
      std::vector<Vec2> out(pts.begin(), pts.begin() + i + 1);
      out.push_back(a + t * r);
      out.insert(out.end(), pts.begin() + j + 1, pts.end());
      pts = std::move(out);
      break;
    }
  }
  return pts;
}

bool offset_curve(const Context& cx, const SweepFront& front, const SweepFront& guide_front,
                  const SurfaceCurve& c, double side, SurfaceCurve& next) {
  const SurfaceFace& face = cx.face;
  const std::size_t last = c.xyz.size() - 1;
  const std::size_t m = std::clamp<std::size_t>(
      static_cast<std::size_t>(0.5 * cx.l1 / std::max(polyline_length(c.xyz) / last, cx.tol)), 1,
      last / 4 + 1);
  std::vector<Vec2> uv(last + 1);
  std::vector<char> ok(last + 1, 0);
  for (std::size_t k = 0; k <= last; ++k) {
    const std::size_t k0 = k >= m ? k - m : 0, k1 = std::min(last, k + m);
    const Vec3 tau = (c.xyz[k1] - c.xyz[k0]).normalized();
    Vec3 d = face.normal(c.uv[k][0], c.uv[k][1]).cross(tau);
    if (d.norm() < 1e-12) continue;
    d = side * d.normalized();
    const Projection pr = project_near(face, c.xyz[k] + cx.advance * d, c.uv[k]);
    uv[k] = pr.uv;
    // On the surface, ahead of the GSM sweep, and not folded back (a
    // concave part of the curve that collapsed into a swallowtail).
    const Vec3 move = pr.point - c.xyz[k];
    ok[k] = pr.distance <= 0.1 * cx.advance && !on_uv_border(face, pr.uv) &&
            move.dot(d) > 0.5 * cx.advance && front.ahead(pr.uv) > 0.0 &&
            guide_front.ahead(pr.uv) > 0.0;
  }
  std::size_t best0 = 0, best_n = 0;
  for (std::size_t k = 0; k <= last;) {
    if (!ok[k]) {
      ++k;
      continue;
    }
    std::size_t e = k;
    while (e <= last && ok[e]) ++e;
    if (e - k > best_n) best0 = k, best_n = e - k;
    k = e;
  }
  if (best_n < 2) return false;
  // The curve collapses where it is concave and is cut where it leaves the
  // face; once its remaining part is a short piece sliding along the border
  // (under a quarter of the last GSM curve) it no longer sweeps new ground.
  if (best_n < last / 4) return false;
  SurfaceCurve run;
  run.uv = cut_self_crossings(std::vector<Vec2>(uv.begin() + best0, uv.begin() + best0 + best_n));
  for (const Vec2& x : run.uv) run.xyz.push_back(face.point(x[0], x[1]));
  if (run.uv.size() < 2) return false;
  const std::size_t n = run.uv.size();
  if (cx.inside.contains(run.uv[0][0], run.uv[0][1])) {
    const Vec2 e = extend_to_boundary(cx, run.uv[0], run.uv[1]);
    if (front.ahead(e) > 0.0) run.uv.front() = e;
  }
  if (cx.inside.contains(run.uv[n - 1][0], run.uv[n - 1][1])) {
    const Vec2 e = extend_to_boundary(cx, run.uv[n - 1], run.uv[n - 2]);
    if (front.ahead(e) > 0.0) run.uv.back() = e;
  }
  run.xyz.front() = face.point(run.uv.front()[0], run.uv.front()[1]);
  run.xyz.back() = face.point(run.uv.back()[0], run.uv.back()[1]);
  if (polyline_length(run.xyz) < 0.5 * cx.l1) return false;
  next = resample(face, run, cx.samples);
  return length_inside(cx, next) >= 0.5 * cx.l1;
}

SurfaceCurve initial_curve(const Context& cx, const std::vector<Vec3>& guide) {
  const SurfaceFace& face = cx.face;
  // Resample the guide polyline evenly, then project it (seed 004 section 4).
  std::vector<double> s(guide.size(), 0.0);
  for (std::size_t i = 1; i < guide.size(); ++i) s[i] = s[i - 1] + (guide[i] - guide[i - 1]).norm();
  if (s.back() <= cx.tol) throw InvalidParameter("guides: the guide curve has no length");
  // A loop has no ends to move along the boundary (seed 004 advances the two
  // end points), so the method cannot start from it.
  if ((guide.front() - guide.back()).norm() <= 1e-6 * s.back())
    throw InvalidParameter(
        "guides: the guide curve is closed (a loop); pick an open curve that runs across the "
        "face from boundary to boundary");
  SurfaceCurve projected;
  std::size_t seg = 0;
  Vec2 start(0, 0);
  for (int i = 0; i < cx.samples; ++i) {
    const double target = s.back() * i / (cx.samples - 1);
    while (seg + 2 < s.size() && s[seg + 1] < target) ++seg;
    const double span = s[seg + 1] - s[seg];
    const double f = span > 0.0 ? std::clamp((target - s[seg]) / span, 0.0, 1.0) : 0.0;
    const Vec3 p = guide[seg] + f * (guide[seg + 1] - guide[seg]);
    const Projection pr = i == 0 ? face.project(p) : face.project(p, start);
    const double limit = cx.tol;
    if (pr.distance > limit) {
      std::ostringstream msg;
      msg << "guides: the guide curve passes " << pr.distance
          << " mm from the face; it must lie within guide_tolerance = " << limit
          << " mm of the face";
      throw InvalidParameter(msg.str());
    }
    start = pr.uv;
    projected.uv.push_back(pr.uv);
    projected.xyz.push_back(pr.point);
  }
  std::vector<SurfaceCurve> runs = inside_runs(cx, projected);
  if (runs.empty()) throw InvalidParameter("guides: the guide curve does not cross the face");
  SurfaceCurve best =
      *std::max_element(runs.begin(), runs.end(), [](const SurfaceCurve& a, const SurfaceCurve& b) {
        return polyline_length(a.xyz) < polyline_length(b.xyz);
      });
  if (polyline_length(best.xyz) < 0.5 * cx.l1)
    throw InvalidParameter(
        "guides: the part of the guide curve on the face is shorter than rod_length / 2");
  // Ends that stop inside the face are extended to the boundary.
  const std::size_t n = best.uv.size();
  best.uv.front() = extend_to_boundary(cx, best.uv[0], best.uv[1]);
  best.uv.back() = extend_to_boundary(cx, best.uv[n - 1], best.uv[n - 2]);
  best.xyz.front() = face.point(best.uv.front()[0], best.uv.front()[1]);
  best.xyz.back() = face.point(best.uv.back()[0], best.uv.back()[1]);
  return resample(face, best, cx.samples);
}

}  // namespace guide_detail

namespace {
using namespace guide_detail;

struct Row {
  std::vector<int> ids;   // mesh vertex ids
  std::vector<int> runs;  // which inside run of the curve each node is on
};

// Every triangle edge as (a < b, triangle, corner where it starts), sorted:
// the uses of one edge are neighbours, in a deterministic order.
struct EdgeUse {
  int a, b, tri, corner;
  bool operator<(const EdgeUse& o) const {
    return std::tie(a, b, tri, corner) < std::tie(o.a, o.b, o.tri, o.corner);
  }
  bool same_edge(const EdgeUse& o) const { return a == o.a && b == o.b; }
};

std::vector<EdgeUse> edge_uses(const PanelMesh& mesh) {
  std::vector<EdgeUse> uses;
  for (int t = 0; t < static_cast<int>(mesh.panels.size()); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.panels[t][k], b = mesh.panels[t][(k + 1) % 3];
      uses.push_back({std::min(a, b), std::max(a, b), t, k});
    }
  std::sort(uses.begin(), uses.end());
  return uses;
}

// Flips the shared edge of two triangles where the other diagonal of their
// quad is shorter, for edges over `threshold`, longest first, until none
// flips (or `passes`). Beyond seed 004: where a curve meets the far border
// at a slant (the last strip of the roof), the 90-degree rule zips a thin
// wedge into fans of rods 1.5-2.7 L1 long; the flips shorten them. The quad
// must stay convex (both new triangles facing the same way as the old ones).
void flip_long_edges(PanelMesh& mesh, double threshold, int passes) {
  auto len = [&](int a, int b) { return (mesh.xyz[a] - mesh.xyz[b]).norm(); };
  auto normal = [&](int a, int b, int c) {
    return Vec3((mesh.xyz[b] - mesh.xyz[a]).cross(mesh.xyz[c] - mesh.xyz[a]));
  };
  for (int pass = 0; pass < passes; ++pass) {
    const std::vector<EdgeUse> uses = edge_uses(mesh);
    std::vector<std::pair<double, std::size_t>> edges;  // (-length, first use), manifold edges
    for (std::size_t i = 0; i + 1 < uses.size(); ++i) {
      if (!uses[i].same_edge(uses[i + 1])) continue;
      if (i + 2 < uses.size() && uses[i].same_edge(uses[i + 2])) continue;  // not manifold
      const double l = len(uses[i].a, uses[i].b);
      if (l > threshold) edges.emplace_back(-l, i);
    }
    std::sort(edges.begin(), edges.end());
    std::vector<char> touched(mesh.panels.size(), 0);
    int done = 0;
    for (const auto& [neg_len, i] : edges) {
      const int t1 = uses[i].tri, t2 = uses[i + 1].tri;
      if (touched[t1] || touched[t2]) continue;
      // t1 = (a, b, c) with the edge a -> b, t2 = (b, a, d).
      const auto& p1 = mesh.panels[t1];
      const int k1 = uses[i].corner;
      const int a = p1[k1], b = p1[(k1 + 1) % 3], c = p1[(k1 + 2) % 3];
      int d = -1;
      for (int v : mesh.panels[t2])
        if (v != a && v != b) d = v;
      if (d < 0 || c == d || len(c, d) >= -neg_len) continue;
      const Vec3 n = normal(a, b, c) + normal(b, a, d);
      const Vec3 n1 = normal(a, d, c), n2 = normal(d, b, c);
      const double tiny = 1e-3 * threshold * threshold;
      if (n1.dot(n) <= 0 || n2.dot(n) <= 0 || n1.norm() < tiny || n2.norm() < tiny) continue;
      mesh.panels[t1] = {a, d, c};
      mesh.panels[t2] = {d, b, c};
      touched[t1] = touched[t2] = 1;
      ++done;
    }
    if (done == 0) break;
  }
}

// Splits the mesh's boundary edges (one triangle) that run along the trim and
// are longer than 1.5 L1 into chords near L1, with the new nodes on the true
// trim, fanning their triangle from its third corner. Beyond seed 004: the
// ends of neighbouring curves that meet the trim at a slant are several L1
// apart (up to 5.4 m on the roof's far edge, 3-4 m along the drum).
void split_long_boundary_edges(const Context& cx, PanelMesh& mesh) {
  const std::vector<EdgeUse> uses = edge_uses(mesh);
  for (std::size_t i = 0; i < uses.size(); ++i) {
    if ((i > 0 && uses[i].same_edge(uses[i - 1])) ||
        (i + 1 < uses.size() && uses[i].same_edge(uses[i + 1])))
      continue;  // shared by two triangles: not on the boundary
    const int t = uses[i].tri, k = uses[i].corner;
    const std::vector<int> tri = mesh.panels[t];
    const int a = tri[k], b = tri[(k + 1) % 3], c = tri[(k + 2) % 3];
    const double len = (mesh.xyz[a] - mesh.xyz[b]).norm();
    const int n = static_cast<int>(std::lround(len / cx.l1));
    if (len <= 1.5 * cx.l1 || n < 2) continue;
    const Vec2 ua = mesh.uv[a], ub = mesh.uv[b], du = ub - ua;
    const Vec2 across = Vec2(-du[1], du[0]) * 0.25;
    std::vector<int> ids = {a};
    bool ok = true;
    for (int q = 1; q < n && ok; ++q) {
      const Vec2 m = ua + (static_cast<double>(q) / n) * du;
      const Vec2 x = m + across, y = m - across;
      const bool in_x = cx.inside.contains(x[0], x[1]), in_y = cx.inside.contains(y[0], y[1]);
      if (in_x == in_y) {  // not along the trim (an open gap between rows)
        ok = false;
        break;
      }
      const Vec2 on = in_x ? bisect_boundary(cx, x, y) : bisect_boundary(cx, y, x);
      const Vec3 p = cx.face.point(on[0], on[1]);
      const Vec3 chord = mesh.xyz[a] + (static_cast<double>(q) / n) * (mesh.xyz[b] - mesh.xyz[a]);
      if ((p - chord).norm() > 0.25 * len) ok = false;
      ids.push_back(static_cast<int>(mesh.uv.size()));
      mesh.uv.push_back(on);
      mesh.xyz.push_back(p);
    }
    if (!ok) continue;  // the nodes added stay unused and are removed later
    ids.push_back(b);
    mesh.panels[t] = {ids[0], ids[1], c};
    for (std::size_t q = 1; q + 1 < ids.size(); ++q) mesh.panels.push_back({ids[q], ids[q + 1], c});
  }
}

}  // namespace

GuideLineResult guide_line_scaling_curves(const SurfaceFace& face,
                                          const GuideLineScalingParams& params) {
  require_in_range("rod_length (mm)", params.rod_length, 1e-3, 1e9);
  require_in_range("advance (mm)", params.advance, 0.0, 1e9);
  require_in_range("merge_fraction", params.merge_fraction, 0.0, 0.999);
  require_in_range("guide_tolerance (mm)", params.guide_tolerance, 0.0, 1e12);
  require_in_range("max_curves", params.max_curves, 1, 1e6);
  require_in_range("max_panels", params.max_panels, 1, 1e9);
  require_in_range("trim_deflection (mm)", params.trim_deflection, 0.0, 1e9);
  if (params.guide.size() < 2)
    throw InvalidParameter("guides: a guide curve needs at least two points");
  for (const Vec3& p : params.guide)
    if (!p.allFinite()) throw InvalidParameter("guides: the guide curve has a non-finite point");

  const double size = face.model_size();
  Context cx{face,
             {},
             params.rod_length,
             params.advance > 0 ? params.advance : params.rod_length * std::sqrt(3.0) / 2.0,
             1e-9 * size,
             0,
             {}};
  require_in_range("advance (mm)", cx.advance, 1e-3, 1e9);
  cx.ends_by_distance = params.ends_by_distance;
  if (size / cx.advance > params.max_curves)
    throw LimitExceeded(
        "guide_line_scaling: the face needs more than max_curves curves at this advance");
  const double guide_len = polyline_length(params.guide);
  const double est_len = std::max(guide_len, size);
  cx.samples = static_cast<int>(std::clamp(std::ceil(4.0 * est_len / cx.l1) + 1.0, 33.0, 4001.0));
  const double deflection = trim_deflection(face, params.trim_deflection);
  const std::vector<TrimLoop> loops = face.trim_loops(deflection);
  for (const TrimLoop& loop : loops)
    if (loop.outer) cx.boundary = {loop.xyz, loop.uv};
  cx.inside = UvTrimClassifier(loops, UvTrimClassifier::Options{-1, &face});
  if (cx.boundary.xyz.size() < 3)
    throw InvalidGeometry("guide_line_scaling: the face has no outer boundary");

  const double tol_guide = params.guide_tolerance > 0 ? params.guide_tolerance : 0.05 * size;
  cx.tol = tol_guide;
  SurfaceCurve c0 = initial_curve(cx, params.guide);
  cx.tol = 1e-9 * size;

  // Advance to both sides (a guide on the boundary stalls at once on one side).
  GuideLineResult result;
  std::vector<SurfaceCurve> sides[2];
  // Finishing offsets could wrap around a closed face (a full period in u
  // or v) onto the curves already there: not on closed faces.
  const UvBounds fb = face.bounds();
  const bool closed_u = face.u_periodic() && fb.u_max - fb.u_min > 0.99 * face.u_period();
  const bool closed_v = face.v_periodic() && fb.v_max - fb.v_min > 0.99 * face.v_period();
  const bool finish = params.finish_sweep && !closed_u && !closed_v;
  // On a closed face each side sweeps half way round (the rows are kept
  // L apart, so half the perimeter through the guide's middle / L curves),
  // where the other side's curves arrive.
  std::size_t max_side = std::numeric_limits<std::size_t>::max();
  if (closed_u || closed_v) {
    const Vec2 mid = c0.uv[c0.uv.size() / 2];
    double perimeter = std::numeric_limits<double>::infinity();
    for (int dir = 0; dir < 2; ++dir) {
      if (!(dir == 0 ? closed_u : closed_v)) continue;
      const double period = dir == 0 ? face.u_period() : face.v_period();
      double len = 0.0;
      Vec3 prev = face.point(mid[0], mid[1]);
      for (int i = 1; i <= 256; ++i) {
        const double t = period * i / 256.0;
        const Vec3 x = dir == 0 ? face.point(mid[0] + t, mid[1]) : face.point(mid[0], mid[1] + t);
        len += (x - prev).norm();
        prev = x;
      }
      perimeter = std::min(perimeter, len);
    }
    max_side =
        static_cast<std::size_t>(std::max(0.0, std::floor(0.5 * perimeter / cx.advance + 0.5)));
  }
  for (int k = 0; k < 2; ++k) {
    const double side = k == 0 ? 1.0 : -1.0;
    SurfaceCurve cur = c0, next;
    bool finishing = false;
    SweepFront front, guide_front;
    for (;;) {
      if (!finishing && !advance_curve(cx, cur, side, next)) {
        finishing = true;
        front = sweep_front(cx, cur, side);
        guide_front = sweep_front(cx, c0, side);
      }
      if (finishing && !finish) break;
      if (finishing && !offset_curve(cx, front, guide_front, cur, side, next)) break;
      if (sides[k].size() >= max_side) break;
      sides[k].push_back(next);
      if (static_cast<int>(sides[0].size() + sides[1].size()) + 1 > params.max_curves)
        throw LimitExceeded("guide_line_scaling: more than max_curves curves; increase advance");
      cur = std::move(next);
    }
  }
  for (auto it = sides[1].rbegin(); it != sides[1].rend(); ++it) result.curves.push_back(*it);
  result.guide_index = result.curves.size();
  result.curves.push_back(c0);
  for (const SurfaceCurve& c : sides[0]) result.curves.push_back(c);

  // Step 7: divide every curve (each piece inside the face) into chords near
  // L1. The guide curve gets the paper's equal chords; with `stagger`, every
  // other curve (outwards from the guide) takes its nodes at the feet of the
  // midpoints of the neighbouring curve's rods nearer the guide, so the rods
  // between the curves are close to sqrt(L^2 + (L1/2)^2) instead of anything
  // from L to sqrt(L^2 + L1^2); gaps under L1/2 are merged, over 3/2 L1 split.
  PanelMesh& mesh = result.mesh;
  ChordDivisionParams cp;
  cp.chord = cx.l1;
  cp.merge_fraction = params.merge_fraction;
  const std::size_t nc = result.curves.size(), guide_index = sides[1].size();
  std::vector<std::vector<std::pair<Vec2, int>>> nodes(nc);  // (uv, run) per curve
  auto divide = [&](std::size_t ci, const std::vector<std::pair<Vec2, int>>* prev) {
    int run_id = 0;
    for (const SurfaceCurve& run : inside_runs(cx, result.curves[ci])) {
      const double len = polyline_length(run.xyz);
      if (len < 1e-6 * size) continue;
      std::vector<double> sk(run.xyz.size(), 0.0);
      for (std::size_t i = 1; i < sk.size(); ++i)
        sk[i] = sk[i - 1] + (run.xyz[i] - run.xyz[i - 1]).norm();
      std::vector<Vec2> uvs;
      if (len < params.merge_fraction * cx.l1) {
        uvs = {run.uv.front(), run.uv.back()};
      } else if (!params.stagger || prev == nullptr) {
        for (double t : divide_by_chords(run.xyz, cp)) {
          const std::size_t k = std::min(static_cast<std::size_t>(t), run.uv.size() - 2);
          const double f = t - static_cast<double>(k);
          uvs.push_back(run.uv[k] + f * (run.uv[k + 1] - run.uv[k]));
        }
      } else {
        // Arc-length positions of the feet of the previous rods' midpoints.
        std::vector<double> pos = {0.0, len};
        for (std::size_t j = 0; j + 1 < prev->size(); ++j) {
          if ((*prev)[j].second != (*prev)[j + 1].second) continue;
          const Vec2 muv = 0.5 * ((*prev)[j].first + (*prev)[j + 1].first);
          const Vec3 m = face.point(muv[0], muv[1]);
          double best = std::numeric_limits<double>::infinity(), at = 0.0;
          for (std::size_t i = 0; i + 1 < run.xyz.size(); ++i) {
            const Vec3 ab = run.xyz[i + 1] - run.xyz[i];
            const double l2 = ab.squaredNorm();
            const double t = l2 > 0 ? std::clamp((m - run.xyz[i]).dot(ab) / l2, 0.0, 1.0) : 0.0;
            const double d = (run.xyz[i] + t * ab - m).norm();
            if (d < best) best = d, at = sk[i] + t * (sk[i + 1] - sk[i]);
          }
          if (best < 1.5 * cx.advance && at > 0.0 && at < len) pos.push_back(at);
        }
        std::sort(pos.begin(), pos.end());
        std::vector<double> kept = {0.0};
        for (std::size_t i = 1; i + 1 < pos.size(); ++i)
          if (pos[i] - kept.back() >= 0.8 * cx.l1 && len - pos[i] >= 0.8 * cx.l1)
            kept.push_back(pos[i]);
        kept.push_back(len);
        std::vector<double> split = {0.0};
        for (std::size_t i = 1; i < kept.size(); ++i) {
          const double gap = kept[i] - kept[i - 1];
          const int n = gap > 1.5 * cx.l1 ? static_cast<int>(std::round(gap / cx.l1)) : 1;
          for (int q = 1; q <= n; ++q) split.push_back(kept[i - 1] + gap * q / n);
        }
        // As many chords as the paper's division lays (len / L1, rounded):
        // the feet follow the previous row's spacing, which drifts where the
        // rows converge or part (a foot under 0.8 L1 from the last is
        // dropped, but the gap it leaves is split in two again), and the
        // rods along the curves averaged 0.93 L1 on the roof. Extra nodes go
        // where the two chords beside them are shortest; missing ones split
        // the longest chord.
        const std::size_t count = static_cast<std::size_t>(std::max(1L, std::lround(len / cx.l1)));
        while (split.size() - 1 > count && split.size() > 2) {
          std::size_t drop = 1;
          for (std::size_t i = 2; i + 1 < split.size(); ++i)
            if (split[i + 1] - split[i - 1] < split[drop + 1] - split[drop - 1]) drop = i;
          split.erase(split.begin() + static_cast<std::ptrdiff_t>(drop));
        }
        while (split.size() - 1 < count) {
          std::size_t longest = 0;
          for (std::size_t i = 1; i + 1 < split.size(); ++i)
            if (split[i + 1] - split[i] > split[longest + 1] - split[longest]) longest = i;
          split.insert(split.begin() + static_cast<std::ptrdiff_t>(longest) + 1,
                       0.5 * (split[longest] + split[longest + 1]));
        }
        // Even out the chords, the feet staying the targets: Gauss-Seidel on
        // sum (x_i - foot_i)^2 + 2 sum (x_{i+1} - x_i)^2, ends fixed.
        const std::vector<double> foot = split;
        for (int it = 0; it < 50; ++it)
          for (std::size_t i = 1; i + 1 < split.size(); ++i)
            split[i] = (foot[i] + 2.0 * (split[i - 1] + split[i + 1])) / 5.0;
        std::size_t k = 0;
        for (double at : split) {
          while (k + 2 < sk.size() && sk[k + 1] < at) ++k;
          const double span = sk[k + 1] - sk[k];
          const double f = span > 0 ? std::clamp((at - sk[k]) / span, 0.0, 1.0) : 0.0;
          uvs.push_back(run.uv[k] + f * (run.uv[k + 1] - run.uv[k]));
        }
      }
      for (const Vec2& uv : uvs) nodes[ci].push_back({uv, run_id});
      ++run_id;
    }
  };
  divide(guide_index, nullptr);
  for (std::size_t ci = guide_index + 1; ci < nc; ++ci) divide(ci, &nodes[ci - 1]);
  for (std::size_t ci = guide_index; ci-- > 0;) divide(ci, &nodes[ci + 1]);
  std::vector<Row> rows;
  for (const auto& list : nodes) {
    Row row;
    for (const auto& [uv, run_id] : list) {
      row.ids.push_back(static_cast<int>(mesh.uv.size()));
      row.runs.push_back(run_id);
      mesh.uv.push_back(uv);
      mesh.xyz.push_back(face.point(uv[0], uv[1]));
    }
    if (!row.ids.empty()) rows.push_back(std::move(row));
  }

  // Step 8: triangles between neighbouring curves (90-degree rule); drop the
  // ones that bridge a hole or leave the face.
  const double max_edge = 3.0 * std::max(cx.l1, cx.advance);
  for (std::size_t r = 0; r + 1 < rows.size(); ++r) {
    const Row& a = rows[r];
    const Row& b = rows[r + 1];
    std::vector<Vec3> p, q;
    for (int id : a.ids) p.push_back(mesh.xyz[id]);
    for (int id : b.ids) q.push_back(mesh.xyz[id]);
    const int n = static_cast<int>(p.size());
    for (const auto& t : connect_rows_right_angle(p, q)) {
      int ids[3], row_of[3], run_of[3];
      for (int k = 0; k < 3; ++k) {
        const bool in_p = t[k] < n;
        ids[k] = in_p ? a.ids[t[k]] : b.ids[t[k] - n];
        row_of[k] = in_p ? 0 : 1;
        run_of[k] = in_p ? a.runs[t[k]] : b.runs[t[k] - n];
      }
      bool ok = true;
      for (int k = 0; k < 3; ++k) {
        const int l = (k + 1) % 3;
        if (row_of[k] == row_of[l] && run_of[k] != run_of[l]) ok = false;
        if ((mesh.xyz[ids[k]] - mesh.xyz[ids[l]]).norm() > max_edge) ok = false;
      }
      if (!ok) continue;
      const Vec2 cuv = (mesh.uv[ids[0]] + mesh.uv[ids[1]] + mesh.uv[ids[2]]) / 3.0;
      if (!cx.inside.contains(cuv[0], cuv[1])) continue;
      const Vec3 e1 = mesh.xyz[ids[1]] - mesh.xyz[ids[0]], e2 = mesh.xyz[ids[2]] - mesh.xyz[ids[0]];
      const Vec3 nrm = e1.cross(e2);
      if (nrm.norm() < 1e-9 * cx.l1 * cx.l1) continue;
      if (nrm.dot(face.normal(cuv[0], cuv[1])) < 0) std::swap(ids[1], ids[2]);
      mesh.panels.push_back({ids[0], ids[1], ids[2]});
      if (static_cast<int>(mesh.panels.size()) > params.max_panels)
        throw LimitExceeded("guide_line_scaling: more panels than max_panels");
    }
  }
  // The strips the rows leave along the trims (glancing curve ends, the far
  // edge): filled when under a row and a half wide (wider ones are what the
  // sweep did not reach; the coverage check reports them).
  if (params.finish_sweep)
    fill_trim_gaps(cx, loops, 4.0 * deflection + 1e-6 * size, 0.1 * cx.advance, 1.5 * cx.advance,
                   mesh);
  const double diagonal = std::sqrt(cx.advance * cx.advance + 0.25 * cx.l1 * cx.l1);
  split_long_boundary_edges(cx, mesh);
  flip_long_edges(mesh, 1.3 * std::max(cx.l1, diagonal), 10);
  mesh.nominal_area = 0.5 * cx.l1 * cx.advance;
  mesh.regular_corners = 3;
  weld_coincident_vertices(mesh, 1e-6 * size);
  remove_unused_vertices(mesh);
  build_rods(mesh);
  if (mesh.panels.empty())
    throw InvalidParameter(
        "guide_line_scaling: no panels (rod_length / advance too large for the face?)");
  return result;
}

PanelMesh guide_line_scaling(const SurfaceFace& face, const GuideLineScalingParams& params) {
  return guide_line_scaling_curves(face, params).mesh;
}

}  // namespace tessella
