#include "tessella/walking_agent.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include "mesh/grid_clipping.h"
#include "mesh/panel_model.h"
#include "mesh/pinned_lines.h"
#include "mesh/seam_sides.h"
#include "methods/agents/agent_walk.h"
#include "methods/agents/local_lines.h"
#include "tessella/errors.h"
#include "tessella/surface_face.h"

namespace tessella {

namespace {

using agents::RowAgents;

// The panel bound is checked against this share of max_deviation, leaving
// room for what a denser, independent sampling finds between our samples.
constexpr double kBoundMargin = 0.98;
constexpr int kPanelSamples = 6;  // per quad side; per triangle side

void check_clip(const GridClipParams& p) {
  require_in_range("max_panels", p.max_panels, 1, 1e8);
  require_in_range("sliver_fraction", p.sliver_fraction, 0.0, 1.0);
  require_in_range("trim_deflection", p.trim_deflection, 0.0, 1e9);
}

void check_common(const SurfaceFace& face, double max_deviation, double sample_step) {
  if (max_deviation == 0.0) throw InvalidParameter("max_deviation (mm) is required");
  require_in_range("max_deviation (mm)", max_deviation, 1e-6 * face.model_size(), 1e9);
  require_in_range("sample_step (fraction of the parameter span)", sample_step, 1e-3, 0.5);
}

// The u lines and v lines the agents place (u_from_min etc. from `start`).
struct Lines {
  std::vector<double> u, v;
};

using Walker1D = std::function<std::vector<double>(RowAgents&, double, double, double)>;

// Runs one walker family per direction from the start (a corner, or the point
// of largest curvature, from which it walks both ways).
Lines walk_lines(const SurfaceFace& face, const UvTrimClassifier& trim, double sample_step,
                 const std::string& start, const Walker1D& walker) {
  const agents::StartSpec s = agents::parse_start(start);
  const UvBounds b = face.bounds();
  const int rows = std::max(2, static_cast<int>(std::ceil(1.0 / sample_step)));
  Lines lines;
  for (int dir = 0; dir < 2; ++dir) {
    const double lo = dir == 0 ? b.u_min : b.v_min, hi = dir == 0 ? b.u_max : b.v_max;
    const double clo = dir == 0 ? b.v_min : b.u_min, chi = dir == 0 ? b.v_max : b.u_max;
    const double step = sample_step * (hi - lo);
    RowAgents agents(face, trim, dir, agents::even_rows(clo, chi, rows));
    std::vector<double> nodes;
    if (s.max_curvature) {
      const Vec2 p = agents::max_curvature_point(face, trim, sample_step);
      const double mid = std::clamp(p[dir], lo, hi);
      std::vector<double> up = walker(agents, mid, hi, step);
      RowAgents back(face, trim, dir, agents.rows());
      nodes = agents::merge_walks(std::move(up), walker(back, mid, lo, step));
      // The start is a node of both walks (a sample node, so it is either on
      // the border or at least one sample step inside: no sliver strip).
    } else {
      const bool from_min = dir == 0 ? s.u_from_min : s.v_from_min;
      nodes = walker(agents, from_min ? lo : hi, from_min ? hi : lo, step);
      std::sort(nodes.begin(), nodes.end());
    }
    // Keep strictly increasing lines; the ends exactly on the bounds.
    std::vector<double>& l = dir == 0 ? lines.u : lines.v;
    l = increasing_lines(nodes, lo, hi);
    // At least the cells a grid takes (three round a closed direction, two
    // between two poles), none half way round, lines through the widest
    // cells: with one or two round, corners joined across the whole face (a
    // 300 mm column at a bound of 300 mm was 100% uncovered; a sphere at one
    // cell pole to pole 157%).
    const bool closed = closed_along(face, dir);
    const std::size_t fewest = static_cast<std::size_t>(fewest_cells_along(face, dir == 0));
    while (l.size() >= 2) {
      std::size_t widest = 0;
      for (std::size_t k = 1; k + 1 < l.size(); ++k)
        if (l[k + 1] - l[k] > l[widest + 1] - l[widest]) widest = k;
      if (l.size() > fewest && (!closed || l[widest + 1] - l[widest] < 0.5 * (hi - lo))) break;
      l.insert(l.begin() + static_cast<std::ptrdiff_t>(widest) + 1,
               0.5 * (l[widest] + l[widest + 1]));
    }
  }
  return lines;
}

// Adds a value strictly between existing neighbours (ignores near duplicates).
bool insert_line(std::vector<double>& lines, double x) {
  auto it = std::lower_bound(lines.begin(), lines.end(), x);
  const double span = lines.back() - lines.front();
  if (it != lines.end() && std::abs(*it - x) <= 1e-9 * span) return false;
  if (it != lines.begin() && std::abs(*(it - 1) - x) <= 1e-9 * span) return false;
  lines.insert(it, x);
  return true;
}

// The diagonal walkers: from each edge node along the cell diagonals; a cell
// whose diagonal chord deviation is over the bound gets a line through its
// middle (across its longer side). Returns the number of lines added.
int diagonal_walkers(const SurfaceFace& face, const UvTrimClassifier& trim, Lines& lines,
                     double bound, int max_panels) {
  int added = 0;
  for (int round = 0; round < 20; ++round) {
    const std::size_t nu = lines.u.size(), nv = lines.v.size();
    if (double(nu - 1) * double(nv - 1) > max_panels) break;  // clip_grid will refuse
    std::vector<Vec3> P(nu * nv);
    for (std::size_t j = 0; j < nv; ++j)
      for (std::size_t i = 0; i < nu; ++i) P[j * nu + i] = face.point(lines.u[i], lines.v[j]);
    std::vector<double> new_u, new_v;
    for (std::size_t j = 0; j + 1 < nv; ++j) {
      const std::vector<double> x =
          agents::row_crossings(face, trim, 0, 0.5 * (lines.v[j] + lines.v[j + 1]));
      for (std::size_t i = 0; i + 1 < nu; ++i) {
        const double um = 0.5 * (lines.u[i] + lines.u[i + 1]);
        const double vm = 0.5 * (lines.v[j] + lines.v[j + 1]);
        // Cells wholly outside the face (on their middle row) do not matter.
        const auto lo = std::lower_bound(x.begin(), x.end(), lines.u[i]) - x.begin();
        const auto hi = std::lower_bound(x.begin(), x.end(), lines.u[i + 1]) - x.begin();
        if (lo == hi && lo % 2 == 0) continue;
        const Vec3& p00 = P[j * nu + i];
        const Vec3& p10 = P[j * nu + i + 1];
        const Vec3& p01 = P[(j + 1) * nu + i];
        const Vec3& p11 = P[(j + 1) * nu + i + 1];
        const Vec2 q00(lines.u[i], lines.v[j]), q11(lines.u[i + 1], lines.v[j + 1]);
        const Vec2 q10(lines.u[i + 1], lines.v[j]), q01(lines.u[i], lines.v[j + 1]);
        const double d = std::max(agents::path_deviation(face, q00, q11, p00, p11),
                                  agents::path_deviation(face, q10, q01, p10, p01));
        if (d <= bound) continue;
        const double lu = 0.5 * ((p10 - p00).norm() + (p11 - p01).norm());
        const double lv = 0.5 * ((p01 - p00).norm() + (p11 - p10).norm());
        (lu >= lv ? new_u : new_v).push_back(lu >= lv ? um : vm);
      }
    }
    int round_added = 0;
    for (double x : new_u) round_added += insert_line(lines.u, x);
    for (double x : new_v) round_added += insert_line(lines.v, x);
    added += round_added;
    if (round_added == 0) break;
  }
  return added;
}

// Distance from a model point x (at model parameter uv) to the surface, as the
// panel check needs it: the distance to the surface point at the same (u,v)
// (an upper bound, one evaluation); only where that is over `limit`, the
// distance to the closest surface point (Newton projection from uv) - the
// smaller of the two, both being upper bounds of the true distance. Samples
// under the limit cannot change the decision, so they are not projected.
// Where Newton and its local retry fail, the first bound stands: a global
// search (0.05-0.1 s a call on OCCT's 312 x 323-pole terrain, thousands of
// calls) would only ever lower it, so it is skipped.
struct Gauge {
  const SurfaceFace& face;
  double limit;
  double operator()(const Vec3& x, const Vec2& uv) const {
    const double d = (face.point(uv.x(), uv.y()) - x).norm();
    if (d <= limit) return d;
    ProjectionParams local;
    local.local_search = true;
    local.global_search = false;
    return std::min(d, face.project(x, uv, local).distance);
  }
};

// The panel estimates below are the largest gauge over a sample grid of the
// panel model; once one sample is over the limit they return at once (a
// value over the limit, not the maximum: only "over or not" is used then).
double flat_triangle_estimate(const Gauge& gauge, const Vec3* p, const Vec2* q,
                              int n = kPanelSamples) {
  double worst = 0;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; i + j <= n; ++j) {
      if ((i == 0 && j == 0) || i == n || j == n) continue;  // corners lie on the surface
      const double s = double(i) / n, r = double(j) / n, t = 1 - s - r;
      const Vec2 uv = t * q[0] + s * q[1] + r * q[2];
      const Vec3 x = t * p[0] + s * p[1] + r * p[2];
      worst = std::max(worst, gauge(x, uv));
      if (worst > gauge.limit) return worst;
    }
  }
  return worst;
}

