#include "tessella/panel_metrics.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <queue>
#include <tuple>
#include <utility>

#include "analysis/deviation_bound.h"
#include "analysis/known_surface_points.h"
#include "common/parallel_chunks.h"
#include "mesh/panel_model.h"
#include "tessella/errors.h"
#include "tessella/progress.h"
#include "tessella/surface_face.h"

namespace tessella {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Indices of `values`, largest first, equal values in index order (the order
// of a stable sort of the indices, without its indirect comparisons), taken
// lazily from a heap: a boundary panel's cut-off stops after a few dozen of
// its ~1,000 samples, so sorting them all (5% of panelize) is wasted. A NaN
// counts as +infinity (such a sample is probed first, never skipped).
class LargestFirst {
 public:
  explicit LargestFirst(const std::vector<double>& values) : heap_(values.size()) {
    for (std::size_t k = 0; k < values.size(); ++k)
      heap_[k] = {std::isnan(values[k]) ? std::numeric_limits<double>::infinity() : values[k], k};
    std::make_heap(heap_.begin(), heap_.end(), After());
  }
  bool empty() const { return heap_.empty(); }
  std::size_t top() const { return heap_.front().second; }
  void pop() {
    std::pop_heap(heap_.begin(), heap_.end(), After());
    heap_.pop_back();
  }

 private:
  // x comes after y: smaller value, or equal value and larger index (a
  // function object, which the heap's code inlines).
  struct After {
    bool operator()(const std::pair<double, std::size_t>& x,
                    const std::pair<double, std::size_t>& y) const {
      return x.first < y.first || (x.first == y.first && x.second > y.second);
    }
  };
  std::vector<std::pair<double, std::size_t>> heap_;
};

// The whole order at once.
std::vector<std::size_t> largest_first(const std::vector<double>& values) {
  std::vector<std::size_t> order;
  order.reserve(values.size());
  for (LargestFirst heap(values); !heap.empty(); heap.pop()) order.push_back(heap.top());
  return order;
}

double mean_edge(const std::vector<Vec3>& p) {
  double sum = 0;
  for (std::size_t k = 0; k < p.size(); ++k) sum += (p[(k + 1) % p.size()] - p[k]).norm();
  return sum / double(p.size());
}

double planarity(const std::vector<Vec3>& p) {
  const double edge = mean_edge(p);
  if (p.size() < 4 || edge <= 0) return 0.0;
  if (p.size() == 4) {
    // Distance between the diagonals as skew lines.
    const Vec3 d1 = p[2] - p[0], d2 = p[3] - p[1];
    const Vec3 n = d1.cross(d2);
    if (n.norm() <= 1e-300) return 0.0;
    return std::abs((p[1] - p[0]).dot(n)) / n.norm() / edge;
  }
  Vec3 c = Vec3::Zero();
  for (const Vec3& q : p) c += q;
  c /= double(p.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3& q : p) cov += (q - c) * (q - c).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Vec3 normal = eig.eigenvectors().col(0);
  double worst = 0;
  for (const Vec3& q : p) worst = std::max(worst, std::abs((q - c).dot(normal)));
  return worst / edge;
}

}  // namespace

namespace {

// Distance from one point of a panel model to the surface, with whether it is
// a verified foot point (an orthogonal local minimum of the distance).
struct Probe {
  double distance = 0;
  bool reliable = true;
  Vec2 foot = Vec2::Zero();
  Vec3 point = Vec3::Zero();  // S(foot)
  // The prober's first `checked` known surface points are none nearer to
  // the sample than `distance` by more than its slack (a recheck need only
  // look at the points met since).
  std::size_t checked = 0;
};

// Every distance here is that of x to a true surface point, so each is an
// upper bound of the true distance; a failed projection (no orthogonal foot
// point) is retried and replaced by the smallest such bound, and marked.
class Prober {
 public:
  Prober(const SurfaceFace& face, const std::vector<Vec2>& uv) : face_(face), uv_(uv) {
    for (const Vec2& q : uv) corner_.push_back(face.point(q.x(), q.y()));
    tiny_ = 1e-9 * face.model_size();
    search_ = face.search_bounds();
    seed_grid();
    local_.local_search = true;
  }

  // A cheap upper bound of the probe at x (sample parameters q): the distance
  // to the surface point at q itself, one evaluation and no projection. A
  // probe never returns more than this + slack(), so a sample whose bound
  // cannot beat a distance already found is not projected.
  // S(q) goes to *at_q if given, for the probe at the same sample.
  double cheap_bound(const Vec3& x, const Vec2& q, Vec3* at_q = nullptr) const {
    const Vec3 s_q = face_.point(q.x(), q.y());
    if (at_q) *at_q = s_q;
    return (s_q - x).norm();
  }
  double slack() const { return tiny_; }
  // A verified foot point within the slack: the probed point lies on the
  // face (no gradient there; a quad on a plane is all such points).
  bool on_face(const Probe& p) const { return p.reliable && !(p.distance > tiny_); }

  // The distance from x (model parameters q) to the surface, projecting from
  // `start`. Never more than cheap_bound(x, q), S(q) being a real surface
  // point: a Newton run that ended farther found no nearer foot point.
  // `known_s_q`: S(q) if cheap_bound already evaluated it.
  Probe operator()(const Vec3& x, const Vec2& start, const Vec2& q,
                   const Vec3* known_s_q = nullptr) const {
    const Probe p = peek(x, start, q, known_s_q);
    remember(p.foot, p.point);
    return p;
  }
  // The same probe, its foot point not remembered: a look that leaves the
  // probes after it exactly as they would have been without it.
  Probe peek(const Vec3& x, const Vec2& start, const Vec2& q,
             const Vec3* known_s_q = nullptr) const {
    Probe p = project(x, start);
    const Vec3 s_q = known_s_q ? *known_s_q : face_.point(q.x(), q.y());
    const double at_q = (s_q - x).norm();
    if (at_q + tiny_ < p.distance) {
      // The projection's foot is farther than S(q): not the nearest point.
      // The global search (OCCT's terrain: border panels kept S(q), 9.749 mm
      // away where the nearest point is 9.522, flagged unreliable, their
      // figures up to 1.6 times the distance).
      p = {at_q, false, q, s_q};
      offer_global(x, [&](double d, bool reliable, const Vec2& foot, const Vec3& at) {
        if (d < p.distance) p = {d, reliable, foot, at};
      });
    }
    return tighten(x, p);
  }

  // A converged Newton run can stop at a foot point on the wrong sheet of a
  // folded or strongly curved surface (an orthogonal local minimum, farther
  // than the true one: MAT.brep reported 3.9 mm where the distance is 2.6).
  // Every surface point met so far bounds the distance from above, so if
  // one is nearer than the probe's answer, Newton again from it and keep
  // the nearer of the two.
  // The points before p.checked are none of them nearer by more than the
  // slack (the scan's rule), so they are not scanned again: the same answer.
  Probe tighten(const Vec3& x, Probe p) const {
    double d_near = p.distance;
    const std::size_t near = known_.nearer(x, d_near, tiny_, p.checked);
    const std::size_t now = known_.size();
    if (near == now) {
      p.checked = now;
      return p;
    }
    const Vec2 from = known_.uv(near);
    const Projection again = face_.project(x, from, local_);
    if (again.distance + tiny_ < d_near) {
      const bool reliable = again.distance <= tiny_ || orthogonal(x, again);
      if (reliable) return {again.distance, reliable, again.uv, again.point, now};
    }
    Probe out{d_near, false, from, known_.xyz(near), now};
    if (again.distance < out.distance) out = {again.distance, false, again.uv, again.point, now};
    if (!again.used_fallback)
      offer_global(x, [&](double d, bool reliable, const Vec2& foot, const Vec3& at) {
        if (d <= out.distance + tiny_) out = {std::min(d, out.distance), reliable, foot, at, now};
      });
    return out;
  }
  // Tighten an earlier probe against every surface point met since.
  Probe recheck(const Vec3& x, const Probe& p) const {
    Probe t = tighten(x, p);
    if (t.distance < p.distance) remember(t.foot, t.point);
    return t;
  }

