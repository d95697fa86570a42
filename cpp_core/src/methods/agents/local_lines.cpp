#include "methods/agents/local_lines.h"

#include <algorithm>
#include <array>
#include <map>

namespace tessella::agents {

namespace {

// A rectangle of grid cells [i0, i1) x [j0, j1), one panel.
struct Rect {
  int i0, i1, j0, j1;
  bool alive = true;
};

// Index of x in the sorted lines if it is one of them exactly, else -1.
int line_index(const std::vector<double>& lines, double x) {
  const auto it = std::lower_bound(lines.begin(), lines.end(), x);
  return it != lines.end() && *it == x ? static_cast<int>(it - lines.begin()) : -1;
}

class CellLayout {
 public:
  CellLayout(const PanelMesh& mesh, const std::vector<double>& us, const std::vector<double>& vs,
             const std::vector<char>& folded)
      : us_(us), vs_(vs), nu_(int(us.size()) - 1), nv_(int(vs.size()) - 1) {
    const std::size_t points = std::size_t(nu_ + 1) * (nv_ + 1);
    vertex_.assign(points, -1);
    permanent_.assign(points, 0);
    corners_.assign(points, 0);
    cell_rect_.assign(std::size_t(nu_) * nv_, -1);
    rect_of_panel_.assign(mesh.panels.size(), -1);
    for (std::size_t p = 0; p < mesh.panels.size(); ++p) {
      const std::vector<Vec2> q = panel_corner_uv(mesh, p);
      std::vector<std::array<int, 2>> g;
      for (const Vec2& c : q) g.push_back({line_index(us, c.x()), line_index(vs, c.y())});
      const auto& panel = mesh.panels[p];
      bool whole = panel.size() == 4 && !folded[p];
      for (std::size_t k = 0; k < panel.size() && whole; ++k)
        whole = g[k][0] >= 0 && g[k][1] >= 0 && tessella::is_node(mesh, panel[k]);
      if (whole) {
        // The cell's corners in clip_grid's order: (i,j), (i+1,j), (i+1,j+1), (i,j+1).
        const int i = g[0][0], j = g[0][1];
        whole = i < nu_ && j < nv_ && g[1] == std::array<int, 2>{i + 1, j} &&
                g[2] == std::array<int, 2>{i + 1, j + 1} && g[3] == std::array<int, 2>{i, j + 1} &&
                cell_rect_[cell(i, j)] < 0;
      }
      if (!whole) {
        // A panel that stays: its grid-point corners stay nodes.
        for (std::size_t k = 0; k < panel.size(); ++k)
          if (g[k][0] >= 0 && g[k][1] >= 0 && tessella::is_node(mesh, panel[k])) {
            permanent_[point(g[k][0], g[k][1])] = 1;
            vertex_[point(g[k][0], g[k][1])] = panel[k];
          }
        continue;
      }
      const int i = g[0][0], j = g[0][1];
      for (std::size_t k = 0; k < 4; ++k) vertex_[point(g[k][0], g[k][1])] = panel[k];
      rect_of_panel_[p] = int(rects_.size());
      cell_rect_[cell(i, j)] = int(rects_.size());
      rects_.push_back({i, i + 1, j, j + 1});
      count_corners(rects_.back(), +1);
    }
    // Grid points that are one vertex (a periodic face's seam: the first and
    // last line meet) stay nodes: a merge on one side must not drop a node
    // the cells on the other side still have as a corner.
    std::map<int, int> first_point;
    for (std::size_t g = 0; g < vertex_.size(); ++g) {
      if (vertex_[g] < 0) continue;
      const auto [it, fresh] = first_point.emplace(vertex_[g], int(g));
      if (!fresh) permanent_[g] = permanent_[std::size_t(it->second)] = 1;
    }
  }

  std::size_t rect_count() const { return rects_.size(); }
  const Rect& rect(std::size_t r) const { return rects_[r]; }
  int rect_of_panel(std::size_t p) const { return rect_of_panel_[p]; }

