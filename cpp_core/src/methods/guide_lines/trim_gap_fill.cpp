// Filling the strips between a guide-line triangulation's boundary and the
// trim (see trim_gap_fill.h).
#include "methods/guide_lines/trim_gap_fill.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include "methods/guide_lines/chord_division.h"
#include "methods/guide_lines/right_angle_rule.h"

namespace tessella::guide_detail {

namespace {

// Where a point lies on the trim loops: loop, segment, parameter on it, its
// arc-length position along the loop and its distance.
struct TrimFoot {
  int loop = -1;
  std::size_t seg = 0;
  double t = 0.0, s = 0.0;
  double dist = std::numeric_limits<double>::infinity();
};

struct LoopIndex {
  const std::vector<TrimLoop>& loops;
  std::vector<std::vector<double>> cum;  // arc length at each loop point
  std::vector<double> perimeter;

  explicit LoopIndex(const std::vector<TrimLoop>& l) : loops(l) {
    for (const TrimLoop& loop : loops) {
      const std::size_t n = loop.xyz.size();
      std::vector<double> c(n + 1, 0.0);
      for (std::size_t i = 0; i < n; ++i)
        c[i + 1] = c[i] + (loop.xyz[(i + 1) % n] - loop.xyz[i]).norm();
      perimeter.push_back(c[n]);
      cum.push_back(std::move(c));
    }
  }

  TrimFoot foot(const Vec3& p) const {
    TrimFoot best;
    for (std::size_t l = 0; l < loops.size(); ++l) {
      const LoopPoint on = nearest_on_loop(loops[l].xyz, p);
      if (on.distance < best.dist) {
        best.loop = static_cast<int>(l), best.seg = on.seg, best.t = on.t, best.dist = on.distance;
        best.s = cum[l][on.seg] + on.t * (cum[l][on.seg + 1] - cum[l][on.seg]);
      }
    }
    return best;
  }

  // The loop from a to b, along its order (forward) or against it.
  SurfaceCurve stretch(const TrimFoot& a, const TrimFoot& b, bool forward) const {
    const TrimLoop& loop = loops[a.loop];
    const std::size_t n = loop.xyz.size();
    SurfaceCurve out;
    auto add = [&](std::size_t seg, double t) {
      const std::size_t next = (seg + 1) % n;
      out.xyz.push_back(loop.xyz[seg] + t * (loop.xyz[next] - loop.xyz[seg]));
      out.uv.push_back(loop.uv[seg] + t * (loop.uv[next] - loop.uv[seg]));
    };
    add(a.seg, a.t);
    if (forward && !(a.seg == b.seg && b.t >= a.t)) {
      for (std::size_t k = 1, i = (a.seg + 1) % n; k <= n; ++k, i = (i + 1) % n) {
        add(i, 0.0);
        if (i == b.seg) break;
      }
    } else if (!forward && !(a.seg == b.seg && b.t <= a.t)) {
      for (std::size_t k = 1, i = a.seg; k <= n; ++k, i = (i + n - 1) % n) {
        add(i, 0.0);
        if (i == (b.seg + 1) % n) break;
      }
    }
    add(b.seg, b.t);
    return out;
  }

