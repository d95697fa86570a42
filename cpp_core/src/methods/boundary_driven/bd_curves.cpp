#include "methods/boundary_driven/bd_curves.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

#include "geometry/segment_closest.h"
#include "mesh/seam_sides.h"
#include "methods/boundary_driven/bd_geometry.h"
#include "tessella/errors.h"

namespace tessella {

namespace {

constexpr double kSameFamily = 0.7;  // |cos| above this: a parallel line (within ~45 deg)

struct FieldDir {
  Vec2 uv;
  Vec3 d3;
};

struct Pole {
  Vec3 xyz;
  Vec2 uv;        // one (u,v) of it
  bool along_u;   // the collapsed iso-line runs along u (v is the pole's)
  int loop = -1;  // the boundary loop holding its stretch
};

// A face the curves run on: its trims, their segment grid, its field and
// classifier, its poles and seams, and the smooth edges to other charts.
struct Chart {
  const SurfaceFace* face;
  const std::vector<BdPolyline>* boundary;
  const std::vector<std::vector<int>>* across;  // null: no smooth edge
  const BdSeedPlan* plan;                       // null: seeds spaced along every trim
  bd::SegmentGrid grid;
  BdTensorGrid field;
  UvTrimClassifier inside;
  std::vector<Pole> poles;
  bool wrap_u = false, wrap_v = false;  // closed round a seam along u / v
  int loop_base = 0;                    // its loops' line ids: -1 - (loop_base + k)

  // The chart across segment `seg` of loop `loop` (-1: a trim).
  int across_at(int loop, int seg) const {
    if (!across || loop < 0 || static_cast<std::size_t>(loop) >= across->size()) return -1;
    const std::vector<int>& a = (*across)[static_cast<std::size_t>(loop)];
    return seg >= 0 && static_cast<std::size_t>(seg) < a.size() ? a[static_cast<std::size_t>(seg)]
                                                                : -1;
  }
};

// A stretch of a curve on one chart: its points (the first piece of a trace
// without its start), where it entered (a later piece: the trim point it
// came in at) and where it ended.
struct Piece {
  int chart = 0;
  std::vector<Vec2> pts;
  BdCurveEnd start, end;
};

// A traced curve: its pieces in order along it (one on a single face).
struct TracedCurve {
  std::vector<BdCurve> pieces;
  std::vector<int> chart;
};

class Tracer {
 public:
  struct Input {
    const SurfaceFace* face;
    const std::vector<BdPolyline>* boundary;
    const std::vector<std::vector<int>>* across;
    const BdSeedPlan* plan;
  };

  Tracer(const std::vector<Input>& inputs, const BdTensor& tensor, const BdCurveParams& p)
      : p_(p), h_(p.spacing * p.step_fraction), hash_(p.spacing * 0.75) {
    double extent = 0;
    int loops = 0;
    for (const Input& in : inputs) {
      const SurfaceFace& face = *in.face;
      const std::vector<BdPolyline>& boundary = *in.boundary;
      Chart c{&face,
              &boundary,
              in.across,
              in.plan,
              make_grid(face, boundary),
              p.field ? *p.field : make_field(face, tensor, p.spacing),
              bd::make_classifier(boundary),
              {},
              closed_along(face, 0),
              closed_along(face, 1),
              loops};
      const int ci = static_cast<int>(charts_.size());
      for (std::size_t k = 0; k < boundary.size(); ++k) {
        const BdPolyline& line = boundary[k];
        for (int i = 0; i < line.segment_count(); ++i)
          c.grid.add(line.uv[i], line.seg_end_uv(i), k, i);
        const int n = std::max(3, static_cast<int>(std::ceil(line.length() / h_)));
        for (int j = 0; j < n; ++j) {
          const double s = line.length() * j / n;
          // A smooth edge to another chart is no line to keep away from.
          double at = s;
          if (c.across_at(static_cast<int>(k), line.segment_at(at)) >= 0) continue;
          Vec3 t3;
          Vec2 tuv;
          bd_tangent_at(line, s, t3, tuv);
          const Vec2 uv = line.uv_at(s);
          hash_.add(
              {face.point(uv.x(), uv.y()), t3, uv, -1 - (loops + static_cast<int>(k)), s, ci});
        }
      }
      loops += static_cast<int>(boundary.size());
      extent += face.model_size();
      // Poles: trim stretches collapsed to one point in 3D (a sphere's apex).
      for (const BdPolyline& line : boundary) {
        const double tiny = 1e-12 * line.length();
        for (int i = 0; i < line.segment_count(); ++i) {
          const Vec2 duv = line.seg_end_uv(i) - line.uv[i];
          if (!line.collapsed(i) || duv.norm() == 0) continue;
          bool known = false;
          for (const Pole& pole : c.poles) known = known || (pole.xyz - line.xyz[i]).norm() <= tiny;
          if (!known)
            c.poles.push_back({line.xyz[i], line.uv[i], std::abs(duv.x()) > std::abs(duv.y()),
                               static_cast<int>(&line - boundary.data())});
        }
      }
      charts_.push_back(std::move(c));
    }
    max_steps_ = static_cast<int>(std::min(1e6, 20.0 * extent / h_ + 100));
  }

