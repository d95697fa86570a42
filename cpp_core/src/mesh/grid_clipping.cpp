// Cutting a tensor grid by the trim loops.
//
// Why Clipper (libpolyclipping): intersecting cells with a polygon-with-holes
// is full of degenerate cases (trim curves running exactly along grid lines,
// as the natural boundary of an untrimmed face always does; loops touching
// grid nodes). Clipper works on integers with exact predicates and handles
// them all. We map (u,v) affinely onto a 2^50 integer range, so the rounding
// is ~1e-15 of the parameter span, far below any length tolerance here.
//
// Vertex sharing: a vertex is identified by its integer point, so the crossing
// of a trim segment with a grid line, computed for both cells beside that line
// from the same operands, becomes one vertex. Vertices on a grid line are then
// inserted into every panel edge running along that line, so the mesh has no
// T-junctions even where a hole forced a cell to be split.
#include "mesh/grid_clipping.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <clipper.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <unordered_map>
#include <utility>

#include "common/parallel_chunks.h"
#include "common/task_tree.h"
#include "geometry/parallel_in_scopes.h"
#include "geometry/segment_closest.h"
#include "geometry/trim_deflection.h"
#include "mesh/clip_to_box.h"
#include "mesh/panel_model.h"
#include "mesh/seam_sides.h"
#include "tessella/errors.h"
#include "tessella/progress.h"
#include "tessella/surface_face.h"

namespace tessella {

namespace {

using ClipperLib::cInt;
using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

struct PointHash {
  std::size_t operator()(const IntPoint& p) const {
    // (the product in unsigned arithmetic: at 2^50 units the signed one
    // overflows, undefined behaviour; the bits are the same)
    const auto x = static_cast<unsigned long long>(p.X) * 1000003ULL;
    return std::hash<long long>()(static_cast<long long>(x)) ^ std::hash<long long>()(p.Y);
  }
};
struct PointEq {
  bool operator()(const IntPoint& a, const IntPoint& b) const { return a.X == b.X && a.Y == b.Y; }
};

constexpr double kIntRange = 1125899906842624.0;  // 2^50
// A point this close (integer units, ~1e-14 of the span) to a trim polyline
// lies on it: Clipper rounds each crossing to the nearest integer point; the
// margin covers the double arithmetic of the distance at 2^50.
constexpr double kOnTrimUnits = 64.0;

// Affine map between (u,v) and Clipper's integer plane.
struct IntegerFrame {
  double u0, v0, su, sv;
  IntegerFrame(const std::vector<double>& u_lines, const std::vector<double>& v_lines)
      : u0(u_lines.front()),
        v0(v_lines.front()),
        su(kIntRange / (u_lines.back() - u_lines.front())),
        sv(kIntRange / (v_lines.back() - v_lines.front())) {}
  IntPoint to_int(const Vec2& p) const {
    return IntPoint(static_cast<cInt>(std::llround((p.x() - u0) * su)),
                    static_cast<cInt>(std::llround((p.y() - v0) * sv)));
  }
  cInt u_to_int(double u) const { return static_cast<cInt>(std::llround((u - u0) * su)); }
  cInt v_to_int(double v) const { return static_cast<cInt>(std::llround((v - v0) * sv)); }
};

// The trim polylines' segments (integer units) bucketed on a uniform grid:
// a crossing looks for the segment it lies on among the few whose box,
// widened by the reach, holds it, not along the whole trim (that scan was
// most of clip_grid's own time on a finely sampled trim).
class NearTrimSegments {
 public:
  NearTrimSegments(const std::vector<TrimLoop>& loops, const IntegerFrame& frame, double reach)
      : reach_(reach) {
    const Vec2 origin(frame.u0, frame.v0), scale(frame.su, frame.sv);
    lo_ = Vec2::Constant(std::numeric_limits<double>::infinity());
    Vec2 hi = -lo_;
    for (std::size_t l = 0; l < loops.size(); ++l) {
      const auto& uv = loops[l].uv;
      for (std::size_t k = 0; k < uv.size(); ++k) {
        const Vec2 a = (uv[k] - origin).cwiseProduct(scale);
        const Vec2 b = (uv[(k + 1) % uv.size()] - origin).cwiseProduct(scale);
        segments_.push_back({a, b - a, static_cast<int>(l)});
        lo_ = lo_.cwiseMin(a), hi = hi.cwiseMax(a);
      }
    }
    if (segments_.empty()) return;
    // Twice the reach around each box: a point the distance test accepts lies
    // well inside it whatever the rounding.
    const double margin = 2 * reach_;
    lo_ -= Vec2::Constant(margin), hi += Vec2::Constant(margin);
    side_ = std::max(1, static_cast<int>(std::ceil(std::sqrt(double(segments_.size())))));
    cell_ = (hi - lo_) / side_;
    cell_ = cell_.cwiseMax(Vec2::Constant(1.0));
    buckets_.resize(static_cast<std::size_t>(side_) * side_);
    for (std::size_t s = 0; s < segments_.size(); ++s) {
      const Vec2 a = segments_[s].a, b = a + segments_[s].d;
      const auto [i0, j0] = bucket(a.cwiseMin(b) - Vec2::Constant(margin));
      const auto [i1, j1] = bucket(a.cwiseMax(b) + Vec2::Constant(margin));
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i)
          buckets_[static_cast<std::size_t>(j) * side_ + i].push_back(static_cast<int>(s));
    }
  }

