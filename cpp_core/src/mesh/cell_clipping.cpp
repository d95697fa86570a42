// Cutting a grid of general quad cells by the trim loops (mesh/cell_clipping.h).
//
// Why Clipper (libpolyclipping): its exact integer predicates survive the
// degenerate cases (a trim running along a cell edge, as the natural boundary
// does along the border cells; a loop through a node). (u,v) maps affinely
// onto a 2^50 integer range, ~1e-15 of the span.
//
// Vertex identity: a grid node and a trim polyline point keep their integer
// point in every cell's output. A crossing of a trim with a slanted cell edge
// is rounded by Clipper, and the two cells beside that edge may round it
// differently: every output point within kOnEdge of a cell edge is recorded
// on that edge, and the points of one edge closer than kOnEdge become one
// vertex. Each edge's vertices then go into every panel side running along
// it, so a vertex that one cell has on the edge (where an opening split it)
// is in its neighbour's outline too.
#include "mesh/cell_clipping.h"

#include <algorithm>
#include <array>
#include <clipper.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "geometry/trim_deflection.h"
#include "geometry/uv_trim_classifier.h"
#include "mesh/clip_to_box.h"
#include "mesh/panel_model.h"
#include "mesh/seam_sides.h"
#include "mesh/sliver_merge.h"
#include "tessella/errors.h"
#include "tessella/progress.h"
#include "tessella/surface_face.h"

namespace tessella {

namespace {

using ClipperLib::cInt;
using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

constexpr double kIntRange = 1125899906842624.0;  // 2^50
// ~1e-11 of the span: far above Clipper's rounding of a crossing (a few
// units), far below any length that matters for a panel.
constexpr double kOnEdge = 1e-11 * kIntRange;
// An opening in a cell is split off by at most this many nested splits.
constexpr int kMaxSplits = 16;

struct PointHash {
  std::size_t operator()(const IntPoint& p) const {
    return std::hash<unsigned long long>()(static_cast<unsigned long long>(p.X) * 1000003ULL ^
                                           static_cast<unsigned long long>(p.Y));
  }
};
struct PointEq {
  bool operator()(const IntPoint& a, const IntPoint& b) const { return a.X == b.X && a.Y == b.Y; }
};
template <class T>
using PointMap = std::unordered_map<IntPoint, T, PointHash, PointEq>;
using PointSet = std::unordered_set<IntPoint, PointHash, PointEq>;

// Affine map of the (u,v) box holding the nodes and the trims onto
// [0, 2^50]^2.
struct Frame {
  double u0 = 0, v0 = 0, su = 1, sv = 1;
  IntPoint to_int(const Vec2& p) const {
    return IntPoint(static_cast<cInt>(std::llround((p.x() - u0) * su)),
                    static_cast<cInt>(std::llround((p.y() - v0) * sv)));
  }
  Vec2 to_uv(const IntPoint& p) const { return {u0 + double(p.X) / su, v0 + double(p.Y) / sv}; }
  // Parameter of the foot of (u,v) point q on the line ab (not clamped).
  double parameter_on(const Vec2& q, const IntPoint& a, const IntPoint& b) const {
    const double dx = double(b.X - a.X), dy = double(b.Y - a.Y);
    const double px = (q.x() - u0) * su - double(a.X), py = (q.y() - v0) * sv - double(a.Y);
    const double l2 = dx * dx + dy * dy;
    return l2 > 0 ? (px * dx + py * dy) / l2 : 0.0;
  }
};

Frame frame_of(const std::vector<Vec2>& nodes, const std::vector<TrimLoop>& loops) {
  Vec2 lo = nodes.front(), hi = nodes.front();
  auto add = [&](const Vec2& p) { lo = lo.cwiseMin(p), hi = hi.cwiseMax(p); };
  for (const Vec2& p : nodes) add(p);
  for (const TrimLoop& l : loops)
    for (const Vec2& p : l.uv) add(p);
  Frame f;
  f.u0 = lo.x(), f.v0 = lo.y();
  f.su = kIntRange / (hi.x() > lo.x() ? hi.x() - lo.x() : 1.0);
  f.sv = kIntRange / (hi.y() > lo.y() ? hi.y() - lo.y() : 1.0);
  return f;
}

Path box(cInt x0, cInt y0, cInt x1, cInt y1) {
  return {IntPoint(x0, y0), IntPoint(x1, y0), IntPoint(x1, y1), IntPoint(x0, y1)};
}

// The trim loops in integers.
struct Domain {
  Paths paths;
  std::vector<int> loop;  // trim_loops index of each path
  PointMap<Vec2> exact_uv;
  PointSet corner;
};

// Drops the trim points strictly inside an axis-parallel straight run (not
// trim corners): the natural boundary of an untrimmed face is four such runs,
// finely discretized because the edges bend in 3D; kept, every point would
// become an outline point of a border cell along its straight side. A run may
// be off the axis by kRunSlack units, ~1e-12 of the span (a cylinder's seam
// pcurve and the circle ending on it meet 23 units apart).
Path without_axis_run_points(const Path& path, const PointSet& corner) {
  constexpr cInt kRunSlack = 1024;
  auto near = [](cInt a, cInt b) { return std::abs(a - b) <= kRunSlack; };
  auto inner = [&](const IntPoint& a, const IntPoint& p, const IntPoint& b) {
    if (corner.count(p)) return false;
    if (near(a.Y, p.Y) && near(a.Y, b.Y))
      return (a.X < p.X && p.X < b.X) || (b.X < p.X && p.X < a.X);
    if (near(a.X, p.X) && near(a.X, b.X))
      return (a.Y < p.Y && p.Y < b.Y) || (b.Y < p.Y && p.Y < a.Y);
    return false;
  };
  const std::size_t n = path.size();
  std::size_t start = 0;  // a point that stays, so no run wraps around the start
  while (start < n && inner(path[(start + n - 1) % n], path[start], path[(start + 1) % n])) ++start;
  if (start == n) return path;
  Path out;
  for (std::size_t k = 0; k <= n; ++k) {
    const IntPoint& p = path[(start + k) % n];
    while (out.size() >= 2 && inner(out[out.size() - 2], out.back(), p)) out.pop_back();
    if (k < n) out.push_back(p);
  }
  return out.size() >= 3 ? out : path;
}

Domain domain_of(const std::vector<TrimLoop>& loops, const Frame& frame) {
  Domain d;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    Path path;
    for (std::size_t k = 0; k < loops[l].uv.size(); ++k) {
      const IntPoint p = frame.to_int(loops[l].uv[k]);
      if (loops[l].corner[k]) d.corner.insert(p);
      if (!path.empty() && p.X == path.back().X && p.Y == path.back().Y) continue;
      path.push_back(p);
      d.exact_uv.emplace(p, loops[l].uv[k]);
    }
    while (path.size() > 1 && path.front().X == path.back().X && path.front().Y == path.back().Y)
      path.pop_back();
    if (path.size() < 3) continue;
    d.paths.push_back(without_axis_run_points(path, d.corner));
    d.loop.push_back(static_cast<int>(l));
  }
  return d;
}

// The trim segments on a uniform grid of buckets over the integer plane.
class SegmentBuckets {
 public:
  struct Segment {
    IntPoint a, b;
    int path;
  };