double bilinear_estimate(const Gauge& gauge, const std::vector<Vec3>& p,
                         const std::vector<Vec2>& q) {
  double worst = 0;
  const int n = kPanelSamples;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      if ((i == 0 || i == n) && (j == 0 || j == n)) continue;
      const double s = double(i) / n, t = double(j) / n;
      const double w0 = (1 - s) * (1 - t), w1 = s * (1 - t), w2 = s * t, w3 = (1 - s) * t;
      const Vec2 uv = w0 * q[0] + w1 * q[1] + w2 * q[2] + w3 * q[3];
      const Vec3 x = w0 * p[0] + w1 * p[1] + w2 * p[2] + w3 * p[3];
      worst = std::max(worst, gauge(x, uv));
      if (worst > gauge.limit) return worst;
    }
  }
  return worst;
}

double polygon_estimate(const Gauge& gauge, const std::vector<Vec3>& p,
                        const std::vector<Vec2>& q) {
  if (p.size() == 4) return bilinear_estimate(gauge, p, q);
  double worst = 0;
  // Each triangle sampled as densely as its size asks (a boundary panel
  // following a finely discretized trim has many thin triangles), at least
  // at its edge midpoints: as the foundation's measure_panels does.
  double extent = 0;
  for (const Vec3& a : p)
    for (const Vec3& b : p) extent = std::max(extent, (a - b).norm());
  for (const auto& t : triangulate_polygon(q)) {
    const Vec3 tp[3] = {p[t[0]], p[t[1]], p[t[2]]};
    const Vec2 tq[3] = {q[t[0]], q[t[1]], q[t[2]]};
    const double longest =
        std::max({(tp[0] - tp[1]).norm(), (tp[1] - tp[2]).norm(), (tp[2] - tp[0]).norm()});
    const int n =
        extent > 0 ? std::max(2, static_cast<int>(std::ceil(kPanelSamples * longest / extent))) : 2;
    worst = std::max(worst, flat_triangle_estimate(gauge, tp, tq, n));
    if (worst > gauge.limit) return worst;
  }
  return worst;
}

