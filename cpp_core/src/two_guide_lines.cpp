// The Two Guide Lines with Two End Vertices Method (seed 004 section 6): each
// guide is moved through pairs of boundary vertices; the intersections of the
// two curve families are the nodes of a quad grid.
#include <algorithm>
#include <cmath>
#include <limits>

#include "guide_curves.h"
#include "tessella/errors.h"
#include "tessella/guide_lines.h"
#include "tessella/surface_face.h"

namespace tessella {

namespace {

using namespace guide_detail;

constexpr double kPi = 3.14159265358979323846;

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

// One family: the guide moved through the vertex pairs on both sides, in order.
std::vector<SurfaceCurve> family(const Context& cx, const Loop& loop, const SurfaceCurve& guide,
                                 int max_curves) {
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
    const std::vector<double> t0 = lay_chords(w0.pts, cx.l1, max_curves + 1);
    const std::vector<double> t1 = lay_chords(w1.pts, cx.l1, max_curves + 1);
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
      if ((v0 - v1).norm() < 0.5 * cx.l1) break;  // the pairs have met
      const Vec2 uv0 = project_near(face, v0, cur.uv.front()).uv;
      const Vec2 uv1 = project_near(face, v1, cur.uv.back()).uv;
      SurfaceCurve next = map_curve(cx, cur, v0, uv0, v1, uv1);
      // A curve that stays where the previous one was (both vertices walk
      // along the guide's own boundary curve) ends this side.
      const std::size_t mid = next.xyz.size() / 2;
      if ((next.xyz[mid] - cur.xyz[mid]).norm() < 0.3 * cx.l1) break;
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

bool segment_intersection(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, Vec2& x) {
  const Vec2 r = b - a, s = d - c;
  const double den = r.x() * s.y() - r.y() * s.x();
  if (std::abs(den) < 1e-300) return false;
  const Vec2 ac = c - a;
  const double t = (ac.x() * s.y() - ac.y() * s.x()) / den;
  const double u = (ac.x() * r.y() - ac.y() * r.x()) / den;
  if (t < 0 || t > 1 || u < 0 || u > 1) return false;
  x = a + t * r;
  return true;
}

}  // namespace

TwoGuideLinesResult two_guide_lines_curves(const SurfaceFace& face,
                                           const TwoGuideLinesParams& params) {
  require_in_range("rod_length (mm)", params.rod_length, 1e-3, 1e9);
  require_in_range("corner_angle (deg)", params.corner_angle, 1.0, 179.0);
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
  const double deflection = params.trim_deflection > 0 ? params.trim_deflection : size * 1e-5;
  const std::vector<TrimLoop> loops = face.trim_loops(deflection);
  for (const TrimLoop& loop : loops)
    if (loop.outer) cx.boundary = {loop.xyz, loop.uv};
  cx.inside = UvInside(face, loops);
  if (cx.boundary.xyz.size() < 3)
    throw InvalidGeometry("two_guide_lines: the face has no outer boundary");
  const Loop loop(cx.boundary, params.corner_angle);

  cx.tol = params.guide_tolerance > 0 ? params.guide_tolerance : 0.05 * size;
  const SurfaceCurve ga = initial_curve(cx, params.guide_a);
  const SurfaceCurve gb = initial_curve(cx, params.guide_b);
  cx.tol = 1e-9 * size;

  TwoGuideLinesResult result;
  result.curves_a = family(cx, loop, ga, params.max_curves);
  result.curves_b = family(cx, loop, gb, params.max_curves);
  const auto& fa = result.curves_a;
  const auto& fb = result.curves_b;

  // Intersections in (u,v), family b's segments bucketed on a grid.
  const UvBounds bb = face.bounds();
  const int g = 128;
  const double du = std::max(bb.u_max - bb.u_min, 1e-300) / g;
  const double dv = std::max(bb.v_max - bb.v_min, 1e-300) / g;
  auto cell = [&](double u, double v) {
    const int i = std::clamp(static_cast<int>((u - bb.u_min) / du), 0, g - 1);
    const int j = std::clamp(static_cast<int>((v - bb.v_min) / dv), 0, g - 1);
    return std::array<int, 2>{i, j};
  };
  std::vector<std::vector<std::array<int, 2>>> buckets(static_cast<std::size_t>(g) * g);
  for (std::size_t j = 0; j < fb.size(); ++j)
    for (std::size_t s = 0; s + 1 < fb[j].uv.size(); ++s) {
      const Vec2 a = fb[j].uv[s], b = fb[j].uv[s + 1];
      const auto lo = cell(std::min(a.x(), b.x()), std::min(a.y(), b.y()));
      const auto hi = cell(std::max(a.x(), b.x()), std::max(a.y(), b.y()));
      for (int x = lo[0]; x <= hi[0]; ++x)
        for (int y = lo[1]; y <= hi[1]; ++y)
          buckets[static_cast<std::size_t>(x) * g + y].push_back(
              {static_cast<int>(j), static_cast<int>(s)});
    }
  const std::size_t na = fa.size(), nb = fb.size();
  std::vector<int> node(na * nb, -1);
  PanelMesh& mesh = result.mesh;
  for (std::size_t i = 0; i < na; ++i)
    for (std::size_t s = 0; s + 1 < fa[i].uv.size(); ++s) {
      const Vec2 a = fa[i].uv[s], b = fa[i].uv[s + 1];
      const auto lo = cell(std::min(a.x(), b.x()), std::min(a.y(), b.y()));
      const auto hi = cell(std::max(a.x(), b.x()), std::max(a.y(), b.y()));
      for (int x = lo[0]; x <= hi[0]; ++x)
        for (int y = lo[1]; y <= hi[1]; ++y)
          for (const auto& js : buckets[static_cast<std::size_t>(x) * g + y]) {
            int& id = node[i * nb + js[0]];
            if (id != -1) continue;  // first crossing along curve a
            Vec2 p;
            if (!segment_intersection(a, b, fb[js[0]].uv[js[1]], fb[js[0]].uv[js[1] + 1], p))
              continue;
            if (!cx.inside(p.x(), p.y())) continue;
            id = static_cast<int>(mesh.uv.size());
            mesh.uv.push_back(p);
            mesh.xyz.push_back(face.point(p.x(), p.y()));
          }
    }

  // Quads of four neighbouring nodes (optionally split along one diagonal).
  const double max_edge = 4.0 * cx.l1;
  for (std::size_t i = 0; i + 1 < na; ++i)
    for (std::size_t j = 0; j + 1 < nb; ++j) {
      int q[4] = {node[i * nb + j], node[(i + 1) * nb + j], node[(i + 1) * nb + j + 1],
                  node[i * nb + j + 1]};
      if (std::any_of(q, q + 4, [](int v) { return v < 0; })) continue;
      bool ok = true;
      for (int k = 0; k < 4; ++k)
        if ((mesh.xyz[q[k]] - mesh.xyz[q[(k + 1) % 4]]).norm() > max_edge) ok = false;
      const Vec2 c = 0.25 * (mesh.uv[q[0]] + mesh.uv[q[1]] + mesh.uv[q[2]] + mesh.uv[q[3]]);
      if (!ok || !cx.inside(c.x(), c.y())) continue;
      const Vec3 nrm = (mesh.xyz[q[2]] - mesh.xyz[q[0]]).cross(mesh.xyz[q[3]] - mesh.xyz[q[1]]);
      if (nrm.norm() < 1e-9 * cx.l1 * cx.l1) continue;
      if (nrm.dot(face.normal(c.x(), c.y())) < 0) std::swap(q[1], q[3]);
      if (params.triangulate) {
        mesh.panels.push_back({q[0], q[1], q[2]});
        mesh.panels.push_back({q[0], q[2], q[3]});
      } else {
        mesh.panels.push_back({q[0], q[1], q[2], q[3]});
      }
      if (static_cast<int>(mesh.panels.size()) > params.max_panels)
        throw LimitExceeded("two_guide_lines: more panels than max_panels");
    }
  mesh.nominal_area = params.triangulate ? 0.5 * cx.l1 * cx.l1 : cx.l1 * cx.l1;
  mesh.regular_corners = params.triangulate ? 3 : 4;
  weld_coincident_vertices(mesh, 1e-6 * size);
  remove_unused_vertices(mesh);
  build_rods(mesh);
  if (mesh.panels.empty())
    throw InvalidParameter(
        "two_guide_lines: no panels (do the two guides cross? is rod_length too large?)");
  return result;
}

PanelMesh two_guide_lines(const SurfaceFace& face, const TwoGuideLinesParams& params) {
  return two_guide_lines_curves(face, params).mesh;
}

}  // namespace tessella
