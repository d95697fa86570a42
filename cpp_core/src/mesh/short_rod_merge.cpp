// Collapsing rods shorter than min_rod_length (see short_rod_merge.h).
//
// The stage edits the mesh in place through a small undo log: each candidate
// collapse is applied, checked, scored and rolled back; the best one is then
// applied for good. The mesh boundary (the trim polyline) is the same set of
// directed edges throughout; only which boundary panel owns which piece of it
// changes, so coverage follows from every changed panel staying a simple,
// consistently oriented polygon whose (u,v) areas add up as before.
#include "mesh/short_rod_merge.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <tuple>
#include <utility>

#include "common/parallel_chunks.h"
#include "mesh/panel_model.h"
#include "mesh/seam_sides.h"
#include "tessella/errors.h"
#include "tessella/panel_metrics.h"
#include "tessella/surface_face.h"

namespace tessella {

namespace {

using Edge = std::pair<int, int>;

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

double signed_area(const std::vector<Vec2>& p) {
  double s = 0;
  for (std::size_t k = 0; k < p.size(); ++k) s += cross2(p[k], p[(k + 1) % p.size()]);
  return 0.5 * s;
}

int orient(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double d = cross2(b - a, c - a);
  return (d > 0) - (d < 0);
}

bool on_segment(const Vec2& a, const Vec2& b, const Vec2& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
}

bool segments_meet(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (o1 != o2 && o3 != o4 && o1 != 0 && o2 != 0 && o3 != 0 && o4 != 0) return true;
  if (o1 == 0 && on_segment(a, b, c)) return true;
  if (o2 == 0 && on_segment(a, b, d)) return true;
  if (o3 == 0 && on_segment(c, d, a)) return true;
  if (o4 == 0 && on_segment(c, d, b)) return true;
  return false;
}

// A simple polygon: no two non-adjacent edges meet, no edge doubles back.
bool is_simple(const std::vector<Vec2>& p) {
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 &a = p[(i + n - 1) % n], &b = p[i], &c = p[(i + 1) % n];
    if (orient(a, b, c) == 0 && (a - b).dot(c - b) > 0) return false;
  }
  for (std::size_t i = 0; i < n; ++i) {
    Vec2 lo = p[i].cwiseMin(p[(i + 1) % n]), hi = p[i].cwiseMax(p[(i + 1) % n]);
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;
      const Vec2 &c = p[j], &d = p[(j + 1) % n];
      if (std::max(c.x(), d.x()) < lo.x() || std::min(c.x(), d.x()) > hi.x() ||
          std::max(c.y(), d.y()) < lo.y() || std::min(c.y(), d.y()) > hi.y())
        continue;
      if (segments_meet(p[i], p[(i + 1) % n], c, d)) return false;
    }
  }
  return true;
}

int index_in(const std::vector<int>& poly, int v) {
  const auto it = std::find(poly.begin(), poly.end(), v);
  return it == poly.end() ? -1 : static_cast<int>(it - poly.begin());
}

class Merger {
 public:
  Merger(const SurfaceFace& face, PanelMesh& mesh, const ShortRodMergeParams& params, double limit)
      : face_(face), m_(mesh), params_(params), limit_(limit) {
    const std::size_t nv = m_.vertex_count(), np = m_.panels.size();
    if (m_.is_node.empty()) m_.is_node.assign(nv, 1);
    if (m_.corner_uv.size() != np) {
      m_.corner_uv.resize(np);
      for (std::size_t p = 0; p < np; ++p)
        if (m_.corner_uv[p].size() != m_.panels[p].size()) {
          m_.corner_uv[p].clear();
          for (int v : m_.panels[p]) m_.corner_uv[p].push_back(m_.uv[v]);
        }
    }
    alive_.assign(np, 1);
    closed_ = closed_round_a_seam(face);
    all_quads_ =
        params.keep_quads && std::all_of(m_.panels.begin(), m_.panels.end(),
                                         [](const std::vector<int>& p) { return p.size() == 4; });
    vpanels_.assign(nv, {});
    double total = 0;
    for (std::size_t p = 0; p < np; ++p) {
      add_incidence(static_cast<int>(p));
      total += signed_area(m_.corner_uv[p]);
    }
    sign_ = total < 0 ? -1.0 : 1.0;
    const UvBounds b = face.bounds();
    const double span = std::hypot(b.u_max - b.u_min, b.v_max - b.v_min);
    area_eps_ = 1e-14 * span * span;
    find_boundary();
    find_corners();
  }