 private:
  Probe project(const Vec3& x, const Vec2& start) const {
    const Projection pr = face_.project(x, start, local_);
    std::size_t near = 0;
    double bound = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < corner_.size(); ++k) {
      const double d = (corner_[k] - x).norm();
      if (d < bound) bound = d, near = k;
    }
    if (!pr.used_fallback && pr.distance <= bound + tiny_)
      return {pr.distance, true, pr.uv, pr.point};
    // Newton failed, or stopped at a local minimum farther than a corner:
    // the fallback's answer if it is a foot point, a Newton run from the
    // nearest corner, the start point itself, the nearest corner.
    Probe best{pr.distance, pr.distance <= bound + tiny_ && orthogonal(x, pr), pr.uv, pr.point};
    auto offer = [&](double d, bool reliable, const Vec2& foot, const Vec3& at) {
      if (d < best.distance) best = {d, reliable, foot, at};
    };
    const Projection again = face_.project(x, uv_[near], local_);
    offer(again.distance, !again.used_fallback || orthogonal(x, again), again.uv, again.point);
    if (!pr.used_fallback && !again.used_fallback &&
        (!best.reliable || best.distance > bound + tiny_))
      offer_global(x, offer);
    offer(bound, false, uv_[near], corner_[near]);
    return best;
  }

  // Both Newton runs stopped at a local minimum farther than a known surface
  // point (another sheet of a folded or wavy surface): the global search, whose
  // answer is the nearest of its candidate basins and of the face's border
  // (MAT.brep reported 1.80 mm against 1.17 when only the nearer known point
  // bounded it). Rare on smooth faces (none on the bench faces; about four
  // a panel on OCCT's rough terrain): its cost is paid only here.
  // A panel asks for the same point's global search again (a probe's peek,
  // then its tightening: 15% of OCCT's terrain's 24,000 searches): each
  // answer is kept for the panel.
  template <class Offer>
  void offer_global(const Vec3& x, const Offer& offer) const {
    if (!local_.global_search) return;
    auto known =
        std::find_if(global_.begin(), global_.end(), [&](const auto& e) { return e.first == x; });
    if (known == global_.end()) known = global_.insert(global_.end(), {x, face_.project(x)});
    const Projection& g = known->second;
    offer(g.distance, true, g.uv, g.point);
  }

  // The corners alone are too few starting points on a surface with waves
  // shorter than the panel (a 2.5 m cell over 1.75 waves kept a foot on the
  // wrong wave, 648.5 mm against 626 mm): a 5 x 5 grid of surface points
  // over the corners' (u,v) box, widened by 10% and kept inside the face's
  // bounds (a periodic direction is not clamped), joins them. 25 evaluations
  // a panel, no projection.
  void seed_grid() {
    std::vector<Vec2> seed_uv;
    std::vector<Vec3> seed_xyz;
    if (!uv_.empty()) {
      Vec2 lo = uv_[0], hi = uv_[0];
      for (const Vec2& q : uv_) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
      const Vec2 margin = 0.1 * (hi - lo);
      lo -= margin, hi += margin;
      const UvBounds b = face_.bounds();
      if (!face_.u_periodic())
        lo.x() = std::max(lo.x(), b.u_min), hi.x() = std::min(hi.x(), b.u_max);
      if (!face_.v_periodic())
        lo.y() = std::max(lo.y(), b.v_min), hi.y() = std::min(hi.y(), b.v_max);
      const int k = 5;
      if (hi.x() > lo.x() && hi.y() > lo.y())
        for (int i = 0; i < k; ++i)
          for (int j = 0; j < k; ++j) {
            const Vec2 q(lo.x() + (hi.x() - lo.x()) * i / (k - 1),
                         lo.y() + (hi.y() - lo.y()) * j / (k - 1));
            seed_uv.push_back(q);
            seed_xyz.push_back(face_.point(q.x(), q.y()));
          }
    }
    // The index's box: the corners and the seed points (later feet lie
    // near them; one outside still lands in a border cell).
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec3& c : corner_) lo = lo.cwiseMin(c), hi = hi.cwiseMax(c);
    for (const Vec3& c : seed_xyz) lo = lo.cwiseMin(c), hi = hi.cwiseMax(c);
    if (!(lo.x() <= hi.x())) lo = hi = Vec3::Zero();
    known_.reset(lo, hi);
    for (std::size_t c = 0; c < corner_.size(); ++c) remember(uv_[c], corner_[c]);
    for (std::size_t c = 0; c < seed_uv.size(); ++c) remember(seed_uv[c], seed_xyz[c]);
  }

  // A foot point: x - S orthogonal to each tangent, except across a border
  // of the search range, where it may point out of the range (the first-order
  // condition of a minimum held at the border).
  bool orthogonal(const Vec3& x, const Projection& pr) const {
    if (pr.distance <= tiny_) return true;
    const SurfacePoint sp = face_.derivatives(pr.uv.x(), pr.uv.y());
    const Vec3 r = x - sp.point;
    const double rn = r.norm(), un = sp.du.norm(), vn = sp.dv.norm();
    if (!(un > 0 && vn > 0 && rn > 0)) return false;
    const double cu = r.dot(sp.du) / (rn * un), cv = r.dot(sp.dv) / (rn * vn);
    const double tol = 1e-6;
    auto ok = [&](double c, double t, double lo, double hi, bool periodic) {
      if (std::abs(c) <= tol) return true;
      if (periodic) return false;
      const double eps = 1e-9 * (hi - lo);
      return (t <= lo + eps && c < 0) || (t >= hi - eps && c > 0);
    };
    return ok(cu, pr.uv.x(), search_.u_min, search_.u_max, face_.u_periodic()) &&
           ok(cv, pr.uv.y(), search_.v_min, search_.v_max, face_.v_periodic());
  }

  void remember(const Vec2& uv, const Vec3& xyz) const { known_.add(uv, xyz); }

  const SurfaceFace& face_;
  const std::vector<Vec2>& uv_;
  std::vector<Vec3> corner_;
  // Surface points met by this panel's probes (the corners first).
  mutable KnownSurfacePoints known_;
  mutable std::vector<std::pair<Vec3, Projection>> global_;  // offer_global's answers
  double tiny_ = 0;
  UvBounds search_;
  ProjectionParams local_;  // a local search before the global one
};

// A sample of the panel model: piece `tri` (-1: the bilinear quad) at
// parameters (a,b) (quad: s,t in [0,1]; triangle: barycentric weights of
// corners 1 and 2, a + b <= 1).
struct Sample {
  int tri = -1;
  double a = 0, b = 0;
  Probe probe;
};

class PanelModel {
 public:
  PanelModel(const std::vector<Vec3>& p, const std::vector<Vec2>& uv,
             const std::vector<std::array<int, 3>>& tris)
      : p_(p), uv_(uv), tris_(tris) {}

  // Clamp (a,b) into the piece's domain; false if a triangle's step leaves it.
  bool inside(int tri, double& a, double& b) const {
    if (tri < 0) {
      a = std::clamp(a, 0.0, 1.0);
      b = std::clamp(b, 0.0, 1.0);
      return true;
    }
    const double e = 1e-12;
    return a >= -e && b >= -e && a + b <= 1 + e;
  }
  void at(int tri, double a, double b, Vec3& x, Vec2& q) const {
    if (tri < 0) {
      const double w0 = (1 - a) * (1 - b), w1 = a * (1 - b), w2 = a * b, w3 = (1 - a) * b;
      x = w0 * p_[0] + w1 * p_[1] + w2 * p_[2] + w3 * p_[3];
      q = w0 * uv_[0] + w1 * uv_[1] + w2 * uv_[2] + w3 * uv_[3];
      return;
    }
    const auto& t = tris_[tri];
    const double c = 1 - a - b;
    x = c * p_[t[0]] + a * p_[t[1]] + b * p_[t[2]];
    q = c * uv_[t[0]] + a * uv_[t[1]] + b * uv_[t[2]];
  }
  // The bilinear quad's tangents d x / d s and d x / d t at (s, t).
  void quad_tangents(double a, double b, Vec3& xa, Vec3& xb) const {
    xa = (1 - b) * (p_[1] - p_[0]) + b * (p_[2] - p_[3]);
    xb = (1 - a) * (p_[3] - p_[0]) + a * (p_[2] - p_[1]);
  }

 private:
  const std::vector<Vec3>& p_;
  const std::vector<Vec2>& uv_;
  const std::vector<std::array<int, 3>>& tris_;
};

// Pattern search for a maximum of the distance around `s` within its piece:
// steps from h0 halved down to h0 / 64, along the piece's edge directions
// (a quad: s and t; a triangle: also along its third edge), so a maximum on
// an edge is followed along that edge.
Sample refine(const PanelModel& model, const Prober& probe, Sample s, double h0) {
  static const double quad_dirs[8][2] = {{1, 0}, {-1, 0},  {0, 1},  {0, -1},
                                         {1, 1}, {-1, -1}, {1, -1}, {-1, 1}};
  static const double tri_dirs[6][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, -1}, {-1, 1}};
  const int nd = s.tri < 0 ? 8 : 6;
  const double(*dirs)[2] = s.tri < 0 ? quad_dirs : tri_dirs;
  int budget = 80;
  for (double h = h0; h >= h0 / 64 && budget > 0; h *= 0.5) {
    bool moved = true;
    while (moved && budget > 0) {
      moved = false;
      for (int d = 0; d < nd && budget > 0; ++d) {
        double a = s.a + h * dirs[d][0], b = s.b + h * dirs[d][1];
        if (!model.inside(s.tri, a, b) || (a == s.a && b == s.b)) continue;
        Vec3 x;
        Vec2 q;
        model.at(s.tri, a, b, x, q);
        --budget;
        Vec3 s_q;
        if (probe.cheap_bound(x, q, &s_q) + probe.slack() <= s.probe.distance) continue;  // no gain
        const Probe pr = probe(x, s.probe.reliable ? s.probe.foot : q, q, &s_q);
        if (pr.distance > s.probe.distance) {
          s = {s.tri, a, b, pr};
          moved = true;
          break;
        }
      }
    }
  }
  return s;
}