  // The field direction closest to `ref` (3D) at uv.
  FieldDir dir_at(int c, const Vec2& uv, const Vec3& ref) const {
    const Chart& ch = charts_[static_cast<std::size_t>(c)];
    const BdDirections d = eval_bd_tensor(ch.field, *ch.face, uv);
    const double a = ref.dot(d.d1), b = ref.dot(d.d2);
    if (std::abs(a) >= std::abs(b)) return a >= 0 ? FieldDir{d.uv1, d.d1} : FieldDir{-d.uv1, -d.d1};
    return b >= 0 ? FieldDir{d.uv2, d.d2} : FieldDir{-d.uv2, -d.d2};
  }

  bool too_close(const Vec3& p, const Vec3& dir, double radius, bool ignore_boundary) const {
    bool hit = false;
    hash_.near(p, [&](const bd::HashedPoint& hp) {
      if (hit || (ignore_boundary && hp.line < 0)) return;
      if (std::abs(hp.dir.dot(dir)) > kSameFamily && (hp.p - p).norm() < radius) hit = true;
    });
    return hit;
  }

  // The first crossing of [p,q] with chart c's trim polylines (ignoring one
  // at p when skip_start): appends it to pts, fills `end` and returns true;
  // `next` is the chart across the segment crossed (-1: a trim).
  bool first_crossing(int c, const Vec2& p, const Vec2& q, bool skip_start, std::vector<Vec2>& pts,
                      BdCurveEnd& end, int& next) const {
    const Chart& ch = charts_[static_cast<std::size_t>(c)];
    double best = 2.0, best_s = 0;
    int best_loop = -1, best_seg = -1;
    ch.grid.query(p, q, [&](int loop, int seg) {
      double t, s;
      const BdPolyline& line = (*ch.boundary)[loop];
      if (!bd::intersect_segments(p, q, line.uv[seg], line.seg_end_uv(seg), t, s)) return;
      if (skip_start && t < 1e-6) return;
      if (t < best) best = t, best_loop = loop, best_seg = seg, best_s = s;
    });
    next = -1;
    if (best_loop < 0) return false;
    const BdPolyline& line = (*ch.boundary)[best_loop];
    best_s = std::clamp(best_s, 0.0, 1.0);
    pts.push_back(line.uv[best_seg] + best_s * (line.seg_end_uv(best_seg) - line.uv[best_seg]));
    end.loop = best_loop;
    end.s = line.s_at(best_seg, best_s);
    next = ch.across_at(best_loop, best_seg);
    return true;
  }

  bool crosses_boundary(int c, const Vec2& a, const Vec2& b) const {
    const Chart& ch = charts_[static_cast<std::size_t>(c)];
    bool hit = false;
    ch.grid.query(a, b, [&](int loop, int seg) {
      double t, s;
      const BdPolyline& line = (*ch.boundary)[loop];
      if (!hit && bd::intersect_segments(a, b, line.uv[seg], line.seg_end_uv(seg), t, s))
        hit = true;
    });
    return hit;
  }

  // Whether a and b lie on the two sides of the seam of a face closed round
  // its period (near in 3D, half a period or more apart in (u,v)). A curve
  // coming up to the seam must end on it, as on a trim, not stop short of
  // it because its own start, or a curve on the other side, is near in 3D:
  // that left a strip as wide as the stop distance without a node beside
  // the seam, meshed with rods five times the size long.
  bool across_seam(int c, const Vec2& a, const Vec2& b) const {
    const Chart& ch = charts_[static_cast<std::size_t>(c)];
    return (ch.wrap_u && std::abs(a.x() - b.x()) > 0.5 * ch.face->u_period()) ||
           (ch.wrap_v && std::abs(a.y() - b.y()) > 0.5 * ch.face->v_period());
  }