  // The loop of the segment nearest q (units; the first in loop order among
  // equally near ones, as a scan of every segment finds it) if it is within
  // the reach, else -1.
  int nearest_loop(const Vec2& q) const {
    if (segments_.empty()) return -1;
    const auto [i, j] = bucket(q);
    double best = std::numeric_limits<double>::infinity();
    int best_loop = -1;
    for (int s : buckets_[static_cast<std::size_t>(j) * side_ + i]) {  // ascending order
      const Segment& g = segments_[static_cast<std::size_t>(s)];
      const double t = closest_fraction(g.a, g.d, q);
      const double dist = (g.a + t * g.d - q).squaredNorm();
      if (dist < best) best = dist, best_loop = g.loop;
    }
    return best <= reach_ * reach_ ? best_loop : -1;
  }

 private:
  struct Segment {
    Vec2 a, d;
    int loop;
  };
  std::pair<int, int> bucket(const Vec2& p) const {
    auto index = [&](double x, double lo, double cell) {
      const double f = std::floor((x - lo) / cell);
      return static_cast<int>(std::clamp(f, 0.0, double(side_ - 1)));
    };
    return {index(p.x(), lo_.x(), cell_.x()), index(p.y(), lo_.y(), cell_.y())};
  }

  double reach_;
  std::vector<Segment> segments_;
  Vec2 lo_ = Vec2::Zero(), cell_ = Vec2::Ones();
  int side_ = 1;
  std::vector<std::vector<int>> buckets_;
};

Path rectangle(cInt x0, cInt y0, cInt x1, cInt y1) {
  return {IntPoint(x0, y0), IntPoint(x1, y0), IntPoint(x1, y1), IntPoint(x0, y1)};
}

// Polygons of `subject` (closed, non-zero fill) inside the rectangle. Outer
// contours that came out with holes (a hole lying wholly inside the cell) are
// split in two at the middle of the hole and clipped again, so every result is
// a simple polygon without holes.
void clip_cell(const Paths& subject, cInt x0, cInt y0, cInt x1, cInt y1, int depth,
               std::vector<Path>& out) {
  ClipperLib::Clipper clipper(ClipperLib::ioPreserveCollinear | ClipperLib::ioStrictlySimple);
  clipper.AddPaths(subject, ClipperLib::ptSubject, true);
  clipper.AddPath(rectangle(x0, y0, x1, y1), ClipperLib::ptClip, true);
  ClipperLib::PolyTree tree;
  clipper.Execute(ClipperLib::ctIntersection, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  for (const ClipperLib::PolyNode* outer : tree.Childs) {
    if (outer->Childs.empty() || depth > 16) {
      out.push_back(outer->Contour);
      continue;
    }
    // Split at the middle of the first hole, along whichever axis is wider.
    const Path& hole = outer->Childs.front()->Contour;
    cInt hx0 = hole[0].X, hx1 = hole[0].X, hy0 = hole[0].Y, hy1 = hole[0].Y;
    for (const IntPoint& p : hole) {
      hx0 = std::min(hx0, p.X), hx1 = std::max(hx1, p.X);
      hy0 = std::min(hy0, p.Y), hy1 = std::max(hy1, p.Y);
    }
    Paths local{outer->Contour};
    for (const ClipperLib::PolyNode* h : outer->Childs) local.push_back(h->Contour);
    if (x1 - x0 >= y1 - y0) {
      const cInt xm = hx0 + (hx1 - hx0) / 2;
      clip_cell(local, x0, y0, xm, y1, depth + 1, out);
      clip_cell(local, xm, y0, x1, y1, depth + 1, out);
    } else {
      const cInt ym = hy0 + (hy1 - hy0) / 2;
      clip_cell(local, x0, y0, x1, ym, depth + 1, out);
      clip_cell(local, x0, ym, x1, y1, depth + 1, out);
    }
  }
}

// Drops the points strictly inside an axis-parallel straight run of a closed
// trim polyline (keeping trim corners). The natural boundary of an untrimmed
// face is four such runs, discretized finely because the edges bend in 3D;
// their inner points add nothing to the cut (a cell cut by the run gets its
// crossings with the grid lines anyway, at the same integer points, and the
// leftover boundary points are removed again by drop_straight_boundary_points)
// but cost Clipper work in every strip and cell. The cells near the trim stay
// the same (the union of the runs' pieces is the run).
Path drop_axis_run_points(const Path& path,
                          const std::unordered_map<IntPoint, char, PointHash, PointEq>& corner) {
  Path cur = path;
  for (bool changed = true; changed && cur.size() > 3;) {
    changed = false;
    Path kept;
    const std::size_t n = cur.size();
    for (std::size_t k = 0; k < n; ++k) {
      const IntPoint& a = kept.empty() ? cur[n - 1] : kept.back();
      const IntPoint& p = cur[k];
      const IntPoint& b = cur[(k + 1) % n];
      const bool on_x =
          a.X == p.X && p.X == b.X && ((a.Y < p.Y && p.Y < b.Y) || (b.Y < p.Y && p.Y < a.Y));
      const bool on_y =
          a.Y == p.Y && p.Y == b.Y && ((a.X < p.X && p.X < b.X) || (b.X < p.X && p.X < a.X));
      if ((on_x || on_y) && !corner.count(p) && n - (k - kept.size()) > 3) {
        changed = true;
        continue;
      }
      kept.push_back(p);
    }
    cur = std::move(kept);
  }
  return cur;
}

// A trim that runs along a grid line a hair's breadth off it (a face cut
// from its surface along an iso-line, its pcurve approximated: up to 2e-6
// off on the British Museum roof in B-spline sub-surfaces) would cut every
// cell beside it just inside its side: the cells' outlines then carry the
// trim's points, some of which land on the line and become nodes (rows broke
// there in a face set, at 63% of the cut's nodes). A point of a closed trim
// polyline that lies, with both its neighbours, within `deflection` (mm, in
// 3D by the surface's first derivative) of one grid line is put on it: the
// polyline stays within twice the deflection of the trim, and the run is an
// axis-parallel run (drop_axis_run_points). A trim corner where such a run
// ends is put on the line too (the caller marks it a corner again).
void snap_runs_onto_lines(Path& path, std::vector<Vec2>& uv, const std::vector<char>& corner,
                          const std::vector<cInt>& X, const std::vector<cInt>& Y,
                          const std::vector<double>& u_lines, const std::vector<double>& v_lines,
                          const IntegerFrame& frame, const SurfaceFace& face, double deflection) {
  const std::size_t n = path.size();
  if (n < 3) return;
  // Per point and direction (0: an x line, 1: a y line): the line it lies
  // near, -1 if none.
  std::vector<std::array<long, 2>> near(n, {-1, -1});
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 2; ++k) {
      const std::vector<cInt>& L = k == 0 ? X : Y;
      const cInt c = k == 0 ? path[i].X : path[i].Y;
      const auto it = std::lower_bound(L.begin(), L.end(), c);
      long best = -1;
      cInt off = 0;
      for (auto j : {it, it == L.begin() ? it : it - 1}) {
        if (j == L.end()) continue;
        const cInt d = c > *j ? c - *j : *j - c;
        if (best < 0 || d < off) best = static_cast<long>(j - L.begin()), off = d;
      }
      if (best < 0) continue;
      if (off == 0) {
        near[i][static_cast<std::size_t>(k)] = best;
        continue;
      }
      // Far in (u,v) (over 1e-6 of the span): no derivative needed.
      if (static_cast<double>(off) > 1e-6 * kIntRange) continue;
      const double duv = static_cast<double>(off) / (k == 0 ? frame.su : frame.sv);
      const SurfacePoint d = face.derivatives(uv[i].x(), uv[i].y());
      if (duv * (k == 0 ? d.du : d.dv).norm() <= deflection)
        near[i][static_cast<std::size_t>(k)] = best;
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t a = (i + n - 1) % n, b = (i + 1) % n;
    for (int k = 0; k < 2; ++k) {
      const long line = near[i][static_cast<std::size_t>(k)];
      const bool before = near[a][static_cast<std::size_t>(k)] == line;
      const bool after = near[b][static_cast<std::size_t>(k)] == line;
      // A corner ends a run along the line on one side at least.
      if (line < 0 || !(corner[i] ? before || after : before && after)) continue;
      if (k == 0) {
        path[i].X = X[static_cast<std::size_t>(line)];
        uv[i].x() = u_lines[static_cast<std::size_t>(line)];
      } else {
        path[i].Y = Y[static_cast<std::size_t>(line)];
        uv[i].y() = v_lines[static_cast<std::size_t>(line)];
      }
    }
  }
}

// Cells whose closed rectangle meets a trim segment's bounding box.
std::vector<char> cells_near_trim(const Paths& domain, const std::vector<cInt>& X,
                                  const std::vector<cInt>& Y) {
  const std::size_t nu = X.size() - 1, nv = Y.size() - 1;
  std::vector<char> near(nu * nv, 0);
  // Columns [first, last] whose closed range [X[i], X[i+1]] meets [lo, hi].
  auto range = [](const std::vector<cInt>& L, cInt lo, cInt hi) {
    const long first = std::max<long>(
        0, static_cast<long>(std::lower_bound(L.begin(), L.end(), lo) - L.begin()) - 1);
    const long last =
        std::min<long>(static_cast<long>(L.size()) - 2,
                       static_cast<long>(std::upper_bound(L.begin(), L.end(), hi) - L.begin()) - 1);
    return std::make_pair(first, last);
  };
  for (const Path& loop : domain) {
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const IntPoint& p = loop[k];
      const IntPoint& q = loop[(k + 1) % loop.size()];
      const auto [i0, i1] = range(X, std::min(p.X, q.X), std::max(p.X, q.X));
      const auto [j0, j1] = range(Y, std::min(p.Y, q.Y), std::max(p.Y, q.Y));
      for (long j = j0; j <= j1; ++j)
        for (long i = i0; i <= i1; ++i) near[j * nu + i] = 1;
    }
  }
  return near;
}