// The bilinear quad's distance d(s, t) with its gradient. At a foot point
// the surface point moves orthogonally to x - S, so to first order only the
// panel point's motion changes d: grad d = (x_s, x_t) . (x - S) / d.
struct QuadPoint {
  Vec2 z = Vec2::Zero();  // (s, t)
  Probe probe;
  Vec2 grad = Vec2::Zero();
  bool has_grad = false;  // a verified foot point at a positive distance
};

class QuadDistance {
 public:
  QuadDistance(const PanelModel& model, const Prober& probe) : model_(model), probe_(probe) {}

  QuadPoint at(const Vec2& z, const Vec2* start) const {
    Vec3 x;
    Vec2 q;
    model_.at(-1, z.x(), z.y(), x, q);
    QuadPoint out;
    out.z = z;
    out.probe = probe_(x, start ? *start : q, q);
    with_gradient(out, x);
    return out;
  }
  // at(z) from z's own parameters, its foot point not remembered (Prober::peek).
  QuadPoint peek(const Vec2& z) const {
    Vec3 x;
    Vec2 q;
    model_.at(-1, z.x(), z.y(), x, q);
    QuadPoint out;
    out.z = z;
    out.probe = probe_.peek(x, q, q);
    with_gradient(out, x);
    return out;
  }
  // A grid sample already probed at x.
  QuadPoint of(const Vec2& z, const Vec3& x, const Probe& pr) const {
    QuadPoint out;
    out.z = z;
    out.probe = pr;
    with_gradient(out, x);
    return out;
  }

 private:
  void with_gradient(QuadPoint& out, const Vec3& x) const {
    const double d = out.probe.distance;
    if (!out.probe.reliable || !(d > probe_.slack())) return;
    Vec3 xa, xb;
    model_.quad_tangents(out.z.x(), out.z.y(), xa, xb);
    const Vec3 n = (x - out.probe.point) / d;
    out.grad = {xa.dot(n), xb.dot(n)};
    out.has_grad = true;
  }

  const PanelModel& model_;
  const Prober& probe_;
};

// Largest distance on the quad's domain [0,1]^2 near `seed`: a Newton ascent
// with a symmetric rank-one update of the Hessian (started from forward
// differences of the gradient at step h), coordinates at the border of the
// square held there while the gradient points out of it, steps limited by a
// trust radius. The distance of a bilinear patch over a smooth surface is
// close to quadratic, so it lands in a few probes (the pattern search it
// replaces took ~30 per seed) and to a far finer precision (1e-6 in s, t).
QuadPoint ascend(const QuadDistance& dist, QuadPoint cur, double h) {
  if (!cur.has_grad) return cur;
  Eigen::Matrix2d H;
  for (int i = 0; i < 2; ++i) {
    Vec2 z = cur.z;
    const double step = z[i] + h <= 1 ? h : -h;
    z[i] += step;
    const QuadPoint o = dist.at(z, &cur.probe.foot);
    if (!o.has_grad) return o.probe.distance > cur.probe.distance ? o : cur;
    H.col(i) = (o.grad - cur.grad) / step;
  }
  H = 0.5 * (H + H.transpose()).eval();
  double radius = 4 * h;
  for (int it = 0; it < 16; ++it) {
    // Free coordinates: not at a border with the gradient pointing out.
    bool fixed[2];
    for (int i = 0; i < 2; ++i)
      fixed[i] = (cur.z[i] <= 0 && cur.grad[i] <= 0) || (cur.z[i] >= 1 && cur.grad[i] >= 0);
    Vec2 step = Vec2::Zero();
    if (!fixed[0] && !fixed[1]) {
      if (H(0, 0) < 0 && H.determinant() > 0)
        step = -H.inverse() * cur.grad;
      else
        step = cur.grad.normalized() * radius;
    } else {
      for (int i = 0; i < 2; ++i) {
        if (fixed[i]) continue;
        step[i] = H(i, i) < 0 ? -cur.grad[i] / H(i, i) : std::copysign(radius, cur.grad[i]);
      }
    }
    if (step.norm() > radius) step *= radius / step.norm();
    const Vec2 next(std::clamp(cur.z.x() + step.x(), 0.0, 1.0),
                    std::clamp(cur.z.y() + step.y(), 0.0, 1.0));
    const Vec2 s = next - cur.z;
    if (s.norm() < 1e-6) break;
    const QuadPoint o = dist.at(next, &cur.probe.foot);
    if (!o.has_grad) {
      if (o.probe.distance > cur.probe.distance) return o;  // no foot point: stop there
      radius = 0.5 * s.norm();
      continue;
    }
    const Vec2 r = (o.grad - cur.grad) - H * s;
    if (std::abs(r.dot(s)) > 1e-8 * r.norm() * s.norm()) H += r * r.transpose() / r.dot(s);
    if (o.probe.distance > cur.probe.distance) {
      cur = o;
      radius = std::max(radius, 2 * s.norm());
    } else {
      radius = 0.5 * s.norm();
    }
  }
  return cur;
}

// Where an ascent stops with a gradient that still promises more than 1%
// within a grid step, it stands on a crease of the distance (the nearest
// surface point jumps between sheets there: no quadratic model or compass
// search climbs along it).
bool on_crease(const QuadPoint& p, double h) {
  if (!p.has_grad) return false;
  double rise = 0;
  for (int i = 0; i < 2; ++i) {
    const double g = p.grad[i];
    const bool held = (p.z[i] <= 0 && g <= 0) || (p.z[i] >= 1 && g >= 0);
    if (!held) rise += std::abs(g) * h;
  }
  return rise > 0.01 * p.probe.distance;
}

// The largest of a 5 x 5 grid of probes over [z - r, z + r]^2 (within the
// square) around a point on a crease: a point on the crease's higher side.
QuadPoint explore(const QuadDistance& dist, const QuadPoint& p, double r) {
  QuadPoint best = p;
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j) {
      if (i == 0 && j == 0) continue;
      const Vec2 z(std::clamp(p.z.x() + r * i / 2, 0.0, 1.0),
                   std::clamp(p.z.y() + r * j / 2, 0.0, 1.0));
      if (z == p.z) continue;
      const QuadPoint o = dist.at(z, &p.probe.foot);
      if (o.probe.distance > best.probe.distance) best = o;
    }
  return best;
}

constexpr double kSeedShare = 0.7;
constexpr int kMaxAscents = 8;

// One pass over an (n+1) x (n+1) grid of the quad's square: the samples are
// projected in order of their cheap bounds down to kSeedShare of the largest
// distance found (a sample whose bound is below that can be neither the
// largest nor the foot of a peak that matters), then each is checked against
// every surface point met since (the first probes met few).
// A point of the grid: its parameters on the quad, the panel point, its own
// surface parameters and S there, and the cheap bound |x - S(q)|.
struct GridSample {
  Vec2 z;
  Vec3 x;
  Vec2 q;
  Vec3 s_q;
  double bound;
};

struct QuadGrid {
  int n = 0;
  std::vector<GridSample> samples;  // row-major, (n+1) x (n+1)
  std::vector<QuadPoint> probed;
  std::vector<int> slot;  // per grid point: index in `probed`, -1 if not probed
  QuadPoint best;

  const QuadPoint* at(int i, int j) const {
    if (i < 0 || j < 0 || i > n || j > n) return nullptr;
    const int k = slot[std::size_t(i) * (n + 1) + j];
    return k < 0 ? nullptr : &probed[k];
  }
};