  // The (u,v) to aim at to join the hashed point hp (on chart c) from p. At
  // a pole (an iso-line collapsed to one point: a sphere's apex) hp's (u,v)
  // is one of the many that give that point, so aim straight across the
  // collapsed line, keeping p's parameter along it; aiming at hp's own (u,v)
  // would cross the whole parameter range and end the curve on the far side
  // of the face.
  Vec2 join_aim(int c, const Vec2& p, const bd::HashedPoint& hp) const {
    const SurfacePoint d =
        charts_[static_cast<std::size_t>(c)].face->derivatives(hp.uv.x(), hp.uv.y());
    const double du = d.du.norm(), dv = d.dv.norm();
    Vec2 aim = hp.uv;
    if (du <= 1e-9 * dv)
      aim.x() = p.x();
    else if (dv <= 1e-9 * du)
      aim.y() = p.y();
    return aim;
  }

  // Where a curve leaving chart `from` at 3D point x enters chart `to`: the
  // nearest point of `to`'s trim segments along the edge to `from`.
  bool enter(int from, int to, const Vec3& x, Vec2& uv, BdCurveEnd& at) const {
    const Chart& ch = charts_[static_cast<std::size_t>(to)];
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < ch.boundary->size(); ++k) {
      const BdPolyline& line = (*ch.boundary)[k];
      for (int i = 0; i < line.segment_count(); ++i) {
        if (ch.across_at(static_cast<int>(k), i) != from) continue;
        const Vec3 a = line.xyz[i], d = line.xyz[(i + 1) % line.xyz.size()] - a;
        const double t = closest_fraction(a, d, x);
        const double dist = (a + t * d - x).squaredNorm();
        if (dist < best) {
          best = dist;
          uv = line.uv[i] + t * (line.seg_end_uv(i) - line.uv[i]);
          at.loop = static_cast<int>(k);
          at.s = line.s_at(i, t);
        }
      }
    }
    return std::isfinite(best);
  }

  // Traces from uv on chart c along `dir` (3D), on into the charts across
  // the smooth edges it reaches. pieces[0] holds the points on c (excluding
  // the start); each later piece starts where its curve entered its chart.
  // Returns how it ended.
  enum class End { Boundary, Outside, Near, Closed, Steps };
  End trace(int c, const Vec2& start, const Vec3& dir, int id, double arc_sign,
            bool start_on_boundary, std::vector<Piece>& pieces) {
    Vec2 p = start;
    Vec3 ref = dir;
    const Vec3 start3 = charts_[static_cast<std::size_t>(c)].face->point(start.x(), start.y());
    double arc = 0;
    bool skip_start = start_on_boundary;
    pieces.assign(1, Piece{});
    pieces.back().chart = c;
    int in_piece = 0;  // steps on this chart
    for (int step = 0; step < max_steps_; ++step, ++in_piece) {
      const Chart& ch = charts_[static_cast<std::size_t>(c)];
      std::vector<Vec2>& pts = pieces.back().pts;
      BdCurveEnd& end = pieces.back().end;
      const FieldDir k1 = dir_at(c, p, ref);
      const Vec2 pm = p + 0.5 * h_ * k1.uv;
      const FieldDir k2 = dir_at(c, pm, k1.d3);
      const Vec2 q = p + h_ * k2.uv;
      ref = k2.d3;
      // the first crossing of [p,q] with the trim polylines
      int next = -1;
      if (first_crossing(c, p, q, in_piece == 0 && skip_start, pts, end, next)) {
        // A piece that crossed straight back (a curve along a smooth edge)
        // ends the curve there.
        if (next < 0 || (pieces.size() > 1 && pts.size() < 3)) return End::Boundary;
        const Vec3 x = ch.face->point(pts.back().x(), pts.back().y());
        Piece into;
        into.chart = next;
        Vec2 uv;
        if (!enter(c, next, x, uv, into.start)) return End::Boundary;
        into.pts.push_back(uv);
        pieces.push_back(std::move(into));
        c = next;
        p = uv;
        skip_start = true;
        in_piece = -1;
        continue;
      }
      if (!ch.inside.contains(q)) return End::Outside;
      const Vec3 q3 = ch.face->point(q.x(), q.y());
      // Near a pole the field turns round the point and a step of h crosses
      // much of the parameter range: the curve ends at the pole, reached
      // straight across the collapsed iso-line from p.
      for (const Pole& pole : ch.poles) {
        if (&pole == leaving_) continue;
        if ((q3 - pole.xyz).norm() >= p_.stop_fraction * p_.spacing) continue;
        const Vec2 aim = pole.along_u ? Vec2(p.x(), pole.uv.y()) : Vec2(pole.uv.x(), p.y());
        if (first_crossing(c, p, p + 1.05 * (aim - p), false, pts, end, next)) return End::Boundary;
        return End::Near;
      }
      arc += h_ * arc_sign;
      // parallel lines nearby (other lines; this one only far back along it)
      const bd::HashedPoint* nearest = nullptr;
      // A curve leaving a pole runs among the lines that reached it, which
      // converge there, until it is a spacing away.
      const bool by_pole = leaving_ && (q3 - leaving_->xyz).norm() < p_.spacing;
      // Round a pole the lines of one family converge: at the stop distance
      // they would join each other until one or two go on, and the cells
      // between two parallels there go round the face as rings. Where the
      // girth round the closed direction is under eight stop distances,
      // lines keep an eighth of it apart instead.
      double nearest_d = p_.stop_fraction * p_.spacing;
      if (!ch.poles.empty() && (ch.wrap_u || ch.wrap_v)) {
        const SurfacePoint d = ch.face->derivatives(q.x(), q.y());
        const double girth =
            ch.wrap_u ? d.du.norm() * ch.face->u_period() : d.dv.norm() * ch.face->v_period();
        nearest_d = std::min(nearest_d, girth / 8);
      }
      hash_.near(q3, [&](const bd::HashedPoint& hp) {
        if (by_pole) return;
        if (std::abs(hp.dir.dot(ref)) <= kSameFamily) return;
        if (hp.chart == c && across_seam(c, q, hp.uv)) return;
        if (hp.line == id && std::abs(arc - hp.arc) <= 4 * p_.spacing) return;
        const double d = (hp.p - q3).norm();
        if (d < nearest_d) nearest_d = d, nearest = &hp;
      });
      if (arc_sign > 0 && std::abs(arc) > 4 * p_.spacing && (q3 - start3).norm() < 1.5 * h_ &&
          !start_on_boundary)
        return End::Closed;
      if (nearest != nullptr) {
        // Join the parallel line: a last step just across it (the network
        // stage finds the crossing), or onto the trim if it is the trim. A
        // line on another chart is left to the network stage (a dangling
        // end, pruned).
        if (nearest->chart != c) return End::Near;
        const Vec2 target = p + 1.05 * (join_aim(c, p, *nearest) - p);
        if (nearest->line < 0) {
          if (first_crossing(c, p, target, false, pts, end, next)) return End::Boundary;
          return End::Near;
        }
        if (ch.inside.contains(target) && !crosses_boundary(c, p, target)) pts.push_back(target);
        return End::Near;
      }
      pts.push_back(q);
      hash_.add({q3, ref, q, id, arc, c});
      p = q;
    }
    return End::Steps;
  }