  // Grid points on r's outline that are nodes, counter-clockwise from (i0, j0).
  std::vector<std::array<int, 2>> outline(const Rect& r) const {
    std::vector<std::array<int, 2>> out;
    auto add = [&](int i, int j) {
      if (is_node(i, j)) out.push_back({i, j});
    };
    for (int i = r.i0; i < r.i1; ++i) add(i, r.j0);
    for (int j = r.j0; j < r.j1; ++j) add(r.i1, j);
    for (int i = r.i1; i > r.i0; --i) add(i, r.j1);
    for (int j = r.j1; j > r.j0; --j) add(r.i0, j);
    return out;
  }
  int vertex(const std::array<int, 2>& g) const { return vertex_[point(g[0], g[1])]; }
  Vec2 uv(const std::array<int, 2>& g) const { return {us_[g[0]], vs_[g[1]]}; }

  // The pairs that would merge across vertical grid line L (dir 0) or
  // horizontal line L (dir 1), walking along it from cell index `from`: the
  // rectangle on each side must share the whole side segment. Stops at the
  // first place where they do not.
  std::vector<std::array<int, 2>> pairs_along(int dir, int line, int from) const {
    std::vector<std::array<int, 2>> out;
    const int end = dir == 0 ? nv_ : nu_;
    for (int k = from; k < end;) {
      const int lo = dir == 0 ? cell_rect_at(line - 1, k) : cell_rect_at(k, line - 1);
      const int hi = dir == 0 ? cell_rect_at(line, k) : cell_rect_at(k, line);
      if (lo < 0 || hi < 0 || lo == hi) break;
      const Rect &a = rects_[lo], &b = rects_[hi];
      const bool fits = dir == 0 ? (a.i1 == line && b.i0 == line && a.j0 == b.j0 && a.j1 == b.j1)
                                 : (a.j1 == line && b.j0 == line && a.i0 == b.i0 && a.i1 == b.i1);
      if (!fits || (dir == 0 ? a.j0 : a.i0) != k) break;
      out.push_back({lo, hi});
      k = dir == 0 ? a.j1 : a.i1;
    }
    return out;
  }
  int cells_u() const { return nu_; }
  int cells_v() const { return nv_; }

  // Merges every pair (a line stopped for that stretch) if `holds` accepts
  // every merged outline (at most `max_corners` corners) and every outline
  // that loses a node by it; else leaves the layout as it was.
  bool try_merge(const std::vector<std::array<int, 2>>& pairs,
                 const std::function<bool(const Rect&)>& holds, int max_corners) {
    std::vector<Rect> merged;
    for (const auto& [r, s] : pairs) {
      const Rect &a = rects_[r], &b = rects_[s];
      merged.push_back(
          {std::min(a.i0, b.i0), std::max(a.i1, b.i1), std::min(a.j0, b.j0), std::max(a.j1, b.j1)});
    }
    auto apply = [&](int sign) {
      for (std::size_t k = 0; k < pairs.size(); ++k) {
        count_corners(rects_[pairs[k][0]], -sign);
        count_corners(rects_[pairs[k][1]], -sign);
        count_corners(merged[k], sign);
      }
    };
    apply(+1);
    // Worth it only if it saves at least as many panels as the triangles it
    // makes where the line ends (a stretch of n pairs: 2n panels -> n, plus
    // one for each end split into a triangle and a quad): quad-dominant.
    int triangles = 0;
    for (const Rect& m : merged) triangles += outline(m).size() == 5 ? 1 : 0;
    bool ok = int(pairs.size()) >= 2 * triangles;
    for (const Rect& m : merged) ok = ok && int(outline(m).size()) <= max_corners && holds(m);
    // The rectangles round every point that stopped being a node lose it.
    std::vector<int> touched;
    for (std::size_t k = 0; k < pairs.size() && ok; ++k)
      for (int side : pairs[k]) {
        const Rect& x = rects_[side];
        for (const auto& [i, j] :
             {std::array<int, 2>{x.i0, x.j0}, {x.i1, x.j0}, {x.i1, x.j1}, {x.i0, x.j1}}) {
          if (is_node(i, j)) continue;
          for (int di = -1; di <= 0; ++di)
            for (int dj = -1; dj <= 0; ++dj) {
              const int t = cell_rect_at(i + di, j + dj);
              bool in_run = false;
              for (const auto& p : pairs) in_run = in_run || t == p[0] || t == p[1];
              if (t >= 0 && !in_run &&
                  std::find(touched.begin(), touched.end(), t) == touched.end())
                touched.push_back(t);
            }
        }
      }
    std::sort(touched.begin(), touched.end());
    for (int t : touched) ok = ok && holds(rects_[t]);
    if (!ok) {
      apply(-1);
      return false;
    }
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const Rect b = rects_[pairs[k][1]];
      rects_[pairs[k][0]] = merged[k];
      rects_[pairs[k][1]].alive = false;
      for (int i = b.i0; i < b.i1; ++i)
        for (int j = b.j0; j < b.j1; ++j) cell_rect_[cell(i, j)] = pairs[k][0];
    }
    return true;
  }