QuadGrid probe_grid(const PanelModel& model, const Prober& probe, const QuadDistance& dist, int n,
                    double floor) {
  const int side = n + 1;
  std::vector<GridSample> grid;
  grid.reserve(std::size_t(side) * std::size_t(side));
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      GridSample g{{double(i) / n, double(j) / n}, Vec3::Zero(), Vec2::Zero(), Vec3::Zero(), 0};
      model.at(-1, g.z.x(), g.z.y(), g.x, g.q);
      g.bound = probe.cheap_bound(g.x, g.q, &g.s_q);
      grid.push_back(g);
    }
  }
  std::vector<double> bounds(grid.size());
  for (std::size_t k = 0; k < grid.size(); ++k) bounds[k] = grid[k].bound;
  // Taken from a heap as far as they are probed (rarely all: ordering the
  // whole fine grid was 14% of a rough terrain's time).
  LargestFirst by_bound(bounds);
  QuadGrid out;
  out.n = n;
  out.slot.assign(grid.size(), -1);
  std::vector<std::size_t> probed_at;
  // Room for every sample (a third are probed on a smooth face): one
  // allocation each instead of a growth step every few probes.
  out.probed.reserve(grid.size());
  probed_at.reserve(grid.size());
  auto largest = [&] { return std::max(floor, out.best.probe.distance); };
  for (;;) {
    for (; !by_bound.empty(); by_bound.pop()) {
      const std::size_t next = by_bound.top();
      const GridSample& g = grid[next];
      if (g.bound + probe.slack() <= kSeedShare * largest()) break;
      // A sample whose bound is within the slack lies on the face: once one
      // is probed, the others of a quad lying on its face (a plane's) add
      // only rounding noise (81 probes a quad).
      if (g.bound <= probe.slack() && !out.probed.empty()) break;
      out.slot[next] = int(out.probed.size());
      out.probed.push_back(dist.of(g.z, g.x, probe(g.x, g.q, g.q, &g.s_q)));
      probed_at.push_back(next);
      if (out.probed.back().probe.distance > out.best.probe.distance) out.best = out.probed.back();
    }
    // If the largest drops, samples skipped for it are probed after all.
    const double before = out.best.probe.distance;
    out.best = QuadPoint();
    for (std::size_t k = 0; k < out.probed.size(); ++k) {
      const GridSample& g = grid[probed_at[k]];
      const Probe t = probe.recheck(g.x, out.probed[k].probe);
      if (t.distance < out.probed[k].probe.distance) out.probed[k] = dist.of(g.z, g.x, t);
      if (out.probed[k].probe.distance > out.best.probe.distance) out.best = out.probed[k];
    }
    if (!(out.best.probe.distance < before) || by_bound.empty()) break;
  }
  out.samples = std::move(grid);
  return out;
}

// The grid's local maxima among its probed samples (no probed neighbour
// farther) within kSeedShare of `largest`, largest first.
std::vector<const QuadPoint*> grid_peaks(const QuadGrid& g, double largest) {
  std::vector<const QuadPoint*> peaks;
  for (int i = 0; i <= g.n; ++i)
    for (int j = 0; j <= g.n; ++j) {
      const QuadPoint* p = g.at(i, j);
      if (!p || !(p->probe.distance > 0) || p->probe.distance < kSeedShare * largest) continue;
      bool peak = true;
      for (int di = -1; di <= 1 && peak; ++di)
        for (int dj = -1; dj <= 1 && peak; ++dj) {
          const QuadPoint* o = (di || dj) ? g.at(i + di, j + dj) : nullptr;
          // Ties go to the earlier grid point, so a plateau seeds once.
          if (o && (o->probe.distance > p->probe.distance ||
                    (o->probe.distance == p->probe.distance && (di < 0 || (di == 0 && dj < 0)))))
            peak = false;
        }
      if (peak) peaks.push_back(p);
    }
  std::stable_sort(peaks.begin(), peaks.end(), [](const QuadPoint* a, const QuadPoint* b) {
    return a->probe.distance > b->probe.distance;
  });
  return peaks;
}

// Where the distance may be rough at the grid's scale near its top: pairs of
// neighbouring samples within kSeedShare of the largest whose values the
// trapezoid rule on their gradients does not connect within kRoughShare of
// the largest (for a smooth distance the mismatch is O(h^3)), and whether
// one of them has no foot point. The distance is then creased (the nearest
// surface point jumps from one sheet of the surface to another) or varies
// faster than the grid: its peaks can lie between the samples and 30% above
// them (MAT.brep).
// Two samples on the face (Prober::on_face, no gradient there) connect: a
// quad lying on its face (a plane's) took the fine pass for nothing, 9 times
// the probes (61% of a filleted box's quads).
constexpr double kRoughShare = 0.005;

struct GridEdge {
  const QuadPoint* from;
  const QuadPoint* to;
  int direction;  // 0: s, 1: t
};

struct Roughness {
  bool footless = false;        // a sample near the top without a foot point
  std::vector<GridEdge> edges;  // pairs the trapezoid rule does not connect
  bool rough() const { return footless || !edges.empty(); }
};

Roughness roughness(const QuadGrid& g, const Prober& probe) {
  Roughness out;
  const double largest = g.best.probe.distance;
  const double h = 1.0 / g.n;
  for (int i = 0; i <= g.n; ++i)
    for (int j = 0; j <= g.n; ++j) {
      const QuadPoint* p = g.at(i, j);
      if (!p) continue;
      for (int d = 0; d < 2; ++d) {
        const QuadPoint* o = d == 0 ? g.at(i + 1, j) : g.at(i, j + 1);
        if (!o) continue;
        if (std::max(p->probe.distance, o->probe.distance) < kSeedShare * largest) continue;
        if (probe.on_face(p->probe) && probe.on_face(o->probe)) continue;
        if (!p->has_grad || !o->has_grad) {
          out.footless = true;
          return out;
        }
        const double predicted = 0.5 * (p->grad[d] + o->grad[d]) * h;
        if (std::abs(o->probe.distance - p->probe.distance - predicted) > kRoughShare * largest)
          out.edges.push_back({p, o, d});
      }
    }
  return out;
}

// A distance smooth at the panel's scale can still fail the trapezoid test:
// one that rises and falls once across the panel (a 1.4 m panel over half a
// hill of a terrain) has a mismatch of about 1% of its peak at 8 steps a
// side, and took the 3x finer pass (9 times the probes, 75% of the time on
// such a face) to find the same peaks (every terrain panel within 3e-10
// relative without it, bench/no_cliff.py). So before that pass, each
// failing pair is looked at once more, at its midpoint: a smooth distance
// passes there, at half the step, with a mismatch 8 times smaller and the
// cubic through the pair's values and slopes predicting the midpoint's value
// and slope to O(h^4); a crease between the pair does not. With the bounds
// below (shares of the test's kRoughShare x largest: the trapezoid rule on
// each half within 1/2, the cubic's value and slope, times half a step,
// within 1/16), no kink of a piecewise linear distance that failed the test
// passes, for any position of the kink within the pair (checked over 999
// positions and slope jumps up to 400 x the test's bound), while a distance
// of up to three quarters of a sine wave across the panel does.
// The midpoints are peeks (their feet not remembered), so where they find a
// crease the fine pass runs exactly as it did without them. More than
// kMaxMidpoints failing pairs: the fine pass at once (a rough top).
constexpr int kMaxMidpoints = 16;

bool smooth_at_half_step(const QuadDistance& dist, const Roughness& r, int n, double largest) {
  if (r.footless || r.edges.size() > std::size_t(kMaxMidpoints)) return false;
  const double h = 1.0 / n, bound = kRoughShare * largest;
  for (const GridEdge& e : r.edges) {
    const QuadPoint mid = dist.peek(0.5 * (e.from->z + e.to->z));
    if (!mid.has_grad) return false;
    const int d = e.direction;
    const double d0 = e.from->probe.distance, d1 = e.to->probe.distance, dm = mid.probe.distance;
    // Slopes per unit of the pair's own parameter (0 at `from`, 1 at `to`).
    const double g0 = e.from->grad[d] * h, g1 = e.to->grad[d] * h, gm = mid.grad[d] * h;
    const double first_half = dm - d0 - 0.25 * (g0 + gm);
    const double second_half = d1 - dm - 0.25 * (gm + g1);
    const double cubic_value = 0.5 * (d0 + d1) + 0.125 * (g0 - g1);
    const double cubic_slope = 1.5 * (d1 - d0) - 0.25 * (g0 + g1);
    if (std::abs(first_half) > 0.5 * bound || std::abs(second_half) > 0.5 * bound ||
        std::abs(dm - cubic_value) > bound / 16 || 0.5 * std::abs(gm - cubic_slope) > bound / 16)
      return false;
  }
  return true;
}