  // Traces a curve through seed (both ways unless from_boundary) and stores it.
  void add_curve(int c, const Vec2& seed, const Vec3& dir, const BdCurveEnd& seed_end,
                 bool from_boundary) {
    if (static_cast<int>(curves_.size()) >= p_.max_curves)
      throw LimitExceeded("more than max_curves = " + std::to_string(p_.max_curves) +
                          " BDCurves: raise size or max_curves");
    const int id = static_cast<int>(curves_.size());
    const SurfaceFace& face = *charts_[static_cast<std::size_t>(c)].face;
    hash_.add({face.point(seed.x(), seed.y()), dir, seed, id, 0.0, c});
    std::vector<Piece> fwd, bwd;
    const End e = trace(c, seed, dir, id, 1.0, from_boundary, fwd);
    BdCurveEnd bend;
    if (from_boundary) {
      bend = seed_end;
    } else if (e != End::Closed) {
      trace(c, seed, -dir, id, -1.0, false, bwd);
      bend = bwd[0].end;
    }
    // The pieces in order: the backward ones reversed, the seed's, the forward ones.
    TracedCurve t;
    auto keep = [&](int chart, BdCurve piece) {
      if (piece.uv.size() < 2) return;
      const SurfaceFace& on = *charts_[static_cast<std::size_t>(chart)].face;
      for (const Vec2& q : piece.uv) piece.xyz.push_back(on.point(q.x(), q.y()));
      t.pieces.push_back(std::move(piece));
      t.chart.push_back(chart);
    };
    for (std::size_t i = bwd.size(); i-- > 1;) {
      BdCurve piece;
      piece.uv.assign(bwd[i].pts.rbegin(), bwd[i].pts.rend());
      piece.start = bwd[i].end;
      piece.end = bwd[i].start;
      keep(bwd[i].chart, std::move(piece));
    }
    BdCurve mid;
    if (!bwd.empty()) mid.uv.assign(bwd[0].pts.rbegin(), bwd[0].pts.rend());
    mid.uv.push_back(seed);
    mid.uv.insert(mid.uv.end(), fwd[0].pts.begin(), fwd[0].pts.end());
    mid.closed = e == End::Closed;
    mid.start = bend;
    mid.end = fwd[0].end;
    keep(c, std::move(mid));
    for (std::size_t i = 1; i < fwd.size(); ++i) {
      BdCurve piece;
      piece.uv = fwd[i].pts;
      piece.start = fwd[i].start;
      piece.end = fwd[i].end;
      keep(fwd[i].chart, std::move(piece));
    }
    curves_.push_back(std::move(t));  // kept even when empty: ids stay aligned
  }