// Folding a quad along diagonal 0-2 (k = 0) or 1-3 (k = 1): the larger estimate
// of its two triangles (over the limit: some value over it).
double fold_deviation(const Gauge& gauge, const std::vector<Vec3>& p, const std::vector<Vec2>& q,
                      int k) {
  const int a = k, b = k + 1, c = k + 2, d = (k + 3) % 4;
  const Vec3 t1[3] = {p[a], p[b], p[c]}, t2[3] = {p[a], p[c], p[d]};
  const Vec2 s1[3] = {q[a], q[b], q[c]}, s2[3] = {q[a], q[c], q[d]};
  const double first = flat_triangle_estimate(gauge, t1, s1);
  if (first > gauge.limit) return first;
  return std::max(first, flat_triangle_estimate(gauge, t2, s2));
}

// Which way to split a panel spanning [u0,u1] x [v0,v1]: along the direction
// whose chords bend more. Adds the line(s); returns how many were added.
int split_panel(const SurfaceFace& face, Lines& lines, const std::vector<Vec2>& q, double bound) {
  double u0 = q[0].x(), u1 = u0, v0 = q[0].y(), v1 = v0;
  for (const Vec2& x : q) {
    u0 = std::min(u0, x.x()), u1 = std::max(u1, x.x());
    v0 = std::min(v0, x.y()), v1 = std::max(v1, x.y());
  }
  const double um = 0.5 * (u0 + u1), vm = 0.5 * (v0 + v1);
  double du = 0, dv = 0;
  for (double t : {0.0, 0.5, 1.0}) {
    const double v = v0 + t * (v1 - v0), u = u0 + t * (u1 - u0);
    du = std::max(
        du, agents::path_deviation(face, {u0, v}, {u1, v}, face.point(u0, v), face.point(u1, v)));
    dv = std::max(
        dv, agents::path_deviation(face, {u, v0}, {u, v1}, face.point(u, v0), face.point(u, v1)));
  }
  int added = 0;
  if (std::max(du, dv) < 0.25 * bound) {
    // Neither direction bends much (a twist, a pole): split both ways.
    added += insert_line(lines.u, um);
    added += insert_line(lines.v, vm);
  } else if (du >= dv) {
    added += insert_line(lines.u, um);
  } else {
    added += insert_line(lines.v, vm);
  }
  return added;
}

// Replaces quad p by two triangles along diagonal k (0: corners 0-2, 1: 1-3).
void apply_fold(PanelMesh& mesh, std::size_t p, int k,
                std::vector<std::vector<int>>& extra_panels) {
  const std::vector<int> c = mesh.panels[p];
  const int a = k, b = k + 1, d = (k + 3) % 4, e = k + 2;
  mesh.panels[p] = {c[a], c[b], c[e]};
  extra_panels.push_back({c[a], c[e], c[d]});
  std::array<int, 2> fold{c[a], c[e]};
  if (fold[0] > fold[1]) std::swap(fold[0], fold[1]);
  mesh.folds.push_back(fold);
}