 private:
  std::size_t point(int i, int j) const { return std::size_t(j) * (nu_ + 1) + i; }
  std::size_t cell(int i, int j) const { return std::size_t(j) * nu_ + i; }
  int cell_rect_at(int i, int j) const {
    if (i < 0 || j < 0 || i >= nu_ || j >= nv_) return -1;
    return cell_rect_[cell(i, j)];
  }
  bool is_node(int i, int j) const { return permanent_[point(i, j)] || corners_[point(i, j)] > 0; }
  void count_corners(const Rect& r, int delta) {
    for (const auto& [i, j] :
         {std::array<int, 2>{r.i0, r.j0}, {r.i1, r.j0}, {r.i1, r.j1}, {r.i0, r.j1}})
      corners_[point(i, j)] += delta;
  }

  const std::vector<double>& us_;
  const std::vector<double>& vs_;
  int nu_, nv_;
  std::vector<int> vertex_;      // per grid point: its vertex in the mesh, -1 none
  std::vector<char> permanent_;  // per grid point: a corner of a panel that stays
  std::vector<int> corners_;     // per grid point: rectangles it is a corner of
  std::vector<int> cell_rect_;   // per cell: its rectangle, -1 not a merged cell
  std::vector<int> rect_of_panel_;
  std::vector<Rect> rects_;
};

// Removes the vertices no panel uses, renumbering panels and folds.
void drop_unused_vertices(PanelMesh& mesh) {
  std::vector<int> map(mesh.xyz.size(), -1);
  for (const auto& panel : mesh.panels)
    for (int v : panel) map[v] = 0;
  int next = 0;
  for (std::size_t v = 0; v < map.size(); ++v)
    if (map[v] == 0) map[v] = next++;
  if (next == int(map.size())) return;
  std::vector<Vec2> uv(next);
  std::vector<Vec3> xyz(next);
  std::vector<char> node(mesh.is_node.empty() ? 0 : next);
  for (std::size_t v = 0; v < map.size(); ++v) {
    if (map[v] < 0) continue;
    uv[map[v]] = mesh.uv[v];
    xyz[map[v]] = mesh.xyz[v];
    if (!node.empty()) node[map[v]] = mesh.is_node[v];
  }
  mesh.uv = std::move(uv);
  mesh.xyz = std::move(xyz);
  mesh.is_node = std::move(node);
  for (auto& panel : mesh.panels)
    for (int& v : panel) v = map[v];
  for (auto& f : mesh.folds) f = {map[f[0]], map[f[1]]};
}

}  // namespace