  void run() {
    const double sp = p_.spacing;
    // 1. seeds on the boundary spans, traced inward; then every loop that fewer
    //    than two curves reach gets two seeds regardless of spacing (a loop
    //    with no curve would leave an opening inside a panel, a loop with one
    //    would hang on a bridge)
    const bool in_order = seed_in_order();
    for (int round = 0; round < 2; ++round) {
      const bool forced = round == 1;
      if (!forced && in_order) {
        ordered_seeds();
        continue;
      }
      for (std::size_t ci = 0; ci < charts_.size(); ++ci) {
        const int c = static_cast<int>(ci);
        const Chart& ch = charts_[ci];
        for (std::size_t k = 0; k < ch.boundary->size(); ++k) {
          if (forced) {
            int ends = 0;
            for (const TracedCurve& t : curves_)
              for (std::size_t i = 0; i < t.pieces.size(); ++i)
                if (t.chart[i] == c)
                  ends += (t.pieces[i].start.loop == int(k)) + (t.pieces[i].end.loop == int(k));
            if (ends >= 2) continue;
          }
          const BdPolyline& line = (*ch.boundary)[k];
          std::vector<double> corners = bd_corners(line, p_.corner_angle_deg);
          std::vector<double> seeds;
          const double len = line.length();
          if (corners.empty()) {
            const int m = std::max(4, static_cast<int>(std::lround(len / sp)));
            for (int j = 0; j < m; ++j) seeds.push_back(len * j / m);
          } else {
            for (std::size_t cc = 0; cc < corners.size(); ++cc) {
              const double a = corners[cc];
              const double b = cc + 1 < corners.size() ? corners[cc + 1] : corners[0] + len;
              const int m = static_cast<int>(std::lround((b - a) / sp));
              for (int j = 1; j < m; ++j) seeds.push_back(a + (b - a) * j / m);
            }
          }
          if (forced && seeds.size() > 2) seeds = {seeds[0], seeds[seeds.size() / 2]};
          if (!forced && ch.plan) dictate_seeds(ch, k, seeds);
          for (double s : seeds) seed_on_trim(c, k, s, forced);
        }
      }
    }
    seed_at_poles();
    // 2. offset seeds, line by line (boundary loops first, then curves as
    //    made); none beside a smooth edge to another chart
    for (std::size_t ci = 0; ci < charts_.size(); ++ci) {
      const Chart& ch = charts_[ci];
      for (std::size_t k = 0; k < ch.boundary->size(); ++k) {
        std::vector<char> skip;
        if (ch.across && k < ch.across->size())
          for (int a : (*ch.across)[k]) skip.push_back(a >= 0 ? 1 : 0);
        offset_seeds_along(static_cast<int>(ci), (*ch.boundary)[k].uv, true,
                           skip.empty() ? nullptr : &skip);
      }
    }
    for (std::size_t c = 0; c < curves_.size(); ++c) {
      const TracedCurve t = curves_[c];  // copy: curves_ grows
      for (std::size_t i = 0; i < t.pieces.size(); ++i)
        offset_seeds_along(t.chart[i], t.pieces[i].uv, false);
    }
  }