  ShortRodMergeReport run() {
    ShortRodMergeReport report;
    report.min_rod_length = limit_;
    std::set<std::tuple<double, int, int>> queue;
    for (std::size_t p = 0; p < m_.panels.size(); ++p) push_short_rods(static_cast<int>(p), queue);
    std::set<std::tuple<double, int, int>> failed;
    while (!queue.empty()) {
      const auto item = *queue.begin();
      queue.erase(queue.begin());
      const int a = std::get<1>(item), b = std::get<2>(item);
      const int ref = rod_panel(a, b);
      if (ref < 0 || length(a, b) >= limit_) continue;  // gone with an earlier collapse
      if (collapse(a, b, ref)) {
        ++report.merged;
        for (int p : last_touched_)
          if (alive_[p]) push_short_rods(p, queue);
        // A neighbour's collapse may have made a refused one possible.
        for (auto it = failed.begin(); it != failed.end();) {
          if (last_vertices_.count(std::get<1>(*it)) || last_vertices_.count(std::get<2>(*it))) {
            queue.insert(*it);
            it = failed.erase(it);
          } else {
            ++it;
          }
        }
      } else {
        failed.insert(item);
      }
    }
    for (const auto& item : failed)
      if (rod_panel(std::get<1>(item), std::get<2>(item)) >= 0) ++report.remaining;
    finish();
    return report;
  }

 private:
  // ---- mesh state -------------------------------------------------------
  void add_incidence(int p) {
    for (int v : m_.panels[p]) {
      auto& list = vpanels_[v];
      if (std::find(list.begin(), list.end(), p) == list.end()) list.push_back(p);
    }
  }
  void remove_incidence(int p) {
    for (int v : m_.panels[p]) {
      auto& list = vpanels_[v];
      list.erase(std::remove(list.begin(), list.end(), p), list.end());
    }
  }
  void assign(int p, std::vector<int> v, std::vector<Vec2> uv) {
    remove_incidence(p);
    m_.panels[p] = std::move(v);
    m_.corner_uv[p] = std::move(uv);
    add_incidence(p);
  }

  struct Saved {
    int panel;
    std::vector<int> v;
    std::vector<Vec2> uv;
    std::vector<Vec3> xyz;
    char alive;
  };
  struct SavedVertex {
    int v;
    Vec2 uv;
    Vec3 xyz;
  };

  void save(int p) {
    if (touched_.count(p)) return;
    touched_.insert(p);
    Saved s{p, m_.panels[p], m_.corner_uv[p], {}, alive_[p]};
    for (int v : s.v) s.xyz.push_back(m_.xyz[v]);
    saved_.push_back(std::move(s));
  }
  void set_panel(int p, std::vector<int> v, std::vector<Vec2> uv) {
    save(p);
    // Drop repeated consecutive corners (a collapsed edge).
    std::vector<int> ids;
    std::vector<Vec2> q;
    for (std::size_t k = 0; k < v.size(); ++k) {
      if (!ids.empty() && ids.back() == v[k]) continue;
      ids.push_back(v[k]);
      q.push_back(uv[k]);
    }
    while (ids.size() > 1 && ids.front() == ids.back()) ids.pop_back(), q.pop_back();
    if (ids.size() < 3) {
      ids.clear();
      q.clear();
      alive_[p] = 0;
    }
    assign(p, std::move(ids), std::move(q));
  }
  void set_node(int v, char flag) {
    saved_nodes_.push_back({v, m_.is_node[v]});
    m_.is_node[v] = flag;
  }
  void set_owner(const Edge& e, int p) {
    saved_owner_.push_back({e, owner_.at(e)});
    owner_[e] = p;
  }
  void move_vertex(int v, const Vec2& uv) {
    saved_vertices_.push_back({v, m_.uv[v], m_.xyz[v]});
    for (int p : std::vector<int>(vpanels_[v])) save(p);
    const Vec2 delta = uv - m_.uv[v];
    for (int p : std::vector<int>(vpanels_[v])) {
      std::vector<Vec2> q = m_.corner_uv[p];
      for (std::size_t k = 0; k < q.size(); ++k)
        if (m_.panels[p][k] == v) q[k] += delta;
      m_.corner_uv[p] = q;
    }
    m_.uv[v] = uv;
    m_.xyz[v] = face_.point(uv.x(), uv.y());
  }
  void rollback() {
    for (auto it = saved_.rbegin(); it != saved_.rend(); ++it) {
      assign(it->panel, it->v, it->uv);
      alive_[it->panel] = it->alive;
    }
    for (auto it = saved_nodes_.rbegin(); it != saved_nodes_.rend(); ++it)
      m_.is_node[it->first] = it->second;
    for (auto it = saved_owner_.rbegin(); it != saved_owner_.rend(); ++it)
      owner_[it->first] = it->second;
    for (auto it = saved_vertices_.rbegin(); it != saved_vertices_.rend(); ++it) {
      m_.uv[it->v] = it->uv;
      m_.xyz[it->v] = it->xyz;
    }
    forget();
    pending_alias_.clear();
  }
  void forget() {
    saved_.clear();
    saved_nodes_.clear();
    saved_owner_.clear();
    saved_vertices_.clear();
    touched_.clear();
  }

  Vec2 uv_in(int p, int v) const {
    return m_.corner_uv[p][static_cast<std::size_t>(index_in(m_.panels[p], v))];
  }
  bool node(int v) const { return m_.is_node[v] != 0; }