// Even-odd test of the cell centres of one row against the domain polylines.
std::vector<char> row_inside(const Paths& domain, const std::vector<cInt>& X, double y) {
  std::vector<double> crossings;
  for (const Path& loop : domain) {
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const IntPoint& p = loop[k];
      const IntPoint& q = loop[(k + 1) % loop.size()];
      if ((p.Y > y) == (q.Y > y)) continue;
      const double t = (y - p.Y) / double(q.Y - p.Y);
      crossings.push_back(p.X + t * double(q.X - p.X));
    }
  }
  std::sort(crossings.begin(), crossings.end());
  std::vector<char> inside(X.size() - 1, 0);
  std::size_t c = 0;
  for (std::size_t i = 0; i + 1 < X.size(); ++i) {
    const double xc = 0.5 * (double(X[i]) + double(X[i + 1]));
    while (c < crossings.size() && crossings[c] < xc) ++c;
    inside[i] = (c % 2) == 1;
  }
  return inside;
}

// Trim points where the trim runs straight in (u,v) - along an iso-line, as
// the natural boundary of an untrimmed face does - add nothing: the panel edge
// there is the same chord of an iso-curve as every inner rod. A point used by
// one panel only, collinear in (u,v) with its two neighbours, is removed.
void drop_straight_boundary_points(PanelMesh& mesh) {
  std::vector<int> uses(mesh.vertex_count(), 0);
  for (const auto& panel : mesh.panels)
    for (int v : panel) ++uses[v];
  for (auto& panel : mesh.panels) {
    bool removed = true;
    while (removed && panel.size() > 3) {
      removed = false;
      for (std::size_t k = 0; k < panel.size() && panel.size() > 3; ++k) {
        const int v = panel[k];
        if (uses[v] != 1) continue;
        const Vec2& a = mesh.uv[panel[(k + panel.size() - 1) % panel.size()]];
        const Vec2& b = mesh.uv[v];
        const Vec2& c = mesh.uv[panel[(k + 1) % panel.size()]];
        const Vec2 ab = b - a, ac = c - a;
        const double cross = ab.x() * ac.y() - ab.y() * ac.x();
        if (std::abs(cross) <= 1e-12 * ac.squaredNorm() && ab.dot(ac) > 0 &&
            ab.squaredNorm() < ac.squaredNorm()) {
          panel.erase(panel.begin() + static_cast<long>(k));
          removed = true;
        }
      }
    }
  }
}

}  // namespace

