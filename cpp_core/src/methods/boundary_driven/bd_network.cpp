#include "methods/boundary_driven/bd_network.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "methods/boundary_driven/bd_geometry.h"
#include "tessella/errors.h"

namespace tessella {

namespace {

struct Entry {
  double param;  // curve: segment index + t; loop: arc length
  int node;
};

struct HalfEdge {
  int from, to;
  double angle;   // of the outgoing direction at `from`, in (u,v)
  bool exterior;  // runs against a trim loop's orientation
};

// uv of a curve at parameter p (segment index + t), wrapping closed curves.
Vec2 curve_uv(const BdCurve& c, double p) {
  const int n = static_cast<int>(c.uv.size());
  const int segs = c.closed ? n : n - 1;
  if (c.closed) p = std::fmod(std::fmod(p, segs) + segs, segs);
  int i = std::clamp(static_cast<int>(std::floor(p)), 0, segs - 1);
  const double t = p - i;
  return c.uv[i] + t * (c.uv[(i + 1) % n] - c.uv[i]);
}

}  // namespace

BdNetwork build_bd_network(const SurfaceFace& face, const std::vector<BdPolyline>& boundary,
                           const std::vector<BdCurve>& curves, const BdNetworkParams& params) {
  require_in_range("corner_angle (deg)", params.corner_angle_deg, 1.0, 179.0);
  const double ms = face.model_size();
  BdNetwork net;
  for (const BdPolyline& line : boundary) net.loop_lengths.push_back(line.length());
  auto add_node = [&](const Vec2& uv, int loop, double s, bool corner) {
    BdNode n;
    n.uv = uv;
    n.xyz = face.point(uv.x(), uv.y());
    n.loop = loop, n.s = s, n.corner = corner;
    net.nodes.push_back(n);
    return static_cast<int>(net.nodes.size()) - 1;
  };

  // ---- boundary nodes: corners and curve ends, merged when they coincide
  std::vector<std::vector<Entry>> loop_entries(boundary.size());
  std::vector<int> start_node(curves.size(), -1), end_node(curves.size(), -1);
  {
    struct Cand {
      double s;
      bool corner;
      int curve;  // -1 corner; else curve index * 2 + (0 start, 1 end)
    };
    std::vector<std::vector<Cand>> cands(boundary.size());
    for (std::size_t k = 0; k < boundary.size(); ++k)
      for (double s : bd_corners(boundary[k], params.corner_angle_deg))
        cands[k].push_back({s, true, -1});
    for (std::size_t c = 0; c < curves.size(); ++c) {
      if (curves[c].start.loop >= 0)
        cands[curves[c].start.loop].push_back({curves[c].start.s, false, int(2 * c)});
      if (curves[c].end.loop >= 0)
        cands[curves[c].end.loop].push_back({curves[c].end.s, false, int(2 * c + 1)});
    }
    for (std::size_t k = 0; k < boundary.size(); ++k) {
      const BdPolyline& line = boundary[k];
      const double len = line.length();
      const double tol = 1e-9 * ms;
      auto& cs = cands[k];
      std::sort(cs.begin(), cs.end(), [](const Cand& a, const Cand& b) { return a.s < b.s; });
      if (cs.size() < 4) {  // a loop few curves reached: at least four nodes
        const double s0 = cs.empty() ? 0.0 : cs[0].s;
        const int have = static_cast<int>(cs.size());
        for (int j = 1; j <= 4 - have; ++j)
          cs.push_back({std::fmod(s0 + len * j / (5.0 - have), len), false, -1});
        std::sort(cs.begin(), cs.end(), [](const Cand& a, const Cand& b) { return a.s < b.s; });
      }
      std::vector<Entry>& es = loop_entries[k];
      for (std::size_t i = 0; i < cs.size(); ++i) {
        const bool same_as_prev = !es.empty() && cs[i].s - net.nodes[es.back().node].s <= tol;
        const bool same_as_first = !es.empty() && i + 1 == cs.size() &&
                                   net.nodes[es.front().node].s + len - cs[i].s <= tol;
        int node;
        if (same_as_prev || same_as_first) {
          node = same_as_prev ? es.back().node : es.front().node;
          net.nodes[node].corner = net.nodes[node].corner || cs[i].corner;
        } else {
          node = add_node(line.uv_at(cs[i].s), static_cast<int>(k), cs[i].s, cs[i].corner);
          es.push_back({cs[i].s, node});
        }
        if (cs[i].curve >= 0) (cs[i].curve % 2 ? end_node : start_node)[cs[i].curve / 2] = node;
      }
    }
  }

  // ---- curve-curve intersections
  std::vector<std::vector<Entry>> curve_entries(curves.size());
  {
    const UvBounds b = face.bounds();
    // Two curves along one streamline (principal lines near a singularity)
    // cross a third at one point: one node there, not two at one position
    // (the faces between them would have no area or pinch).
    const double same = 1e-12 * std::hypot(b.u_max - b.u_min, b.v_max - b.v_min);
    std::map<std::pair<long long, long long>, std::vector<int>> crossing_cells;
    auto crossing_node = [&](const Vec2& uv) {
      const long long cx = static_cast<long long>(std::floor(uv.x() / (same * 4))),
                      cy = static_cast<long long>(std::floor(uv.y() / (same * 4)));
      for (long long dx = -1; dx <= 1; ++dx)
        for (long long dy = -1; dy <= 1; ++dy) {
          const auto it = crossing_cells.find({cx + dx, cy + dy});
          if (it == crossing_cells.end()) continue;
          for (int n : it->second)
            if ((net.nodes[n].uv - uv).norm() <= same) return n;
        }
      const int n = add_node(uv, -1, 0.0, false);
      crossing_cells[{cx, cy}].push_back(n);
      return n;
    };
    std::size_t segs = 0;
    for (const auto& c : curves) segs += c.uv.size();
    bd::SegmentGrid grid(Vec2(b.u_min, b.v_min), Vec2(b.u_max, b.v_max),
                         std::clamp(static_cast<int>(std::sqrt(double(segs)) / 2), 8, 1024));
    auto seg_count = [&](const BdCurve& c) {
      return static_cast<int>(c.closed ? c.uv.size() : c.uv.size() - 1);
    };
    for (std::size_t c = 0; c < curves.size(); ++c)
      for (int i = 0; i < seg_count(curves[c]); ++i)
        grid.add(curves[c].uv[i], curves[c].uv[(i + 1) % curves[c].uv.size()], c, i);
    std::vector<std::array<int, 2>> cand;
    for (std::size_t c = 0; c < curves.size(); ++c) {
      const BdCurve& A = curves[c];
      const int na = seg_count(A);
      for (int i = 0; i < na; ++i) {
        const Vec2& a0 = A.uv[i];
        const Vec2& a1 = A.uv[(i + 1) % A.uv.size()];
        cand.clear();
        grid.query(a0, a1, [&](int d, int j) {
          if (d > static_cast<int>(c)) cand.push_back({d, j});
        });
        std::sort(cand.begin(), cand.end());
        cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
        for (const auto& [d, j] : cand) {
          const BdCurve& B = curves[d];
          const Vec2& b0 = B.uv[j];
          const Vec2& b1 = B.uv[(j + 1) % B.uv.size()];
          double t, s;
          if (!bd::intersect_segments(a0, a1, b0, b1, t, s)) continue;
          // half-open segments so a crossing at a shared vertex counts once
          const bool a_last = !A.closed && i == na - 1, b_last = !B.closed && j == seg_count(B) - 1;
          if (t < 0 || s < 0 || (t >= 1 && !a_last) || (s >= 1 && !b_last)) continue;
          t = std::min(t, 1.0), s = std::min(s, 1.0);
          // a crossing at a curve's end on the trim is that end's node
          if (a_last && t >= 1 - 1e-9 && end_node[c] >= 0) continue;
          if (b_last && s >= 1 - 1e-9 && end_node[d] >= 0) continue;
          if (i == 0 && t <= 1e-9 && start_node[c] >= 0) continue;
          if (j == 0 && s <= 1e-9 && start_node[d] >= 0) continue;
          const int node = crossing_node(a0 + t * (a1 - a0));
          curve_entries[c].push_back({i + t, node});
          curve_entries[d].push_back({j + s, node});
        }
      }
    }
  }

  // ---- edges along curves and loops, with their directions at both ends
  std::vector<HalfEdge> half;
  // The direction of an edge at its end: toward the polyline's next vertex,
  // else (that vertex is the end itself) along the chord.
  auto or_chord = [](const Vec2& d, const Vec2& chord) { return d.norm() > 0 ? d : chord; };
  auto add_edge = [&](int a, int b, const Vec2& dir_a, const Vec2& dir_b, bool boundary_edge) {
    if (a == b || dir_a.norm() == 0 || dir_b.norm() == 0) return;
    half.push_back({a, b, std::atan2(dir_a.y(), dir_a.x()), false});
    half.push_back({b, a, std::atan2(dir_b.y(), dir_b.x()), boundary_edge});
  };
  for (std::size_t c = 0; c < curves.size(); ++c) {
    const BdCurve& C = curves[c];
    const int n = static_cast<int>(C.uv.size());
    const int segs = C.closed ? n : n - 1;
    auto& es = curve_entries[c];
    if (start_node[c] >= 0) es.push_back({0.0, start_node[c]});
    if (end_node[c] >= 0) es.push_back({double(segs), end_node[c]});
    std::sort(es.begin(), es.end(),
              [](const Entry& x, const Entry& y) { return x.param < y.param; });
    const std::size_t m = es.size();
    const std::size_t pairs = C.closed ? (m >= 2 ? m : 0) : (m >= 1 ? m - 1 : 0);
    for (std::size_t k = 0; k < pairs; ++k) {
      const Entry& e0 = es[k];
      Entry e1 = es[(k + 1) % m];
      if (k + 1 == m) e1.param += segs;  // closed curve: wrap around
      const Vec2 pa = curve_uv(C, e0.param), pb = curve_uv(C, e1.param);
      // first polyline vertex after e0 (or pb), last one before e1 (or pa)
      const double na = std::floor(e0.param) + 1, nb = std::ceil(e1.param) - 1;
      const Vec2 qa = na < e1.param ? curve_uv(C, na) : pb;
      const Vec2 qb = nb > e0.param ? curve_uv(C, nb) : pa;
      add_edge(e0.node, e1.node, or_chord(qa - pa, pb - pa), or_chord(qb - pb, pa - pb), false);
    }
  }
  for (std::size_t k = 0; k < boundary.size(); ++k) {
    const BdPolyline& L = boundary[k];
    const auto& es = loop_entries[k];
    const std::size_t m = es.size();
    const double len = L.length();
    for (std::size_t i = 0; i < m; ++i) {
      const double sa = es[i].param, sb = i + 1 < m ? es[i + 1].param : es[0].param + len;
      const Vec2 pa = L.uv_at(sa), pb = L.uv_at(sb);
      // the first polyline vertex after sa and the last one before sb (arc
      // lengths unwrapped past the loop's start)
      // A node's s is an arc length summed in floating point: one ulp short
      // of a polyline vertex it stands on, the "next vertex" would be its own
      // point (a zero direction, the edge dropped and the panels on both
      // sides of it lost), hence the shift by eps.
      const double eps = 1e-9 * len;
      double x = sa + eps;
      const int ia = L.segment_at(x);
      const double va = L.arc[ia + 1] + (sa + eps - x);
      const Vec2 qa = va < sb ? L.uv_at(va) : pb;
      double y = sb - eps;
      const int ib = L.segment_at(y);
      const double vb =
          (y > L.arc[ib] ? L.arc[ib]
                         : (ib > 0 ? L.arc[ib - 1] : L.arc[L.segment_count() - 1] - len)) +
          (sb - eps - y);
      const Vec2 qb = vb > sa ? L.uv_at(vb) : pa;
      add_edge(es[i].node, i + 1 < m ? es[i + 1].node : es[0].node, or_chord(qa - pa, pb - pa),
               or_chord(qb - pb, pa - pb), true);
    }
  }

  // ---- prune dangling interior ends
  const int nn = static_cast<int>(net.nodes.size());
  std::vector<int> degree(nn, 0);
  std::vector<char> alive(half.size() / 2, 1);
  for (std::size_t e = 0; e < alive.size(); ++e)
    ++degree[half[2 * e].from], ++degree[half[2 * e].to];
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t e = 0; e < alive.size(); ++e) {
      if (!alive[e]) continue;
      const int a = half[2 * e].from, b = half[2 * e].to;
      if ((degree[a] <= 1 && net.nodes[a].loop < 0) || (degree[b] <= 1 && net.nodes[b].loop < 0)) {
        alive[e] = 0, --degree[a], --degree[b], changed = true;
      }
    }
  }

  // ---- faces of the planar graph
  std::vector<std::vector<int>> out(nn);  // half-edge ids leaving each node, by angle
  for (std::size_t e = 0; e < alive.size(); ++e) {
    if (!alive[e]) continue;
    out[half[2 * e].from].push_back(2 * e);
    out[half[2 * e + 1].from].push_back(2 * e + 1);
    net.edges.push_back({half[2 * e].from, half[2 * e].to});
  }
  std::vector<int> pos(half.size(), -1);
  for (int v = 0; v < nn; ++v) {
    auto& o = out[v];
    std::sort(o.begin(), o.end(), [&](int x, int y) {
      return half[x].angle < half[y].angle || (half[x].angle == half[y].angle && x < y);
    });
    for (std::size_t i = 0; i < o.size(); ++i) pos[o[i]] = static_cast<int>(i);
  }
  std::vector<char> used(half.size(), 0);
  for (std::size_t h0 = 0; h0 < half.size(); ++h0) {
    if (pos[h0] < 0 || used[h0]) continue;
    std::vector<int> cycle;
    bool exterior = false, ok = true;
    int h = static_cast<int>(h0);
    while (!used[h]) {
      used[h] = 1;
      cycle.push_back(half[h].from);
      exterior = exterior || half[h].exterior;
      const int twin = h ^ 1;
      const auto& o = out[half[h].to];
      h = o[(pos[twin] + o.size() - 1) % o.size()];
      if (cycle.size() > 4096) {
        ok = false;
        break;
      }
    }
    if (!ok || h != static_cast<int>(h0) || exterior || cycle.size() < 3) continue;
    // A face that visits a node twice (a spike left by a dangling tree, or a
    // bridge) is split there; the simple, positive parts are kept.
    std::vector<std::vector<int>> parts{cycle};
    while (!parts.empty()) {
      std::vector<int> c = std::move(parts.back());
      parts.pop_back();
      std::size_t i = 0, j = 0;
      bool repeated = false;
      for (i = 0; i < c.size() && !repeated; ++i)
        for (j = i + 1; j < c.size(); ++j)
          if (c[i] == c[j]) {
            repeated = true;
            break;
          }
      if (repeated) {
        --i;  // the for loop advanced it once more
        std::vector<int> inner(c.begin() + i, c.begin() + j);
        std::vector<int> outer(c.begin(), c.begin() + i);
        outer.insert(outer.end(), c.begin() + j, c.end());
        if (inner.size() >= 3) parts.push_back(std::move(inner));
        if (outer.size() >= 3) parts.push_back(std::move(outer));
        continue;
      }
      double area = 0;
      for (std::size_t k = 0; k < c.size(); ++k)
        area += bd::cross2(net.nodes[c[k]].uv, net.nodes[c[(k + 1) % c.size()]].uv);
      if (area > 0) net.panels.push_back(std::move(c));
    }
  }
  return net;
}

}  // namespace tessella