// From a peak of the grid: an ascent on the distance; an ascent on a wrong
// sheet (a foot point that later surface points show to be farther than the
// nearest) climbs the wrong function: its top is checked, and if it was
// wrong, the climb starts again from there with the nearer foot point
// (MAT.brep: 2.157 on a wrong sheet at a sample, 2.012 there in truth, the
// true peak 2.10 a fifth of a step away). Where it stops on a crease, a
// pattern search along the crease, then a look around it. h: the grid step.
QuadPoint climb(const PanelModel& model, const Prober& probe, const QuadDistance& dist,
                QuadPoint top, double h) {
  for (int attempt = 0; attempt < 6; ++attempt) {
    top = ascend(dist, top, 0.5 * h);
    Vec3 x;
    Vec2 q;
    model.at(-1, top.z.x(), top.z.y(), x, q);
    const Probe checked = probe.recheck(x, top.probe);
    if (checked.distance + probe.slack() < top.probe.distance) {
      top = dist.of(top.z, x, checked);
      continue;
    }
    if (!on_crease(top, h)) break;
    Sample polish{-1, top.z.x(), top.z.y(), top.probe};
    polish = refine(model, probe, polish, 0.25 * h);
    if (polish.probe.distance > top.probe.distance) {
      model.at(-1, polish.a, polish.b, x, q);
      top = dist.of({polish.a, polish.b}, x, polish.probe);
    }
    const QuadPoint around = explore(dist, top, h);
    if (!(around.probe.distance > top.probe.distance + probe.slack())) break;
    top = around;
  }
  return top;
}

// The top checked against every surface point met (its answer if larger).
// The largest distance found on a panel so far, with the panel point where.
struct Answer {
  Probe probe;
  Vec3 at = Vec3::Zero();
};

void offer_top(const PanelModel& model, const Prober& probe, const QuadPoint& top, Answer& answer) {
  Vec3 x;
  Vec2 q;
  model.at(-1, top.z.x(), top.z.y(), x, q);
  const Probe checked = probe.recheck(x, top.probe);
  if (checked.distance > answer.probe.distance) answer = {checked, x};
}

// The certificate of a panel's answer D: every cell of the finest grid (a
// quad's, or each flat piece's triangles) gets an upper bound of the
// distance over the whole cell, not only at its corners (deviation_bound.h:
// the surface's second-derivative bounds and the surface points met at the
// corners). A cell whose bound exceeds D by more than kCertifyShare of D
// (plus kCertifyFloor of the panel's size) is split (a quad in four, or in
// two across a crease; a triangle in four); each new point gets the
// surface point at its own parameters, and is probed where that is farther
// than D (only there can a new top lie); a probe above D is climbed like a
// grid peak. Until every cell is below, or the splits allowed are spent
// (kMaxCertifySplits and eight per cell of the grid): then the panel is
// flagged unreliable. The answer never drops; where every cell is below, the
// true largest distance is at most (1 + kCertifyShare) D plus the floor.
// Before it (stop 43), the border panels of OCCT's terrain read as low as
// half their distance, flagged reliable (panel 4,392: 5.40 mm where the
// global search finds 10.16): dips of 20 mm within 10-15 mm, narrower than
// the 13 mm grid step, between samples that agreed with their gradients.
constexpr double kCertifyShare = 0.01;
constexpr double kCertifyFloor = 1e-5;
constexpr int kMaxCertifySplits = 256;

// Feet that move this many times as far as the own parameters across a cell.
constexpr double kCreaseJump = 4.0;

class DeviationCertificate {
 public:
  DeviationCertificate(const SurfaceFace& face, const PanelModel& model, const Prober& probe,
                       const std::vector<Vec3>& p)
      : face_(face), model_(model), probe_(probe) {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec3& a : p) lo = lo.cwiseMin(a), hi = hi.cwiseMax(a);
    if (!p.empty()) size_ = (hi - lo).norm();
  }

  // Whether the face has the bounds a certificate needs.
  static bool possible(const SurfaceFace& face) {
    SecondDerivativeBound m;
    const UvBounds b = face.bounds();
    return face.second_derivative_bound({b.u_min, b.u_min, b.v_min, b.v_min}, m);
  }

  // A grid point of piece `tri` (-1: the bilinear quad) at z with its
  // probe, if probed, and the surface point at its own parameters; returns
  // its index for add_cell.
  int add_point(int tri, const Vec2& z, const Vec3& x, const Vec2& q, const Vec3& s_q,
                const Probe* probed) {
    BoundCorner c{x, q, s_q, q, s_q};
    if (probed && (x - probed->point).norm() < (x - s_q).norm())
      c.f = probed->foot, c.s = probed->point;
    corners_.push_back(c);
    gap_.push_back((c.x - c.s).norm());
    z_.push_back(z);
    piece_.push_back(tri);
    return int(corners_.size()) - 1;
  }
  // Room for the grid's points and cells (the splits' points come after).
  void reserve(std::size_t points, std::size_t cells) {
    corners_.reserve(points);
    gap_.reserve(points);
    z_.reserve(points);
    piece_.reserve(points);
    cells_.reserve(cells);
  }
  // A cell of the grid: a quad's (corner[3] >= 0, in the order (lo, lo),
  // (hi, lo), (hi, hi), (lo, hi)) or a triangle's (corner[3] = -1).
  void add_cell(const std::array<int, 4>& corner) { cells_.push_back(corner); }

  // Whether every cell of a triangle piece sampled n times a side, its
  // samples' own parameters within `box` and their cheap bounds at most
  // `cheap`, is below the answer `answer` (the cells' bounds through their
  // own parameters: the triangle form of deviation_bound.h).
  bool passes_whole(double cheap, const UvBounds& box, int n, double answer) const {
    SecondDerivativeBound m;
    if (!face_.second_derivative_bound(box, m)) return false;
    const double du = (box.u_max - box.u_min) / n, dv = (box.v_max - box.v_min) / n;
    const double error = along_edge(m, du, dv) / 8;
    return cheap + error <= answer * (1 + kCertifyShare) + kCertifyFloor * size_;
  }

  // true: certified (`answer` may have risen); false: the splits ran out.
  // `dist`: the quad's distance (ascents from new tops), null for pieces.
  bool run(Answer& answer, const QuadDistance* dist) {
    answer_ = &answer;
    dist_ = dist;
    // One bound over the box of the grid's surface parameters, for the
    // first try of each cell (not across a periodic seam: unwrapped cells
    // would leave it).
    if (!face_.u_periodic() && !face_.v_periodic() && !corners_.empty()) {
      UvBounds& b = hint_.box;
      b = {corners_[0].q.x(), corners_[0].q.x(), corners_[0].q.y(), corners_[0].q.y()};
      for (const BoundCorner& c : corners_)
        for (const Vec2& f : {c.f, c.q}) {
          b.u_min = std::min(b.u_min, f.x()), b.u_max = std::max(b.u_max, f.x());
          b.v_min = std::min(b.v_min, f.y()), b.v_max = std::max(b.v_max, f.y());
        }
      has_hint_ = face_.second_derivative_bound(b, hint_.m);
    }
    for (const auto& cell : cells_) push(cell);
    // A boundary panel of a thousand thin pieces may need each of them
    // split once or twice: the allowance grows with the cells (a 160-corner
    // panel along a trim of the freeform test face needed more than two a
    // cell).
    const std::size_t allowed = kMaxCertifySplits + 8 * cells_.size();
    std::size_t splits = 0;
    while (!open_.empty()) {
      const Cell cell = open_.top();
      open_.pop();
      if (passes(cell.bound)) continue;  // the answer rose since
      if (splits++ >= allowed) return false;
      split(cell.corner);
    }
    return true;
  }

 private:
  struct Cell {
    double bound;
    std::size_t order;  // ties: the cell pushed first
    std::array<int, 4> corner;
    bool operator<(const Cell& o) const {
      return bound < o.bound || (bound == o.bound && order > o.order);
    }
  };

  // A quad in four, or in two across a crease (the feet jump across one
  // direction of the cell far more than its own parameters move: the cell
  // need only be thin across it, and a crease can run the panel's length);
  // a triangle in four at its edges' midpoints.
  void split(const std::array<int, 4>& k) {
    const auto [i0, i1, i2, i3] = k;
    auto mid = [&](int a, int b) { return point(piece_[a], 0.5 * (z_[a] + z_[b]), a, b); };
    if (i3 < 0) {
      const int m01 = mid(i0, i1), m12 = mid(i1, i2), m20 = mid(i2, i0);
      push({i0, m01, m20, -1});
      push({m01, i1, m12, -1});
      push({m20, m12, i2, -1});
      push({m01, m12, m20, -1});
      return;
    }
    auto jump = [&](int a, int b, int d, int e) {
      const BoundCorner &ca = corners_[a], &cb = corners_[b], &cd = corners_[d], &ce = corners_[e];
      const double own = (ca.q - cb.q).norm() + (cd.q - ce.q).norm();
      return own > 0 ? ((ca.f - cb.f).norm() + (cd.f - ce.f).norm()) / own : 0.0;
    };
    const double across_s = jump(i0, i1, i3, i2), across_t = jump(i0, i3, i1, i2);
    if (across_t > kCreaseJump * std::max(1.0, across_s)) {
      const int l = mid(i0, i3), r = mid(i1, i2);
      push({i0, i1, r, l});
      push({l, r, i2, i3});
      return;
    }
    if (across_s > kCreaseJump * std::max(1.0, across_t)) {
      const int b = mid(i0, i1), t = mid(i3, i2);
      push({i0, b, t, i3});
      push({b, i1, i2, t});
      return;
    }
    const int b = mid(i0, i1), r = mid(i1, i2), t = mid(i3, i2), l = mid(i0, i3);
    const int m = mid(i0, i2);
    push({i0, b, m, l});
    push({b, i1, r, m});
    push({m, r, i2, t});
    push({l, m, t, i3});
  }

  double enough() const {
    return answer_->probe.distance * (1 + kCertifyShare) + kCertifyFloor * size_;
  }
  bool passes(double bound) const { return bound <= enough(); }

  void push(const std::array<int, 4>& k) {
    if (has_hint_ && k[3] >= 0) {
      // The first try of bilinear_cell_bound, from the kept gaps: most
      // cells pass here.
      double gap = 0;  // (as bilinear_cell_bound takes the largest: from 0)
      for (int i : k) gap = std::max(gap, gap_[std::size_t(i)]);
      const double quick = bilinear_hint_bound(
          {corners_[k[0]].f, corners_[k[1]].f, corners_[k[2]].f, corners_[k[3]].f}, gap, hint_);
      if (quick >= 0 && passes(quick)) return;
    }
    double bound;
    const CurvatureOverBox* hint = has_hint_ ? &hint_ : nullptr;
    if (k[3] < 0)
      bound = triangle_cell_bound(face_, {corners_[k[0]], corners_[k[1]], corners_[k[2]]}, enough(),
                                  hint);
    else
      bound = bilinear_cell_bound(
          face_, {corners_[k[0]], corners_[k[1]], corners_[k[2]], corners_[k[3]]}, enough(), hint);
    if (!passes(bound)) open_.push({bound, pushed_++, k});
  }

  // The index of the point at z of piece `tri` (the midpoint of corners a
  // and b): the surface point at its own parameters, and where that is
  // farther than the answer (a new top may lie there) its probe, climbed
  // if it is.
  int point(int tri, const Vec2& z, int a, int b) {
    const auto key = std::make_tuple(tri, z.x(), z.y());
    const auto found = added_.find(key);
    if (found != added_.end()) return found->second;
    Vec3 x, s_q;
    Vec2 q;
    model_.at(tri, z.x(), z.y(), x, q);
    const double cheap = probe_.cheap_bound(x, q, &s_q);
    Probe pr;
    const bool far = cheap > answer_->probe.distance + probe_.slack();
    // Checked against every surface point met (a foot on a wrong sheet
    // would hold the cell's bound above the answer).
    if (far) pr = probe_.recheck(x, probe_(x, q, q, &s_q));
    const int k = add_point(tri, z, x, q, s_q, far ? &pr : nullptr);
    added_.emplace(key, k);
    if (far && pr.distance > answer_->probe.distance + probe_.slack()) {
      const double step = (z_[a] - z_[b]).cwiseAbs().maxCoeff();
      if (dist_) {
        offer_top(model_, probe_, climb(model_, probe_, *dist_, dist_->of(z, x, pr), step),
                  *answer_);
      } else {
        Sample top = refine(model_, probe_, {tri, z.x(), z.y(), pr}, 0.5 * step);
        model_.at(tri, top.a, top.b, x, q);
        top.probe = probe_.recheck(x, top.probe);
        if (top.probe.distance > answer_->probe.distance) *answer_ = {top.probe, x};
      }
    }
    return k;
  }

  const SurfaceFace& face_;
  const PanelModel& model_;
  const Prober& probe_;
  const QuadDistance* dist_ = nullptr;
  double size_ = 0;
  Answer* answer_ = nullptr;
  std::vector<BoundCorner> corners_;  // the grid's points, then the points added
  std::vector<double> gap_;           // |x - S(f)| of each
  std::vector<Vec2> z_;               // each point's parameters on its piece
  std::vector<int> piece_;
  std::vector<std::array<int, 4>> cells_;
  std::map<std::tuple<int, double, double>, int> added_;
  std::priority_queue<Cell> open_;
  std::size_t pushed_ = 0;
  CurvatureOverBox hint_;
  bool has_hint_ = false;
};