// Applies the folds (quad index, diagonal) found by the hard bound: folded
// quads keep their place, their second triangles follow all panels; rods rebuilt.
void apply_folds(PanelMesh& mesh, const std::vector<std::pair<std::size_t, int>>& folds) {
  std::vector<std::vector<int>> extra;
  for (const auto& [p, k] : folds) apply_fold(mesh, p, k, extra);
  if (!mesh.corner_uv.empty()) {
    for (const auto& [p, k] : folds) {
      const std::vector<Vec2> c = mesh.corner_uv[p];
      const int a = k, b = k + 1, d = (k + 3) % 4, e = k + 2;
      mesh.corner_uv[p] = {c[a], c[b], c[e]};
      mesh.corner_uv.push_back({c[a], c[e], c[d]});
    }
  }
  for (auto& panel : extra) mesh.panels.push_back(std::move(panel));
  build_rods(mesh);
}

// The hard bound on one panel whose estimate is `e`: kept as it is, or (a
// quad) folded along its better diagonal; `kept` is the estimate it keeps.
struct Verdict {
  bool ok = false;
  int fold = -1;  // the diagonal to fold along, -1: none
  double kept = 0;
};
Verdict judge_panel(const Gauge& gauge, const std::vector<Vec3>& x, const std::vector<Vec2>& q,
                    double e) {
  if (e <= gauge.limit) return {true, -1, e};
  if (x.size() == 4) {
    const double f0 = fold_deviation(gauge, x, q, 0), f1 = fold_deviation(gauge, x, q, 1);
    const int k = f0 <= f1 ? 0 : 1;
    if (std::min(f0, f1) <= gauge.limit) return {true, k, std::min(f0, f1)};
  }
  return {};
}

// The uniform (u,v) grid of nu x nv cells over the face's bounds, as iso_grid
// places it.
Lines iso_lines(const UvBounds& b, int nu, int nv) {
  Lines lines;
  for (int i = 0; i <= nu; ++i) lines.u.push_back(b.u_min + (b.u_max - b.u_min) * i / nu);
  for (int j = 0; j <= nv; ++j) lines.v.push_back(b.v_min + (b.v_max - b.v_min) * j / nv);
  lines.u.back() = b.u_max, lines.v.back() = b.v_max;
  return lines;
}

// The coarsest iso grid that holds the hard bound with fewer panels than
// `fewer_than`, if there is one: the walking agent's fallback (where
// curvature is even its lines, each obeying its worst row, cost more panels
// than a uniform grid: a gentle dome took 49 against 42).
//
// The search walks the frontier of the smallest feasible v count per u count
// (it does not grow with the u count): a grid is first screened on its whole
// cells with a corner or middle inside the trim, from the cell of largest
// curvature outwards, stopping at the first over the bound (an infeasible grid
// costs a few estimates); the candidate then has to pass the hard bound on its
// clipped panels, folds allowed. `share` (panels per cell of the agents'
// grid) turns the panel budget into a cell budget on a trimmed face.
// The longest side of an outline.
double longest_side(const std::vector<Vec3>& x) {
  double longest = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    longest = std::max(longest, (x[(i + 1) % x.size()] - x[i]).norm());
  return longest;
}

// Area of the panels' outlines (each a fan of flat triangles).
double panels_area(const PanelMesh& mesh) {
  double area = 0;
  for (const auto& p : mesh.panels)
    for (std::size_t i = 1; i + 1 < p.size(); ++i)
      area +=
          0.5 * (mesh.xyz[p[i]] - mesh.xyz[p[0]]).cross(mesh.xyz[p[i + 1]] - mesh.xyz[p[0]]).norm();
  return area;
}

