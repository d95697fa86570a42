#include "methods/boundary_driven/bd_refine.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

#include "mesh/seam_sides.h"
#include "methods/boundary_driven/bd_geometry.h"
#include "methods/boundary_driven/bd_trim_crossing.h"
#include "tessella/errors.h"

namespace tessella {

namespace {

double corner_angle(const Vec3& prev, const Vec3& p, const Vec3& next) {
  const Vec3 a = prev - p, b = next - p;
  const double na = a.norm(), nb = b.norm();
  if (na == 0 || nb == 0) return 0;
  return std::acos(std::clamp(a.dot(b) / (na * nb), -1.0, 1.0));
}

int rank(const BdNode& n) { return n.corner ? 2 : (n.loop >= 0 ? 1 : 0); }

// Nodes per trim loop used by the panels (a loop keeps at least four).
std::map<int, int> loop_node_counts(const BdNetwork& net) {
  std::vector<char> used(net.nodes.size(), 0);
  for (const auto& p : net.panels)
    for (int v : p) used[v] = 1;
  std::map<int, int> count;
  for (std::size_t v = 0; v < net.nodes.size(); ++v)
    if (used[v] && net.nodes[v].loop >= 0) ++count[net.nodes[v].loop];
  return count;
}
constexpr int kMinLoopNodes = 4;

// Whether trim node v may merge into w: w on the same loop and near v along
// it, not only in space. A short edge between two far points of one loop (a
// curve across a strip narrower than the spacing, or across a notch) is a
// real edge of the tiling; merging its ends pinches the face and the panels
// no longer cover it (a 0.06 mm wide cylinder strip lost all but 6 panels).
bool may_merge_along_loop(const BdNetwork& net, int v, int w) {
  const BdNode &a = net.nodes[v], &b = net.nodes[w];
  if (a.loop < 0 || b.loop != a.loop) return false;
  double arc = std::abs(a.s - b.s);
  if (static_cast<std::size_t>(a.loop) < net.loop_lengths.size())
    arc = std::min(arc, net.loop_lengths[a.loop] - arc);
  return arc <= 1.5 * (a.xyz - b.xyz).norm() + 1e-12;
}

// Whether replacing node v by w would make a panel around v visit w twice
// (w a corner of it not next to v): the panel would come out with a spike
// or pinched in two.
bool merge_repeats_a_corner(const BdNetwork& net, const std::vector<int>& panels, int v, int w) {
  for (int pi : panels) {
    const auto& p = net.panels[static_cast<std::size_t>(pi)];
    const std::size_t n = p.size();
    for (std::size_t i = 0; i < n; ++i)
      if (p[i] == w && p[(i + 1) % n] != v && p[(i + n - 1) % n] != v) return true;
  }
  return false;
}

// Whether replacing node v by w (w moved to w_uv) keeps every panel around v
// and w unfolded in (u,v) (panels that vanish do not count).
bool merge_keeps_panels(const BdNetwork& net, const std::vector<int>& panels, int v, int w,
                        const Vec2& w_uv) {
  for (int pi : panels) {
    std::vector<int> q;
    for (int x : net.panels[pi]) {
      const int y = x == v ? w : x;
      if (q.empty() || q.back() != y) q.push_back(y);
    }
    while (q.size() > 1 && q.front() == q.back()) q.pop_back();
    if (q.size() < 3) continue;
    double a = 0;
    for (std::size_t i = 0; i < q.size(); ++i) {
      const Vec2 p0 = q[i] == w ? w_uv : net.nodes[q[i]].uv;
      const Vec2 p1 = q[(i + 1) % q.size()] == w ? w_uv : net.nodes[q[(i + 1) % q.size()]].uv;
      a += bd::cross2(p0, p1);
    }
    if (!(a > 0)) return false;
  }
  return true;
}

// Whether replacing node v by w (w moved to w_uv) widens no panel around
// them past 0.3 of a turn round a face closed round a seam (panel_turn):
// near a spire's apex the few lines that reach it are closer than the
// collapse length, and merging two of them made the cells between them
// rings (a 1:10 cone); later stages (the skewed triangles' removal,
// quadrangulation, smoothing) widen a cell further, so the bound is kept
// well under the half turn the method refuses. A panel already as wide (a
// column three panels round) may stay so.
bool merge_keeps_panels_narrow_round(const SurfaceFace& face, const BdNetwork& net,
                                     const std::vector<int>& panels, int v, int w,
                                     const Vec2& w_uv) {
  constexpr double kWidest = 0.3;
  for (int pi : panels) {
    std::vector<Vec2> before, after;
    for (int x : net.panels[static_cast<std::size_t>(pi)]) {
      const Vec2& uv = net.nodes[static_cast<std::size_t>(x)].uv;
      before.push_back(uv);
      after.push_back(x == v || x == w ? w_uv : uv);
    }
    const double turn = panel_turn(face, after);
    if (turn >= kWidest && turn > panel_turn(face, before) + 1e-9) return false;
  }
  return true;
}

// Drops repeated consecutive corners and panels left with fewer than three.
void clean_panels(std::vector<std::vector<int>>& panels) {
  std::vector<std::vector<int>> out;
  for (auto& p : panels) {
    std::vector<int> q;
    for (int v : p)
      if (q.empty() || q.back() != v) q.push_back(v);
    while (q.size() > 1 && q.front() == q.back()) q.pop_back();
    if (q.size() >= 3) out.push_back(std::move(q));
  }
  panels = std::move(out);
}

double uv_area(const std::vector<BdNode>& nodes, const std::vector<int>& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    a += bd::cross2(nodes[p[i]].uv, nodes[p[(i + 1) % p.size()]].uv);
  return 0.5 * a;
}

// Splits p (counter-clockwise in (u,v)) along a diagonal from its first reflex
// corner into two polygons (a, b) when one exists that stays inside p; the
// diagonal chosen makes the two parts' corner counts closest to quads. Inside
// p means inside its outline too: a diagonal across a trim (p's side along an
// opening's bend is a chord, the outline the trim) is no split
// (trimmed_bspline_holes at 1200 mm: a rod across a hole's rim).
bool split_at_reflex_corner(const std::vector<BdNode>& nodes, const std::vector<int>& p,
                            const bd::TrimCrossingTest& trim, std::vector<int>& a,
                            std::vector<int>& b) {
  const int n = static_cast<int>(p.size());
  auto uv = [&](int i) { return nodes[p[((i % n) + n) % n]].uv; };
  for (int r = 0; r < n; ++r) {
    if (bd::cross2(uv(r) - uv(r - 1), uv(r + 1) - uv(r)) >= 0) continue;  // convex corner
    int best = -1;
    double best_score = 1e300;
    for (int k = r + 2; k <= r + n - 2; ++k) {
      // the diagonal r-k must not cross an edge of p and must leave both parts positive
      bool crosses = false;
      for (int e = 0; e < n && !crosses; ++e) {
        const int e0 = e, e1 = (e + 1) % n;
        if (e0 == r || e1 == r || e0 == k % n || e1 == k % n) continue;
        double t, s;
        if (bd::intersect_segments(uv(r), uv(k), uv(e0), uv(e1), t, s)) crosses = true;
      }
      if (crosses || trim.crosses(nodes[p[r]], nodes[p[k % n]])) continue;
      std::vector<int> pa, pb;
      for (int i = r; i <= k; ++i) pa.push_back(p[i % n]);
      for (int i = k; i <= r + n; ++i) pb.push_back(p[i % n]);
      auto area = [&](const std::vector<int>& q) {
        double s2 = 0;
        for (std::size_t i = 0; i < q.size(); ++i)
          s2 += bd::cross2(nodes[q[i]].uv, nodes[q[(i + 1) % q.size()]].uv);
        return s2;
      };
      if (area(pa) <= 0 || area(pb) <= 0) continue;
      const double score = std::abs(double(pa.size()) - 4) + std::abs(double(pb.size()) - 4);
      if (score < best_score) best_score = score, best = k, a = pa, b = pb;
    }
    if (best >= 0) return true;
  }
  return false;
}

// Splits a panel of six or more corners along its shortest diagonal (3D)
// among those whose two parts are closest to quads. Centre + midpoint
// quadrangulation of a big n-gon makes spokes about its radius long, twice
// the other rods; two smaller parts have shorter spokes. (No diagonal
// across a trim, as above.)
bool split_big_panel(const std::vector<BdNode>& nodes, const std::vector<int>& p,
                     const bd::TrimCrossingTest& trim, std::vector<int>& a, std::vector<int>& b) {
  const int n = static_cast<int>(p.size());
  if (n < 6) return false;
  double best_score = 1e300, best_len = 1e300;
  bool found = false;
  for (int r = 0; r < n; ++r)
    for (int k = r + 3; k <= r + n - 3; ++k) {
      std::vector<int> pa, pb;
      for (int i = r; i <= k; ++i) pa.push_back(p[i % n]);
      for (int i = k; i <= r + n; ++i) pb.push_back(p[i % n]);
      if (!(uv_area(nodes, pa) > 0) || !(uv_area(nodes, pb) > 0)) continue;
      bool crosses = false;
      const Vec2 d0 = nodes[p[r]].uv, d1 = nodes[p[k % n]].uv;
      for (int e = 0; e < n && !crosses; ++e) {
        const int e0 = e, e1 = (e + 1) % n;
        if (e0 == r || e1 == r || e0 == k % n || e1 == k % n) continue;
        double t, s;
        if (bd::intersect_segments(d0, d1, nodes[p[e0]].uv, nodes[p[e1]].uv, t, s)) crosses = true;
      }
      if (crosses || trim.crosses(nodes[p[r]], nodes[p[k % n]])) continue;
      const double score = std::abs(double(pa.size()) - 4) + std::abs(double(pb.size()) - 4);
      const double len = (nodes[p[r]].xyz - nodes[p[k % n]].xyz).norm();
      if (score < best_score - 1e-9 || (score < best_score + 1e-9 && len < best_len)) {
        best_score = score, best_len = len, a = pa, b = pb, found = true;
      }
    }
  return found;
}

// One pass of node merges (v into w), the bookkeeping both merging passes
// share: each node merges at most once a pass, and neither it nor a node of
// its panels takes part in another merge of the same pass.
struct MergePass {
  explicit MergePass(const BdNetwork& net)
      : rep(net.nodes.size()),
        touched(net.nodes.size(), 0),
        on_loop(loop_node_counts(net)),
        incident(net.nodes.size()) {
    std::iota(rep.begin(), rep.end(), 0);
    for (std::size_t pi = 0; pi < net.panels.size(); ++pi)
      for (int x : net.panels[pi]) incident[x].push_back(static_cast<int>(pi));
  }

