#include "faceset/aligned_grid_lines.h"

#include <Geom2d_Curve.hxx>
#include <algorithm>
#include <array>
#include <cmath>
#include <deque>

#include "faceset/smooth_groups.h"
#include "mesh/pinned_lines.h"

namespace tessella {

namespace {

// An edge the lines continue across: per side, the coordinate (0: u, 1: v)
// that varies along it, i.e. the lines crossing it are that coordinate's.
struct Crossing {
  std::size_t shared = 0;
  std::array<int, 2> along{};
};

double coordinate(const Handle(Geom2d_Curve) & c, double t, int k) {
  const gp_Pnt2d q = c->Value(t);
  return k == 0 ? q.X() : q.Y();
}

// The coordinate of pcurve `side` of e that varies along it, if the other is
// constant (an iso-line: 9 points within 1e-9 of the face's span); -1 if
// neither is.
int varying_coordinate(const SharedEdge& e, int side, const UvBounds& b) {
  const Handle(Geom2d_Curve)& c = e.pcurve[static_cast<std::size_t>(side)];
  for (int k = 0; k < 2; ++k) {
    const double span = k == 0 ? b.u_max - b.u_min : b.v_max - b.v_min;
    const double c0 = coordinate(c, e.first, k);
    bool constant = true;
    for (int s = 1; s <= 8 && constant; ++s)
      constant =
          std::abs(coordinate(c, e.first + (e.last - e.first) * s / 8.0, k) - c0) <= 1e-9 * span;
    if (constant) return 1 - k;
  }
  return -1;
}

// The edge parameter at which coordinate k of curve c equals x (c's
// coordinate runs monotonically along the edge), or NaN outside its span.
double parameter_at(const Handle(Geom2d_Curve) & c, int k, double first, double last, double x,
                    double eps) {
  double lo = first, hi = last;
  double flo = coordinate(c, lo, k) - x, fhi = coordinate(c, hi, k) - x;
  if (std::abs(flo) <= eps) return lo;
  if (std::abs(fhi) <= eps) return hi;
  if ((flo > 0) == (fhi > 0)) return std::nan("");
  for (int i = 0; i < 100 && hi - lo > 1e-15 * std::max(1.0, std::abs(last - first)); ++i) {
    const double mid = 0.5 * (lo + hi);
    const double fm = coordinate(c, mid, k) - x;
    if ((fm > 0) == (flo > 0))
      lo = mid, flo = fm;
    else
      hi = mid, fhi = fm;
  }
  return std::abs(flo) <= std::abs(fhi) ? lo : hi;
}

// `from`'s lines carried over into `to`'s lines `mine` (bounds lo, hi):
// the carried values within the bounds (none closer to a bound than a
// quarter of `mine`'s spacing but on it), and `mine` beyond their span (each
// at least half its spacing away from it), the bounds first and last.
std::vector<double> merge_lines(std::vector<double> carried, const std::vector<double>& mine,
                                double lo, double hi) {
  const double eps = 1e-9 * (hi - lo);
  const double spacing = (hi - lo) / std::max<double>(1.0, double(mine.size()) - 1.0);
  std::vector<double> kept;
  for (double x : carried) {
    if (x < lo - eps || x > hi + eps) continue;
    // A line a sliver's width inside a bound (the edge ending a little
    // short of the face's corner) would make a column of slivers.
    const bool at_bound = x - lo <= eps || hi - x <= eps;
    if (!at_bound && (x - lo < 0.25 * spacing || hi - x < 0.25 * spacing)) continue;
    kept.push_back(std::clamp(x, lo, hi));
  }
  if (kept.empty()) return mine;
  std::sort(kept.begin(), kept.end());
  const double a = kept.front(), b = kept.back();
  for (double x : mine)
    if (x < a - 0.5 * spacing || x > b + 0.5 * spacing) kept.push_back(x);
  kept.push_back(lo);
  kept.push_back(hi);
  std::sort(kept.begin(), kept.end());
  return increasing_lines(kept, lo, hi);
}

// Whether the face's (u,v) has a pole on its boundary (a trim stretch
// collapsed to one point in 3D: a sphere's corner patch on a filleted box):
// lines carried into it converge there, and its panels' straight (u,v)
// sides cut off more of it than its own lines' do (a flattened corner patch
// lost 10% of its area against 3%). It keeps its own lines.
bool has_pole(const SurfaceFace& face) {
  const double tiny = 1e-9 * face.model_size();
  for (const TrimLoop& loop : face.trim_loops(1e-3 * face.model_size()))
    for (std::size_t i = 0; i < loop.uv.size(); ++i) {
      const std::size_t j = (i + 1) % loop.uv.size();
      if ((loop.xyz[i] - loop.xyz[j]).norm() <= tiny && (loop.uv[i] - loop.uv[j]).norm() > 0)
        return true;
    }
  return false;
}

}  // namespace

std::vector<GridLines> align_grid_lines(const FaceSet::Impl& set, std::vector<GridLines> own,
                                        const std::vector<int>& surface,
                                        std::vector<char>* aligned) {
  const std::size_t n = set.faces.size();
  if (aligned) aligned->assign(n, 0);
  if (own.size() != n || n < 2) return own;
  // The edges: iso-lines on both sides, the faces meeting tangentially.
  std::vector<int> pole(n, -1);  // computed once per face, when asked
  auto pole_in = [&](int f) {
    int& p = pole[static_cast<std::size_t>(f)];
    if (p < 0) p = has_pole(*set.faces[static_cast<std::size_t>(f)]) ? 1 : 0;
    return p == 1;
  };
  std::vector<Crossing> crossings;
  std::vector<std::vector<std::size_t>> at(n);
  for (std::size_t e = 0; e < set.shared.size(); ++e) {
    const SharedEdge& s = set.shared[e];
    if (s.faces[0] == s.faces[1]) continue;
    const int ga = static_cast<std::size_t>(s.faces[0]) < surface.size() ? surface[s.faces[0]] : -1;
    const int gb = static_cast<std::size_t>(s.faces[1]) < surface.size() ? surface[s.faces[1]] : -1;
    if (ga >= 0 && ga == gb) continue;
    const SurfaceFace& a = *set.faces[static_cast<std::size_t>(s.faces[0])];
    const SurfaceFace& b = *set.faces[static_cast<std::size_t>(s.faces[1])];
    const int ka = varying_coordinate(s, 0, a.bounds()), kb = varying_coordinate(s, 1, b.bounds());
    if (ka < 0 || kb < 0 || !meets_tangentially(s, a, b) || pole_in(s.faces[0]) ||
        pole_in(s.faces[1]))
      continue;
    at[static_cast<std::size_t>(s.faces[0])].push_back(crossings.size());
    at[static_cast<std::size_t>(s.faces[1])].push_back(crossings.size());
    crossings.push_back({e, {ka, kb}});
  }
  if (crossings.empty()) return own;
  auto lines_of = [&](std::size_t f, int k) -> std::vector<double>& {
    return k == 0 ? own[f].u : own[f].v;
  };
  std::vector<std::array<char, 2>> fixed(n, {0, 0});
  std::vector<char> visited(n, 0);
  std::vector<std::size_t> order(n);
  for (std::size_t f = 0; f < n; ++f) order[f] = f;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
    return set.faces[x]->area() > set.faces[y]->area();
  });
  for (std::size_t root : order) {
    if (visited[root] || at[root].empty()) continue;
    visited[root] = 1;
    std::deque<std::size_t> queue{root};
    while (!queue.empty()) {
      const std::size_t f = queue.front();
      queue.pop_front();
      for (std::size_t c : at[f]) {
        const Crossing& x = crossings[c];
        const SharedEdge& s = set.shared[x.shared];
        const int side = static_cast<std::size_t>(s.faces[0]) == f ? 0 : 1;
        const std::size_t g = static_cast<std::size_t>(s.faces[static_cast<std::size_t>(1 - side)]);
        const int kf = x.along[static_cast<std::size_t>(side)];
        const int kg = x.along[static_cast<std::size_t>(1 - side)];
        if (fixed[g][static_cast<std::size_t>(kg)]) continue;
        const Handle(Geom2d_Curve)& cf = s.pcurve[static_cast<std::size_t>(side)];
        const Handle(Geom2d_Curve)& cg = s.pcurve[static_cast<std::size_t>(1 - side)];
        const UvBounds bf = set.faces[f]->bounds(), bg = set.faces[g]->bounds();
        const double span_f = kf == 0 ? bf.u_max - bf.u_min : bf.v_max - bf.v_min;
        std::vector<double> carried;
        for (double value : lines_of(f, kf)) {
          const double t = parameter_at(cf, kf, s.first, s.last, value, 1e-9 * span_f);
          if (std::isfinite(t)) carried.push_back(coordinate(cg, t, kg));
        }
        const double lo = kg == 0 ? bg.u_min : bg.v_min, hi = kg == 0 ? bg.u_max : bg.v_max;
        lines_of(g, kg) = merge_lines(std::move(carried), lines_of(g, kg), lo, hi);
        fixed[f][static_cast<std::size_t>(kf)] = 1;
        fixed[g][static_cast<std::size_t>(kg)] = 1;
        if (aligned) (*aligned)[g] = 1;
        if (!visited[g]) {
          visited[g] = 1;
          queue.push_back(g);
        }
      }
    }
  }
  return own;
}

}  // namespace tessella