  explicit SegmentBuckets(const Paths& paths) {
    for (std::size_t p = 0; p < paths.size(); ++p)
      for (std::size_t k = 0; k < paths[p].size(); ++k)
        segments_.push_back({paths[p][k], paths[p][(k + 1) % paths[p].size()], int(p)});
    g_ = std::clamp(static_cast<int>(std::sqrt(double(segments_.size()))), 1, 256);
    buckets_.resize(std::size_t(g_) * g_);
    for (std::size_t s = 0; s < segments_.size(); ++s) {
      const Segment& e = segments_[s];
      for (int j = index(std::min(e.a.Y, e.b.Y)); j <= index(std::max(e.a.Y, e.b.Y)); ++j)
        for (int i = index(std::min(e.a.X, e.b.X)); i <= index(std::max(e.a.X, e.b.X)); ++i)
          buckets_[std::size_t(j) * g_ + i].push_back(static_cast<int>(s));
    }
  }

  const Segment& operator[](int s) const { return segments_[std::size_t(s)]; }

  // The segments whose bounding box meets [x0, x1] x [y0, y1], in index order.
  std::vector<int> near(double x0, double y0, double x1, double y1) const {
    std::vector<int> out;
    for (int j = index(y0); j <= index(y1); ++j)
      for (int i = index(x0); i <= index(x1); ++i)
        for (int s : buckets_[std::size_t(j) * g_ + i]) {
          const Segment& e = segments_[std::size_t(s)];
          if (std::max(e.a.X, e.b.X) >= x0 && std::min(e.a.X, e.b.X) <= x1 &&
              std::max(e.a.Y, e.b.Y) >= y0 && std::min(e.a.Y, e.b.Y) <= y1)
            out.push_back(s);
        }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

 private:
  int index(double x) const {
    return std::clamp(static_cast<int>(std::floor(x / kIntRange * g_)), 0, g_ - 1);
  }

  std::vector<Segment> segments_;
  int g_ = 1;
  std::vector<std::vector<int>> buckets_;
};

// Distance of p from the segment ab (integer units) and the parameter of its
// foot on ab (clamped to [0, 1]).
double segment_distance(const IntPoint& p, const IntPoint& a, const IntPoint& b, double* t) {
  const double dx = double(b.X - a.X), dy = double(b.Y - a.Y);
  const double px = double(p.X - a.X), py = double(p.Y - a.Y);
  const double l2 = dx * dx + dy * dy;
  const double s = l2 > 0 ? std::clamp((px * dx + py * dy) / l2, 0.0, 1.0) : 0.0;
  if (t) *t = s;
  return std::hypot(px - s * dx, py - s * dy);
}

double distance(const IntPoint& a, const IntPoint& b) {
  return std::hypot(double(a.X - b.X), double(a.Y - b.Y));
}

// A lattice node closer to a trim than this share of its shortest cell edge
// goes onto the trim: rows that run along a trim a hair off it (a net laid
// along the very curves a face set was cut along, each computed to its own
// tolerance) would otherwise cut knife-edge slivers and crossings at grazing
// angles that the two faces of a shared edge resolve differently.
constexpr double kSnapShare = 1e-3;

// Between a node put into a trim's path (or moved onto one of its points)
// and the next such node or trim corner, the trim points lying on one of
// the node's own lattice edges (within its reach) go: there the trim runs
// along the row, and its points would sit on the cell edge as crossings
// (nodes a few millimetres apart along a row, on one side of a shared edge
// only). Trim corners stay, and so do points where the trim leaves the row
// (a boundary panel's outline).
// node_edges(k): the lattice edges at the node put in at path point k.
Path without_points_along_rows(
    const Path& path, const std::vector<double>& reach, const PointSet& corner,
    const std::function<std::vector<std::array<IntPoint, 2>>(std::size_t)>& node_edges) {
  const std::size_t n = path.size();
  std::vector<std::size_t> put;  // nodes put in and trim corners, in path order
  for (std::size_t k = 0; k < n; ++k)
    if (reach[k] > 0 || corner.count(path[k])) put.push_back(k);
  if (put.size() < 2) return path;
  std::vector<char> drop(n, 0);
  // Each node's lattice edges, asked once.
  std::vector<std::vector<std::array<IntPoint, 2>>> edges(n);
  for (std::size_t k : put)
    if (reach[k] > 0) edges[k] = node_edges(k);
  auto on_row = [&](const IntPoint& q, std::size_t node_at) {
    for (const auto& e : edges[node_at])
      if (segment_distance(q, e[0], e[1], nullptr) <= reach[node_at]) return true;
    return false;
  };
  for (std::size_t m = 0; m < put.size(); ++m) {
    const std::size_t a = put[m], b = put[(m + 1) % put.size()];
    if ((b + n - a) % n < 2 || (reach[a] <= 0 && reach[b] <= 0)) continue;
    for (std::size_t q = (a + 1) % n; q != b; q = (q + 1) % n)
      if (on_row(path[q], a) || on_row(path[q], b)) drop[q] = 1;
  }
  Path out;
  for (std::size_t k = 0; k < n; ++k)
    if (!drop[k]) out.push_back(path[k]);
  return out.size() >= 3 ? out : path;
}

// Moves each node within kSnapShare of its shortest cell edge from a trim
// segment onto the trim curve, and puts the moved node into the trim's path
// as a point of its own, so that the cut meets it exactly (Clipper's integer
// predicates then see the trim run through the cell corner). A node whose
// foot lies past an end of the segment in (u,v) takes that trim point.
// uv and N are the nodes' (u,v) and integer points, updated in place.
void snap_nodes_onto_trims(const SurfaceFace& face, const Frame& frame, Domain& domain, int nu,
                           int nv, std::vector<Vec2>& uv, std::vector<IntPoint>& N) {
  const SegmentBuckets trim(domain.paths);
  struct Insert {
    int path;
    std::size_t segment;
    double t;
    IntPoint point;
    double reach;
    std::size_t node;
  };
  std::vector<Insert> inserts;
  // Nodes moved onto a trim point already in the path: its reach, the node.
  PointMap<std::pair<double, std::size_t>> onto_point;
  PointSet taken;
  for (const Path& path : domain.paths)
    for (const IntPoint& p : path) taken.insert(p);
  // Segment index within its path, from the buckets' running index.
  std::vector<std::size_t> first_of_path(domain.paths.size() + 1, 0);
  for (std::size_t k = 0; k < domain.paths.size(); ++k)
    first_of_path[k + 1] = first_of_path[k] + domain.paths[k].size();
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const std::size_t k = std::size_t(j) * std::size_t(nu) + std::size_t(i);
      const IntPoint p = N[k];
      double edge = std::numeric_limits<double>::infinity();
      if (i > 0) edge = std::min(edge, distance(p, N[k - 1]));
      if (i + 1 < nu) edge = std::min(edge, distance(p, N[k + 1]));
      if (j > 0) edge = std::min(edge, distance(p, N[k - std::size_t(nu)]));
      if (j + 1 < nv) edge = std::min(edge, distance(p, N[k + std::size_t(nu)]));
      const double reach = kSnapShare * edge;
      if (!(reach >= 1.0) || taken.count(p)) continue;
      const double x = double(p.X), y = double(p.Y);
      int best_segment = -1;
      double best = reach, best_t = 0;
      for (int seg : trim.near(x - reach, y - reach, x + reach, y + reach)) {
        double t = 0;
        const double d = segment_distance(p, trim[seg].a, trim[seg].b, &t);
        if (d <= best) best = d, best_segment = seg, best_t = t;
      }
      if (best_segment < 0) continue;
      const auto& seg = trim[best_segment];
      const std::size_t in_path = std::size_t(best_segment) - first_of_path[std::size_t(seg.path)];
      if (best <= kOnEdge) {
        // On the trim within Clipper's exactness: the node stays where it
        // is and goes into the path as it is.
        if (best_t > 0 && best_t < 1) inserts.push_back({seg.path, in_path, best_t, p, reach, k});
        taken.insert(p);
        continue;
      }
      const Vec2 on_chord = frame.to_uv(seg.a) + best_t * (frame.to_uv(seg.b) - frame.to_uv(seg.a));
      const Vec2 q = face.snap_to_trim(domain.loop[std::size_t(seg.path)], on_chord);
      const double t = frame.parameter_on(q, seg.a, seg.b);
      if (t <= 0 || t >= 1) {
        // Past an end (or on it): the node becomes that trim point.
        const IntPoint end = t <= 0 ? seg.a : seg.b;
        if (onto_point.count(end)) continue;  // another node's place
        const auto ex = domain.exact_uv.find(end);
        uv[k] = ex != domain.exact_uv.end() ? ex->second : frame.to_uv(end);
        N[k] = end;
        onto_point.emplace(end, std::make_pair(reach, k));
        continue;
      }
      const IntPoint at = frame.to_int(q);
      if (const auto ex = domain.exact_uv.find(at); ex != domain.exact_uv.end()) {
        if (onto_point.count(at)) continue;
        uv[k] = ex->second, N[k] = at;  // onto a trim point (a corner, in rounding)
        onto_point.emplace(at, std::make_pair(reach, k));
        continue;
      }
      if (taken.count(at)) continue;  // another node's place
      taken.insert(at);
      inserts.push_back({seg.path, in_path, t, at, reach, k});
      uv[k] = q;
      N[k] = at;
    }
  }
  if (inserts.empty() && onto_point.empty()) return;
  // Into the paths, each segment's points in order along it.
  std::sort(inserts.begin(), inserts.end(), [](const Insert& a, const Insert& b) {
    return std::tie(a.path, a.segment, a.t) < std::tie(b.path, b.segment, b.t);
  });
  std::size_t next = 0;
  for (std::size_t pi = 0; pi < domain.paths.size(); ++pi) {
    const Path& old = domain.paths[pi];
    bool any = next < inserts.size() && inserts[next].path == int(pi);
    for (std::size_t s = 0; s < old.size() && !any; ++s) any = onto_point.count(old[s]) > 0;
    if (!any) continue;
    Path out;
    std::vector<double> reach;    // of each point: > 0 where a node was put in
    std::vector<std::size_t> at;  // that node
    for (std::size_t s = 0; s < old.size(); ++s) {
      out.push_back(old[s]);
      const auto moved = onto_point.find(old[s]);
      reach.push_back(moved != onto_point.end() ? moved->second.first : 0.0);
      at.push_back(moved != onto_point.end() ? moved->second.second : 0);
      while (next < inserts.size() && inserts[next].path == int(pi) && inserts[next].segment == s) {
        out.push_back(inserts[next].point);
        reach.push_back(inserts[next].reach);
        at.push_back(inserts[next++].node);
      }
    }
    domain.paths[pi] = without_points_along_rows(out, reach, domain.corner, [&](std::size_t q) {
      const std::size_t k = at[q];
      const int i = int(k % std::size_t(nu)), j = int(k / std::size_t(nu));
      std::vector<std::array<IntPoint, 2>> edges;
      if (i > 0) edges.push_back({N[k], N[k - 1]});
      if (i + 1 < nu) edges.push_back({N[k], N[k + 1]});
      if (j > 0) edges.push_back({N[k], N[k - std::size_t(nu)]});
      if (j + 1 < nv) edges.push_back({N[k], N[k + std::size_t(nu)]});
      return edges;
    });
  }
}