  // Orders the pair so that v, the node removed, is of the lower rank, and
  // says whether it may go at all: a corner never, a trim node only along
  // its own loop and while the loop keeps kMinLoopNodes.
  bool allowed(const BdNetwork& net, int& v, int& w) {
    if (rank(net.nodes[v]) > rank(net.nodes[w])) std::swap(v, w);
    if (rank(net.nodes[v]) == 2) return false;
    if (rank(net.nodes[v]) == 1 && !may_merge_along_loop(net, v, w)) return false;
    if (rank(net.nodes[v]) == 1 && on_loop[net.nodes[v].loop] <= kMinLoopNodes) return false;
    return true;
  }

  void take(const BdNetwork& net, int v, int w) {
    if (rank(net.nodes[v]) == 1) --on_loop[net.nodes[v].loop];
    rep[v] = w;
    touched[v] = touched[w] = 1;
    for (int pi : incident[v])
      for (int x : net.panels[pi]) touched[x] = 1;
    ++merged;
  }

  // The merges applied to the panels.
  void apply(BdNetwork& net) const {
    for (auto& p : net.panels)
      for (int& v : p) v = rep[v];
    clean_panels(net.panels);
  }

  std::vector<int> rep;
  std::vector<char> touched;
  std::map<int, int> on_loop;
  std::vector<std::vector<int>> incident;
  int merged = 0;
};

}  // namespace

int remove_skewed_triangles(BdNetwork& net, double ratio) {
  require_in_range("skew_ratio", ratio, 0.0, 1.0);
  int removed = 0;
  for (int pass = 0; pass < 20; ++pass) {
    MergePass merges(net);
    for (const auto& p : net.panels) {
      if (p.size() != 3) continue;
      if (merges.touched[p[0]] || merges.touched[p[1]] || merges.touched[p[2]]) continue;  // next
      double ang[3];
      for (int i = 0; i < 3; ++i)
        ang[i] = corner_angle(net.nodes[p[(i + 2) % 3]].xyz, net.nodes[p[i]].xyz,
                              net.nodes[p[(i + 1) % 3]].xyz);
      const int imax = static_cast<int>(std::max_element(ang, ang + 3) - ang);
      const double amin = *std::min_element(ang, ang + 3);
      if (ang[imax] <= 0 || amin / ang[imax] >= ratio) continue;
      int v = p[imax];
      const int a = p[(imax + 1) % 3], b = p[(imax + 2) % 3];
      int w = (net.nodes[a].xyz - net.nodes[v].xyz).norm() <=
                      (net.nodes[b].xyz - net.nodes[v].xyz).norm()
                  ? a
                  : b;
      if (!merges.allowed(net, v, w)) continue;  // v is removed, w kept
      // (A disk's triangle whose far corner w was also a corner of the
      // next panel round v: that panel came out [.., w, x, .., w, ..], a
      // spike the coverage check found as 0.2% of overlap in space;
      // bench_faces.random_face_set(64).)
      if (merge_repeats_a_corner(net, merges.incident[v], v, w)) continue;
      if (!merge_keeps_panels(net, merges.incident[v], v, w, net.nodes[w].uv)) continue;
      merges.take(net, v, w);
    }
    if (merges.merged == 0) break;
    removed += merges.merged;
    merges.apply(net);
  }
  return removed;
}

int collapse_short_edges(const SurfaceFace& face, BdNetwork& net, double min_length) {
  require_in_range("min edge length (mm)", min_length, 0.0, face.model_size());
  const bool closed = closed_round_a_seam(face);
  int merged_total = 0;
  for (int pass = 0; pass < 20; ++pass) {
    // candidate edges, shortest first
    std::vector<std::pair<double, std::pair<int, int>>> cand;
    for (const auto& p : net.panels)
      for (std::size_t i = 0; i < p.size(); ++i) {
        const int a = p[i], b = p[(i + 1) % p.size()];
        const double l = (net.nodes[a].xyz - net.nodes[b].xyz).norm();
        if (a < b && l < min_length) cand.push_back({l, {a, b}});
        if (b < a && l < min_length) cand.push_back({l, {b, a}});
      }
    std::sort(cand.begin(), cand.end());
    cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
    MergePass merges(net);
    for (const auto& [len, e] : cand) {
      int v = e.first, w = e.second;  // v is removed, w kept
      if (merges.touched[v] || merges.touched[w]) continue;
      if (!merges.allowed(net, v, w)) continue;
      if (merge_repeats_a_corner(net, merges.incident[v], v, w)) continue;
      Projection moved;
      bool both_inside = rank(net.nodes[v]) == 0 && rank(net.nodes[w]) == 0;
      if (both_inside) {
        const BdNode& k = net.nodes[w];
        moved = face.project(0.5 * (k.xyz + net.nodes[v].xyz), 0.5 * (k.uv + net.nodes[v].uv));
        // Two interior nodes either side of an opening's bend: their middle
        // may lie in the opening, as a quad's centre can (quadrangulate
        // below). w then stays where it is.
        both_inside = face.is_inside(moved.uv.x(), moved.uv.y());
      }
      const Vec2 w_uv = both_inside ? moved.uv : net.nodes[w].uv;
      std::vector<int> around = merges.incident[v];
      around.insert(around.end(), merges.incident[w].begin(), merges.incident[w].end());
      if (!merge_keeps_panels(net, around, v, w, w_uv)) continue;
      if (closed && !merge_keeps_panels_narrow_round(face, net, around, v, w, w_uv)) continue;
      if (both_inside) net.nodes[w].uv = moved.uv, net.nodes[w].xyz = moved.point;
      merges.take(net, v, w);
    }
    if (merges.merged == 0) break;
    merged_total += merges.merged;
    merges.apply(net);
  }
  return merged_total;
}

// A chord's middle (or a panel's centre) farther from the surface than this
// share of its length is bent round so much of the surface (half a thin
// cylinder) that its projection is no longer a well-defined point.
constexpr double kFarFromSurface = 0.25;

void quadrangulate(const SurfaceFace& face, const std::vector<BdPolyline>& boundary, BdNetwork& net,
                   double short_shared_edge) {
  std::map<std::pair<int, int>, int> uses;
  std::map<std::pair<int, int>, int> mid;
  auto add = [&](const BdNode& n) {
    net.nodes.push_back(n);
    return static_cast<int>(net.nodes.size()) - 1;
  };
  const UvTrimClassifier inside = bd::make_classifier(boundary);
  const bd::TrimCrossingTest trim(boundary);
  auto is_in = [&](const Vec2& uv) { return boundary.empty() || inside.contains(uv); };
  auto midpoint = [&](int a, int b, const Vec2& centre_uv) {
    const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
    auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    const BdNode na = net.nodes[a], nb = net.nodes[b];
    BdNode m;
    if (uses[key] == 1 && na.loop >= 0 && na.loop == nb.loop) {
      // along the trim from a to b (panels run along their loop's orientation)
      const BdPolyline& L = boundary[na.loop];
      double ds = std::fmod(nb.s - na.s, L.length());
      if (ds < 0) ds += L.length();
      double s = na.s + 0.5 * ds;
      L.segment_at(s);
      m.loop = na.loop, m.s = s;
      m.uv = L.uv_at(s);
      m.xyz = face.point(m.uv.x(), m.uv.y());
    } else {
      const Projection pr = face.project(0.5 * (na.xyz + nb.xyz), 0.5 * (na.uv + nb.uv));
      m.uv = pr.uv, m.xyz = pr.point;
      // An edge bent round much of a thin cylinder has its chord's middle
      // near the axis, where every surface point is about as near: the
      // middle in (u,v) instead.
      if (!(pr.distance <= kFarFromSurface * (na.xyz - nb.xyz).norm())) {
        m.uv = 0.5 * (na.uv + nb.uv);
        m.xyz = face.point(m.uv.x(), m.uv.y());
      }
      // The point on the surface nearest the chord's middle may lie off the
      // edge's line in (u,v): beside an opening's bend its halves then cross
      // the trim where the edge did not (trimmed_bspline_holes at 1200 mm).
      // The middle in (u,v) keeps them on the edge's line.
      if ((trim.crosses(na, m) || trim.crosses(m, nb)) && !trim.crosses(na, nb)) {
        m.uv = 0.5 * (na.uv + nb.uv);
        m.xyz = face.point(m.uv.x(), m.uv.y());
      }
      // an edge between two trim nodes may chord across an opening: move its
      // midpoint toward the panel's centre until it is on the face
      for (int k = 1; k <= 4 && !is_in(m.uv); ++k) {
        m.uv = 0.5 * (na.uv + nb.uv) + 0.25 * k * (centre_uv - 0.5 * (na.uv + nb.uv));
        m.xyz = face.point(m.uv.x(), m.uv.y());
      }
    }
    return mid[key] = add(m);
  };
  // A panel with a reflex corner (in (u,v)) has no centre that sees all its
  // corners: cut it first along a diagonal from that corner.
  std::vector<std::vector<int>> convex;
  std::vector<std::vector<int>> todo = net.panels;
  while (!todo.empty()) {
    std::vector<int> p = std::move(todo.back());
    todo.pop_back();
    std::vector<int> a, b;
    if (p.size() >= 4 && split_at_reflex_corner(net.nodes, p, trim, a, b)) {
      todo.push_back(std::move(a));
      todo.push_back(std::move(b));
    } else {
      convex.push_back(std::move(p));
    }
  }
  std::reverse(convex.begin(), convex.end());
  // Network edges much longer than the median (curves stopped or joined
  // leaving a wide gap) would give rods of half their length: subdivide them,
  // then cut panels of six or more corners in two (shorter spokes).
  {
    std::map<std::pair<int, int>, int> edge_uses;
    std::vector<double> lengths;
    for (const auto& p : convex)
      for (std::size_t i = 0; i < p.size(); ++i) {
        const int a = p[i], b = p[(i + 1) % p.size()];
        if (edge_uses[{std::min(a, b), std::max(a, b)}]++ == 0)
          lengths.push_back((net.nodes[a].xyz - net.nodes[b].xyz).norm());
      }
    std::map<std::pair<int, int>, std::vector<int>> inner;  // from min to max node
    if (!lengths.empty()) {
      std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
      const double median = lengths[lengths.size() / 2];
      for (const auto& [key, count] : edge_uses) {
        const BdNode na = net.nodes[key.first], nb = net.nodes[key.second];
        const double len = (na.xyz - nb.xyz).norm();
        if (!(median > 0) || len < 1.8 * median) continue;
        const int k = static_cast<int>(std::lround(len / median));
        if (k < 2) continue;
        std::vector<BdNode> made;
        bool ok = true;
        for (int j = 1; j < k && ok; ++j) {
          const double t = double(j) / k;
          if (count != 2) {  // only interior edges (trim edges keep their trim midpoints)
            ok = false;
            break;
          }
          const Projection pr =
              face.project((1 - t) * na.xyz + t * nb.xyz, (1 - t) * na.uv + t * nb.uv);
          BdNode m;
          m.uv = pr.uv, m.xyz = pr.point;
          ok = is_in(m.uv);
          made.push_back(m);
        }
        if (!ok) continue;
        // (as for the midpoints below: points off the edge's line in (u,v)
        // beside an opening's bend give pieces across the trim)
        bool across = false;
        for (std::size_t j = 0; j <= made.size() && !across; ++j)
          across = trim.crosses(j == 0 ? na : made[j - 1], j == made.size() ? nb : made[j]);
        if (across && !trim.crosses(na, nb))
          for (std::size_t j = 0; j < made.size(); ++j) {
            const double t = double(j + 1) / k;
            made[j].uv = (1 - t) * na.uv + t * nb.uv;
            made[j].xyz = face.point(made[j].uv.x(), made[j].uv.y());
          }
        std::vector<int> ids;
        for (const BdNode& m : made) ids.push_back(add(m));
        inner[key] = ids;
      }
    }
    std::vector<std::vector<int>> todo2;
    for (const auto& p : convex) {
      std::vector<int> q;
      for (std::size_t i = 0; i < p.size(); ++i) {
        const int a = p[i], b = p[(i + 1) % p.size()];
        q.push_back(a);
        auto it = inner.find({std::min(a, b), std::max(a, b)});
        if (it == inner.end()) continue;
        if (a < b)
          q.insert(q.end(), it->second.begin(), it->second.end());
        else
          q.insert(q.end(), it->second.rbegin(), it->second.rend());
      }
      todo2.push_back(std::move(q));
    }
    std::reverse(todo2.begin(), todo2.end());
    convex.clear();
    while (!todo2.empty()) {
      std::vector<int> p = std::move(todo2.back());
      todo2.pop_back();
      std::vector<int> a, b;
      if (split_big_panel(net.nodes, p, trim, a, b)) {
        todo2.push_back(std::move(a));
        todo2.push_back(std::move(b));
      } else {
        convex.push_back(std::move(p));
      }
    }
  }
  net.panels = std::move(convex);
  for (const auto& p : net.panels)
    for (std::size_t i = 0; i < p.size(); ++i) {
      const int a = p[i], b = p[(i + 1) % p.size()];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  // Sides left without a midpoint (face sets' strips along shared edges).
  // A side on the trim (one panel) shorter than short_shared_edge is free:
  // no neighbour needs its midpoint, so it takes whatever its panel's split
  // needs.
  std::set<std::pair<int, int>> bare;
  auto key_of = [](int a, int b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
  enum Split { kFull = -1, kWhole = -2, kMixed = -3 };  // or >= 0: strip across sides i, i + 2
  auto split_of = [&](const std::vector<int>& p) {
    const std::size_t n = p.size();
    std::vector<char> side(n);  // 'B' bare, 'F' free, 'M' midpoint
    bool any_bare = false, all_bare = true;
    for (std::size_t i = 0; i < n; ++i) {
      const int a = p[i], b = p[(i + 1) % n];
      const auto key = key_of(a, b);
      if (bare.count(key)) {
        side[i] = 'B';
      } else if (uses[key] == 1 &&
                 (net.nodes[a].xyz - net.nodes[b].xyz).norm() < short_shared_edge) {
        side[i] = 'F';
      } else {
        side[i] = 'M';
      }
      any_bare = any_bare || side[i] == 'B';
      all_bare = all_bare && side[i] != 'M';
    }
    if (!any_bare) return static_cast<int>(kFull);
    // A strip across sides i and i + 2 (bare or free), the other two (i + 1
    // and i + 3 modulo 4: side 0 for i = 1) not bare. (Read as side[4], a
    // byte past the vector, heap garbage decided for i = 1: a face set's
    // result differed once between two runs.)
    if (n == 4)
      for (int i = 0; i < 2; ++i)
        if (side[i] != 'M' && side[i + 2] != 'M' && side[i + 1] != 'B' && side[(i + 3) % 4] != 'B')
          return i;
    return static_cast<int>(all_bare ? kWhole : kMixed);
  };
  if (short_shared_edge > 0) {
    for (const auto& p : net.panels)
      for (std::size_t i = 0; i < p.size(); ++i) {
        const BdNode& na = net.nodes[p[i]];
        const BdNode& nb = net.nodes[p[(i + 1) % p.size()]];
        if (na.shared != nb.shared && (na.xyz - nb.xyz).norm() < short_shared_edge)
          bare.insert(key_of(p[i], p[(i + 1) % p.size()]));
      }
    // A panel that can keep its bare sides neither as a strip nor whole gives
    // them midpoints, and so its neighbours across them.
    for (bool changed = !bare.empty(); changed;) {
      changed = false;
      for (const auto& p : net.panels) {
        if (split_of(p) != kMixed) continue;
        for (std::size_t i = 0; i < p.size(); ++i)
          changed = bare.erase(key_of(p[i], p[(i + 1) % p.size()])) > 0 || changed;
      }
    }
  }
  std::vector<std::vector<int>> out;
  for (const auto& p : net.panels) {
    const std::size_t n = p.size();
    const int split = short_shared_edge > 0 ? split_of(p) : static_cast<int>(kFull);
    if (split == kWhole) {  // a small piece between shared edges and curves
      out.push_back(p);
      continue;
    }
    if (split >= 0) {
      // p[i] -> p[i+1] and p[i+2] -> p[i+3] bare: cut between the other two
      // sides' midpoints (counter-clockwise kept).
      const int a = p[split], b = p[(split + 1) % 4], c = p[(split + 2) % 4],
                d = p[(split + 3) % 4];
      Vec2 c2 = Vec2::Zero();
      for (int v : p) c2 += 0.25 * net.nodes[v].uv;
      const int m1 = midpoint(b, c, c2), m3 = midpoint(d, a, c2);
      const std::vector<int> q0{a, b, m1, m3}, q1{m3, m1, c, d};
      if (uv_area(net.nodes, q0) > 0 && uv_area(net.nodes, q1) > 0) {
        out.push_back(q0);
        out.push_back(q1);
      } else {
        out.push_back({a, b, m1, c, d, m3});
      }
      continue;
    }
    Vec3 c3 = Vec3::Zero();
    Vec2 c2 = Vec2::Zero();
    for (int v : p) c3 += net.nodes[v].xyz, c2 += net.nodes[v].uv;
    c3 /= double(n), c2 /= double(n);
    BdNode c;
    const Projection pr = face.project(c3, c2);
    c.uv = pr.uv, c.xyz = pr.point;
    double span = 0;  // the panel's largest corner-to-corner distance
    for (int a : p)
      for (int b : p) span = std::max(span, (net.nodes[a].xyz - net.nodes[b].xyz).norm());
    // (As for the midpoints: a centre near a thin cylinder's axis.)
    if (!is_in(c.uv) || !(pr.distance <= kFarFromSurface * span))
      c.uv = c2, c.xyz = face.point(c2.x(), c2.y());
    // A panel beside an opening's bend: its corners' middle may lie in the
    // opening (an interior node 25.9 mm inside a hole, its four quads
    // reaching over it; bench_faces.random_face_set(1058)). A point on the
    // way to a corner instead; with none on the face, the panel keeps its
    // midpoints below (as where no centre sees every corner).
    bool centre_inside = is_in(c.uv);
    for (std::size_t k = 0; k < n && !centre_inside; ++k)
      for (double t : {0.25, 0.5, 0.75}) {
        const Vec2 q = c2 + t * (net.nodes[p[k]].uv - c2);
        if (!is_in(q)) continue;
        c.uv = q, c.xyz = face.point(q.x(), q.y());
        centre_inside = true;
        break;
      }
    const int ci = add(c);
    std::vector<int> m(n);
    for (std::size_t i = 0; i < n; ++i) m[i] = midpoint(p[i], p[(i + 1) % n], c.uv);
    std::vector<std::vector<int>> quads;
    bool folded = !centre_inside;
    for (std::size_t i = 0; i < n; ++i) {
      quads.push_back({p[i], m[i], ci, m[(i + n - 1) % n]});
      folded = folded || !(uv_area(net.nodes, quads.back()) > 0);
      // a spoke across an opening's bend (bd_trim_crossing.h)
      folded = folded || trim.crosses(net.nodes[ci], net.nodes[m[i]]);
    }
    if (!folded) {
      out.insert(out.end(), quads.begin(), quads.end());
    } else {  // no centre sees every corner: keep the panel, with its midpoints
      std::vector<int> poly;
      for (std::size_t i = 0; i < n; ++i) poly.push_back(p[i]), poly.push_back(m[i]);
      out.push_back(std::move(poly));
    }
  }
  net.panels = std::move(out);
}

namespace {

// Who touches whom in the network: neighbours (sorted, unique), incident
// panels, and the previous / next node along a trim loop through trim edges
// (edges used by one panel whose ends lie on the same loop).
struct NodeAdjacency {
  std::vector<std::vector<int>> nbr, incident;
  std::vector<int> prev, next;
};

NodeAdjacency node_adjacency(const BdNetwork& net) {
  const std::size_t nn = net.nodes.size();
  NodeAdjacency adj{std::vector<std::vector<int>>(nn), std::vector<std::vector<int>>(nn),
                    std::vector<int>(nn, -1), std::vector<int>(nn, -1)};
  std::map<std::pair<int, int>, int> uses;
  for (std::size_t pi = 0; pi < net.panels.size(); ++pi) {
    const auto& p = net.panels[pi];
    for (std::size_t i = 0; i < p.size(); ++i) {
      const int a = p[i], b = p[(i + 1) % p.size()];
      ++uses[{std::min(a, b), std::max(a, b)}];
      adj.nbr[a].push_back(b), adj.nbr[b].push_back(a);
      adj.incident[a].push_back(static_cast<int>(pi));
    }
  }
  for (const auto& p : net.panels)
    for (std::size_t i = 0; i < p.size(); ++i) {
      const int a = p[i], b = p[(i + 1) % p.size()];
      if (uses[{std::min(a, b), std::max(a, b)}] == 1 && net.nodes[a].loop >= 0 &&
          net.nodes[a].loop == net.nodes[b].loop)
        adj.next[a] = b, adj.prev[b] = a;
    }
  for (auto& v : adj.nbr) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }
  return adj;
}

// How many edges at v cross a trim (bd_trim_crossing.h); trim edges (v's
// neighbours along its loop), which follow the trim, are not counted. A quad
// at v beside a trim whose two diagonals both cross it counts too: a
// boundary panel is built bent along a diagonal inside it
// (mesh/boundary_pieces.h); with none, it stays a curved piece and unfolds
// as a fan of folds (a hole's rim bulging into the quad, once the angle
// moves slid its trim node round the rim).
int trim_crossings(const BdNetwork& net, const NodeAdjacency& adj, const bd::TrimCrossingTest& trim,
                   int v) {
  int n = 0;
  for (int w : adj.nbr[v])
    if (w != adj.next[v] && w != adj.prev[v] && trim.crosses(net.nodes[v], net.nodes[w])) ++n;
  for (int pi : adj.incident[static_cast<std::size_t>(v)]) {
    const auto& p = net.panels[static_cast<std::size_t>(pi)];
    if (p.size() != 4) continue;
    bool on_trim = false;
    for (int x : p) on_trim = on_trim || net.nodes[static_cast<std::size_t>(x)].loop >= 0;
    if (on_trim && trim.crosses(net.nodes[p[0]], net.nodes[p[2]]) &&
        trim.crosses(net.nodes[p[1]], net.nodes[p[3]]))
      ++n;
  }
  return n;
}

}  // namespace

void smooth_bd_mesh(const SurfaceFace& face, const std::vector<BdPolyline>& boundary,
                    BdNetwork& net, int iterations, double factor) {
  require_in_range("smoothing_iterations", iterations, 0, 1000);
  require_in_range("smoothing factor", factor, 0.0, 1.0);
  const std::size_t nn = net.nodes.size();
  NodeAdjacency adj = node_adjacency(net);
  auto& nbr = adj.nbr;
  auto& incident = adj.incident;
  auto& prev = adj.prev;
  auto& next = adj.next;
  auto folds = [&](int v) {
    for (int pi : incident[v])
      if (uv_area(net.nodes, net.panels[pi]) <= 0) return true;
    return false;
  };
  const UvTrimClassifier inside = bd::make_classifier(boundary);
  const bd::TrimCrossingTest trim(boundary);
  for (int it = 0; it < iterations; ++it) {
    for (std::size_t v = 0; v < nn; ++v) {
      BdNode& n = net.nodes[v];
      if (n.corner || nbr[v].empty()) continue;
      const BdNode old = n;
      if (n.loop >= 0) {
        if (prev[v] < 0 || next[v] < 0) continue;
        const BdPolyline& L = boundary[n.loop];
        const double len = L.length();
        double dp = std::fmod(n.s - net.nodes[prev[v]].s, len),
               dn = std::fmod(net.nodes[next[v]].s - n.s, len);
        if (dp < 0) dp += len;
        if (dn < 0) dn += len;
        double s = n.s + factor * 0.5 * (dn - dp);
        L.segment_at(s);
        n.s = s;
        n.uv = L.uv_at(s);
        n.xyz = face.point(n.uv.x(), n.uv.y());
      } else {
        Vec3 c = Vec3::Zero();
        for (int w : nbr[v]) c += net.nodes[w].xyz;
        c /= double(nbr[v].size());
        const Projection pr = face.project(n.xyz + factor * (c - n.xyz), n.uv);
        if (!inside.contains(pr.uv)) continue;
        n.uv = pr.uv, n.xyz = pr.point;
      }
      if (folds(static_cast<int>(v))) {
        n = old;
      } else if (const int after = trim_crossings(net, adj, trim, static_cast<int>(v)); after > 0) {
        // no more rods across a trim than before (counted only when needed)
        const BdNode moved = n;
        n = old;
        if (after <= trim_crossings(net, adj, trim, static_cast<int>(v))) n = moved;
      }
    }
  }
}

}  // namespace tessella

namespace tessella {

namespace {

// Smallest corner angle (3D, radians) of panel p; an interior corner that is
// reflex in (u,v) counts as 0 (a trim node may be reflex where its trim is
// concave) and a panel folded in (u,v) as -1.
double panel_quality(const std::vector<BdNode>& nodes, const std::vector<int>& p) {
  if (!(uv_area(nodes, p) > 0)) return -1.0;
  const std::size_t n = p.size();
  double q = 1e9;
  for (std::size_t i = 0; i < n; ++i) {
    const BdNode& a = nodes[p[(i + n - 1) % n]];
    const BdNode& b = nodes[p[i]];
    const BdNode& c = nodes[p[(i + 1) % n]];
    if (b.loop < 0 && bd::cross2(b.uv - a.uv, c.uv - b.uv) < 0) return 0.0;
    q = std::min(q, corner_angle(a.xyz, b.xyz, c.xyz));
  }
  return q;
}

// The positions a local move tries for node v: a trim node slides along its
// loop by a share of the way to either trim neighbour (so it stays on the
// trim polyline); an interior node steps toward / away from and square to
// each neighbour in the tangent plane (the (u,v) step solves the same move to
// first order), projected onto the surface and kept inside the trim.
template <class F>
void for_each_move(const SurfaceFace& face, const std::vector<BdPolyline>& boundary,
                   const BdNetwork& net, const NodeAdjacency& adj, const UvTrimClassifier& inside,
                   int v, F&& f) {
  static const double kSteps[] = {0.05, 0.1, 0.2, 0.3, 0.45};
  const BdNode old = net.nodes[static_cast<std::size_t>(v)];
  if (old.loop >= 0) {
    const int pv = adj.prev[static_cast<std::size_t>(v)],
              nv = adj.next[static_cast<std::size_t>(v)];
    if (pv < 0 || nv < 0) return;
    const BdPolyline& L = boundary[static_cast<std::size_t>(old.loop)];
    const double len = L.length();
    double dp = std::fmod(old.s - net.nodes[static_cast<std::size_t>(pv)].s, len),
           dn = std::fmod(net.nodes[static_cast<std::size_t>(nv)].s - old.s, len);
    if (dp < 0) dp += len;
    if (dn < 0) dn += len;
    for (double t : kSteps)
      for (double ds : {t * dn, -t * dp}) {
        BdNode c = old;
        double s = old.s + ds;
        L.segment_at(s);
        c.s = s;
        c.uv = L.uv_at(s);
        c.xyz = face.point(c.uv.x(), c.uv.y());
        f(c);
      }
    return;
  }
  const Vec3 nrm = face.normal(old.uv.x(), old.uv.y());
  for (int w : adj.nbr[static_cast<std::size_t>(v)]) {
    const BdNode& o = net.nodes[static_cast<std::size_t>(w)];
    const Vec3 d = o.xyz - old.xyz;
    const Vec2 duv = o.uv - old.uv;
    const Vec3 dp = nrm.cross(d);
    const Vec2 duvp(-duv.y(), duv.x());  // a quarter turn in (u,v), same sense
    for (double t : kSteps)
      for (double sign : {1.0, -1.0})
        for (int perp = 0; perp < 2; ++perp) {
          const Vec3 x = old.xyz + sign * t * (perp ? dp : d);
          const Vec2 g = old.uv + sign * t * (perp ? duvp : duv);
          const Projection pr = face.project(x, g);
          if (!inside.contains(pr.uv)) continue;
          BdNode c = old;
          c.uv = pr.uv, c.xyz = pr.point;
          f(c);
        }
  }
}

// The point the outline leaves trim node n toward along its trim, forward
// (dir = +1, to the trim neighbour `to`) or backward (-1): the first trim
// polyline point past n that is not n itself, or `to` when that comes first.
// The chord to `to` may leave at a very different angle: a rod nearly
// tangent to a hole's rim makes a spike of the panel only with the trim.
Vec3 along_trim(const std::vector<BdPolyline>& boundary, const BdNode& n, const BdNode& to,
                int dir) {
  const BdPolyline& l = boundary[static_cast<std::size_t>(n.loop)];
  const double len = l.length();
  const std::size_t count = l.xyz.size();
  double s = n.s;
  const int seg = l.segment_at(s);
  double reach = std::fmod(dir * (to.s - s), len);
  if (reach <= 0) reach += len;
  const double tiny = 1e-9 * len;
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t idx = dir > 0 ? (static_cast<std::size_t>(seg) + 1 + k) % count
                                    : (static_cast<std::size_t>(seg) + count - k) % count;
    double gone = std::fmod(dir * (l.arc[idx] - s), len);
    if (gone < 0) gone += len;
    if (gone >= reach) break;
    if ((l.xyz[idx] - n.xyz).norm() > tiny) return l.xyz[idx];
  }
  return to.xyz;
}

// Smallest corner angle (3D, radians) of panel p's outline as follow_trims
// will make it: a side along the trim leaves its trim node along the trim.
double outline_quality(const std::vector<BdNode>& nodes, const std::vector<BdPolyline>& boundary,
                       const NodeAdjacency& adj, const std::vector<int>& p) {
  const std::size_t n = p.size();
  double q = 1e9;
  for (std::size_t i = 0; i < n; ++i) {
    const int a = p[(i + n - 1) % n], b = p[i], c = p[(i + 1) % n];
    const BdNode& nb = nodes[static_cast<std::size_t>(b)];
    const Vec3 in = adj.next[static_cast<std::size_t>(a)] == b
                        ? along_trim(boundary, nb, nodes[static_cast<std::size_t>(a)], -1)
                        : nodes[static_cast<std::size_t>(a)].xyz;
    const Vec3 out = adj.next[static_cast<std::size_t>(b)] == c
                         ? along_trim(boundary, nb, nodes[static_cast<std::size_t>(c)], +1)
                         : nodes[static_cast<std::size_t>(c)].xyz;
    q = std::min(q, corner_angle(in, nb.xyz, out));
  }
  return q;
}

// panel_quality, and the outline's own angles where they are smaller.
double cut_quality(const std::vector<BdNode>& nodes, const std::vector<BdPolyline>& boundary,
                   const NodeAdjacency& adj, const std::vector<int>& p) {
  const double q = panel_quality(nodes, p);
  return q <= 0 ? q : std::min(q, outline_quality(nodes, boundary, adj, p));
}

}  // namespace

int improve_bd_angles(const SurfaceFace& face, const std::vector<BdPolyline>& boundary,
                      BdNetwork& net, double target_deg, int passes) {
  require_in_range("angle target (deg)", target_deg, 0.0, 90.0);
  require_in_range("angle passes", passes, 0, 1000);
  const double target = target_deg * 3.14159265358979323846 / 180.0;
  const std::size_t nn = net.nodes.size();
  NodeAdjacency adj = node_adjacency(net);
  auto& nbr = adj.nbr;
  auto& incident = adj.incident;
  auto& prev = adj.prev;
  auto& next = adj.next;
  const UvTrimClassifier inside = bd::make_classifier(boundary);
  const bd::TrimCrossingTest trim(boundary);
  auto local = [&](int v) {
    double q = 1e9;
    for (int pi : incident[v])
      q = std::min(q, cut_quality(net.nodes, boundary, adj, net.panels[pi]));
    return q;
  };
  // a move may not make an edge at v shorter than 0.3 x the median edge
  // (unless it was already shorter and gets no shorter): no tiny rods
  std::vector<double> lengths;
  for (std::size_t v = 0; v < nn; ++v)
    for (int w : nbr[v])
      if (static_cast<int>(v) < w) lengths.push_back((net.nodes[v].xyz - net.nodes[w].xyz).norm());
  if (lengths.empty()) return 0;
  std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
  const double min_edge = 0.3 * lengths[lengths.size() / 2];
  auto short_edge = [&](int v, const BdNode& old) {
    for (int w : nbr[v]) {
      const double l = (net.nodes[v].xyz - net.nodes[w].xyz).norm();
      if (l < min_edge && l < (old.xyz - net.nodes[w].xyz).norm()) return true;
    }
    return false;
  };
  int moves = 0;
  for (int pass = 0; pass < passes; ++pass) {
    // nodes of the panels with a corner under the target, in index order
    std::vector<char> todo(nn, 0);
    for (const auto& p : net.panels)
      if (cut_quality(net.nodes, boundary, adj, p) < target)
        for (int v : p) todo[v] = 1;
    int moved = 0;
    for (std::size_t vi = 0; vi < nn; ++vi) {
      if (!todo[vi]) continue;
      const int v = static_cast<int>(vi);
      BdNode& n = net.nodes[v];
      if (n.corner || nbr[v].empty()) continue;
      const BdNode old = n;
      double best_q = local(v);
      BdNode best = old;
      int crossings = -1;  // at old, counted when a candidate first needs it
      auto try_node = [&](const BdNode& cand) {
        n = cand;
        // better, not shorter, and no more rods across a trim
        if (!short_edge(v, old)) {
          const double q = local(v);
          if (q > best_q + 1e-9) {
            const int x = trim_crossings(net, adj, trim, v);
            if (x > 0 && crossings < 0) {
              n = old;
              crossings = trim_crossings(net, adj, trim, v);
              n = cand;
            }
            if (x == 0 || x <= crossings) best_q = q, best = cand;
          }
        }
        n = old;
      };
      if (n.loop >= 0 && (prev[v] < 0 || next[v] < 0)) continue;
      for_each_move(face, boundary, net, adj, inside, v, try_node);
      n = best;
      if (best.uv != old.uv) ++moved;
    }
    moves += moved;
    if (moved == 0) break;
  }
  return moves;
}

int untangle_trim_crossings(const SurfaceFace& face, const std::vector<BdPolyline>& boundary,
                            BdNetwork& net, int passes) {
  require_in_range("untangle passes", passes, 0, 1000);
  const std::size_t nn = net.nodes.size();
  const NodeAdjacency adj = node_adjacency(net);
  const UvTrimClassifier inside = bd::make_classifier(boundary);
  const bd::TrimCrossingTest trim(boundary);
  // the panels' smallest angle, -1 when one folds in (u,v)
  auto local = [&](int v) {
    double q = 1e9;
    for (int pi : adj.incident[static_cast<std::size_t>(v)]) {
      const double pq =
          cut_quality(net.nodes, boundary, adj, net.panels[static_cast<std::size_t>(pi)]);
      if (pq < 0) return -1.0;
      q = std::min(q, pq);
    }
    return q;
  };
  int moves = 0;
  for (int pass = 0; pass < passes; ++pass) {
    // both ends of every edge across a trim, in index order
    std::vector<char> todo(nn, 0);
    bool any = false;
    for (std::size_t v = 0; v < nn; ++v)
      if (trim_crossings(net, adj, trim, static_cast<int>(v)) > 0) todo[v] = 1, any = true;
    if (!any) break;
    int moved = 0;
    for (std::size_t vi = 0; vi < nn; ++vi) {
      if (!todo[vi] || net.nodes[vi].corner) continue;
      const int v = static_cast<int>(vi);
      BdNode& n = net.nodes[vi];
      const BdNode old = n;
      int best_x = trim_crossings(net, adj, trim, v);
      if (best_x == 0) continue;  // a move of its neighbour untangled it
      double best_q = -1.0;
      BdNode best = old;
      // fewest crossings first, then the best smallest angle; never a fold
      for_each_move(face, boundary, net, adj, inside, v, [&](BdNode cand) {
        if (cand.loop >= 0) {  // onto the trim's own curve, as the other trim nodes
          cand.uv = face.snap_to_trim(cand.loop, cand.uv);
          cand.xyz = face.point(cand.uv.x(), cand.uv.y());
        }
        n = cand;
        const double q = local(v);
        if (q >= 0) {
          const int x = trim_crossings(net, adj, trim, v);
          if (x < best_x || (x == best_x && best.uv != old.uv && q > best_q))
            best_x = x, best_q = q, best = cand;
        }
        n = old;
      });
      n = best;
      if (best.uv != old.uv) ++moved;
    }
    moves += moved;
    if (moved == 0) break;
  }
  return moves;
}

}  // namespace tessella