// measure_panel_deviation for the bilinear quad (no pieces): a grid pass;
// where the distance is rough near its top (and not smooth at half the step
// where the grid found it rough), a second pass three times as fine; from
// each peak of the finest grid an ascent, a pattern search that follows a
// ridge the ascent's quadratic model cannot, and, where the top still sits
// on a crease, a 5 x 5 exploration around it (and again from its best
// point); then the certificate (DeviationCertificate) over the finest grid.
PanelDeviation measure_quad_deviation(const SurfaceFace& face, const std::vector<Vec3>& p,
                                      const PanelModel& model, const Prober& probe, int n) {
  const QuadDistance dist(model, probe);
  QuadGrid grid = probe_grid(model, probe, dist, n, 0.0);
  const Roughness roughness_at_grid = roughness(grid, probe);
  if (roughness_at_grid.rough() &&
      !smooth_at_half_step(dist, roughness_at_grid, n, grid.best.probe.distance)) {
    QuadGrid fine = probe_grid(model, probe, dist, 3 * n, grid.best.probe.distance);
    if (fine.best.probe.distance < grid.best.probe.distance) fine.best = grid.best;
    grid = std::move(fine);
  }
  const double h = 1.0 / grid.n;
  QuadPoint best = grid.best;
  std::vector<const QuadPoint*> seeds = grid_peaks(grid, best.probe.distance);
  if (seeds.size() > kMaxAscents) seeds.resize(kMaxAscents);
  // A quad whose largest sample is a verified foot point within the slack
  // lies on its face (a plane's quad): its "peaks" are rounding noise, and
  // ascents on them climbed nothing (up to 8 a quad).
  if (probe.on_face(best.probe)) seeds.clear();
  std::vector<QuadPoint> tops;
  for (const QuadPoint* seed : seeds) tops.push_back(climb(model, probe, dist, *seed, h));
  // Each top (and the best sample) checked against every surface point met;
  // the largest checked value is the answer.
  tops.push_back(best);
  Answer last;
  last.probe.distance = -1;
  for (const QuadPoint& top : tops) offer_top(model, probe, top, last);
  bool certified = true;
  if (DeviationCertificate::possible(face)) {
    DeviationCertificate certificate(face, model, probe, p);
    const int side = grid.n + 1;
    certificate.reserve(std::size_t(side) * side, std::size_t(grid.n) * grid.n);
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j) {
        const GridSample& g = grid.samples[std::size_t(i) * side + j];
        const QuadPoint* pr = grid.at(i, j);
        certificate.add_point(-1, g.z, g.x, g.q, g.s_q, pr ? &pr->probe : nullptr);
      }
    for (int i = 0; i + 1 < side; ++i)
      for (int j = 0; j + 1 < side; ++j)
        certificate.add_cell(
            {i * side + j, (i + 1) * side + j, (i + 1) * side + j + 1, i * side + j + 1});
    certified = certificate.run(last, &dist);
  }
  return {last.probe.distance, !last.probe.reliable || !certified, last.at};
}

// The three largest of the pieces' own largest probed distances (pieces:
// a panel model's triangles; -1, the bilinear quad, counts as piece 0), and
// the cut-off below which a sample can no longer change the answer.
class TopPieces {
 public:
  explicit TopPieces(std::size_t pieces) : largest_(pieces, -1.0) {}
  void offer(int piece, double d) {
    const std::size_t p = piece < 0 ? 0 : static_cast<std::size_t>(piece);
    if (!(d > largest_[p])) return;
    largest_[p] = d;
    // top_ holds distinct pieces, largest first.
    auto it = std::find_if(top_.begin(), top_.end(), [&](const auto& e) { return e.second == p; });
    if (it == top_.end()) {
      if (top_.size() == 3 && !(d > top_.back().first)) return;
      if (top_.size() == 3) top_.pop_back();
      top_.push_back({d, p});
    } else {
      it->first = d;
    }
    std::sort(top_.begin(), top_.end(), [](const auto& a, const auto& b) {
      return a.first > b.first || (a.first == b.first && a.second < b.second);
    });
  }
  double cut_off(double largest) const {
    return std::max(0.7 * largest, top_.size() == 3 ? top_.back().first : 0.0);
  }

 private:
  std::vector<double> largest_;
  std::vector<std::pair<double, std::size_t>> top_;
};

}  // namespace