// A line the opening split ran along: x = at (axis 0) or y = at (axis 1).
struct SplitLine {
  int axis;
  cInt at;
};

// Polygons of `subject` (non-zero fill) inside `clip`. A polygon that came out
// with holes (an opening wholly inside the cell) is cut in two by the axis
// line through the middle of its first hole, across its wider side, and both
// sides are cut again: every polygon is simple and without holes, and the
// split runs inside the polygon from its outline to the hole.
void clip_to(const Paths& subject, const Path& clip, int depth, std::vector<Path>& out,
             std::vector<SplitLine>& splits) {
  ClipperLib::Clipper clipper(ClipperLib::ioPreserveCollinear | ClipperLib::ioStrictlySimple);
  clipper.AddPaths(subject, ClipperLib::ptSubject, true);
  clipper.AddPath(clip, ClipperLib::ptClip, true);
  ClipperLib::PolyTree tree;
  clipper.Execute(ClipperLib::ctIntersection, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  // Outer contours: the tree's first level and the islands inside holes.
  std::vector<const ClipperLib::PolyNode*> outers(tree.Childs.begin(), tree.Childs.end());
  for (std::size_t k = 0; k < outers.size(); ++k) {
    const ClipperLib::PolyNode* outer = outers[k];
    for (const ClipperLib::PolyNode* hole : outer->Childs)
      for (const ClipperLib::PolyNode* island : hole->Childs) outers.push_back(island);
    if (outer->Childs.empty() || depth >= kMaxSplits) {
      out.push_back(outer->Contour);
      continue;
    }
    cInt ox0 = outer->Contour[0].X, ox1 = ox0, oy0 = outer->Contour[0].Y, oy1 = oy0;
    for (const IntPoint& p : outer->Contour) {
      ox0 = std::min(ox0, p.X), ox1 = std::max(ox1, p.X);
      oy0 = std::min(oy0, p.Y), oy1 = std::max(oy1, p.Y);
    }
    const Path& hole = outer->Childs.front()->Contour;
    cInt hx0 = hole[0].X, hx1 = hx0, hy0 = hole[0].Y, hy1 = hy0;
    for (const IntPoint& p : hole) {
      hx0 = std::min(hx0, p.X), hx1 = std::max(hx1, p.X);
      hy0 = std::min(hy0, p.Y), hy1 = std::max(hy1, p.Y);
    }
    Paths local{outer->Contour};
    for (const ClipperLib::PolyNode* h : outer->Childs) local.push_back(h->Contour);
    if (ox1 - ox0 >= oy1 - oy0) {
      const cInt xm = hx0 + (hx1 - hx0) / 2;
      splits.push_back({0, xm});
      clip_to(local, box(ox0 - 1, oy0 - 1, xm, oy1 + 1), depth + 1, out, splits);
      clip_to(local, box(xm, oy0 - 1, ox1 + 1, oy1 + 1), depth + 1, out, splits);
    } else {
      const cInt ym = hy0 + (hy1 - hy0) / 2;
      splits.push_back({1, ym});
      clip_to(local, box(ox0 - 1, oy0 - 1, ox1 + 1, ym), depth + 1, out, splits);
      clip_to(local, box(ox0 - 1, ym, ox1 + 1, oy1 + 1), depth + 1, out, splits);
    }
  }
}

// Puts the points the polygons of one cell have on a split line into every
// polygon side running along it (the two sides of a split meet the same
// trim crossings, but a side may end at a point of the other).
void join_split_lines(std::vector<Path>& polys, const std::vector<SplitLine>& splits) {
  for (const SplitLine& line : splits) {
    auto on = [&](const IntPoint& p) { return (line.axis == 0 ? p.X : p.Y) == line.at; };
    auto along = [&](const IntPoint& p) { return line.axis == 0 ? p.Y : p.X; };
    std::vector<cInt> at;
    for (const Path& poly : polys)
      for (const IntPoint& p : poly)
        if (on(p)) at.push_back(along(p));
    std::sort(at.begin(), at.end());
    at.erase(std::unique(at.begin(), at.end()), at.end());
    if (at.size() < 3) continue;
    for (Path& poly : polys) {
      Path fixed;
      for (std::size_t k = 0; k < poly.size(); ++k) {
        const IntPoint& a = poly[k];
        const IntPoint& b = poly[(k + 1) % poly.size()];
        fixed.push_back(a);
        if (!on(a) || !on(b)) continue;
        const cInt lo = std::min(along(a), along(b)), hi = std::max(along(a), along(b));
        auto first = std::upper_bound(at.begin(), at.end(), lo);
        auto last = std::lower_bound(at.begin(), at.end(), hi);
        std::vector<cInt> between(first, last);
        if (along(a) > along(b)) std::reverse(between.begin(), between.end());
        for (cInt c : between)
          fixed.push_back(line.axis == 0 ? IntPoint(line.at, c) : IntPoint(c, line.at));
      }
      poly = std::move(fixed);
    }
  }
}

// Vertices merged by union-find; the root is the best of a group: a grid node
// before a trim point before a computed crossing, then the first made.
struct VertexGroups {
  std::vector<int> parent, kind;
  int add(int k) {
    parent.push_back(static_cast<int>(parent.size()));
    kind.push_back(k);
    return parent.back();
  }
  int find(int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  }
  void unite(int a, int b) {
    a = find(a), b = find(b);
    if (a == b) return;
    if (std::make_pair(kind[b], b) < std::make_pair(kind[a], a)) std::swap(a, b);
    parent[b] = a;
  }
};

enum Kind { kGridNode = 0, kTrimPoint = 1, kCrossing = 2 };

}  // namespace