  // A face closed round a pole (a cone's apex, a dome's top) needs at
  // least three curves from the pole: else the cell round it is one panel
  // going all the way round (a ring with a slit to the pole, refused; the
  // curves that come up from the rim converge and stop a stop distance
  // from each other, before the pole's own capture radius, on any cone
  // steeper than about 1:2). Curves are added from the pole, a third of a
  // turn apart, starting from one that reached it, each traced from a
  // hundredth of a spacing off the pole (its frame is undefined at the
  // point itself) and starting at the pole.
  void seed_at_poles() {
    for (std::size_t ci = 0; ci < charts_.size(); ++ci) {
      const Chart& ch = charts_[ci];
      const SurfaceFace& face = *ch.face;
      for (const Pole& pole : ch.poles) {
        if (pole.loop < 0 || !(pole.along_u ? ch.wrap_u : ch.wrap_v)) continue;
        const int axis = pole.along_u ? 0 : 1;
        const double period = axis == 0 ? face.u_period() : face.v_period();
        const double near = 1e-6 * p_.spacing;
        std::vector<double> reached;
        for (const TracedCurve& t : curves_)
          for (std::size_t i = 0; i < t.pieces.size(); ++i) {
            if (t.chart[i] != static_cast<int>(ci) || t.pieces[i].uv.empty()) continue;
            const BdCurve& piece = t.pieces[i];
            if (piece.start.loop == pole.loop && (piece.xyz.front() - pole.xyz).norm() <= near)
              reached.push_back(piece.uv.front()[axis]);
            if (piece.end.loop == pole.loop && (piece.xyz.back() - pole.xyz).norm() <= near)
              reached.push_back(piece.uv.back()[axis]);
          }
        if (reached.size() >= 3) continue;
        const BdPolyline& line = (*ch.boundary)[static_cast<std::size_t>(pole.loop)];
        const double base = reached.empty() ? pole.uv[axis] + period / 6 : reached.front();
        for (int j = 0; j < 3; ++j) {
          const double at = base + period * j / 3;
          bool taken = false;
          for (double r : reached) {
            const double d = std::remainder(at - r, period);
            taken = taken || std::abs(d) < period / 6;
          }
          if (!taken) seed_at_pole(static_cast<int>(ci), pole, line, at, period);
        }
      }
    }
  }

  void seed_at_pole(int c, const Pole& pole, const BdPolyline& line, double at, double period) {
    const int axis = pole.along_u ? 0 : 1;
    const SurfaceFace& face = *charts_[static_cast<std::size_t>(c)].face;
    for (int i = 0; i < line.segment_count(); ++i) {
      if (!line.collapsed(i) ||
          (line.xyz[static_cast<std::size_t>(i)] - pole.xyz).norm() > 1e-9 * face.model_size())
        continue;
      const Vec2 a = line.uv[static_cast<std::size_t>(i)], b = line.seg_end_uv(i);
      const double lo = std::min(a[axis], b[axis]), hi = std::max(a[axis], b[axis]);
      double x = lo + std::fmod(std::fmod(at - lo, period) + period, period);
      if (x > hi) continue;
      const double t = (x - a[axis]) / (b[axis] - a[axis]);
      const Vec2 on_pole = a + t * (b - a);
      // Off the pole, inward (the face lies left of its loop in (u,v)).
      const Vec2 along = (b - a).normalized();
      const Vec2 inward_uv(-along.y(), along.x());
      const SurfacePoint dp = face.derivatives(on_pole.x(), on_pole.y());
      const double speed = (dp.du * inward_uv.x() + dp.dv * inward_uv.y()).norm();
      if (!(speed > 0)) return;
      const Vec2 start = on_pole + (0.01 * p_.spacing / speed) * inward_uv;
      if (!charts_[static_cast<std::size_t>(c)].inside.contains(start)) return;
      const SurfacePoint ds = face.derivatives(start.x(), start.y());
      const Vec3 inward = ds.du * inward_uv.x() + ds.dv * inward_uv.y();
      const FieldDir fd = dir_at(c, start, inward);
      if (fd.d3.dot(inward.normalized()) < 0.3) return;
      leaving_ = &pole;
      add_curve(c, start, fd.d3, {pole.loop, line.s_at(i, t)}, true);
      leaving_ = nullptr;
      TracedCurve& made = curves_.back();
      if (!made.pieces.empty() && made.chart[0] == c) {
        made.pieces[0].uv.insert(made.pieces[0].uv.begin(), on_pole);
        made.pieces[0].xyz.insert(made.pieces[0].xyz.begin(), pole.xyz);
      }
      return;
    }
  }

  // A curve from arc length s of chart c's loop k, inward along the field
  // (none where the field runs along the trim, or, unless forced, near a
  // parallel curve).
  void seed_on_trim(int c, std::size_t k, double s, bool forced) {
    const Chart& ch = charts_[static_cast<std::size_t>(c)];
    const SurfaceFace& face = *ch.face;
    const BdPolyline& line = (*ch.boundary)[k];
    Vec3 t3;
    Vec2 tuv;
    bd_tangent_at(line, s, t3, tuv);
    const Vec2 uv = line.uv_at(s);
    const SurfacePoint dp = face.derivatives(uv.x(), uv.y());
    const Vec3 inward = dp.du * -tuv.y() + dp.dv * tuv.x();  // left of the loop in (u,v)
    const FieldDir fd = dir_at(c, uv, inward);
    if (fd.d3.dot(inward.normalized()) < 0.3) return;  // field nearly along the trim here
    if (!forced && too_close(face.point(uv.x(), uv.y()), fd.d3, 0.4 * p_.spacing, true)) return;
    BdCurveEnd se{static_cast<int>(k), s};
    line.segment_at(se.s);  // wraps s into [0, length)
    add_curve(c, uv, fd.d3, se, true);
  }