PanelMesh clip_grid(const SurfaceFace& face, const std::vector<double>& u_lines,
                    const std::vector<double>& v_lines, const GridClipParams& params) {
  if (u_lines.size() < 2 || v_lines.size() < 2) {
    throw InvalidParameter("a grid needs at least two lines in each direction");
  }
  const double cells = double(u_lines.size() - 1) * double(v_lines.size() - 1);
  if (cells > double(params.max_panels)) {
    throw LimitExceeded("the grid would have " + std::to_string(static_cast<long long>(cells)) +
                        " panels, more than max_panels = " + std::to_string(params.max_panels) +
                        ": choose a larger size or raise max_panels");
  }
  const double deflection = trim_deflection(face, params.trim_deflection);
  const std::vector<TrimLoop> loops = face.trim_loops(deflection);
  if (loops.empty()) throw InvalidGeometry("the face has no usable trim loop");

  const IntegerFrame frame(u_lines, v_lines);
  std::vector<cInt> X, Y;
  for (double u : u_lines) X.push_back(frame.u_to_int(u));
  for (double v : v_lines) Y.push_back(frame.v_to_int(v));
  for (std::size_t i = 1; i < X.size(); ++i)
    if (X[i] <= X[i - 1]) throw InvalidParameter("grid u lines must be strictly increasing");
  for (std::size_t j = 1; j < Y.size(); ++j)
    if (Y[j] <= Y[j - 1]) throw InvalidParameter("grid v lines must be strictly increasing");

  // Trim loops in integers; remember the exact (u,v) of every loop vertex.
  Paths domain;
  std::unordered_map<IntPoint, Vec2, PointHash, PointEq> exact_uv;
  std::unordered_map<IntPoint, char, PointHash, PointEq> trim_corner;
  for (const TrimLoop& loop : loops) {
    Path path;
    std::vector<Vec2> path_uv;
    std::vector<char> path_corner;
    for (std::size_t k = 0; k < loop.uv.size(); ++k) {
      const IntPoint p = frame.to_int(loop.uv[k]);
      if (loop.corner[k]) trim_corner[p] = 1;
      if (!path.empty() && p.X == path.back().X && p.Y == path.back().Y) continue;
      path.push_back(p);
      path_uv.push_back(loop.uv[k]);
      path_corner.push_back(trim_corner.count(p) ? 1 : 0);
    }
    snap_runs_onto_lines(path, path_uv, path_corner, X, Y, u_lines, v_lines, frame, face,
                         deflection);
    for (std::size_t k = 0; k < path.size(); ++k)
      if (path_corner[k]) trim_corner[path[k]] = 1;
    Path kept;
    for (std::size_t k = 0; k < path.size(); ++k) {
      if (!kept.empty() && path[k].X == kept.back().X && path[k].Y == kept.back().Y) continue;
      kept.push_back(path[k]);
      exact_uv.emplace(path[k], path_uv[k]);
    }
    if (kept.size() >= 3) domain.push_back(drop_axis_run_points(kept, trim_corner));
  }

  const std::size_t nu = X.size() - 1, nv = Y.size() - 1;
  const std::vector<char> near = cells_near_trim(domain, X, Y);

  // Cell polygons, row by row (v), then column (u): a deterministic order.
  std::vector<std::vector<Path>> cell_polys(nu * nv);
  std::vector<char> full(nu * nv, 0);
  for (std::size_t j = 0; j < nv; ++j) {
    const std::vector<char> inside = row_inside(domain, X, 0.5 * (double(Y[j]) + double(Y[j + 1])));
    for (std::size_t i = 0; i < nu; ++i) {
      if (!near[j * nu + i] && inside[i]) {
        full[j * nu + i] = 1;
        cell_polys[j * nu + i].push_back(rectangle(X[i], Y[j], X[i + 1], Y[j + 1]));
      }
    }
  }
  // Boundary cells: the domain is cut in halves of the grid (the longer
  // side, in cells), the halves again, down to single cells, skipping parts
  // with no cell at the trim: each level costs one pass over the trim, not
  // one per column or cell. The parts end on grid lines (as the cells do), so
  // a crossing on a part's side is the one the cells on both sides get.
  std::vector<std::size_t> near_sum((nu + 1) * (nv + 1), 0);  // 2D prefix sums
  for (std::size_t j = 0; j < nv; ++j)
    for (std::size_t i = 0; i < nu; ++i)
      near_sum[(j + 1) * (nu + 1) + i + 1] =
          near_sum[j * (nu + 1) + i + 1] + near_sum[(j + 1) * (nu + 1) + i] -
          near_sum[j * (nu + 1) + i] + (near[j * nu + i] ? 1 : 0);
  auto near_in = [&](std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1) {
    return near_sum[j1 * (nu + 1) + i1] - near_sum[j0 * (nu + 1) + i1] -
           near_sum[j1 * (nu + 1) + i0] + near_sum[j0 * (nu + 1) + i0];
  };
  const std::size_t near_total = near_in(0, nu, 0, nv);
  std::atomic<std::size_t> near_done{0};
  const cInt y_lo = Y.front() - 1, y_hi = Y.back() + 1;
  const auto cut = clip_to_box;
  // The parts are tasks any thread takes (with only the top split's two
  // halves on two threads, the one with less of the trim waited for the
  // other): each cell's polygons come from the same operations on any thread
  // and in any order (only integer Clipper calls; each leaf writes its own
  // cell), so the mesh is the same.
  struct Part {
    Paths piece;
    std::size_t i0 = 0, i1 = 0, j0 = 0, j1 = 0;
  };
  const int threads = worker_threads();
  // The domain's loops count by parity; Clipper's output (holes turning the
  // other way) by winding from here on.
  if (near_total > 0)
    run_task_tree(
        Part{cut(domain, ClipperLib::pftEvenOdd, rectangle(X.front(), y_lo, X.back(), y_hi)), 0, nu,
             0, nv},
        threads, [&](const Part& part, const auto& push) {
          const auto [i0, i1, j0, j1] =
              std::array<std::size_t, 4>{part.i0, part.i1, part.j0, part.j1};
          if (i1 - i0 == 1 && j1 - j0 == 1) {
            clip_cell(part.piece, X[i0], Y[j0], X[i1], Y[j1], 0, cell_polys[j0 * nu + i0]);
            const std::size_t done = ++near_done;
            if (done % 64 == 0)  // (a no-op off the calling thread: no sink there)
              report_progress(double(done) / double(near_total), "cutting the grid by the trim");
            return;
          }
          const bool split_u = i1 - i0 >= j1 - j0;
          const std::size_t mid = split_u ? (i0 + i1) / 2 : (j0 + j1) / 2;
          for (int half = 0; half < 2; ++half) {
            const std::size_t a0 = split_u ? (half ? mid : i0) : i0;
            const std::size_t a1 = split_u ? (half ? i1 : mid) : i1;
            const std::size_t b0 = split_u ? j0 : (half ? mid : j0);
            const std::size_t b1 = split_u ? j1 : (half ? j1 : mid);
            if (near_in(a0, a1, b0, b1) == 0) continue;
            push(Part{cut(part.piece, ClipperLib::pftNonZero,
                          rectangle(X[a0], b0 == 0 ? y_lo : Y[b0], X[a1], b1 == nv ? y_hi : Y[b1])),
                      a0, a1, b0, b1});
          }
        });

  // Weld vertices by integer point; exact (u,v) where the point is a grid line
  // or a trim loop vertex.
  PanelMesh mesh;
  std::unordered_map<IntPoint, int, PointHash, PointEq> index_of;
  // The grid line at an integer coordinate (X and Y increase strictly): its
  // index, -1 if none. Each vertex's lines are looked up once, when it is
  // made (a map asked again by every later step was a fifth of the cut's
  // serial time).
  auto line_at = [](const std::vector<cInt>& lines, cInt c) {
    const auto it = std::lower_bound(lines.begin(), lines.end(), c);
    return it != lines.end() && *it == c ? static_cast<int>(it - lines.begin()) : -1;
  };
  std::vector<IntPoint> int_points;
  std::vector<int> x_line_of, y_line_of;  // per vertex: its u and v grid lines, -1 if none
  auto vertex = [&](const IntPoint& p) {
    auto it = index_of.find(p);
    if (it != index_of.end()) return it->second;
    Vec2 q;
    auto ex = exact_uv.find(p);
    if (ex != exact_uv.end()) {
      q = ex->second;
    } else {
      q = {frame.u0 + double(p.X) / frame.su, frame.v0 + double(p.Y) / frame.sv};
    }
    const int xl = line_at(X, p.X), yl = line_at(Y, p.Y);
    if (xl >= 0) q.x() = u_lines[static_cast<std::size_t>(xl)];
    if (yl >= 0) q.y() = v_lines[static_cast<std::size_t>(yl)];
    x_line_of.push_back(xl);
    y_line_of.push_back(yl);
    const int id = static_cast<int>(mesh.uv.size());
    mesh.uv.push_back(q);
    mesh.xyz.push_back(face.point(q.x(), q.y()));
    int_points.push_back(p);
    index_of.emplace(p, id);
    return id;
  };
  std::vector<char> panel_full;
  std::vector<std::size_t> panel_cell;
  for (std::size_t c = 0; c < cell_polys.size(); ++c) {
    for (Path& poly : cell_polys[c]) {
      if (!ClipperLib::Orientation(poly)) std::reverse(poly.begin(), poly.end());
      std::vector<int> ids;
      for (const IntPoint& p : poly) {
        const int id = vertex(p);
        if (ids.empty() || ids.back() != id) ids.push_back(id);
      }
      while (ids.size() > 1 && ids.front() == ids.back()) ids.pop_back();
      if (ids.size() < 3) continue;
      mesh.panels.push_back(std::move(ids));
      panel_full.push_back(full[c]);
      panel_cell.push_back(c);
    }
  }

  // Remove T-junctions along grid lines: every vertex on a grid line goes into
  // each panel edge that runs along that line past it.
  std::vector<std::vector<std::pair<cInt, int>>> on_x(X.size()), on_y(Y.size());
  for (std::size_t k = 0; k < int_points.size(); ++k) {
    const IntPoint& p = int_points[k];
    if (x_line_of[k] >= 0) on_x[static_cast<std::size_t>(x_line_of[k])].push_back({p.Y, int(k)});
    if (y_line_of[k] >= 0) on_y[static_cast<std::size_t>(y_line_of[k])].push_back({p.X, int(k)});
  }
  for (auto* lines : {&on_x, &on_y})
    for (auto& list : *lines) std::sort(list.begin(), list.end());
  auto insert_between = [](const std::vector<std::pair<cInt, int>>& list, cInt a, cInt b,
                           std::vector<int>& out) {
    const cInt lo = std::min(a, b), hi = std::max(a, b);
    auto first = std::upper_bound(list.begin(), list.end(), std::make_pair(lo, INT32_MAX));
    auto last = std::lower_bound(list.begin(), list.end(), std::make_pair(hi, INT32_MIN));
    if (first >= last) return;
    if (a < b) {
      for (auto it = first; it != last; ++it) out.push_back(it->second);
    } else {
      for (auto it = last; it != first; --it) out.push_back((it - 1)->second);
    }
  };
  for (std::vector<int>& panel : mesh.panels) {
    std::vector<int> fixed;
    for (std::size_t k = 0; k < panel.size(); ++k) {
      const int a = panel[k], b = panel[(k + 1) % panel.size()];
      fixed.push_back(a);
      const IntPoint& pa = int_points[a];
      const IntPoint& pb = int_points[b];
      // (a vertex on a grid line is in that line's list)
      if (pa.X == pb.X && x_line_of[a] >= 0)
        insert_between(on_x[static_cast<std::size_t>(x_line_of[a])], pa.Y, pb.Y, fixed);
      else if (pa.Y == pb.Y && y_line_of[a] >= 0)
        insert_between(on_y[static_cast<std::size_t>(y_line_of[a])], pa.X, pb.X, fixed);
    }
    panel = std::move(fixed);
  }

  // Crossings of a grid line (or a hole's split line) with a trim lie on the
  // trim polyline's chord; move them onto the trim edges' own curves, so every
  // boundary vertex is on the true trim (the polyline's own points already are).
  // Only points on the polyline (within Clipper's rounding) are crossings: a
  // hole's split line also ends on a grid line away from any trim, and moving
  // that point to the nearest trim would drag both halves' corners (and the
  // neighbour's T-junction) across other panels.
  // In integer units, where the crossings were rounded.
  const Vec2 origin(frame.u0, frame.v0), scale(frame.su, frame.sv);
  const NearTrimSegments trim_segments(loops, frame, kOnTrimUnits);
  std::vector<std::size_t> off_grid;
  for (std::size_t v = 0; v < int_points.size(); ++v) {
    const IntPoint& p = int_points[v];
    const bool grid_node = x_line_of[v] >= 0 && y_line_of[v] >= 0;
    if (!grid_node && !exact_uv.count(p)) off_grid.push_back(v);
  }
  // Each crossing snaps on its own (OCCT's extrema on the trim's pcurves, a
  // tenth of a trimmed dome's panelize when it ran on one thread): on every
  // worker.
  for_each_in_scopes(face, off_grid.size(), 16, [&](std::size_t k) {
    const std::size_t v = off_grid[k];
    const Vec2 q = mesh.uv[v];
    const int best_loop = trim_segments.nearest_loop((q - origin).cwiseProduct(scale));
    if (best_loop < 0) return;
    const Vec2 snapped = face.snap_to_trim(best_loop, q);
    mesh.uv[v] = snapped;
    mesh.xyz[v] = face.point(snapped.x(), snapped.y());
  });

  // Nodes (rod ends): grid nodes and grid/trim crossings (on a grid line),
  // trim corners, and any point two panels share (e.g. where a hole split a
  // cell). The other trim points only shape the boundary panels' outlines.
  {
    std::vector<int> uses(mesh.uv.size(), 0);
    for (const auto& panel : mesh.panels)
      for (int v : panel) ++uses[v];
    mesh.is_node.assign(mesh.uv.size(), 0);
    for (std::size_t v = 0; v < int_points.size(); ++v) {
      const IntPoint& p = int_points[v];
      mesh.is_node[v] =
          x_line_of[v] >= 0 || y_line_of[v] >= 0 || trim_corner.count(p) || uses[v] >= 2;
    }
  }

  // Nominal panel area: the mean full cell (all cells if none is full).
  double sum = 0;
  int n = 0;
  for (std::size_t k = 0; k < mesh.panels.size(); ++k) {
    if (!panel_full[k]) continue;
    sum += panel_area(mesh, k);
    ++n;
  }
  mesh.nominal_area = n > 0 ? sum / n : face.area() / std::max(cells, 1.0);

  // A sliver is a cut piece much smaller than the cell it was cut from (cells
  // differ in size, e.g. towards a pole, so compare with its own cell).
  std::vector<double> cell_area(mesh.panels.size(), 0.0);
  for (std::size_t k = 0; k < mesh.panels.size(); ++k) {
    if (panel_full[k]) continue;
    const std::size_t i = panel_cell[k] % nu, j = panel_cell[k] / nu;
    const std::vector<Vec2> uv = {{u_lines[i], v_lines[j]},
                                  {u_lines[i + 1], v_lines[j]},
                                  {u_lines[i + 1], v_lines[j + 1]},
                                  {u_lines[i], v_lines[j + 1]}};
    std::vector<Vec3> xyz;
    for (const Vec2& q : uv) xyz.push_back(face.point(q.x(), q.y()));
    cell_area[k] = panel_model_area(xyz, uv);
  }
  drop_straight_boundary_points(mesh);
  mesh.merged_slivers = merge_slivers(mesh, params.sliver_fraction, cell_area);
  weld_coincident_vertices(mesh, 1e-9 * face.model_size());
  weld_loose_seam(face, mesh);
  if (face.reversed()) reverse_panels(mesh);
  remove_unused_vertices(mesh);
  build_rods(mesh);
  return mesh;
}

std::vector<Vec2> trim_turning_points(const SurfaceFace& face, const GridClipParams& params) {
  std::vector<Vec2> turning;
  for (const TrimLoop& loop : face.trim_loops(trim_deflection(face, params.trim_deflection))) {
    const std::size_t n = loop.uv.size();
    if (n < 3) continue;
    for (std::size_t k = 0; k < n; ++k) {
      if (loop.corner[k]) continue;
      const Vec2& a = loop.uv[(k + n - 1) % n];
      const Vec2& b = loop.uv[k];
      const Vec2& c = loop.uv[(k + 1) % n];
      const Vec2 ab = b - a, bc = c - b;
      // Well clear of the collinear test that removes straight-run points
      // (1e-12 there): only points that surely stay in an outline count.
      const double cross = ab.x() * bc.y() - ab.y() * bc.x();
      if (std::abs(cross) > 1e-6 * ab.norm() * bc.norm()) turning.push_back(b);
    }
  }
  return turning;
}

}  // namespace tessella
