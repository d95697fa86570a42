// The Two Guide Lines with Two End Vertices Method (seed 004 section 6): each
// guide is moved through pairs of boundary vertices; the intersections of the
// two curve families are the nodes of a quad grid.
#include "tessella/two_guide_lines.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/trim_deflection.h"
#include "mesh/curve_family_mesh.h"
#include "methods/guide_lines/chord_division.h"
#include "methods/guide_lines/guide_curves.h"
#include "methods/guide_lines/right_angle_rule.h"
#include "tessella/errors.h"
#include "tessella/guide_line_scaling.h"
#include "tessella/surface_face.h"

namespace tessella {

namespace {

using namespace guide_detail;

constexpr double kPi = 3.14159265358979323846;
constexpr bool kAlongNormals = true;

struct LoopPos {
  std::size_t seg = 0;
  double f = 0;
};

struct Loop {
  const Boundary& b;
  std::vector<double> cum;  // arc length at each vertex; cum[n] = total
  std::vector<bool> corner;

  Loop(const Boundary& bd, double corner_deg) : b(bd) {
    const std::size_t n = b.xyz.size();
    cum.assign(n + 1, 0.0);
    for (std::size_t i = 0; i < n; ++i)
      cum[i + 1] = cum[i] + (b.xyz[(i + 1) % n] - b.xyz[i]).norm();
    corner.assign(n, false);
    const double limit = std::cos(corner_deg * kPi / 180.0);
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 d0 = b.xyz[i] - b.xyz[(i + n - 1) % n], d1 = b.xyz[(i + 1) % n] - b.xyz[i];
      if (d0.norm() > 0 && d1.norm() > 0 && d0.normalized().dot(d1.normalized()) < limit)
        corner[i] = true;
    }
  }
  std::size_t size() const { return b.xyz.size(); }
  double total() const { return cum.back(); }
  Vec3 at(const LoopPos& p) const {
    const std::size_t n = size();
    return b.xyz[p.seg] + p.f * (b.xyz[(p.seg + 1) % n] - b.xyz[p.seg]);
  }
  double s(const LoopPos& p) const { return cum[p.seg] + p.f * (cum[p.seg + 1] - cum[p.seg]); }
  LoopPos locate(const Vec3& x) const {
    const std::size_t n = size();
    LoopPos best;
    double dist = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 a = b.xyz[i], d = b.xyz[(i + 1) % n] - a;
      const double f =
          d.squaredNorm() > 0 ? std::clamp((x - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
      const double e = (a + f * d - x).norm();
      if (e < dist) dist = e, best = {i, f};
    }
    return best;
  }
};

// From `from` along the loop in direction dir (+1 = increasing index) for at
// most max_len, stopping at a corner; then a straight extension of length ext
// along the last direction. real_end = parameter where the extension starts.
struct Walk {
  std::vector<Vec3> pts;
  double real_end = 0;
};

Walk walk(const Loop& loop, const LoopPos& from, int dir, double max_len, double ext) {
  const std::size_t n = loop.size();
  Walk w;
  w.pts.push_back(loop.at(from));
  double len = 0;
  std::size_t v = dir > 0 ? (from.seg + 1) % n : from.seg;
  for (std::size_t steps = 0; steps <= n && len < max_len; ++steps) {
    const Vec3 q = loop.b.xyz[v];
    const double d = (q - w.pts.back()).norm();
    if (d > 1e-9) {
      if (len + d >= max_len) {
        w.pts.push_back(w.pts.back() + (q - w.pts.back()) * ((max_len - len) / d));
        len = max_len;
        break;
      }
      w.pts.push_back(q);
      len += d;
      if (loop.corner[v]) break;
    }
    v = dir > 0 ? (v + 1) % n : (v + n - 1) % n;
  }
  w.real_end = static_cast<double>(w.pts.size() - 1);
  Vec3 d(0, 0, 0);
  if (w.pts.size() >= 2) d = w.pts.back() - w.pts[w.pts.size() - 2];
  if (d.norm() > 0) w.pts.push_back(w.pts.back() + ext * d.normalized());
  return w;
}

// The chord that divides the boundary curve a walker starting at `at` in
// direction dir walks along (from the corner behind it, or at it, to the next
// corner ahead; the whole loop when it has no corner) into `divisions` equal
// chords: straight chords, as lay_chords lays them, found by bisection (arc
// length / divisions would leave the last chord short on a curved boundary).
double equal_boundary_chord(const Loop& loop, const LoopPos& at, int dir, int divisions) {
  const std::size_t n = loop.size();
  const double total = loop.total(), here = loop.s(at), eps = 1e-9 * total;
  // Vertex indices of the corners behind and ahead.
  std::size_t behind = n, ahead = n;
  double d_behind = total, d_ahead = total;
  for (std::size_t i = 0; i < n; ++i) {
    if (!loop.corner[i]) continue;
    double d = dir * (loop.cum[i] - here);
    d = std::fmod(std::fmod(d, total) + total, total);
    if (d > eps && d < d_ahead) d_ahead = d, ahead = i;
    const double back = d <= eps ? 0.0 : total - d;
    if (back < d_behind) d_behind = back, behind = i;
  }
  std::vector<Vec3> pts;
  if (ahead == n) {  // no corner: the whole loop from `at` round to it
    for (std::size_t k = 0; k <= n; ++k)
      pts.push_back(loop.b.xyz[(at.seg + (dir > 0 ? k + 1 : n - k)) % n]);
    pts.insert(pts.begin(), loop.at(at));
    pts.back() = loop.at(at);
  } else {
    for (std::size_t i = behind;; i = dir > 0 ? (i + 1) % n : (i + n - 1) % n) {
      pts.push_back(loop.b.xyz[i]);
      if (i == ahead || pts.size() > n + 1) break;
    }
  }
  const double len = guide_detail::polyline_length(pts);
  double lo = 0.5 * len / divisions, hi = len / divisions;  // chords fit at lo, not beyond hi
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (static_cast<int>(lay_chords(pts, mid, divisions).size()) > divisions ? lo : hi) = mid;
  }
  return lo;
}

// (u,v) of the vertex at chord parameter t of walk w. On the boundary: its
// projection. On the straight extension beyond the boundary's end (the
// paper's boundary extension, Fig. 31), projecting would clamp it onto the
// surface's border, i.e. onto the corner, and every curve through such
// vertices would fan out of that corner; the extension is taken in (u,v)
// instead, along the boundary's direction at its end, on the surface's
// continuation (B-spline evaluation extrapolates), so the curves through it
// keep their spacing and are cut by the trim.
Vec2 vertex_uv(const SurfaceFace& face, const Walk& w, double t, const Vec2& start) {
  const Vec3 v = polyline_point(w.pts, t);
  if (t <= w.real_end + 1e-9 || w.pts.size() < 2) return project_near(face, v, start).uv;
  const Vec3 e = polyline_point(w.pts, w.real_end);
  const Vec2 uv_e = project_near(face, e, start).uv;
  const SurfacePoint sp = face.derivatives(uv_e[0], uv_e[1]);
  Eigen::Matrix<double, 3, 2> j;
  j << sp.du, sp.dv;
  const Vec3 d = (w.pts.back() - e).normalized();
  const Vec2 duv = (j.transpose() * j).ldlt().solve(j.transpose() * d);
  if (!duv.allFinite()) return project_near(face, v, start).uv;
  return uv_e + (v - e).norm() * duv;
}

// One family: the guide moved through the vertex pairs on both sides, in order.
// The vertex chord is cx.l1, or with `divisions` > 0 the length of each end's
// boundary curve / divisions (the paper's equal division of the boundaries);
// `min_chord` is lowered to the smallest chord used.
std::vector<SurfaceCurve> family(const Context& cx, const Loop& loop, const SurfaceCurve& guide,
                                 int max_curves, int divisions, bool map_in_uv, double& min_chord) {
  const SurfaceFace& face = cx.face;
  const LoopPos p0 = loop.locate(guide.xyz.front()), p1 = loop.locate(guide.xyz.back());
  const double total = loop.total();
  double fwd = loop.s(p1) - loop.s(p0);
  if (fwd < 0) fwd += total;
  const double ext = 2.0 * face.model_size();
  std::vector<SurfaceCurve> sides[2];
  for (int k = 0; k < 2; ++k) {
    const int dir = k == 0 ? 1 : -1;
    const double half = 0.5 * (k == 0 ? fwd : total - fwd);
    const Walk w0 = walk(loop, p0, dir, half, ext), w1 = walk(loop, p1, -dir, half, ext);
    const double c0 = divisions > 0 ? equal_boundary_chord(loop, p0, dir, divisions) : cx.l1;
    const double c1 = divisions > 0 ? equal_boundary_chord(loop, p1, -dir, divisions) : cx.l1;
    min_chord = std::min({min_chord, c0, c1});
    const std::vector<double> t0 = lay_chords(w0.pts, c0, max_curves + 1);
    const std::vector<double> t1 = lay_chords(w1.pts, c1, max_curves + 1);
    auto real = [](const std::vector<double>& t, double end) {
      int c = 0;
      for (std::size_t i = 1; i < t.size(); ++i) c += t[i] <= end + 1e-9 ? 1 : 0;
      return c;
    };
    // A vertex without a twin gets one on the other boundary's extension.
    const int count = std::min({std::max(real(t0, w0.real_end), real(t1, w1.real_end)),
                                static_cast<int>(t0.size()) - 1, static_cast<int>(t1.size()) - 1});
    SurfaceCurve cur = guide;
    for (int i = 1; i <= count; ++i) {
      const Vec3 v0 = polyline_point(w0.pts, t0[i]), v1 = polyline_point(w1.pts, t1[i]);
      if ((v0 - v1).norm() < 0.5 * std::min(c0, c1)) break;  // the pairs have met
      const Vec2 uv0 = vertex_uv(face, w0, t0[i], cur.uv.front());
      const Vec2 uv1 = vertex_uv(face, w1, t1[i], cur.uv.back());
      // "The original guide line is then advanced by moving the end points to
      // the next two vertices" (section 6.1): every curve is the guide itself
      // mapped (not the previous curve), so mapping errors do not add up from
      // curve to curve. map_in_uv (default): the guide's (u,v) polyline moved
      // by a similarity of the parameter plane; false: the paper's steps 4-6
      // in 3D (scale, rotate, nearest-point projection), which bows every
      // curve towards the lower edge on a dome (the scaled copy lies under
      // the surface). British Museum roof, west + south guides, 2000 mm: rod
      // length variance 51,208 mm^2 in (u,v) against 168,206 in 3D (and
      // 187,551 with the points moved along the normals instead).
      SurfaceCurve next = map_in_uv ? map_curve_uv(face, guide, uv0, uv1)
                                    : map_curve(cx, guide, v0, uv0, v1, uv1, &cur);
      // A curve that stays where the previous one was, or runs along the
      // outline (both vertices walk along the guide's own boundary curve),
      // ends this side.
      const std::size_t mid = next.xyz.size() / 2;
      const double step = std::min(c0, c1);
      if ((next.xyz[mid] - cur.xyz[mid]).norm() < 0.3 * step) break;
      if ((loop.at(loop.locate(next.xyz[mid])) - next.xyz[mid]).norm() < 0.05 * step) break;
      sides[k].push_back(next);
      cur = std::move(next);
      if (static_cast<int>(sides[0].size() + sides[1].size()) > max_curves)
        throw LimitExceeded("two_guide_lines: more than max_curves curves; increase rod_length");
    }
  }
  std::vector<SurfaceCurve> out(sides[1].rbegin(), sides[1].rend());
  out.push_back(guide);
  out.insert(out.end(), sides[0].begin(), sides[0].end());
  return out;
}

}  // namespace