PanelDeviation measure_panel_deviation(const SurfaceFace& face, const std::vector<Vec3>& p,
                                       const std::vector<Vec2>& uv,
                                       const std::vector<std::array<int, 3>>& tris, int samples) {
  const Prober probe(face, uv);
  const PanelModel model(p, uv, tris);
  if (tris.empty() && p.size() == 4)
    return measure_quad_deviation(face, p, model, probe, std::max(2, samples));
  std::vector<Sample> grid;
  std::vector<Vec3> grid_x;
  std::vector<Vec2> grid_q;
  std::vector<double> grid_bound;  // cheap_bound of each sample
  std::vector<Vec3> grid_s;        // S(q) of each sample
  std::vector<double> step;        // grid step of each piece, in its parameters
  std::vector<std::pair<std::size_t, int>> piece_grid;  // first sample and n of each piece
  auto sample_piece = [&](int tri, int n) {
    step.push_back(1.0 / n);
    piece_grid.push_back({grid.size(), n});
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; j <= (tri < 0 ? n : n - i); ++j) {
        Sample s{tri, double(i) / n, double(j) / n, {}};
        Vec3 x;
        Vec2 q;
        model.at(tri, s.a, s.b, x, q);
        grid.push_back(s);
        grid_x.push_back(x);
        grid_q.push_back(q);
        Vec3 s_q;
        grid_bound.push_back(probe.cheap_bound(x, q, &s_q));
        grid_s.push_back(s_q);
      }
    }
  };
  // Each piece's samples per side: the quad at least its edge midpoints;
  // each triangle as densely as its size asks (a boundary panel has many
  // thin triangles), at least at its edge midpoints.
  std::vector<int> piece_n;
  if (tris.empty()) {
    piece_n.push_back(std::max(2, samples));
  } else {
    double extent = 0;
    for (const Vec3& a : p)
      for (const Vec3& b : p) extent = std::max(extent, (a - b).norm());
    for (const auto& t : tris) {
      const double longest = std::max(
          {(p[t[0]] - p[t[1]]).norm(), (p[t[1]] - p[t[2]]).norm(), (p[t[2]] - p[t[0]]).norm()});
      piece_n.push_back(extent > 0 ? std::max(2, int(std::ceil(samples * longest / extent))) : 2);
    }
  }
  // Room for every sample up front (a boundary panel has ~800: the growth
  // steps of five lists were 8% of its measure).
  std::size_t total = 0;
  for (int n : piece_n) {
    const std::size_t m = std::size_t(n);
    total += tris.empty() ? (m + 1) * (m + 1) : (m + 1) * (m + 2) / 2;
  }
  grid.reserve(total);
  grid_x.reserve(total);
  grid_q.reserve(total);
  grid_bound.reserve(total);
  grid_s.reserve(total);
  step.reserve(piece_n.size());
  piece_grid.reserve(piece_n.size());
  for (std::size_t k = 0; k < piece_n.size(); ++k)
    sample_piece(tris.empty() ? -1 : static_cast<int>(k), piece_n[k]);
  // Project the samples in order of their cheap bounds while one may still
  // matter: the answer is the largest sample and the ascents from the
  // largest samples of three distinct places (at least 70% of the largest,
  // below). Samples of different pieces are distinct places, so with M3 the
  // third largest of the pieces' own largest distances, the third seed is at
  // least M3; a sample whose bound is under max(0.7 x largest, M3) is neither
  // the largest nor a seed (its distance is under its bound), and it is not
  // projected. (With the 70% cut-off alone a boundary panel of thin pieces
  // projected ~45% of its ~1,000 samples.)
  LargestFirst by_bound(grid_bound);
  std::vector<char> probed(grid.size(), 0);
  const TopPieces start(tris.empty() ? 1 : tris.size());
  TopPieces pieces = start;
  double top = 0;
  bool any_probed = false;
  for (;;) {
    for (; !by_bound.empty(); by_bound.pop()) {
      const std::size_t k = by_bound.top();
      if (grid_bound[k] + probe.slack() < pieces.cut_off(top)) break;
      if (grid_bound[k] <= probe.slack() && any_probed) break;  // on the face (as for quads)
      grid[k].probe = probe(grid_x[k], grid_q[k], grid_q[k], &grid_s[k]);
      probed[k] = 1;
      any_probed = true;
      top = std::max(top, grid[k].probe.distance);
      pieces.offer(grid[k].tri, grid[k].probe.distance);
    }
    // As for quads: the first probes met few surface points, so each is
    // checked against all met since; where that lowers the figures, the
    // samples the cut-off skipped for them are probed after all.
    top = 0;
    pieces = start;
    for (std::size_t k = 0; k < grid.size(); ++k) {
      if (!probed[k]) continue;
      grid[k].probe = probe.recheck(grid_x[k], grid[k].probe);
      top = std::max(top, grid[k].probe.distance);
      pieces.offer(grid[k].tri, grid[k].probe.distance);
    }
    if (by_bound.empty() || grid_bound[by_bound.top()] + probe.slack() < pieces.cut_off(top) ||
        (grid_bound[by_bound.top()] <= probe.slack() && any_probed))
      break;
  }
  // Refine around the largest samples of distinct places (at most three, at
  // least 70% of the largest): the maximum usually lies between grid points.
  std::vector<std::size_t> order;
  {
    std::vector<std::size_t> index;
    std::vector<double> distance;
    for (std::size_t k = 0; k < grid.size(); ++k)
      if (probed[k]) index.push_back(k), distance.push_back(grid[k].probe.distance);
    for (std::size_t k : largest_first(distance)) order.push_back(index[k]);
  }
  Sample best = grid[order[0]];
  std::vector<Sample> seeds;
  for (std::size_t k : order) {
    const Sample& s = grid[k];
    if (seeds.size() >= 3 || s.probe.distance < 0.7 * best.probe.distance) break;
    const double h = step[s.tri < 0 ? 0 : s.tri];
    bool distinct = true;
    for (const Sample& o : seeds)
      if (o.tri == s.tri && std::abs(o.a - s.a) <= 1.5 * h && std::abs(o.b - s.b) <= 1.5 * h)
        distinct = false;
    if (distinct) seeds.push_back(s);
  }
  // (No refinement where the largest sample lies on the face, as for quads:
  // it would climb rounding noise.)
  const bool on_face = probe.on_face(best.probe);
  if (best.probe.distance > 0 && !on_face) {
    std::vector<Sample> tops;
    for (const Sample& s : seeds)
      tops.push_back(refine(model, probe, s, 0.5 * step[s.tri < 0 ? 0 : s.tri]));
    tops.push_back(best);
    // A refinement can climb onto a wrong sheet: each top (and the best grid
    // sample) is checked against every surface point met, and the largest
    // checked value is the answer.
    best.probe.distance = -1;
    for (Sample& t : tops) {
      Vec3 x;
      Vec2 q;
      model.at(t.tri, t.a, t.b, x, q);
      t.probe = probe.recheck(x, t.probe);
      if (t.probe.distance >= best.probe.distance) best = t;
    }
  }
  Answer answer{best.probe, Vec3::Zero()};
  {
    Vec2 q;
    model.at(best.tri, best.a, best.b, answer.at, q);
  }
  bool certified = true;
  if (DeviationCertificate::possible(face)) {
    DeviationCertificate certificate(face, model, probe, p);
    std::vector<int> index(grid.size(), -1);
    for (std::size_t piece = 0; piece < piece_grid.size(); ++piece) {
      const auto [first, n] = piece_grid[piece];
      const bool quad = grid[first].tri < 0;
      const std::size_t end =
          piece + 1 < piece_grid.size() ? piece_grid[piece + 1].first : grid.size();
      // A piece far below the answer passes whole: through the surface
      // points at the samples' own parameters, every cell's bound is at most
      // the piece's largest cheap bound plus the interpolation error of a
      // cell (the piece's parameter box over n each way). Most pieces of a
      // boundary panel lie so (500 cells a panel of a trimmed dome).
      if (!quad) {
        double cheap = 0;
        UvBounds box{grid_q[first].x(), grid_q[first].x(), grid_q[first].y(), grid_q[first].y()};
        for (std::size_t k = first; k < end; ++k) {
          cheap = std::max(cheap, grid_bound[k]);
          box.u_min = std::min(box.u_min, grid_q[k].x()),
          box.u_max = std::max(box.u_max, grid_q[k].x());
          box.v_min = std::min(box.v_min, grid_q[k].y()),
          box.v_max = std::max(box.v_max, grid_q[k].y());
        }
        if (certificate.passes_whole(cheap, box, n, answer.probe.distance)) continue;
      }
      for (std::size_t k = first; k < end; ++k)
        index[k] = certificate.add_point(grid[k].tri, {grid[k].a, grid[k].b}, grid_x[k], grid_q[k],
                                         grid_s[k], probed[k] ? &grid[k].probe : nullptr);
      // Sample (i, j) of the piece: rows of n + 1 (quad) or n + 1 - i (triangle).
      auto at = [&, first = first, n = n](int i, int j) {
        const std::size_t row = quad ? std::size_t(i) * (n + 1)
                                     : std::size_t(i) * (n + 1) - std::size_t(i) * (i - 1) / 2;
        return index[first + row + j];
      };
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < (quad ? n : n - i); ++j) {
          if (quad) {
            certificate.add_cell({at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
            continue;
          }
          certificate.add_cell({at(i, j), at(i + 1, j), at(i, j + 1), -1});
          if (i + j + 2 <= n)
            certificate.add_cell({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), -1});
        }
    }
    certified = certificate.run(answer, nullptr);
  }
  return {answer.probe.distance, !answer.probe.reliable || !certified, answer.at};
}

