#include "methods/boundary_driven/bd_curves.h"

#include <cmath>
#include <deque>

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

class Tracer {
 public:
  Tracer(const SurfaceFace& face, const BdTensor& tensor, const std::vector<BdPolyline>& boundary,
         const BdCurveParams& p)
      : face_(face),
        boundary_(boundary),
        p_(p),
        h_(p.spacing * p.step_fraction),
        hash_(p.spacing * 0.75),
        grid_(make_grid(face, boundary)),
        grid_field_(p.field ? *p.field : make_field(face, tensor, p.spacing)),
        inside_(bd::make_classifier(boundary)) {
    for (std::size_t k = 0; k < boundary.size(); ++k) {
      const BdPolyline& line = boundary[k];
      for (int i = 0; i < line.segment_count(); ++i)
        grid_.add(line.uv[i], line.seg_end_uv(i), k, i);
      const int n = std::max(3, static_cast<int>(std::ceil(line.length() / h_)));
      for (int j = 0; j < n; ++j) {
        const double s = line.length() * j / n;
        Vec3 t3;
        Vec2 tuv;
        bd_tangent_at(line, s, t3, tuv);
        const Vec2 uv = line.uv_at(s);
        hash_.add({face.point(uv.x(), uv.y()), t3, uv, -1 - static_cast<int>(k), s});
      }
    }
    max_steps_ = static_cast<int>(std::min(1e6, 20.0 * face.model_size() / h_ + 100));
    wrap_u_ = closed_along(face, 0);
    wrap_v_ = closed_along(face, 1);
    // Poles: trim stretches collapsed to one point in 3D (a sphere's apex).
    for (const BdPolyline& line : boundary) {
      const double tiny = 1e-12 * line.length();
      for (int i = 0; i < line.segment_count(); ++i) {
        const Vec2 duv = line.seg_end_uv(i) - line.uv[i];
        if (!line.collapsed(i) || duv.norm() == 0) continue;
        bool known = false;
        for (const Pole& pole : poles_) known = known || (pole.xyz - line.xyz[i]).norm() <= tiny;
        if (!known)
          poles_.push_back({line.xyz[i], line.uv[i], std::abs(duv.x()) > std::abs(duv.y())});
      }
    }
  }