  bool seed_in_order() const {
    for (const Chart& ch : charts_)
      if (ch.plan && !ch.plan->order.empty()) return true;
    return false;
  }

  // The plans' seeds over all charts in their one order (the charts' own
  // spaced seeds are not used: a group's plans dictate every segment).
  void ordered_seeds() {
    struct Ordered {
      int order, chart;
      BdCurveEnd at;
    };
    std::vector<Ordered> all;
    for (std::size_t ci = 0; ci < charts_.size(); ++ci) {
      const BdSeedPlan* plan = charts_[ci].plan;
      if (!plan) continue;
      for (std::size_t i = 0; i < plan->seeds.size(); ++i)
        all.push_back(
            {i < plan->order.size() ? plan->order[i] : 0, static_cast<int>(ci), plan->seeds[i]});
    }
    std::stable_sort(all.begin(), all.end(),
                     [](const Ordered& a, const Ordered& b) { return a.order < b.order; });
    for (const Ordered& o : all)
      seed_on_trim(o.chart, static_cast<std::size_t>(o.at.loop), o.at.s, false);
  }

  // Along the segments the plan dictates, its seeds replace the spaced ones
  // (in order along the loop, so the curves are traced in a fixed order).
  static void dictate_seeds(const Chart& ch, std::size_t k, std::vector<double>& seeds) {
    const BdSeedPlan& plan = *ch.plan;
    if (k >= plan.dictated.size()) return;
    const std::vector<char>& flag = plan.dictated[k];
    const BdPolyline& line = (*ch.boundary)[k];
    std::vector<double> kept;
    for (double s : seeds) {
      double at = s;
      const int seg = line.segment_at(at);
      if (seg < 0 || static_cast<std::size_t>(seg) >= flag.size() || !flag[seg]) kept.push_back(s);
    }
    for (const BdCurveEnd& e : plan.seeds)
      if (e.loop == static_cast<int>(k)) kept.push_back(e.s);
    std::sort(kept.begin(), kept.end());
    seeds = std::move(kept);
  }

  // `skip`: per segment, no seed beside it (flagged segments still count
  // towards the spacing along the line).
  void offset_seeds_along(int c, const std::vector<Vec2>& uv, bool is_boundary,
                          const std::vector<char>* skip = nullptr) {
    const SurfaceFace& face = *charts_[static_cast<std::size_t>(c)].face;
    const double sp = p_.spacing;
    // points every `spacing` of 3D arc length, starting half a spacing in
    double acc = 0.5 * sp;
    for (std::size_t i = 0; i + 1 < uv.size() + (is_boundary ? 1 : 0); ++i) {
      const Vec2& a = uv[i];
      const Vec2& b = uv[(i + 1) % uv.size()];
      const double l = (face.point(b.x(), b.y()) - face.point(a.x(), a.y())).norm();
      if (l <= 0) continue;
      double t = (acc <= l) ? acc / l : 2.0;
      const bool skipped = skip && i < skip->size() && (*skip)[i];
      while (t <= 1.0) {
        const Vec2 p = a + t * (b - a);
        const SurfacePoint dp = face.derivatives(p.x(), p.y());
        const Vec2 tuv = b - a;
        const Vec3 t3 = (dp.du * tuv.x() + dp.dv * tuv.y()).normalized();
        const Vec3 left = dp.du * -tuv.y() + dp.dv * tuv.x();
        for (int side : {1, -1}) {
          if ((is_boundary && side < 0) || skipped) continue;
          try_offset_seed(c, p, t3, side * left);
        }
        acc += sp;
        t = acc / l;
      }
      acc -= l;
    }
  }

  void try_offset_seed(int c, const Vec2& p, const Vec3& along, const Vec3& across) {
    const Chart& ch = charts_[static_cast<std::size_t>(c)];
    const double sp = p_.spacing;
    Vec2 q = p;
    Vec3 ref = across;
    const int n = 4;
    for (int k = 0; k < n; ++k) {
      const FieldDir k1 = dir_at(c, q, ref);
      const FieldDir k2 = dir_at(c, q + 0.5 * (sp / n) * k1.uv, k1.d3);
      q += (sp / n) * k2.uv;
      ref = k2.d3;
      if (!ch.inside.contains(q)) return;
    }
    const FieldDir fd = dir_at(c, q, along);
    if (too_close(ch.face->point(q.x(), q.y()), fd.d3, 0.75 * sp, false)) return;
    add_curve(c, q, fd.d3, BdCurveEnd{}, false);
  }