int stop_lines_early(PanelMesh& mesh, const std::vector<double>& u_lines,
                     const std::vector<double>& v_lines,
                     std::vector<std::pair<std::size_t, int>>& folds, const OutlineCheck& holds,
                     int max_corners) {
  if (u_lines.size() < 3 && v_lines.size() < 3) return 0;
  std::vector<char> folded(mesh.panels.size(), 0);
  for (const auto& f : folds) folded[f.first] = 1;
  CellLayout layout(mesh, u_lines, v_lines, folded);
  // The panels a rectangle becomes (outline indices): itself if a quad; a
  // rectangle with a line's end node on one side (five corners), a triangle
  // at that node and a quad, split the first way that holds the bound (no
  // panel of five corners: its model would be bent pieces); none if it does
  // not hold.
  auto split_outline = [&](const Rect& r, const std::vector<std::array<int, 2>>& outline) {
    const int n = int(outline.size());
    std::vector<std::vector<int>> none;
    auto check = [&](const std::vector<int>& part) {
      std::vector<Vec3> x;
      std::vector<Vec2> q;
      for (int k : part) {
        x.push_back(mesh.xyz[layout.vertex(outline[k])]);
        q.push_back(layout.uv(outline[k]));
      }
      double longest = 0;
      for (std::size_t k = 0; k < x.size(); ++k)
        longest = std::max(longest, (x[(k + 1) % x.size()] - x[k]).norm());
      return holds(x, q, longest);
    };
    if (n == 4) return check({0, 1, 2, 3}) ? std::vector<std::vector<int>>{{0, 1, 2, 3}} : none;
    if (n != 5) return none;
    int t = 0;  // the end node: the corner that is not a corner of the rectangle
    for (int k = 0; k < n; ++k) {
      const auto& g = outline[k];
      if (!((g[0] == r.i0 || g[0] == r.i1) && (g[1] == r.j0 || g[1] == r.j1))) t = k;
    }
    const int a = (t + 1) % n, b = (t + 2) % n, c = (t + 3) % n, d = (t + 4) % n;
    for (const auto& split : {std::vector<std::vector<int>>{{t, a, b}, {d, t, b, c}},
                              std::vector<std::vector<int>>{{d, t, c}, {t, a, b, c}}})
      if (check(split[0]) && check(split[1])) return split;
    return none;
  };
  // The answers depend on the outline's grid points alone (the geometry does
  // not change): remembered, so a stretch that failed is not estimated again
  // on the next pass (OCCT's terrain at sqrt(area) / 12: the method took
  // 26 s without, 6 s with; 7 s with lines across the face).
  std::map<std::vector<std::array<int, 2>>, std::vector<std::vector<int>>> known;
  auto panels_of = [&](const Rect& r) {
    const std::vector<std::array<int, 2>> outline = layout.outline(r);
    const auto hit = known.find(outline);
    if (hit != known.end()) return hit->second;
    return known[outline] = split_outline(r, outline);
  };
  auto rect_holds = [&](const Rect& r) { return !panels_of(r).empty(); };
  // The four corners alone: a pair whose merged quad does not hold splits a
  // stretch (the merged panels there are quads, or a quad and a triangle).
  std::map<std::array<int, 4>, bool> quads;
  auto quad_holds = [&](const Rect& r) {
    const std::array<int, 4> key{r.i0, r.i1, r.j0, r.j1};
    const auto hit = quads.find(key);
    if (hit != quads.end()) return hit->second;
    const std::vector<std::array<int, 2>> corners{
        {r.i0, r.j0}, {r.i1, r.j0}, {r.i1, r.j1}, {r.i0, r.j1}};
    std::vector<Vec3> x;
    std::vector<Vec2> q;
    for (const auto& g : corners) {
      x.push_back(mesh.xyz[layout.vertex(g)]);
      q.push_back(layout.uv(g));
    }
    double longest = 0;
    for (std::size_t k = 0; k < 4; ++k) longest = std::max(longest, (x[(k + 1) % 4] - x[k]).norm());
    return quads[key] = holds(x, q, longest);
  };
  // Passes over the grid lines (u lines, then v lines; the other way round on
  // odd passes, so neither direction's lines are always the ones kept): along
  // each, every maximal stretch where the cells on both sides can merge is
  // tried whole, then shortened from its ends, down to two cells (a single
  // cell would leave a panel of six corners).
  int merges = 0;
  for (int pass = 0; pass < 64; ++pass) {
    int merged = 0;
    for (int k = 0; k < 2; ++k) {
      const int dir = (k + pass) % 2;
      const int lines = dir == 0 ? layout.cells_u() : layout.cells_v();
      const int along = dir == 0 ? layout.cells_v() : layout.cells_u();
      for (int line = 1; line < lines; ++line) {
        for (int from = 0; from < along;) {
          const std::vector<std::array<int, 2>> run = layout.pairs_along(dir, line, from);
          if (run.size() < 2) {
            ++from;
            continue;
          }
          // The stretch cut where a pair's merged quad does not hold; each
          // piece tried whole, then shortened from its ends (at most 16 tries).
          bool done = false;
          for (std::size_t a = 0; a < run.size() && !done;) {
            std::size_t b = a;
            while (b < run.size()) {
              const Rect &lo = layout.rect(run[b][0]), &hi = layout.rect(run[b][1]);
              if (!quad_holds({std::min(lo.i0, hi.i0), std::max(lo.i1, hi.i1),
                               std::min(lo.j0, hi.j0), std::max(lo.j1, hi.j1)}))
                break;
              ++b;
            }
            int tries = 0;
            for (std::size_t len = b - a; len >= 2 && !done && tries < 16; --len)
              for (std::size_t first = a; first + len <= b && !done && tries < 16;
                   ++first, ++tries) {
                const std::vector<std::array<int, 2>> part(run.begin() + first,
                                                           run.begin() + first + len);
                done = layout.try_merge(part, rect_holds, max_corners);
              }
            a = b + 1;
          }
          if (done) ++merged;
          // On past this stretch (merged or not).
          const Rect& last = layout.rect(run.back()[0]);
          from = std::max(from + 1, dir == 0 ? last.j1 : last.i1);
        }
      }
    }
    merges += merged;
    if (merged == 0) break;
  }
  if (merges == 0) return 0;
  // The panels: those that stay in their order, each merged rectangle in its
  // first cell's place.
  std::vector<std::vector<int>> panels;
  std::vector<std::vector<Vec2>> corner_uv;
  std::vector<int> new_index(mesh.panels.size(), -1);
  for (std::size_t p = 0; p < mesh.panels.size(); ++p) {
    const int r = layout.rect_of_panel(p);
    if (r >= 0 && !layout.rect(r).alive) continue;
    new_index[p] = int(panels.size());
    if (r < 0) {
      panels.push_back(mesh.panels[p]);
      if (!mesh.corner_uv.empty()) corner_uv.push_back(mesh.corner_uv[p]);
      continue;
    }
    const std::vector<std::array<int, 2>> outline = layout.outline(layout.rect(r));
    std::vector<std::vector<int>> parts = panels_of(layout.rect(r));
    // A cell never merged is kept as the method made it (it held the
    // method's own bound; the check here may differ by a margin).
    if (parts.empty()) {
      parts.emplace_back(outline.size());
      for (std::size_t k = 0; k < outline.size(); ++k) parts.back()[k] = int(k);
    }
    for (const std::vector<int>& part : parts) {
      std::vector<int> panel;
      std::vector<Vec2> q;
      for (int k : part) {
        panel.push_back(layout.vertex(outline[k]));
        q.push_back(layout.uv(outline[k]));
      }
      panels.push_back(std::move(panel));
      if (!mesh.corner_uv.empty()) corner_uv.push_back(std::move(q));
    }
  }
  mesh.panels = std::move(panels);
  if (!mesh.corner_uv.empty()) mesh.corner_uv = std::move(corner_uv);
  for (auto& f : folds) f.first = static_cast<std::size_t>(new_index[f.first]);
  drop_unused_vertices(mesh);
  build_rods(mesh);
  return merges;
}

}  // namespace tessella::agents