  // The field direction closest to `ref` (3D) at uv.
  FieldDir dir_at(const Vec2& uv, const Vec3& ref) const {
    const BdDirections d = eval_bd_tensor(grid_field_, face_, uv);
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

  // The first crossing of [p,q] with the trim polylines (ignoring one at p when
  // skip_start): appends it to pts, fills `end` and returns true.
  bool first_crossing(const Vec2& p, const Vec2& q, bool skip_start, std::vector<Vec2>& pts,
                      BdCurveEnd& end) const {
    double best = 2.0, best_s = 0;
    int best_loop = -1, best_seg = -1;
    grid_.query(p, q, [&](int loop, int seg) {
      double t, s;
      const BdPolyline& line = boundary_[loop];
      if (!bd::intersect_segments(p, q, line.uv[seg], line.seg_end_uv(seg), t, s)) return;
      if (skip_start && t < 1e-6) return;
      if (t < best) best = t, best_loop = loop, best_seg = seg, best_s = s;
    });
    if (best_loop < 0) return false;
    const BdPolyline& line = boundary_[best_loop];
    best_s = std::clamp(best_s, 0.0, 1.0);
    pts.push_back(line.uv[best_seg] + best_s * (line.seg_end_uv(best_seg) - line.uv[best_seg]));
    end.loop = best_loop;
    end.s = line.s_at(best_seg, best_s);
    return true;
  }

  bool crosses_boundary(const Vec2& a, const Vec2& b) const {
    bool hit = false;
    grid_.query(a, b, [&](int loop, int seg) {
      double t, s;
      const BdPolyline& line = boundary_[loop];
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
  bool across_seam(const Vec2& a, const Vec2& b) const {
    return (wrap_u_ && std::abs(a.x() - b.x()) > 0.5 * face_.u_period()) ||
           (wrap_v_ && std::abs(a.y() - b.y()) > 0.5 * face_.v_period());
  }

  // The (u,v) to aim at to join the hashed point hp from p. At a pole (an
  // iso-line collapsed to one point: a sphere's apex) hp's (u,v) is one of
  // the many that give that point, so aim straight across the collapsed line,
  // keeping p's parameter along it; aiming at hp's own (u,v) would cross the
  // whole parameter range and end the curve on the far side of the face.
  Vec2 join_aim(const Vec2& p, const bd::HashedPoint& hp) const {
    const SurfacePoint d = face_.derivatives(hp.uv.x(), hp.uv.y());
    const double du = d.du.norm(), dv = d.dv.norm();
    Vec2 aim = hp.uv;
    if (du <= 1e-9 * dv)
      aim.x() = p.x();
    else if (dv <= 1e-9 * du)
      aim.y() = p.y();
    return aim;
  }

  // Traces from uv along `dir` (3D). Appends points (excluding the start) to pts.
  // Returns how it ended.
  enum class End { Boundary, Outside, Near, Closed, Steps };
  End trace(const Vec2& start, const Vec3& dir, int id, double arc_sign, bool start_on_boundary,
            std::vector<Vec2>& pts, BdCurveEnd& end) {
    Vec2 p = start;
    Vec3 ref = dir;
    const Vec3 start3 = face_.point(start.x(), start.y());
    double arc = 0;
    for (int step = 0; step < max_steps_; ++step) {
      const FieldDir k1 = dir_at(p, ref);
      const Vec2 pm = p + 0.5 * h_ * k1.uv;
      const FieldDir k2 = dir_at(pm, k1.d3);
      const Vec2 q = p + h_ * k2.uv;
      ref = k2.d3;
      // the first crossing of [p,q] with the trim polylines
      if (first_crossing(p, q, step == 0 && start_on_boundary, pts, end)) return End::Boundary;
      if (!inside_.contains(q)) return End::Outside;
      const Vec3 q3 = face_.point(q.x(), q.y());
      // Near a pole the field turns round the point and a step of h crosses
      // much of the parameter range: the curve ends at the pole, reached
      // straight across the collapsed iso-line from p.
      for (const Pole& pole : poles_) {
        if ((q3 - pole.xyz).norm() >= p_.stop_fraction * p_.spacing) continue;
        const Vec2 aim = pole.along_u ? Vec2(p.x(), pole.uv.y()) : Vec2(pole.uv.x(), p.y());
        if (first_crossing(p, p + 1.05 * (aim - p), false, pts, end)) return End::Boundary;
        return End::Near;
      }
      arc += h_ * arc_sign;
      // parallel lines nearby (other lines; this one only far back along it)
      const bd::HashedPoint* nearest = nullptr;
      double nearest_d = p_.stop_fraction * p_.spacing;
      hash_.near(q3, [&](const bd::HashedPoint& hp) {
        if (std::abs(hp.dir.dot(ref)) <= kSameFamily) return;
        if (across_seam(q, hp.uv)) return;
        if (hp.line == id && std::abs(arc - hp.arc) <= 4 * p_.spacing) return;
        const double d = (hp.p - q3).norm();
        if (d < nearest_d) nearest_d = d, nearest = &hp;
      });
      if (arc_sign > 0 && std::abs(arc) > 4 * p_.spacing && (q3 - start3).norm() < 1.5 * h_ &&
          !start_on_boundary)
        return End::Closed;
      if (nearest != nullptr) {
        // Join the parallel line: a last step just across it (the network
        // stage finds the crossing), or onto the trim if it is the trim.
        const Vec2 target = p + 1.05 * (join_aim(p, *nearest) - p);
        if (nearest->line < 0) {
          if (first_crossing(p, target, false, pts, end)) return End::Boundary;
          return End::Near;
        }
        if (inside_.contains(target) && !crosses_boundary(p, target)) pts.push_back(target);
        return End::Near;
      }
      pts.push_back(q);
      hash_.add({q3, ref, q, id, arc});
      p = q;
    }
    return End::Steps;
  }

  // Traces a curve through seed (both ways unless from_boundary) and stores it.
  void add_curve(const Vec2& seed, const Vec3& dir, const BdCurveEnd& seed_end,
                 bool from_boundary) {
    if (static_cast<int>(curves_.size()) >= p_.max_curves)
      throw LimitExceeded("more than max_curves = " + std::to_string(p_.max_curves) +
                          " BDCurves: raise size or max_curves");
    const int id = static_cast<int>(curves_.size());
    hash_.add({face_.point(seed.x(), seed.y()), dir, seed, id, 0.0});
    BdCurve c;
    std::vector<Vec2> fwd, bwd;
    BdCurveEnd fend, bend;
    const End e = trace(seed, dir, id, 1.0, from_boundary, fwd, fend);
    if (from_boundary) {
      bend = seed_end;
    } else if (e != End::Closed) {
      trace(seed, -dir, id, -1.0, false, bwd, bend);
    }
    c.uv.assign(bwd.rbegin(), bwd.rend());
    c.uv.push_back(seed);
    c.uv.insert(c.uv.end(), fwd.begin(), fwd.end());
    c.closed = e == End::Closed;
    c.start = bend;
    c.end = fend;
    if (c.uv.size() < 2) {
      curves_.push_back(BdCurve{});  // keep ids aligned; dropped at the end
      return;
    }
    for (const Vec2& q : c.uv) c.xyz.push_back(face_.point(q.x(), q.y()));
    curves_.push_back(std::move(c));
  }

  void run() {
    const double sp = p_.spacing;
    // 1. seeds on the boundary spans, traced inward; then every loop that fewer
    //    than two curves reach gets two seeds regardless of spacing (a loop
    //    with no curve would leave an opening inside a panel, a loop with one
    //    would hang on a bridge)
    for (int round = 0; round < 2; ++round) {
      const bool forced = round == 1;
      for (std::size_t k = 0; k < boundary_.size(); ++k) {
        if (forced) {
          int ends = 0;
          for (const BdCurve& c : curves_)
            ends += (c.start.loop == int(k)) + (c.end.loop == int(k));
          if (ends >= 2) continue;
        }
        const BdPolyline& line = boundary_[k];
        std::vector<double> corners = bd_corners(line, p_.corner_angle_deg);
        std::vector<double> seeds;
        const double len = line.length();
        if (corners.empty()) {
          const int m = std::max(4, static_cast<int>(std::lround(len / sp)));
          for (int j = 0; j < m; ++j) seeds.push_back(len * j / m);
        } else {
          for (std::size_t c = 0; c < corners.size(); ++c) {
            const double a = corners[c];
            const double b = c + 1 < corners.size() ? corners[c + 1] : corners[0] + len;
            const int m = static_cast<int>(std::lround((b - a) / sp));
            for (int j = 1; j < m; ++j) seeds.push_back(a + (b - a) * j / m);
          }
        }
        if (forced && seeds.size() > 2) seeds = {seeds[0], seeds[seeds.size() / 2]};
        for (double s : seeds) {
          Vec3 t3;
          Vec2 tuv;
          bd_tangent_at(line, s, t3, tuv);
          const Vec2 uv = line.uv_at(s);
          const SurfacePoint dp = face_.derivatives(uv.x(), uv.y());
          const Vec3 inward = dp.du * -tuv.y() + dp.dv * tuv.x();  // left of the loop in (u,v)
          const FieldDir fd = dir_at(uv, inward);
          if (fd.d3.dot(inward.normalized()) < 0.3) continue;  // field nearly along the trim here
          if (!forced && too_close(face_.point(uv.x(), uv.y()), fd.d3, 0.4 * sp, true)) continue;
          BdCurveEnd se{static_cast<int>(k), s};
          line.segment_at(se.s);  // wraps s into [0, length)
          add_curve(uv, fd.d3, se, true);
        }
      }
    }
    // 2. offset seeds, line by line (boundary loops first, then curves as made)
    for (std::size_t k = 0; k < boundary_.size(); ++k) offset_seeds_along(boundary_[k].uv, true);
    for (std::size_t c = 0; c < curves_.size(); ++c) {
      if (curves_[c].uv.size() < 2) continue;
      const std::vector<Vec2> uv = curves_[c].uv;  // copy: curves_ grows
      offset_seeds_along(uv, false);
    }
  }

  void offset_seeds_along(const std::vector<Vec2>& uv, bool is_boundary) {
    const double sp = p_.spacing;
    // points every `spacing` of 3D arc length, starting half a spacing in
    double acc = 0.5 * sp;
    for (std::size_t i = 0; i + 1 < uv.size() + (is_boundary ? 1 : 0); ++i) {
      const Vec2& a = uv[i];
      const Vec2& b = uv[(i + 1) % uv.size()];
      const double l = (face_.point(b.x(), b.y()) - face_.point(a.x(), a.y())).norm();
      if (l <= 0) continue;
      double t = (acc <= l) ? acc / l : 2.0;
      while (t <= 1.0) {
        const Vec2 p = a + t * (b - a);
        const SurfacePoint dp = face_.derivatives(p.x(), p.y());
        const Vec2 tuv = b - a;
        const Vec3 t3 = (dp.du * tuv.x() + dp.dv * tuv.y()).normalized();
        const Vec3 left = dp.du * -tuv.y() + dp.dv * tuv.x();
        for (int side : {1, -1}) {
          if (is_boundary && side < 0) continue;
          try_offset_seed(p, t3, side * left);
        }
        acc += sp;
        t = acc / l;
      }
      acc -= l;
    }
  }

  void try_offset_seed(const Vec2& p, const Vec3& along, const Vec3& across) {
    const double sp = p_.spacing;
    Vec2 q = p;
    Vec3 ref = across;
    const int n = 4;
    for (int k = 0; k < n; ++k) {
      const FieldDir k1 = dir_at(q, ref);
      const FieldDir k2 = dir_at(q + 0.5 * (sp / n) * k1.uv, k1.d3);
      q += (sp / n) * k2.uv;
      ref = k2.d3;
      if (!inside_.contains(q)) return;
    }
    const FieldDir fd = dir_at(q, along);
    if (too_close(face_.point(q.x(), q.y()), fd.d3, 0.75 * sp, false)) return;
    add_curve(q, fd.d3, BdCurveEnd{}, false);
  }

  std::vector<BdCurve> take() {
    std::vector<BdCurve> out;
    for (auto& c : curves_)
      if (c.uv.size() >= 2) out.push_back(std::move(c));
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

  struct Pole {
    Vec3 xyz;
    Vec2 uv;       // one (u,v) of it
    bool along_u;  // the collapsed iso-line runs along u (v is the pole's)
  };
  const SurfaceFace& face_;
  std::vector<Pole> poles_;
  bool wrap_u_ = false, wrap_v_ = false;  // closed round a seam along u / v
  const std::vector<BdPolyline>& boundary_;
  BdCurveParams p_;
  double h_;
  bd::PointHash hash_;
  bd::SegmentGrid grid_;
  BdTensorGrid grid_field_;
  UvTrimClassifier inside_;
  int max_steps_ = 0;
  std::vector<BdCurve> curves_;
};

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
  const double ms = face.model_size();
  require_in_range("curve spacing (mm)", params.spacing, 1e-6 * ms, ms);
  require_in_range("step_fraction", params.step_fraction, 0.01, 0.5);
  require_in_range("stop_fraction", params.stop_fraction, 0.1, 0.9);
  require_in_range("corner_angle (deg)", params.corner_angle_deg, 1.0, 179.0);
  require_in_range("max_curves", params.max_curves, 1, 1e7);
  if (boundary.empty()) throw InvalidGeometry("the face has no trim loops");
  Tracer t(face, tensor, boundary, params);
  t.run();
  return t.take();
}

}  // namespace tessella