PanelMesh clip_cells(const SurfaceFace& face, const std::vector<Vec2>& grid_nodes, int nu, int nv,
                     const GridClipParams& params) {
  if (nu < 2 || nv < 2 || grid_nodes.size() != std::size_t(nu) * std::size_t(nv)) {
    throw InvalidParameter("a cell grid needs at least 2 x 2 nodes, row by row");
  }
  const int cu = nu - 1, cv = nv - 1;  // cells per row, per column
  const double cells = double(cu) * double(cv);
  if (cells > double(params.max_panels)) {
    throw LimitExceeded("the grid would have " + std::to_string(static_cast<long long>(cells)) +
                        " panels, more than max_panels = " + std::to_string(params.max_panels) +
                        ": choose smaller counts or raise max_panels");
  }
  const std::vector<TrimLoop> loops =
      face.trim_loops(trim_deflection(face, params.trim_deflection));
  if (loops.empty()) throw InvalidGeometry("the face has no usable trim loop");
  const Frame frame = frame_of(grid_nodes, loops);
  Domain domain = domain_of(loops, frame);
  if (domain.paths.empty()) throw InvalidGeometry("the face has no usable trim loop");
  std::vector<Vec2> nodes = grid_nodes;
  std::vector<IntPoint> N(nodes.size());
  for (std::size_t k = 0; k < nodes.size(); ++k) N[k] = frame.to_int(nodes[k]);
  snap_nodes_onto_trims(face, frame, domain, nu, nv, nodes, N);
  const SegmentBuckets trim(domain.paths);
  const UvTrimClassifier inside(loops);
  auto node = [nu](int i, int j) { return j * nu + i; };
  auto corners = [&](int i, int j) -> std::array<int, 4> {
    return {node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)};
  };

  // Cell polygons: far from every trim segment a cell is wholly in or out.
  std::vector<std::vector<Path>> cell_polys(std::size_t(cu) * cv);
  std::vector<char> full(cell_polys.size(), 0), near(cell_polys.size(), 0);
  for (int j = 0; j < cv; ++j) {
    for (int i = 0; i < cu; ++i) {
      const std::size_t c = std::size_t(j) * cu + i;
      Path quad;
      for (int k : corners(i, j)) quad.push_back(N[k]);
      cInt x0 = quad[0].X, x1 = x0, y0 = quad[0].Y, y1 = y0;
      for (const IntPoint& p : quad) {
        x0 = std::min(x0, p.X), x1 = std::max(x1, p.X);
        y0 = std::min(y0, p.Y), y1 = std::max(y1, p.Y);
      }
      if (!trim.near(double(x0), double(y0), double(x1), double(y1)).empty()) {
        near[c] = 1;
        continue;
      }
      Vec2 mid = Vec2::Zero();
      for (int k : corners(i, j)) mid += 0.25 * nodes[std::size_t(k)];
      if (inside.contains(mid)) {
        full[c] = 1;
        cell_polys[c].push_back(quad);
      }
    }
  }
  // Cells at a trim: the domain is cut to the bounding box of half the grid
  // (the longer side, in cells), that piece to the box of half of that half,
  // down to single cells, skipping parts with no cell at the trim: each level
  // costs one pass over the trim, not one per column or cell. Each box has a
  // margin, so no box side touches a cell of its part.
  std::vector<std::size_t> near_sum(std::size_t(cu + 1) * (cv + 1), 0);  // 2D prefix sums
  auto at = [cu](int i, int j) { return std::size_t(j) * std::size_t(cu + 1) + std::size_t(i); };
  for (int j = 0; j < cv; ++j)
    for (int i = 0; i < cu; ++i)
      near_sum[at(i + 1, j + 1)] = near_sum[at(i + 1, j)] + near_sum[at(i, j + 1)] -
                                   near_sum[at(i, j)] + (near[std::size_t(j) * cu + i] ? 1 : 0);
  auto near_in = [&](int i0, int i1, int j0, int j1) {
    return near_sum[at(i1, j1)] - near_sum[at(i1, j0)] - near_sum[at(i0, j1)] +
           near_sum[at(i0, j0)];
  };
  const auto cut = clip_to_box;
  // The box of the nodes of cells [i0, i1) x [j0, j1), with a margin.
  auto part_box = [&](int i0, int i1, int j0, int j1) {
    cInt x0 = std::numeric_limits<cInt>::max(), x1 = std::numeric_limits<cInt>::min();
    cInt y0 = x0, y1 = x1;
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const IntPoint& p = N[node(i, j)];
        x0 = std::min(x0, p.X), x1 = std::max(x1, p.X);
        y0 = std::min(y0, p.Y), y1 = std::max(y1, p.Y);
      }
    }
    const cInt mx = (x1 - x0) / 16 + 16, my = (y1 - y0) / 16 + 16;
    return box(x0 - mx, y0 - my, x1 + mx, y1 + my);
  };
  const std::size_t near_total = near_in(0, cu, 0, cv);
  std::size_t near_done = 0;
  // Recursion depth ~ log2(cells): bounded, no deep stack.
  std::function<void(const Paths&, int, int, int, int)> part = [&](const Paths& piece, int i0,
                                                                   int i1, int j0, int j1) {
    if (i1 - i0 == 1 && j1 - j0 == 1) {
      const std::size_t c = std::size_t(j0) * cu + i0;
      Path quad;
      for (int k : corners(i0, j0)) quad.push_back(N[k]);
      std::vector<SplitLine> splits;
      clip_to(piece, quad, 0, cell_polys[c], splits);
      join_split_lines(cell_polys[c], splits);
      if (++near_done % 64 == 0)
        report_progress(double(near_done) / double(near_total), "cutting the grid by the trim");
      return;
    }
    const bool split_u = i1 - i0 >= j1 - j0;
    const int mid = split_u ? (i0 + i1) / 2 : (j0 + j1) / 2;
    for (int half = 0; half < 2; ++half) {
      const int a0 = split_u ? (half ? mid : i0) : i0, a1 = split_u ? (half ? i1 : mid) : i1;
      const int b0 = split_u ? j0 : (half ? mid : j0), b1 = split_u ? j1 : (half ? j1 : mid);
      if (near_in(a0, a1, b0, b1) == 0) continue;
      part(cut(piece, ClipperLib::pftNonZero, part_box(a0, a1, b0, b1)), a0, a1, b0, b1);
    }
  };
  // The domain's loops count by parity; Clipper's output (holes turning the
  // other way) by winding from here on.
  if (near_total > 0)
    part(cut(domain.paths, ClipperLib::pftEvenOdd, part_box(0, cu, 0, cv)), 0, cu, 0, cv);

  // Vertices by integer point: grid nodes, trim points, computed crossings.
  PointMap<int> node_at;
  for (std::size_t k = 0; k < N.size(); ++k) node_at.emplace(N[k], static_cast<int>(k));
  VertexGroups groups;
  std::vector<IntPoint> point;
  std::vector<int> node_of;  // grid node of a vertex, -1 if none
  PointMap<int> index_of;
  auto vertex = [&](const IntPoint& p) {
    const auto it = index_of.find(p);
    if (it != index_of.end()) return it->second;
    const auto n = node_at.find(p);
    const int kind = n != node_at.end()              ? kGridNode
                     : domain.exact_uv.count(p) != 0 ? kTrimPoint
                                                     : kCrossing;
    const int id = groups.add(kind);
    point.push_back(p);
    node_of.push_back(n != node_at.end() ? n->second : -1);
    index_of.emplace(p, id);
    return id;
  };
  // Cell edges: (i,j)-(i+1,j) first, then (i,j)-(i,j+1); per edge the
  // vertices found on it (parameter from its first node, vertex).
  const int h_edges = cu * nv;
  auto h_edge = [&](int i, int j) { return j * cu + i; };
  auto v_edge = [&](int i, int j) { return h_edges + j * nu + i; };
  std::vector<std::array<int, 2>> edge_nodes(std::size_t(h_edges) + std::size_t(nu) * cv);
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      if (i < cu) edge_nodes[h_edge(i, j)] = {node(i, j), node(i + 1, j)};
      if (j < cv) edge_nodes[v_edge(i, j)] = {node(i, j), node(i, j + 1)};
    }
  std::vector<std::vector<std::pair<double, int>>> on_edge(edge_nodes.size());

  std::vector<std::vector<int>> panels;
  std::vector<std::size_t> panel_cell;
  for (int j = 0; j < cv; ++j) {
    for (int i = 0; i < cu; ++i) {
      const std::size_t c = std::size_t(j) * cu + i;
      const std::array<int, 4> cell_edges = {h_edge(i, j), v_edge(i + 1, j), h_edge(i, j + 1),
                                             v_edge(i, j)};
      for (Path& poly : cell_polys[c]) {
        if (!ClipperLib::Orientation(poly)) std::reverse(poly.begin(), poly.end());
        std::vector<int> ids;
        for (const IntPoint& p : poly) ids.push_back(vertex(p));
        for (int v : ids) {
          if (node_of[std::size_t(v)] >= 0) continue;
          for (int e : cell_edges) {
            const auto [na, nb] = edge_nodes[std::size_t(e)];
            double t = 0;
            if (segment_distance(point[v], N[na], N[nb], &t) > kOnEdge) continue;
            // On a node: the node itself (a trim through it).
            if (distance(point[v], N[na]) <= kOnEdge) {
              groups.unite(v, vertex(N[na]));
            } else if (distance(point[v], N[nb]) <= kOnEdge) {
              groups.unite(v, vertex(N[nb]));
            } else {
              on_edge[std::size_t(e)].push_back({t, v});
            }
          }
        }
        panels.push_back(std::move(ids));
        panel_cell.push_back(c);
      }
    }
  }
  // One vertex per point of an edge (the two cells' roundings of a crossing).
  for (std::size_t e = 0; e < on_edge.size(); ++e) {
    auto& list = on_edge[e];
    std::sort(list.begin(), list.end());
    const double length = distance(N[edge_nodes[e][0]], N[edge_nodes[e][1]]);
    for (std::size_t k = 1; k < list.size(); ++k)
      if ((list[k].first - list[k - 1].first) * length <= kOnEdge)
        groups.unite(list[k - 1].second, list[k].second);
  }
  // A computed crossing on a trim lies on a polyline chord: it moves onto the
  // trim edges' own curves. (u,v) is not isotropic, so the closest point may
  // lie past an end of the chord: then the crossing becomes that trim point
  // (no outline folding back past it).
  std::unordered_map<int, Vec2> snapped;
  for (std::size_t v = 0; v < point.size(); ++v) {
    if (groups.kind[v] != kCrossing || groups.find(static_cast<int>(v)) != static_cast<int>(v))
      continue;
    const IntPoint p = point[v];
    const double x = double(p.X), y = double(p.Y);
    int best_segment = -1;
    double best = kOnEdge;
    for (int s : trim.near(x - kOnEdge, y - kOnEdge, x + kOnEdge, y + kOnEdge)) {
      const double d = segment_distance(p, trim[s].a, trim[s].b, nullptr);
      if (d <= best) best = d, best_segment = s;
    }
    if (best_segment < 0) continue;
    const auto& seg = trim[best_segment];
    const Vec2 q = face.snap_to_trim(domain.loop[std::size_t(seg.path)], frame.to_uv(p));
    const double t = frame.parameter_on(q, seg.a, seg.b);
    if (t < 0 || t > 1) {
      groups.unite(static_cast<int>(v), vertex(t < 0 ? seg.a : seg.b));
    } else {
      snapped.emplace(static_cast<int>(v), q);
    }
  }
  std::vector<char> on_cell_edge(point.size(), 0);
  std::vector<std::vector<int>> edges_of(point.size());
  for (std::size_t e = 0; e < on_edge.size(); ++e) {
    std::vector<std::pair<double, int>> list;
    for (int k : {0, 1}) {
      const auto it = index_of.find(N[edge_nodes[e][std::size_t(k)]]);
      if (it != index_of.end()) list.push_back({double(k), groups.find(it->second)});
    }
    for (const auto& [t, v] : on_edge[e]) {
      const int root = groups.find(v);
      bool seen = false;
      for (const auto& x : list) seen = seen || x.second == root;
      if (!seen) list.push_back({t, root});
      on_cell_edge[std::size_t(root)] = 1;
    }
    std::sort(list.begin(), list.end());
    for (const auto& x : list) edges_of[std::size_t(x.second)].push_back(static_cast<int>(e));
    on_edge[e] = std::move(list);
  }

  // Panels on the merged vertices, each side along a cell edge through every
  // vertex of that edge between its ends.
  PanelMesh mesh;
  std::vector<char> panel_full;
  std::vector<std::size_t> kept_cell;
  for (std::size_t k = 0; k < panels.size(); ++k) {
    std::vector<int> ids;
    for (int v : panels[k]) {
      const int r = groups.find(v);
      if (ids.empty() || ids.back() != r) ids.push_back(r);
    }
    while (ids.size() > 1 && ids.front() == ids.back()) ids.pop_back();
    if (ids.size() < 3) continue;
    std::vector<int> fixed;
    for (std::size_t s = 0; s < ids.size(); ++s) {
      const int a = ids[s], b = ids[(s + 1) % ids.size()];
      fixed.push_back(a);
      for (int e : edges_of[std::size_t(a)]) {
        const auto& eb = edges_of[std::size_t(b)];
        if (std::find(eb.begin(), eb.end(), e) == eb.end()) continue;
        const auto& list = on_edge[std::size_t(e)];
        std::size_t ia = 0, ib = 0;
        for (std::size_t q = 0; q < list.size(); ++q) {
          if (list[q].second == a) ia = q;
          if (list[q].second == b) ib = q;
        }
        if (ia < ib)
          for (std::size_t q = ia + 1; q < ib; ++q) fixed.push_back(list[q].second);
        else
          for (std::size_t q = ia; q-- > ib + 1;) fixed.push_back(list[q].second);
        break;
      }
    }
    mesh.panels.push_back(std::move(fixed));
    panel_full.push_back(full[panel_cell[k]]);
    kept_cell.push_back(panel_cell[k]);
  }
  if (mesh.panels.empty()) throw InvalidGeometry("no grid cell lies in the face");

  // Positions: nodes and trim points exact, crossings as snapped above.
  mesh.uv.resize(point.size());
  for (std::size_t v = 0; v < point.size(); ++v) {
    if (groups.find(static_cast<int>(v)) != static_cast<int>(v)) continue;
    const auto ex = domain.exact_uv.find(point[v]);
    mesh.uv[v] = node_of[v] >= 0                      ? nodes[std::size_t(node_of[v])]
                 : ex != domain.exact_uv.end()        ? ex->second
                 : snapped.count(static_cast<int>(v)) ? snapped.at(static_cast<int>(v))
                                                      : frame.to_uv(point[v]);
  }
  mesh.xyz.resize(point.size());
  for (std::size_t v = 0; v < point.size(); ++v)
    if (groups.find(static_cast<int>(v)) == static_cast<int>(v))
      mesh.xyz[v] = face.point(mesh.uv[v].x(), mesh.uv[v].y());

  // Nodes (rod ends): grid nodes, points on a cell edge (its crossings with
  // the trims), trim corners and points two panels share (on a split line).
  // The other trim points only shape the boundary panels' outlines.
  {
    std::vector<int> uses(point.size(), 0);
    for (const auto& panel : mesh.panels)
      for (int v : panel) ++uses[std::size_t(v)];
    mesh.is_node.assign(point.size(), 0);
    for (std::size_t v = 0; v < point.size(); ++v)
      mesh.is_node[v] =
          node_of[v] >= 0 || on_cell_edge[v] || domain.corner.count(point[v]) || uses[v] >= 2;
  }
  remove_unused_vertices(mesh);  // the merged-away points

  // Nominal panel area: the mean whole cell (all panels if none is whole).
  double sum = 0, sum_all = 0;
  int n_full = 0;
  for (std::size_t k = 0; k < mesh.panels.size(); ++k) {
    const double a = panel_area(mesh, k);
    sum_all += a;
    if (panel_full[k]) sum += a, ++n_full;
  }
  mesh.nominal_area = n_full > 0 ? sum / n_full : sum_all / double(mesh.panels.size());

  // A sliver is a cut piece much smaller than the cell it was cut from (the
  // relaxed cells differ in size, so compare with its own cell).
  std::vector<double> cell_area(mesh.panels.size(), 0.0);
  for (std::size_t k = 0; k < mesh.panels.size(); ++k) {
    if (panel_full[k]) continue;
    const int i = static_cast<int>(kept_cell[k] % std::size_t(cu));
    const int j = static_cast<int>(kept_cell[k] / std::size_t(cu));
    std::vector<Vec2> uv;
    std::vector<Vec3> xyz;
    for (int q : corners(i, j)) {
      uv.push_back(nodes[std::size_t(q)]);
      xyz.push_back(face.point(uv.back().x(), uv.back().y()));
    }
    cell_area[k] = panel_model_area(xyz, uv);
  }
  mesh.merged_slivers = merge_slivers(mesh, params.sliver_fraction, cell_area);
  weld_coincident_vertices(mesh, 1e-9 * face.model_size());
  weld_loose_seam(face, mesh);
  if (face.reversed()) reverse_panels(mesh);
  remove_unused_vertices(mesh);
  build_rods(mesh);
  return mesh;
}

}  // namespace tessella