TwoGuideLinesResult two_guide_lines_curves(const SurfaceFace& face,
                                           const TwoGuideLinesParams& params) {
  require_in_range("rod_length (mm)", params.rod_length, 1e-3, 1e9);
  require_in_range("corner_angle (deg)", params.corner_angle, 1.0, 179.0);
  require_in_range("boundary_divisions", params.boundary_divisions, 0, 100000);
  require_in_range("guide_tolerance (mm)", params.guide_tolerance, 0.0, 1e12);
  require_in_range("max_curves", params.max_curves, 1, 1e6);
  require_in_range("max_panels", params.max_panels, 1, 1e9);
  require_in_range("trim_deflection (mm)", params.trim_deflection, 0.0, 1e9);
  for (const auto* g : {&params.guide_a, &params.guide_b}) {
    if (g->size() < 2) throw InvalidParameter("guides: a guide curve needs at least two points");
    for (const Vec3& p : *g)
      if (!p.allFinite()) throw InvalidParameter("guides: the guide curve has a non-finite point");
  }
  const double size = face.model_size();
  if (size / params.rod_length > params.max_curves)
    throw LimitExceeded(
        "two_guide_lines: the face needs more than max_curves curves at this rod_length");
  Context cx{face, {}, params.rod_length, params.rod_length, 1e-9 * size, 0, {}};
  cx.samples = static_cast<int>(std::clamp(std::ceil(4.0 * size / cx.l1) + 1.0, 33.0, 4001.0));
  const double deflection = trim_deflection(face, params.trim_deflection);
  const std::vector<TrimLoop> loops = face.trim_loops(deflection);
  for (const TrimLoop& loop : loops)
    if (loop.outer) cx.boundary = {loop.xyz, loop.uv};
  cx.inside = UvTrimClassifier(loops, UvTrimClassifier::Options{-1, &face});
  if (cx.boundary.xyz.size() < 3)
    throw InvalidGeometry("two_guide_lines: the face has no outer boundary");
  const Loop loop(cx.boundary, params.corner_angle);

  cx.tol = params.guide_tolerance > 0 ? params.guide_tolerance : 0.05 * size;
  const SurfaceCurve ga = initial_curve(cx, params.guide_a);
  const SurfaceCurve gb = initial_curve(cx, params.guide_b);
  cx.tol = 1e-9 * size;

  TwoGuideLinesResult result;
  double min_chord = cx.l1;
  result.curves_a = family(cx, loop, ga, params.max_curves, params.boundary_divisions,
                           params.map_in_uv, min_chord);
  result.curves_b = family(cx, loop, gb, params.max_curves, params.boundary_divisions,
                           params.map_in_uv, min_chord);

  // Cells between the two families, closed by the trim (curve_family_mesh.h).
  CurveFamilyMeshParams mp;
  mp.rod_length = min_chord;
  mp.triangulate = params.triangulate;
  mp.corner_angle = params.corner_angle;
  mp.trim_deflection = deflection;
  mp.max_panels = params.max_panels;
  result.mesh = mesh_curve_families(face, {result.curves_a, result.curves_b}, mp);
  return result;
}

PanelMesh two_guide_lines(const SurfaceFace& face, const TwoGuideLinesParams& params) {
  return two_guide_lines_curves(face, params).mesh;
}

}  // namespace tessella