double panel_model_deviation(const SurfaceFace& face, const std::vector<Vec3>& p,
                             const std::vector<Vec2>& uv,
                             const std::vector<std::array<int, 3>>& tris, int samples) {
  return measure_panel_deviation(face, p, uv, tris, samples).value;
}

namespace {

void measure_panel(const SurfaceFace& face, const PanelMesh& mesh, std::size_t k, int samples,
                   PanelMetrics& m, std::size_t slot) {
  const auto& panel = mesh.panels[k];
  std::vector<Vec3> p;
  for (int v : panel) p.push_back(mesh.xyz[v]);
  const std::vector<Vec2> uv = panel_corner_uv(mesh, k);
  // One triangulation for the deviation and the area (an outline along a trim
  // has hundreds of points).
  const std::vector<std::array<int, 3>> tris = panel_model_triangles(mesh, k);
  const PanelDeviation dev = measure_panel_deviation(face, p, uv, tris, samples);
  m.deviation[slot] = dev.value;
  m.deviation_unreliable[slot] = dev.unreliable ? 1 : 0;
  m.planarity[slot] = planarity(p);
  if (tris.empty()) {
    m.area[slot] = panel_area(mesh, k);  // the bilinear quad
  } else {
    double area = 0;
    for (const auto& t : tris) area += 0.5 * (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).norm();
    m.area[slot] = area;
  }
  double lo = 180.0, hi = 0.0;
  for (std::size_t c = 0; c < p.size(); ++c) {
    const Vec3 a = p[(c + p.size() - 1) % p.size()] - p[c];
    const Vec3 b = p[(c + 1) % p.size()] - p[c];
    const double angle = std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / kPi;
    lo = std::min(lo, angle);
    hi = std::max(hi, angle);
  }
  m.min_angle[slot] = lo;
  m.max_angle[slot] = hi;
}

// Panels per chunk of the parallel loop: small enough to balance the threads,
// large enough that claiming a chunk costs nothing.
constexpr std::size_t kChunk = 8;

// measure(k) for every panel k on `threads` threads, each in a FastEvaluation
// scope (span-cached evaluation and its own global search; the other threads
// on their own copy of the surface; the calling thread keeps an open scope);
// progress from the calling thread.
template <class Measure>
void for_each_panel(const SurfaceFace& face, std::size_t np, int threads, bool report,
                    const Measure& measure) {
  // Asked at once (not after the 50 ms of report_progress): a cancelled sink
  // stops even a run shorter than that.
  if (report) report_stage(0.0, "measuring panels");
  ChunkQueue queue(np, kChunk);
  run_chunks(queue, worker_threads(threads), [&](bool calling) {
    std::optional<SurfaceFace::FastEvaluation> fast;
    if (!calling || !SurfaceFace::FastEvaluation::active(face)) fast.emplace(face, !calling);
    std::size_t begin = 0, end = 0;
    while (queue.next(begin, end)) {
      for (std::size_t k = begin; k < end; ++k) measure(k);
      if (calling && report) report_progress(queue.claimed(), "measuring panels");
    }
  });
}

void resize(PanelMetrics& m, std::size_t np) {
  m.deviation.resize(np);
  m.deviation_unreliable.assign(np, 0);
  m.planarity.resize(np);
  m.area.resize(np);
  m.min_angle.resize(np);
  m.max_angle.resize(np);
}

void measure_rods(const PanelMesh& mesh, PanelMetrics& m) {
  m.rod_length.clear();
  m.rod_length.reserve(mesh.rods.size());
  for (const auto& rod : mesh.rods)
    m.rod_length.push_back((mesh.xyz[rod[0]] - mesh.xyz[rod[1]]).norm());
}

}  // namespace

PanelMetrics measure_panels(const SurfaceFace& face, const PanelMesh& mesh,
                            const MetricsParams& params) {
  require_in_range("samples", params.samples, 1, 64);
  PanelMetrics m;
  const std::size_t np = mesh.panels.size();
  resize(m, np);
  for_each_panel(face, np, params.threads, true,
                 [&](std::size_t k) { measure_panel(face, mesh, k, params.samples, m, k); });
  measure_rods(mesh, m);
  return m;
}

PanelMetrics measure_panels(const SurfaceFace& face, const PanelMesh& mesh,
                            const MetricsParams& params, const std::vector<char>& which) {
  require_in_range("samples", params.samples, 1, 64);
  if (which.size() != mesh.panels.size())
    throw InvalidParameter("measure_panels: one flag per panel expected");
  PanelMetrics m;
  const std::size_t np = mesh.panels.size();
  resize(m, np);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for_each_panel(face, np, params.threads, true, [&](std::size_t k) {
    if (which[k])
      measure_panel(face, mesh, k, params.samples, m, k);
    else
      m.deviation[k] = m.planarity[k] = m.area[k] = m.min_angle[k] = m.max_angle[k] = nan;
  });
  measure_rods(mesh, m);
  return m;
}

PanelMetrics remeasure_panels(const SurfaceFace& face, const PanelMesh& mesh,
                              const PanelMetrics& before, const std::vector<int>& origin,
                              const std::vector<char>& changed, const MetricsParams& params) {
  require_in_range("samples", params.samples, 1, 64);
  const std::size_t np = mesh.panels.size();
  if (origin.size() != np || changed.size() != np)
    throw InvalidParameter("remeasure_panels: origin and changed must have one entry per panel");
  PanelMetrics m;
  resize(m, np);
  std::vector<std::size_t> todo;
  for (std::size_t k = 0; k < np; ++k)
    if (changed[k]) todo.push_back(k);
  // The panels of most outline points first (a boundary panel's cost grows
  // with its pieces; in panel order the heaviest came last and one thread
  // measured them while the other waited). Each panel's figures are its own,
  // whatever the order and the thread.
  std::stable_sort(todo.begin(), todo.end(), [&](std::size_t a, std::size_t b) {
    return mesh.panels[a].size() > mesh.panels[b].size();
  });
  for_each_panel(face, todo.size(), params.threads, false, [&](std::size_t i) {
    measure_panel(face, mesh, todo[i], params.samples, m, todo[i]);
  });
  for (std::size_t k = 0; k < np; ++k) {
    if (changed[k]) continue;
    const std::size_t o = static_cast<std::size_t>(origin[k]);
    m.deviation[k] = before.deviation.at(o);
    m.deviation_unreliable[k] = before.deviation_unreliable.at(o);
    m.planarity[k] = before.planarity.at(o);
    m.area[k] = before.area.at(o);
    m.min_angle[k] = before.min_angle.at(o);
    m.max_angle[k] = before.max_angle.at(o);
  }
  measure_rods(mesh, m);
  return m;
}

SummaryStats summarize(const std::vector<double>& values) {
  SummaryStats s;
  s.count = int(values.size());
  if (values.empty()) return s;
  s.min = *std::min_element(values.begin(), values.end());
  s.max = *std::max_element(values.begin(), values.end());
  double sum = 0;
  for (double v : values) sum += v;
  s.mean = sum / values.size();
  double sq = 0;
  for (double v : values) sq += (v - s.mean) * (v - s.mean);
  s.variance = sq / values.size();
  return s;
}

std::vector<bool> irregular_panels(const PanelMesh& mesh, const PanelMetrics& metrics,
                                   const IrregularParams& params) {
  require_in_range("min_angle", params.min_angle_deg, 0.0, 180.0);
  require_in_range("min_area_fraction", params.min_area_fraction, 0.0, 1.0);
  std::vector<bool> flags(mesh.panels.size());
  for (std::size_t k = 0; k < mesh.panels.size(); ++k) {
    flags[k] = static_cast<int>(mesh.panels[k].size()) != mesh.regular_corners ||
               metrics.min_angle[k] < params.min_angle_deg ||
               metrics.area[k] < params.min_area_fraction * mesh.nominal_area;
  }
  return flags;
}

}  // namespace tessella