  // Whether position s lies strictly inside the stretch from a to b.
  bool within(const TrimFoot& a, const TrimFoot& b, bool forward, double s) const {
    const double per = perimeter[a.loop];
    auto ahead = [&](double from, double to) { return std::fmod(to - from + 2.0 * per, per); };
    const double span = forward ? ahead(a.s, b.s) : ahead(b.s, a.s);
    const double at = forward ? ahead(a.s, s) : ahead(s, a.s);
    return at > 1e-9 * per && at < span - 1e-9 * per;
  }
};

// Largest distance from the stretch (sampled along its segments) to the chain.
double strip_width(const SurfaceCurve& stretch, const std::vector<Vec3>& chain) {
  double width = 0.0;
  for (std::size_t i = 0; i + 1 < stretch.xyz.size(); ++i)
    for (double f : {0.0, 0.25, 0.5, 0.75})
      width = std::max(width, distance_to_polyline(chain, stretch.xyz[i] + f * (stretch.xyz[i + 1] -
                                                                                stretch.xyz[i])));
  return width;
}

}  // namespace

int fill_trim_gaps(const Context& cx, const std::vector<TrimLoop>& loops, double on_trim,
                   double min_width, double max_width, PanelMesh& mesh) {
  // Boundary half-edges (used by one triangle), in the triangles' direction.
  std::map<std::pair<int, int>, int> uses;
  for (const auto& panel : mesh.panels)
    for (std::size_t k = 0; k < panel.size(); ++k) {
      const int a = panel[k], b = panel[(k + 1) % panel.size()];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  std::map<int, int> next;
  std::map<int, int> outgoing;
  for (const auto& panel : mesh.panels)
    for (std::size_t k = 0; k < panel.size(); ++k) {
      const int a = panel[k], b = panel[(k + 1) % panel.size()];
      if (uses[{std::min(a, b), std::max(a, b)}] != 1) continue;
      next[a] = b;
      ++outgoing[a];
    }
  const LoopIndex index(loops);
  std::map<int, TrimFoot> feet;
  for (const auto& edge : next) feet[edge.first] = index.foot(mesh.xyz[edge.first]);
  auto is_on_trim = [&](int v) {
    const auto it = feet.find(v);
    return it != feet.end() && it->second.dist <= on_trim;
  };

  // The boundary cycles, each walked once; a vertex with two outgoing
  // boundary edges (two cycles touching) stops its cycles from being filled.
  std::map<int, char> seen;
  std::vector<std::vector<int>> cycles;
  for (const auto& edge : next) {
    const int start = edge.first;
    if (seen[start]) continue;
    std::vector<int> cycle;
    bool clean = true;
    int v = start;
    while (!seen[v]) {
      seen[v] = 1;
      cycle.push_back(v);
      if (outgoing[v] != 1) clean = false;
      const auto it = next.find(v);
      if (it == next.end()) {
        clean = false;
        break;
      }
      v = it->second;
    }
    if (clean && v == start) cycles.push_back(std::move(cycle));
  }

  int filled = 0;
  ChordDivisionParams cp;
  cp.chord = cx.l1;
  for (const std::vector<int>& cycle : cycles) {
    const std::size_t n = cycle.size();
    std::vector<std::size_t> on;
    for (std::size_t i = 0; i < n; ++i)
      if (is_on_trim(cycle[i])) on.push_back(i);
    if (on.size() < 2) continue;
    for (std::size_t k = 0; k < on.size(); ++k) {
      const std::size_t i = on[k], j = on[(k + 1) % on.size()];
      const int a = cycle[i], b = cycle[j];
      const TrimFoot fa = feet[a], fb = feet[b];
      if (fa.loop != fb.loop || a == b) continue;
      std::vector<int> chain;
      for (std::size_t m = i;; m = (m + 1) % n) {
        chain.push_back(cycle[m]);
        if (m == j) break;
      }
      std::vector<Vec3> chain_xyz;
      for (int v : chain) chain_xyz.push_back(mesh.xyz[v]);
      // The stretch of the trim on the strip's side: the narrower one, with
      // no other node of the mesh's boundary on the trim inside it.
      SurfaceCurve best;
      double best_width = std::numeric_limits<double>::infinity();
      bool best_forward = true;
      for (bool forward : {true, false}) {
        SurfaceCurve s = index.stretch(fa, fb, forward);
        const double w = strip_width(s, chain_xyz);
        if (w < best_width) best_width = w, best = std::move(s), best_forward = forward;
      }
      if (best_width < min_width || best_width > max_width) continue;
      bool blocked = false;
      for (const auto& [v, f] : feet)
        if (v != a && v != b && f.dist <= on_trim && f.loop == fa.loop &&
            index.within(fa, fb, best_forward, f.s))
          blocked = true;
      if (blocked) continue;
      // Nodes along the stretch about L1 apart, on the true trim.
      std::vector<int> row = {a};
      const std::vector<double> ts = divide_by_chords(best.xyz, cp);
      for (std::size_t q = 1; q + 1 < ts.size(); ++q) {
        const std::size_t s = std::min(static_cast<std::size_t>(ts[q]), best.uv.size() - 2);
        const double f = ts[q] - static_cast<double>(s);
        Vec2 uv = best.uv[s] + f * (best.uv[s + 1] - best.uv[s]);
        const Vec2 du = best.uv[s + 1] - best.uv[s];
        if (du.norm() > 0.0) {
          const Vec2 across = Vec2(-du[1], du[0]) * 1e-3;
          const Vec2 x = uv + across, y = uv - across;
          const bool in_x = cx.inside.contains(x[0], x[1]), in_y = cx.inside.contains(y[0], y[1]);
          if (in_x != in_y) uv = in_x ? bisect_boundary(cx, x, y) : bisect_boundary(cx, y, x);
        }
        row.push_back(static_cast<int>(mesh.uv.size()));
        mesh.uv.push_back(uv);
        mesh.xyz.push_back(cx.face.point(uv[0], uv[1]));
      }
      row.push_back(b);
      std::vector<Vec3> p, q;
      for (int v : chain) p.push_back(mesh.xyz[v]);
      for (int v : row) q.push_back(mesh.xyz[v]);
      const int np = static_cast<int>(p.size());
      for (const auto& t : connect_rows_right_angle(p, q)) {
        int ids[3];
        for (int c = 0; c < 3; ++c) ids[c] = t[c] < np ? chain[t[c]] : row[t[c] - np];
        if (ids[0] == ids[1] || ids[1] == ids[2] || ids[0] == ids[2]) continue;
        const Vec3 e1 = mesh.xyz[ids[1]] - mesh.xyz[ids[0]],
                   e2 = mesh.xyz[ids[2]] - mesh.xyz[ids[0]];
        const Vec3 nrm = e1.cross(e2);
        if (nrm.norm() < 1e-9 * cx.l1 * cx.l1) continue;
        const Vec2 cuv = (mesh.uv[ids[0]] + mesh.uv[ids[1]] + mesh.uv[ids[2]]) / 3.0;
        if (!cx.inside.contains(cuv[0], cuv[1])) continue;
        if (nrm.dot(cx.face.normal(cuv[0], cuv[1])) < 0) std::swap(ids[1], ids[2]);
        mesh.panels.push_back({ids[0], ids[1], ids[2]});
      }
      ++filled;
    }
  }
  return filled;
}

}  // namespace tessella::guide_detail