std::optional<PanelMesh> coarsest_iso_grid(const SurfaceFace& face, const UvTrimClassifier& trim,
                                           const Gauge& gauge, const GridClipParams& clip,
                                           double sample_step, double max_size,
                                           const PanelMesh& agents, double share, bool local_lines,
                                           const agents::OutlineCheck& holds,
                                           WalkingAgentReport& rep) {
  const std::size_t fewer_than = agents.panels.size();
  const UvBounds b = face.bounds();
  std::optional<PanelMesh> found;
  std::size_t best = fewer_than;
  const double per_cell = std::max(share, 1e-3);
  // Round a closed direction a cell spans under a third of the period (one
  // or two cells would join corners across the whole face).
  const int nu_min = face.u_periodic() ? 3 : 1, nv_min = face.v_periodic() ? 3 : 1;
  // A grid whose lines miss a point where the trim turns has a panel with a
  // vertex that is no node (refused below): refused before it is cut, which
  // on a face with a curved trim is every grid (90% of the method's time
  // went into cutting grids only to refuse them).
  const std::vector<Vec2> turning = trim_turning_points(face, clip);
  // Whether x lies on one of the n + 1 uniform lines from lo to hi.
  auto on_a_line = [](double lo, double hi, int n, double x) {
    const double t = (x - lo) / (hi - lo) * n;
    const double i = std::clamp(std::round(t), 0.0, static_cast<double>(n));
    return std::abs(t - i) <= 1e-9 * n;
  };
  auto misses_a_turn = [&](int nu, int nv) {
    for (const Vec2& p : turning)
      if (!on_a_line(b.u_min, b.u_max, nu, p.x()) && !on_a_line(b.v_min, b.v_max, nv, p.y()))
        return true;
    return false;
  };
  // The search below only ever cuts grids of nu x nv cells with nv at most
  // the first cell budget / nu: when every one of them misses a turn of the
  // trim, none can be found and the screens (most of the rest) are skipped.
  const double first_cells = (static_cast<double>(best) - 1) / per_cell;
  bool any_may_pass = false;
  for (int nu = nu_min; !any_may_pass && std::floor(first_cells / nu) >= nv_min; ++nu)
    for (int nv = nv_min; !any_may_pass && nv <= std::floor(first_cells / nu); ++nv)
      any_may_pass = !misses_a_turn(nu, nv);
  if (!any_may_pass) return found;
  const double covered = panels_area(agents);
  // Where grids failed so far (first: the point of largest curvature), most
  // recent first: the next grid is tried there first, so an infeasible grid
  // costs one or two cell estimates.
  std::vector<Vec2> failed{agents::max_curvature_point(face, trim, sample_step)};
  auto screen = [&](int nu, int nv) {
    const Lines l = iso_lines(b, nu, nv);
    auto cell_of = [&](const Vec2& p) {
      const int i =
          std::clamp(static_cast<int>((p.x() - b.u_min) / (b.u_max - b.u_min) * nu), 0, nu - 1);
      const int j =
          std::clamp(static_cast<int>((p.y() - b.v_min) / (b.v_max - b.v_min) * nv), 0, nv - 1);
      return std::array<int, 2>{i, j};
    };
    std::vector<Vec3> x(4);
    std::vector<Vec2> q(4);
    // Whether cell (i, j) holds the bound (a cell wholly outside the trim does).
    auto holds = [&](int i, int j) {
      q = {{l.u[i], l.v[j]}, {l.u[i + 1], l.v[j]}, {l.u[i + 1], l.v[j + 1]}, {l.u[i], l.v[j + 1]}};
      bool inside = trim.contains(0.5 * (q[0] + q[2]));
      for (const Vec2& c : q) inside = inside || trim.contains(c);
      if (!inside) return true;
      for (int c = 0; c < 4; ++c) x[c] = face.point(q[c].x(), q[c].y());
      if (longest_side(x) > max_size) return false;
      return judge_panel(gauge, x, q, bilinear_estimate(gauge, x, q)).ok;
    };
    auto fail_at = [&](int i, int j) {
      const Vec2 centre(0.5 * (l.u[i] + l.u[i + 1]), 0.5 * (l.v[j] + l.v[j + 1]));
      failed.insert(failed.begin(), centre);
      if (failed.size() > 8) failed.pop_back();
      return false;
    };
    std::set<std::array<int, 2>> tried;
    for (const Vec2& f : std::vector<Vec2>(failed)) {
      const std::array<int, 2> c = cell_of(f);
      if (!tried.insert(c).second) continue;
      if (!holds(c[0], c[1])) return fail_at(c[0], c[1]);
    }
    // The rest by their distance (in cells) from the first, then row-major.
    const std::array<int, 2> h = cell_of(failed.front());
    std::vector<std::array<int, 3>> order;
    order.reserve(static_cast<std::size_t>(nu) * nv);
    for (int j = 0; j < nv; ++j)
      for (int i = 0; i < nu; ++i)
        if (!tried.count({i, j}))
          order.push_back({std::max(std::abs(i - h[0]), std::abs(j - h[1])), j, i});
    std::sort(order.begin(), order.end());
    for (const auto& [ring, j, i] : order) {
      (void)ring;
      if (!holds(i, j)) return fail_at(i, j);
    }
    return true;
  };
  // The clipped grid under the hard bound (folds applied; counted in `got`),
  // or nothing.
  WalkingAgentReport got;
  auto bounded = [&](int nu, int nv, bool merge) -> std::optional<PanelMesh> {
    if (misses_a_turn(nu, nv)) return std::nullopt;
    const Lines l = iso_lines(b, nu, nv);
    PanelMesh mesh;
    try {
      mesh = clip_grid(face, l.u, l.v, clip);
    } catch (const LimitExceeded&) {
      return std::nullopt;
    }
    std::vector<std::pair<std::size_t, int>> folds;
    double worst = 0;
    for (std::size_t p = 0; p < mesh.panels.size(); ++p) {
      // No panel cut by a trim: a coarse grid's big boundary pieces are held
      // to the bound by the pipeline with folds up to 83 degrees (a notched
      // face at 60 mm); the agents' smaller panels along the trims are not.
      for (int v : mesh.panels[p])
        if (!is_node(mesh, v)) return std::nullopt;
      std::vector<Vec3> x;
      for (int v : mesh.panels[p]) x.push_back(mesh.xyz[v]);
      const std::vector<Vec2> q = panel_corner_uv(mesh, p);
      if (longest_side(x) > max_size) return std::nullopt;
      const Verdict verdict = judge_panel(gauge, x, q, polygon_estimate(gauge, x, q));
      if (!verdict.ok) return std::nullopt;
      if (verdict.fold >= 0) folds.push_back({p, verdict.fold});
      worst = std::max(worst, verdict.kept);
    }
    if (merge) got.merged_cells = agents::stop_lines_early(mesh, l.u, l.v, folds, holds);
    apply_folds(mesh, folds);
    got.folds = static_cast<int>(folds.size());
    got.max_estimate = worst;
    return mesh;
  };
  int v = std::numeric_limits<int>::max();
  for (int nu = nu_min;; ++nu) {
    const double cells = (static_cast<double>(best) - 1) / per_cell;
    const int cap = static_cast<int>(std::min<double>(v, std::floor(cells / nu)));
    if (cap < nv_min) break;
    if (!screen(nu, cap)) continue;
    int w = cap;
    while (w > nv_min && screen(nu, w - 1)) --w;
    v = w;
    // The frontier point, or the next count up if its clipped panels fail.
    for (int nv = w; nv <= std::min(cap, w + 1); ++nv) {
      std::optional<PanelMesh> mesh = bounded(nu, nv, false);
      if (!mesh) continue;
      // The same surface covered (a grid the trim cut differently, e.g. round
      // a pole, is no fallback).
      if (mesh->panels.size() < best && std::abs(panels_area(*mesh) - covered) <= 0.01 * covered) {
        best = mesh->panels.size();
        rep.folds = got.folds, rep.max_estimate = got.max_estimate;
        rep.merged_cells = got.merged_cells;
        rep.iso_u_count = nu, rep.iso_v_count = nv;
        found = std::move(mesh);
      }
      break;
    }
  }
  // The lines of the grid kept stop early too (not while searching: a search
  // tries dozens of grids).
  if (found && local_lines) {
    if (std::optional<PanelMesh> merged = bounded(rep.iso_u_count, rep.iso_v_count, true)) {
      found = std::move(merged);
      rep.folds = got.folds, rep.max_estimate = got.max_estimate;
      rep.merged_cells = got.merged_cells;
    }
  }
  return found;
}

}  // namespace