  // Per chart, the pieces of the curves on it, in the order traced.
  std::vector<std::vector<BdCurve>> take() {
    std::vector<std::vector<BdCurve>> out(charts_.size());
    for (TracedCurve& t : curves_)
      for (std::size_t i = 0; i < t.pieces.size(); ++i)
        out[static_cast<std::size_t>(t.chart[i])].push_back(std::move(t.pieces[i]));
    return out;
  }

 private:
  static BdTensorGrid make_field(const SurfaceFace& face, const BdTensor& tensor, double spacing) {
    int nu = 0, nv = 0;
    bd_field_grid_size(face, spacing, nu, nv);
    return sample_bd_tensor(tensor, face, nu, nv);
  }

  static bd::SegmentGrid make_grid(const SurfaceFace& face,
                                   const std::vector<BdPolyline>& boundary) {
    const UvBounds b = face.bounds();
    std::size_t segs = 0;
    for (const auto& l : boundary) segs += l.uv.size();
    const int cells =
        std::clamp(static_cast<int>(std::sqrt(static_cast<double>(segs)) / 2), 8, 512);
    return bd::SegmentGrid(Vec2(b.u_min, b.v_min), Vec2(b.u_max, b.v_max), cells);
  }

  BdCurveParams p_;
  double h_;
  bd::PointHash hash_;
  std::vector<Chart> charts_;
  const Pole* leaving_ = nullptr;  // the pole the curve being traced starts at
  int max_steps_ = 0;
  std::vector<TracedCurve> curves_;
};

void check_curve_params(double model_size, const BdCurveParams& params) {
  require_in_range("curve spacing (mm)", params.spacing, 1e-6 * model_size, model_size);
  require_in_range("step_fraction", params.step_fraction, 0.01, 0.5);
  require_in_range("stop_fraction", params.stop_fraction, 0.1, 0.9);
  require_in_range("corner_angle (deg)", params.corner_angle_deg, 1.0, 179.0);
  require_in_range("max_curves", params.max_curves, 1, 1e7);
}

}  // namespace

void bd_field_grid_size(const SurfaceFace& face, double spacing, int& nu, int& nv) {
  const UvBounds b = face.bounds();
  auto length = [&](bool along_u) {
    double len = 0;
    Vec3 prev = Vec3::Zero();
    for (int k = 0; k <= 64; ++k) {
      const double t = k / 64.0;
      const Vec3 p = along_u
                         ? face.point(b.u_min + t * (b.u_max - b.u_min), 0.5 * (b.v_min + b.v_max))
                         : face.point(0.5 * (b.u_min + b.u_max), b.v_min + t * (b.v_max - b.v_min));
      if (k > 0) len += (p - prev).norm();
      prev = p;
    }
    return len;
  };
  nu = std::clamp(static_cast<int>(3 * length(true) / spacing) + 2, 16, 400);
  nv = std::clamp(static_cast<int>(3 * length(false) / spacing) + 2, 16, 400);
}

std::vector<BdCurve> trace_bd_curves(const SurfaceFace& face, const BdTensor& tensor,
                                     const std::vector<BdPolyline>& boundary,
                                     const BdCurveParams& params) {
  check_curve_params(face.model_size(), params);
  if (boundary.empty()) throw InvalidGeometry("the face has no trim loops");
  Tracer t({{&face, &boundary, nullptr, nullptr}}, tensor, params);
  t.run();
  return std::move(t.take()[0]);
}

std::vector<std::vector<BdCurve>> trace_bd_curves_across(const std::vector<BdChart>& charts,
                                                         const BdTensor& tensor,
                                                         const BdCurveParams& params) {
  double smallest = std::numeric_limits<double>::infinity();
  std::vector<Tracer::Input> inputs;
  for (const BdChart& c : charts) {
    if (!c.face || !c.boundary || c.boundary->empty())
      throw InvalidGeometry("a face of the group has no trim loops");
    smallest = std::min(smallest, c.face->model_size());
    inputs.push_back({c.face, c.boundary, &c.across, &c.plan});
  }
  if (charts.empty()) return {};
  if (params.field)
    throw InvalidParameter("trace_bd_curves_across: each chart samples its own field");
  check_curve_params(smallest, params);
  Tracer t(inputs, tensor, params);
  t.run();
  return t.take();
}

}  // namespace tessella