  // ---- boundary ---------------------------------------------------------
  void find_boundary() {
    // Every directed panel side with the last panel that has it, in edge
    // order: a sorted array, not a map of ~4 entries a panel (the map was
    // most of the merge's set-up).
    std::vector<std::pair<Edge, int>> directed;
    for (std::size_t p = 0; p < m_.panels.size(); ++p) {
      const auto& poly = m_.panels[p];
      for (std::size_t k = 0; k < poly.size(); ++k)
        directed.push_back({{poly[k], poly[(k + 1) % poly.size()]}, static_cast<int>(p)});
    }
    // Equal edges keep their order (panels ascending), so the last is the
    // one a map assigned last.
    std::stable_sort(directed.begin(), directed.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    std::size_t kept = 0;
    for (std::size_t i = 0; i < directed.size(); ++i) {
      if (i + 1 < directed.size() && directed[i + 1].first == directed[i].first) continue;
      directed[kept++] = directed[i];
    }
    directed.resize(kept);
    auto has = [&](const Edge& e) {
      const auto it = std::lower_bound(directed.begin(), directed.end(), e,
                                       [](const auto& x, const Edge& y) { return x.first < y; });
      return it != directed.end() && it->first == e;
    };
    const std::size_t nv = m_.vertex_count();
    next_.assign(nv, -1);
    prev_.assign(nv, -1);
    fixed_.assign(nv, 0);
    for (const auto& [e, p] : directed) {
      if (has({e.second, e.first})) continue;
      owner_[e] = p;
      next_[e.first] = next_[e.first] == -1 ? e.second : -2;
      prev_[e.second] = prev_[e.second] == -1 ? e.first : -2;
    }
    // A vertex where two boundary loops touch is never moved nor passed.
    for (std::size_t v = 0; v < nv; ++v)
      if (next_[v] == -2 || prev_[v] == -2 || (next_[v] == -1) != (prev_[v] == -1)) fixed_[v] = 1;
  }
  bool on_boundary(int v) const { return next_[v] != -1 || prev_[v] != -1; }

  void find_corners() {
    const double size = face_.model_size();
    const double tol = 1e-6 * size;
    std::vector<Vec3> corners;
    for (const TrimLoop& loop : face_.trim_loops(1e-3 * size))
      for (std::size_t k = 0; k < loop.xyz.size(); ++k)
        if (loop.corner[k]) corners.push_back(loop.xyz[k]);
    corner_.assign(m_.vertex_count(), 0);
    for (std::size_t v = 0; v < m_.vertex_count(); ++v) {
      if (!on_boundary(static_cast<int>(v))) continue;
      if (fixed_[v]) corner_[v] = 1;
      for (const Vec3& c : corners)
        if ((m_.xyz[v] - c).norm() <= tol) corner_[v] = 1;
    }
  }

  // The chain of boundary vertices from x (forward: along the boundary
  // edges' direction) up to the next node, x first; empty if it passes a
  // fixed vertex or runs round the loop.
  std::vector<int> chain(int x, bool forward) const {
    std::vector<int> out{x};
    int v = x;
    for (std::size_t guard = 0; guard <= m_.vertex_count(); ++guard) {
      v = forward ? next_[v] : prev_[v];
      if (v < 0 || v == x) return {};
      out.push_back(v);
      if (node(v)) return out;
      if (fixed_[v]) return {};
    }
    return {};
  }

  // ---- rods -------------------------------------------------------------
  std::vector<int> nodes_of(int p) const {
    std::vector<int> out;
    for (int v : m_.panels[p])
      if (node(v)) out.push_back(v);
    return out;
  }
  double length(int a, int b) const { return (m_.xyz[a] - m_.xyz[b]).norm(); }
  void push_short_rods(int p, std::set<std::tuple<double, int, int>>& queue) const {
    const std::vector<int> n = nodes_of(p);
    if (n.size() < 2) return;
    for (std::size_t k = 0; k < n.size(); ++k) {
      const int a = std::min(n[k], n[(k + 1) % n.size()]),
                b = std::max(n[k], n[(k + 1) % n.size()]);
      if (a == b) continue;
      const double len = length(a, b);
      if (len < limit_) queue.insert({len, a, b});
    }
  }
  // A live panel in which a and b are consecutive nodes (-1: no such rod).
  int rod_panel(int a, int b) const {
    if (!node(a) || !node(b)) return -1;
    for (int p : vpanels_[a]) {
      if (!alive_[p]) continue;
      const std::vector<int> n = nodes_of(p);
      for (std::size_t k = 0; k < n.size(); ++k) {
        const int x = n[k], y = n[(k + 1) % n.size()];
        if ((x == a && y == b) || (x == b && y == a)) return p;
      }
    }
    return -1;
  }
  // Shortest rod of the touched live panels (the score of a collapse).
  double shortest_touched() const {
    double best = std::numeric_limits<double>::infinity();
    for (int p : touched_) {
      if (!alive_[p]) continue;
      const std::vector<int> n = nodes_of(p);
      if (n.size() < 2) continue;
      for (std::size_t k = 0; k < n.size(); ++k)
        if (n[k] != n[(k + 1) % n.size()])
          best = std::min(best, length(n[k], n[(k + 1) % n.size()]));
    }
    return best;
  }

  // ---- primitive operations (logged) --------------------------------------
  // Interior node g joins node k: every panel of g uses k instead.
  bool move_onto(int g, int k, int ref) {
    const Vec2 delta = uv_in(ref, k) - uv_in(ref, g);
    for (int p : std::vector<int>(vpanels_[g])) {
      std::vector<int> v = m_.panels[p];
      std::vector<Vec2> q = m_.corner_uv[p];
      const int has_k = index_in(v, k);
      for (std::size_t i = 0; i < v.size(); ++i) {
        if (v[i] != g) continue;
        q[i] = has_k >= 0 ? q[static_cast<std::size_t>(has_k)] : Vec2(q[i] + delta);
        v[i] = k;
      }
      set_panel(p, std::move(v), std::move(q));
    }
    pending_alias_.push_back({g, k});
    return true;
  }

  // Trim node x moves along the trim to vertex y (forward or backward, past
  // outline points only) and becomes an outline point; y becomes the node.
  // The outline points between them go to the boundary panel on x's other
  // side.
  bool chain_move(int x, int y, bool forward) {
    if (fixed_[x]) return false;
    const std::vector<int> full = chain(x, forward);
    if (full.empty()) return false;
    const auto end = std::find(full.begin(), full.end(), y);
    if (end == full.end() || end == full.begin()) return false;
    const std::vector<int> path(full.begin(), end + 1);  // x ... y
    auto edge = [&](std::size_t t) {
      return forward ? Edge{path[t], path[t + 1]} : Edge{path[t + 1], path[t]};
    };
    const int p1 = owner_.at(edge(0));
    for (std::size_t t = 1; t + 1 < path.size(); ++t)
      if (owner_.at(edge(t)) != p1) return false;
    const Edge other = forward ? Edge{prev_[x], x} : Edge{x, next_[x]};
    if (other.first < 0 || other.second < 0) return false;
    const int p2 = owner_.at(other);
    if (p1 == p2 || !alive_[p1] || !alive_[p2]) return false;
    const Vec2 delta_y = uv_in(p1, y) - uv_in(p1, x);
    const Vec2 delta_2 = uv_in(p2, x) - uv_in(p1, x);
    // p1 loses x and the points up to y.
    {
      std::vector<int> v;
      std::vector<Vec2> q;
      const auto& pv = m_.panels[p1];
      const auto& pq = m_.corner_uv[p1];
      std::set<int> gone(path.begin(), path.end() - 1);
      for (std::size_t i = 0; i < pv.size(); ++i)
        if (!gone.count(pv[i])) v.push_back(pv[i]), q.push_back(pq[i]);
      std::vector<Vec2> path_uv;
      for (int c : path) path_uv.push_back(uv_in(p1, c) + delta_2);
      set_panel(p1, std::move(v), std::move(q));
      // p2 gains them on x's far side (x stays in p2 as an outline point).
      std::vector<int> v2 = m_.panels[p2];
      std::vector<Vec2> q2 = m_.corner_uv[p2];
      const int i = index_in(v2, x);
      if (forward) {
        v2.insert(v2.begin() + i + 1, path.begin() + 1, path.end());
        q2.insert(q2.begin() + i + 1, path_uv.begin() + 1, path_uv.end());
      } else {
        v2.insert(v2.begin() + i, path.rbegin(), path.rend() - 1);
        q2.insert(q2.begin() + i, path_uv.rbegin(), path_uv.rend() - 1);
      }
      set_panel(p2, std::move(v2), std::move(q2));
    }
    // The other panels at x use y instead.
    for (int p : std::vector<int>(vpanels_[x])) {
      if (p == p1 || p == p2) continue;
      std::vector<int> v = m_.panels[p];
      std::vector<Vec2> q = m_.corner_uv[p];
      const int has_y = index_in(v, y);
      for (std::size_t i = 0; i < v.size(); ++i) {
        if (v[i] != x) continue;
        q[i] = has_y >= 0 ? q[static_cast<std::size_t>(has_y)] : Vec2(q[i] + delta_y);
        v[i] = y;
      }
      set_panel(p, std::move(v), std::move(q));
    }
    for (std::size_t t = 0; t + 1 < path.size(); ++t) set_owner(edge(t), p2);
    set_node(x, 0);
    set_node(y, 1);
    pending_alias_.push_back({x, y});
    return true;
  }

  // Two-node panels left by a collapse (a sliver between a chord and the
  // trim): their other trim node joins the survivor along the trim.
  bool repair(int survivor) {
    for (int round = 0; round < 4; ++round) {
      int bad = -1;
      for (int p : touched_)
        if (alive_[p] && nodes_of(p).size() < std::min<std::size_t>(3, nodes_before(p))) bad = p;
      if (bad < 0) return true;
      const std::vector<int> n = nodes_of(bad);
      if (n.size() != 2) return false;
      int keep = n[0] == survivor ? n[0] : n[1], give = n[0] == survivor ? n[1] : n[0];
      if (corner_[give] && !corner_[keep]) std::swap(keep, give);
      if (!on_boundary(give) || !on_boundary(keep)) return false;
      const std::vector<int> f = chain(give, true), b = chain(give, false);
      if (!f.empty() && f.back() == keep) {
        if (!chain_move(give, keep, true)) return false;
      } else if (!b.empty() && b.back() == keep) {
        if (!chain_move(give, keep, false)) return false;
      } else {
        return false;
      }
      if (!fix_owners()) return false;
    }
    return false;
  }

  // Whether v was a node before the candidate being tried.
  bool was_node(int v) const {
    for (const auto& [w, flag] : saved_nodes_)
      if (w == v) return flag != 0;
    return node(v);
  }
  std::size_t nodes_before(int p) const {
    for (const Saved& s : saved_)
      if (s.panel == p) {
        std::size_t n = 0;
        for (int v : s.v) n += was_node(v) ? 1 : 0;
        return n;
      }
    return nodes_of(p).size();
  }

  // After a step: each boundary edge the touched panels had goes to the live
  // panel that has it now; none may be lost.
  bool has_edge(int p, int a, int b) const {
    const auto& v = m_.panels[p];
    const int i = index_in(v, a);
    return alive_[p] && i >= 0 && v[(static_cast<std::size_t>(i) + 1) % v.size()] == b;
  }
  bool fix_owners() {
    for (std::size_t s = 0; s < saved_.size(); ++s) {
      const std::vector<int> old = saved_[s].v;  // (saved_ may grow below)
      for (std::size_t k = 0; k < old.size(); ++k) {
        const Edge e{old[k], old[(k + 1) % old.size()]};
        const auto it = owner_.find(e);
        if (it == owner_.end() || has_edge(it->second, e.first, e.second)) continue;
        int found = -1;
        for (int p : vpanels_[e.first])
          if (has_edge(p, e.first, e.second)) found = p;
        if (found < 0) return false;
        set_owner(e, found);
      }
    }
    return true;
  }

  // ---- checks -------------------------------------------------------------
  // The largest deviation of the panels with these corners, each as
  // measure_panels measures it (its model, its samples, in a span-cached
  // scope as its calling thread opens one), without the other metrics, the
  // rods and a progress stage for each candidate. A panel's figure depends
  // on its corners alone and is kept: the candidates of a rod measure the
  // same panels before it again and again (walking_agent, whose panels sit
  // near its bound).
  //
  // Panels not yet measured are measured on every thread where there are
  // several and one of them is modelled as pieces (a boundary panel costs
  // about ten quads; walking_agent's merge was 13% of the dome's time on
  // two threads, all of it on one): a worker evaluates in a scope of its own, as the
  // metrics' workers do, so the figures are the same on any thread count.
  double deviation_of(const std::vector<std::vector<Vec2>>& uv,
                      const std::vector<std::vector<Vec3>>& xyz) const {
    std::vector<std::vector<double>> keys(uv.size());
    std::vector<std::size_t> missing;
    for (std::size_t p = 0; p < uv.size(); ++p) {
      for (std::size_t k = 0; k < uv[p].size(); ++k)
        keys[p].insert(keys[p].end(),
                       {uv[p][k].x(), uv[p][k].y(), xyz[p][k].x(), xyz[p][k].y(), xyz[p][k].z()});
      if (!measured_.count(keys[p]) &&
          std::find_if(missing.begin(), missing.end(),
                       [&](std::size_t m) { return keys[m] == keys[p]; }) == missing.end())
        missing.push_back(p);
    }
    std::vector<double> figure(missing.size());
    auto measure = [&](std::size_t i) {
      const std::size_t p = missing[i];
      PanelMesh one;
      one.xyz = xyz[p];
      one.uv = uv[p];
      one.corner_uv.push_back(uv[p]);
      one.panels.emplace_back();
      for (std::size_t k = 0; k < uv[p].size(); ++k) one.panels.back().push_back(int(k));
      figure[i] = measure_panel_deviation(face_, xyz[p], uv[p], panel_model_triangles(one, 0),
                                          params_.samples)
                      .value;
    };
    const bool heavy = std::any_of(missing.begin(), missing.end(),
                                   [&](std::size_t p) { return uv[p].size() > 4; });
    const int threads = missing.size() > 1 && heavy ? worker_threads() : 1;
    ChunkQueue queue(missing.size(), 1);
    if (!missing.empty())
      run_chunks(queue, threads, [&](bool calling) {
        std::optional<SurfaceFace::FastEvaluation> fast;
        if (!calling || !SurfaceFace::FastEvaluation::active(face_)) fast.emplace(face_, !calling);
        std::size_t begin = 0, end = 0;
        while (queue.next(begin, end))
          for (std::size_t i = begin; i < end; ++i) measure(i);
      });
    for (std::size_t i = 0; i < missing.size(); ++i) measured_.emplace(keys[missing[i]], figure[i]);
    double worst = 0;
    for (std::size_t p = 0; p < uv.size(); ++p) {
      const double d = measured_.at(keys[p]);
      if (p == 0 || d > worst) worst = d;
    }
    return worst;
  }

  // Why a collapse is refused (kept for reading; a debugger can break here).
  void why(const char* /*reason*/, int /*panel*/) const {}
  // Whether the applied collapse leaves a valid mesh, the deviation bound
  // aside (deviation_kept).
  bool valid() const {
    double before = 0, after = 0, scale = 0;
    for (const Saved& s : saved_) {
      if (!s.alive) continue;
      before += sign_ * signed_area(s.uv);
      scale += std::abs(signed_area(s.uv));
    }
    for (int p : touched_) {
      if (!alive_[p]) continue;
      const auto& v = m_.panels[p];
      const auto& q = m_.corner_uv[p];
      std::vector<int> sorted = v;
      std::sort(sorted.begin(), sorted.end());
      if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
        return why("repeated vertex", p), false;
      const double a = sign_ * signed_area(q);
      if (a <= area_eps_) return why("orientation", p), false;
      after += a;
      if (!is_simple(q)) return why("not simple", p), false;
      // A quad is modelled as the bilinear patch of its corners, which folds
      // over unless the quad is convex.
      if (q.size() == 4)
        for (std::size_t k = 0; k < 4; ++k)
          if (sign_ * cross2(q[(k + 1) % 4] - q[k], q[(k + 2) % 4] - q[(k + 1) % 4]) <= 0)
            return why("quad not convex", p), false;
      // An all-quad layout stays one (keep_quads).
      if (all_quads_ && v.size() != 4) return why("not a quad", p), false;
      // No panel half way round a closed face (a cone's top rim of three
      // short rods collapsed to two: a panel turning 240 degrees).
      if (closed_ && panel_turn(face_, q) >= 0.5 - 1e-9) return why("half way round", p), false;
      if (nodes_of(p).size() < std::min<std::size_t>(3, nodes_before(p)))
        return why("nodes", p), false;
      for (std::size_t k = 0; k < v.size(); ++k) {
        const int x = v[k], y = v[(k + 1) % v.size()];
        bool twin = owner_.count({x, y}) > 0;
        for (int o : vpanels_[y]) twin = twin || (o != p && has_edge(o, y, x));
        if (!twin) return why("gap", p), false;
        for (int o : vpanels_[x]) {
          if (o == p || !alive_[o]) continue;
          const auto& w = m_.panels[o];
          const int i = index_in(w, x);
          if (w[(static_cast<std::size_t>(i) + 1) % w.size()] == y)
            return why("edge twice", p), false;
        }
      }
    }
    if (std::abs(after - before) > 1e-9 * scale + area_eps_) return why("area", -1), false;
    return true;
  }
  // Whether the applied collapse keeps the deviation bound: no changed panel
  // over it, or none worse than the panels it replaces.
  bool deviation_kept() const {
    if (params_.max_deviation > 0) {
      std::vector<std::vector<Vec2>> ub, ua;
      std::vector<std::vector<Vec3>> xb, xa;
      for (const Saved& s : saved_)
        if (s.alive) ub.push_back(s.uv), xb.push_back(s.xyz);
      for (int p : touched_) {
        if (!alive_[p]) continue;
        ua.push_back(m_.corner_uv[p]);
        std::vector<Vec3> x;
        for (int v : m_.panels[p]) x.push_back(m_.xyz[v]);
        xa.push_back(std::move(x));
      }
      const double dev = deviation_of(ua, xa);
      if (dev > params_.max_deviation && dev > deviation_of(ub, xb) * (1 + 1e-9))
        return why("deviation", -1), false;
    }
    return true;
  }

  // ---- one rod ------------------------------------------------------------
  // Candidate collapses of rod (a, b): a list of primitive steps. rank: 0
  // keeps every trim corner and crossing, 1 moves both to a trim point
  // between, 2 gives up a trim corner.
  struct Candidate {
    int rank = 0;
    int survivor = -1;
    std::vector<std::tuple<int, int, int, int>> steps;  // (kind, x, y, ref/forward)
  };
  enum { kMoveOnto = 0, kChain = 1, kMoveTo = 2, kDemote = 3 };
  int live_panels(int v) const {
    int n = 0;
    for (int p : vpanels_[v]) n += alive_[p] ? 1 : 0;
    return n;
  }

  std::vector<Candidate> candidates(int a, int b, int ref) const {
    std::vector<Candidate> out;
    const bool ba = on_boundary(a), bb = on_boundary(b);
    if (!ba && !bb) {
      out.push_back({0, b, {{kMoveOnto, a, b, ref}}});
      out.push_back({0, a, {{kMoveOnto, b, a, ref}}});
      out.push_back({0, b, {{kMoveTo, b, a, ref}, {kMoveOnto, a, b, ref}}});
      return out;
    }
    if (ba != bb) {
      const int g = ba ? b : a, k = ba ? a : b;
      out.push_back({0, k, {{kMoveOnto, g, k, ref}}});
      return out;
    }
    // Both on the trim: only neighbours along it.
    int x = -1, y = -1;
    std::vector<int> path = chain(a, true);
    if (!path.empty() && path.back() == b) {
      x = a, y = b;
    } else {
      path = chain(b, true);
      if (path.empty() || path.back() != a) return out;
      x = b, y = a;
    }
    const int rx = corner_[x] ? 2 : 0, ry = corner_[y] ? 2 : 0;
    out.push_back({rx, y, {{kChain, x, y, 1}}});
    out.push_back({ry, x, {{kChain, y, x, 0}}});
    // A trim node only one panel uses (no rod leaves it inwards, e.g. where a
    // sliver was merged away) simply stops being a node.
    if (live_panels(x) == 1) out.push_back({rx, y, {{kDemote, x, -1, 0}}});
    if (live_panels(y) == 1) out.push_back({ry, x, {{kDemote, y, -1, 0}}});
    // Trim points between (a few, evenly spread).
    const std::size_t inner = path.size() - 2;
    const std::size_t picks = std::min<std::size_t>(inner, 7);
    for (std::size_t k = 1; k <= picks; ++k) {
      const int o = path[k * (inner + 1) / (picks + 1)];
      out.push_back({std::max(1, std::max(rx, ry)), o, {{kChain, x, o, 1}, {kChain, y, o, 0}}});
    }
    return out;
  }

  bool apply(const Candidate& c) {
    for (const auto& [kind, x, y, arg] : c.steps) {
      if (kind == kMoveOnto) {
        if (!node(x) || !node(y)) return false;
        const int ref = rod_panel(x, y) >= 0 ? rod_panel(x, y) : arg;
        if (index_in(m_.panels[ref], x) < 0 || index_in(m_.panels[ref], y) < 0) return false;
        if (!move_onto(x, y, ref)) return false;
      } else if (kind == kChain) {
        if (!chain_move(x, y, arg != 0)) return false;
      } else if (kind == kDemote) {
        if (fixed_[x] || live_panels(x) != 1) return false;
        for (int p : vpanels_[x]) save(p);
        set_node(x, 0);
      } else {
        const Vec2 mid = 0.5 * (uv_in(arg, x) + uv_in(arg, y));
        move_vertex(x, m_.uv[x] + (mid - uv_in(arg, x)));
      }
      if (!fix_owners()) return false;
    }
    return repair(c.survivor);
  }

  bool collapse(int a, int b, int ref) {
    const std::vector<Candidate> cands = candidates(a, b, ref);
    // The valid candidates, best first (ties: the earlier); the deviation
    // bound, which measures the changed panels (walking_agent: two thirds
    // of this stage's time when every candidate was measured), is checked
    // in that order until one keeps it: the same winner.
    using Key = std::tuple<int, int, double>;
    std::vector<std::pair<Key, int>> valid_ones;
    for (std::size_t i = 0; i < cands.size(); ++i) {
      const bool ok = apply(cands[i]) && valid();
      const double score = ok ? shortest_touched() : 0.0;
      rollback();
      if (ok) valid_ones.push_back({Key{score >= limit_ ? 1 : 0, -cands[i].rank, score}, int(i)});
    }
    std::stable_sort(valid_ones.begin(), valid_ones.end(),
                     [](const auto& x, const auto& y) { return x.first > y.first; });
    int best = -1;
    for (const auto& [key, i] : valid_ones) {
      if (params_.max_deviation > 0) {
        apply(cands[std::size_t(i)]);
        const bool kept = deviation_kept();
        rollback();
        if (!kept) continue;
      }
      best = i;
      break;
    }
    if (best < 0) return false;
    apply(cands[static_cast<std::size_t>(best)]);
    last_touched_.assign(touched_.begin(), touched_.end());
    last_vertices_.clear();
    for (const Saved& s : saved_) last_vertices_.insert(s.v.begin(), s.v.end());
    alias_.insert(alias_.end(), pending_alias_.begin(), pending_alias_.end());
    pending_alias_.clear();
    forget();
    return true;
  }

  // ---- the end --------------------------------------------------------------
  void finish() {
    // Folds: renamed through the merges, kept where two live triangles share them.
    std::map<int, int> to;
    for (const auto& [from, into] : alias_) to[from] = into;
    auto resolve = [&](int v) {
      for (std::size_t guard = 0; guard < alias_.size() + 1; ++guard) {
        const auto it = to.find(v);
        if (it == to.end()) break;
        v = it->second;
      }
      return v;
    };
    auto triangles_on = [&](int x, int y) {
      int n = 0;
      for (int p : vpanels_[x]) {
        const auto& v = m_.panels[p];
        if (!alive_[p] || v.size() != 3) continue;
        const int i = index_in(v, x);
        if (v[(i + 1) % 3] == y || v[(i + 2) % 3] == y) ++n;
      }
      return n;
    };
    std::vector<std::array<int, 2>> folds;
    for (const auto& f : m_.folds) {
      for (const std::array<int, 2>& g : {f, std::array<int, 2>{resolve(f[0]), resolve(f[1])}}) {
        if (g[0] == g[1] || triangles_on(g[0], g[1]) != 2) continue;
        folds.push_back({std::min(g[0], g[1]), std::max(g[0], g[1])});
        break;
      }
    }
    std::sort(folds.begin(), folds.end());
    folds.erase(std::unique(folds.begin(), folds.end()), folds.end());
    // Keep the methods' fold order where nothing changed.
    std::vector<std::array<int, 2>> ordered;
    for (const auto& f : m_.folds) {
      std::array<int, 2> g{std::min(f[0], f[1]), std::max(f[0], f[1])};
      if (std::binary_search(folds.begin(), folds.end(), g) &&
          std::find(ordered.begin(), ordered.end(), g) == ordered.end())
        ordered.push_back(g);
    }
    for (const auto& g : folds)
      if (std::find(ordered.begin(), ordered.end(), g) == ordered.end()) ordered.push_back(g);
    m_.folds = std::move(ordered);

    std::vector<std::vector<int>> panels;
    std::vector<std::vector<Vec2>> corner_uv;
    for (std::size_t p = 0; p < m_.panels.size(); ++p) {
      if (!alive_[p]) continue;
      panels.push_back(std::move(m_.panels[p]));
      corner_uv.push_back(std::move(m_.corner_uv[p]));
    }
    m_.panels = std::move(panels);
    m_.corner_uv = std::move(corner_uv);
    remove_unused_vertices(m_);
  }

  const SurfaceFace& face_;
  PanelMesh& m_;
  ShortRodMergeParams params_;
  double limit_;
  double sign_ = 1.0;
  bool all_quads_ = false;
  double area_eps_ = 0.0;
  bool closed_ = false;  // the face is closed round a seam
  std::vector<char> alive_;
  std::vector<std::vector<int>> vpanels_;
  std::map<Edge, int> owner_;  // boundary edge -> the panel that has it
  std::vector<int> next_, prev_;
  std::vector<char> fixed_, corner_;
  // undo log of the candidate being tried
  std::vector<Saved> saved_;
  std::set<int> touched_;
  std::vector<std::pair<int, char>> saved_nodes_;
  std::vector<std::pair<Edge, int>> saved_owner_;
  std::vector<SavedVertex> saved_vertices_;
  std::vector<std::pair<int, int>> pending_alias_, alias_;
  std::vector<int> last_touched_;
  std::set<int> last_vertices_;
  // deviation_of's figures by panel corners ((u, v, x, y, z) each).
  mutable std::map<std::vector<double>, double> measured_;
};

}  // namespace