bool is_valid_agent_start(const std::string& start) {
  try {
    agents::parse_start(start);
    return true;
  } catch (const InvalidParameter&) {
    return false;
  }
}

namespace {

void check_walking_agent(const SurfaceFace& face, const WalkingAgentParams& params) {
  check_common(face, params.max_deviation, params.sample_step);
  if (params.max_size != 0.0) require_in_range("max_size (mm)", params.max_size, 1e-3, 1e9);
  if (params.diagonal_deviation != 0.0) {
    require_in_range("diagonal_deviation (mm)", params.diagonal_deviation, 1e-6 * face.model_size(),
                     1e9);
  }
  require_in_range("max_refinements", params.max_refinements, 0, 1000);
  if (params.edge_share != 0.0) require_in_range("edge_share", params.edge_share, 0.1, 1.0);
  check_clip(params.clip);
  agents::parse_start(params.start);
}

// What the agents' runs share on one face: the gauge of the bound and the
// test a merged panel must pass.
struct AgentSetup {
  AgentSetup(const SurfaceFace& face, const WalkingAgentParams& params)
      : face(face),
        params(params),
        max_size(params.max_size > 0 ? params.max_size : 1e300),
        gauge{face, kBoundMargin * params.max_deviation},
        // A merged panel (lines stopped early) must hold the bound as it is: no fold.
        holds([this](const std::vector<Vec3>& x, const std::vector<Vec2>& q, double longest) {
          return longest <= max_size && polygon_estimate(gauge, x, q) <= gauge.limit;
        }) {}
  AgentSetup(const AgentSetup&) = delete;  // `holds` refers to this one
  const SurfaceFace& face;
  const WalkingAgentParams& params;
  const double max_size;
  const Gauge gauge;
  const agents::OutlineCheck holds;
};

// 3. The hard bound on whole panels of the grid of `lines`: fold or insert
// lines until none is over; then the lines stop early where they may and
// the folds are applied. `lines` ends as the grid's lines.
PanelMesh hard_bound(const AgentSetup& setup, Lines& lines, WalkingAgentReport& rep) {
  const SurfaceFace& face = setup.face;
  const WalkingAgentParams& params = setup.params;
  const Gauge& gauge = setup.gauge;
  // Panels a new line does not touch come back with the same corners: their
  // deviation is remembered (keyed by the corner (u,v)s) instead of re-sampled.
  std::map<std::vector<double>, double> known;
  for (int round = 0;; ++round) {
    PanelMesh mesh = clip_grid(face, lines.u, lines.v, params.clip);
    std::vector<std::pair<std::size_t, int>> folds;
    int added = 0;
    double worst_kept = 0;
    for (std::size_t p = 0; p < mesh.panels.size(); ++p) {
      const std::vector<Vec2> q = panel_corner_uv(mesh, p);
      std::vector<Vec3> x;
      for (int v : mesh.panels[p]) x.push_back(mesh.xyz[v]);
      std::vector<double> key;
      key.reserve(2 * q.size());
      for (const Vec2& c : q) key.push_back(c.x()), key.push_back(c.y());
      auto hit = known.find(key);
      double e;
      if (hit != known.end()) {
        e = hit->second;
      } else {
        // The estimate (surface point at the same (u,v)) is an upper bound;
        // it adds a tangential offset where the parameterization is uneven.
        // Samples over the limit are measured exactly (closest surface point).
        e = polygon_estimate(gauge, x, q);
        known.emplace(std::move(key), e);
      }
      const Verdict verdict = judge_panel(gauge, x, q, e);
      if (verdict.ok) {
        if (verdict.fold >= 0) folds.push_back({p, verdict.fold});
        worst_kept = std::max(worst_kept, verdict.kept);
        continue;
      }
      added += split_panel(face, lines, q, params.max_deviation);
    }
    rep.refinement_rounds = round;
    if (added == 0) {
      rep.grid_cells = static_cast<double>(lines.u.size() - 1) * (lines.v.size() - 1);
      rep.grid_panels = static_cast<double>(mesh.panels.size() + folds.size());
      if (params.local_lines)
        rep.merged_cells = agents::stop_lines_early(mesh, lines.u, lines.v, folds, setup.holds);
      apply_folds(mesh, folds);
      rep.folds = static_cast<int>(folds.size());
      rep.max_estimate = worst_kept;
      return mesh;
    }
    rep.inserted_lines += added;
    rep.bound_lines += added;
    if (round >= params.max_refinements) {
      throw GeometryFailure("walking_agent: panels still over max_deviation after " +
                            std::to_string(params.max_refinements) +
                            " refinement rounds; raise max_refinements or max_deviation");
    }
  }
}

// walking_agent; `final_lines` (if given): the lines of the layout kept.
PanelMesh run_walking_agent(const SurfaceFace& face, const WalkingAgentParams& params,
                            WalkingAgentReport* report, Lines* final_lines) {
  check_walking_agent(face, params);
  // Hundreds of thousands of evaluations close together: keep the span cache.
  const SurfaceFace::FastEvaluation fast(face);

  const double bound = params.max_deviation;
  const UvTrimClassifier trim = agents::agent_trim(face);
  const AgentSetup setup(face, params);

  // One run of the agents whose edge rule uses `share` x max_deviation.
  auto attempt = [&](double share, WalkingAgentReport& rep, Lines& lines) -> PanelMesh {
    const double edge_bound = share * bound;
    // Default diagonal bound 2 x max_deviation: where both principal
    // curvatures are equal the diagonal's sagitta is the sum of its two edges'
    // sagittas, so a quad whose edges are at the bound has a diagonal at twice
    // it without bending more than its edges show. (Twice the edge bound
    // instead trips on every quad of a dome walked at half the bound and
    // doubles the lines: measured.) Whole panels are checked by the hard bound.
    const double diagonal = params.diagonal_deviation > 0 ? params.diagonal_deviation : 2 * bound;
    // 1. The edge agents (and their twins on every sample row) place the lines.
    lines = walk_lines(face, trim, params.sample_step, params.start,
                       [&](RowAgents& a, double s0, double s1, double step) {
                         return agents::walk(s0, s1, step, [&](double x, double y) {
                           const RowAgents::Probe p = a.probe(x, y);
                           return p.deviation <= edge_bound && p.length <= setup.max_size;
                         });
                       });
    // 2. The diagonal walkers.
    rep.inserted_lines += diagonal_walkers(face, trim, lines, diagonal, params.clip.max_panels);
    // 3. The hard bound.
    return hard_bound(setup, lines, rep);
  };

  // The thesis' rule bounds each edge; a doubly curved panel then bends about
  // the sum of its two edges' deviations, and the hard bound has to halve
  // lines. Walking with a share of the bound avoids that: 1 is best for
  // single curvature (a cylinder), 1/2 for equal curvatures (a dome). With
  // edge_share = 0 the agents try 1, 0.7 and 0.5 and keep the fewest panels.
  std::vector<double> shares;
  if (params.edge_share > 0)
    shares = {params.edge_share};
  else
    shares = {1.0, 0.7, 0.5};
  PanelMesh best;
  WalkingAgentReport best_rep;
  Lines best_lines;
  bool have = false;
  std::exception_ptr failure;
  for (double share : shares) {
    WalkingAgentReport rep;
    PanelMesh mesh;
    Lines lines;
    try {
      mesh = attempt(share, rep, lines);
    } catch (const LimitExceeded&) {
      // Too many panels with this share: another share may fit under the cap.
      failure = std::current_exception();
      continue;
    } catch (const GeometryFailure&) {
      failure = std::current_exception();
      continue;
    }
    rep.edge_share = share;
    const bool done = rep.bound_lines == 0 && rep.folds == 0;
    if (!have || mesh.panels.size() < best.panels.size()) {
      best = std::move(mesh);
      best_rep = rep;
      best_lines = std::move(lines);
      have = true;
    }
    // The hard bound added nothing: a smaller share only walks a tighter rule,
    // whose greedy walk places at least as many nodes. Stop here.
    if (done && params.edge_share == 0) break;
  }
  if (!have) std::rethrow_exception(failure);
  // Never more panels than the coarsest iso grid that holds the bound.
  if (params.iso_fallback && best_rep.grid_cells > 0) {
    // Panels per cell before lines stopped early (merged cells would make
    // the iso search's cell budget several times too large).
    const double share = best_rep.grid_panels / best_rep.grid_cells;
    if (std::optional<PanelMesh> iso = coarsest_iso_grid(
            face, trim, setup.gauge, params.clip, params.sample_step, setup.max_size, best, share,
            params.local_lines, setup.holds, best_rep)) {
      best = std::move(*iso);
      best_lines = iso_lines(face.bounds(), best_rep.iso_u_count, best_rep.iso_v_count);
    }
  }
  if (report) *report = best_rep;
  if (final_lines) *final_lines = std::move(best_lines);
  return best;
}

// The lines strictly inside [lo, hi] (farther than eps from both), with lo
// and hi as the first and last.
std::vector<double> lines_within(const std::vector<double>& lines, double lo, double hi) {
  const double eps = 1e-9 * (hi - lo);
  std::vector<double> out{lo};
  for (double x : lines)
    if (x > lo + eps && x < hi - eps) out.push_back(x);
  out.push_back(hi);
  return out;
}

}  // namespace