double automatic_min_rod_length(const PanelMesh& mesh) {
  if (mesh.nominal_area > 0) return 0.25 * std::sqrt(mesh.nominal_area);
  std::vector<double> lengths;
  for (const auto& r : mesh.rods) lengths.push_back((mesh.xyz[r[0]] - mesh.xyz[r[1]]).norm());
  if (lengths.empty()) return 0.0;
  std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
  return 0.25 * lengths[lengths.size() / 2];
}

ShortRodMergeReport merge_short_rods(const SurfaceFace& face, PanelMesh& mesh,
                                     const ShortRodMergeParams& params) {
  require_in_range("min_rod_length (mm)", params.min_rod_length, 0.0, 1e9);
  require_in_range("max_deviation (mm)", params.max_deviation, 0.0, 1e9);
  const double limit =
      params.min_rod_length > 0 ? params.min_rod_length : automatic_min_rod_length(mesh);
  ShortRodMergeReport report;
  report.min_rod_length = limit;
  if (limit <= 0 || mesh.panels.empty()) return report;
  bool any = false;
  if (mesh.rods.empty()) build_rods(mesh);
  for (const auto& r : mesh.rods) any = any || (mesh.xyz[r[0]] - mesh.xyz[r[1]]).norm() < limit;
  if (!any) return report;
  const bool had_corner_uv = !mesh.corner_uv.empty();
  const bool had_nodes = !mesh.is_node.empty();
  Merger merger(face, mesh, params, limit);
  report = merger.run();
  if (!had_corner_uv) {
    bool same = true;
    for (std::size_t p = 0; p < mesh.panels.size() && same; ++p)
      for (std::size_t k = 0; k < mesh.panels[p].size() && same; ++k)
        same = mesh.corner_uv[p][k] == mesh.uv[mesh.panels[p][k]];
    if (same) mesh.corner_uv.clear();
  }
  if (!had_nodes &&
      std::all_of(mesh.is_node.begin(), mesh.is_node.end(), [](char c) { return c != 0; }))
    mesh.is_node.clear();
  build_rods(mesh);
  return report;
}

}  // namespace tessella