PanelMesh walking_agent(const SurfaceFace& face, const WalkingAgentParams& params,
                        WalkingAgentReport* report) {
  return run_walking_agent(face, params, report, nullptr);
}

WalkingAgentLines walking_agent_lines(const SurfaceFace& face, const WalkingAgentParams& params,
                                      const WalkingAgentLines& pinned) {
  Lines lines;
  run_walking_agent(face, params, nullptr, &lines);
  if (!pinned.u.empty() || !pinned.v.empty()) {
    pin_lines(lines.u, pinned.u);
    pin_lines(lines.v, pinned.v);
    const SurfaceFace::FastEvaluation fast(face);
    const AgentSetup setup(face, params);
    WalkingAgentReport rep;
    hard_bound(setup, lines, rep);
  }
  return {std::move(lines.u), std::move(lines.v)};
}

PanelMesh walking_agent_on_lines(const SurfaceFace& face, const WalkingAgentParams& params,
                                 const WalkingAgentLines& given, WalkingAgentReport* report) {
  check_walking_agent(face, params);
  if (given.u.size() < 2 || given.v.size() < 2)
    throw InvalidParameter("walking_agent_on_lines: at least two lines in u and in v");
  const SurfaceFace::FastEvaluation fast(face);
  const UvBounds b = face.bounds();
  Lines lines{lines_within(given.u, b.u_min, b.u_max), lines_within(given.v, b.v_min, b.v_max)};
  const AgentSetup setup(face, params);
  WalkingAgentReport rep;
  PanelMesh mesh = hard_bound(setup, lines, rep);
  if (report) *report = rep;
  return mesh;
}

PanelMesh gradient_descent(const SurfaceFace& face, const GradientDescentParams& params) {
  check_common(face, params.max_deviation, params.sample_step);
  require_in_range("max_step (fraction of the parameter span)", params.max_step, params.sample_step,
                   1.0);
  check_clip(params.clip);
  agents::parse_start(params.start);
  const UvTrimClassifier trim = agents::agent_trim(face);
  const double target = params.max_deviation;
  const double max_step_fraction = params.max_step;
  Lines lines =
      walk_lines(face, trim, params.sample_step, params.start,
                 [&](RowAgents& a, double s0, double s1, double step) {
                   const double span_step = step / params.sample_step;  // = the parameter span
                   return agents::gradient_walk(
                       s0, s1, step, 1e-3 * span_step, max_step_fraction * span_step, target,
                       [&](double x, double y) { return a.probe(x, y).deviation; });
                 });
  return clip_grid(face, lines.u, lines.v, params.clip);
}

}  // namespace tessella
