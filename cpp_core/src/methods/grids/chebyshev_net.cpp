// The Chebyshev net (tessella/chebyshev_net.h): generators, the fishnet
// rule, the lattice past the bounds, its checks, the trim cut.
#include "tessella/chebyshev_net.h"

#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "geometry/trim_deflection.h"
#include "geometry/uv_trim_classifier.h"
#include "mesh/cell_clipping.h"
#include "mesh/seam_sides.h"
#include "methods/grids/path_along_cuts.h"
#include "tessella/errors.h"
#include "tessella/surface_face.h"

namespace tessella {

namespace {

constexpr double kPi = 3.14159265358979323846;

bool in_bounds(const UvBounds& b, const Vec2& p) {
  return p.x() >= b.u_min && p.x() <= b.u_max && p.y() >= b.v_min && p.y() <= b.v_max;
}

double angle_deg(const Vec3& a, const Vec3& b) {
  const double na = a.norm(), nb = b.norm();
  if (!(na > 0) || !(nb > 0)) return 0.0;
  return std::acos(std::clamp(a.dot(b) / (na * nb), -1.0, 1.0)) * 180.0 / kPi;
}

bool shear_ok(double deg) {
  return deg >= kChebyshevMinShearDeg && deg <= 180.0 - kChebyshevMinShearDeg;
}

// A generator's way in (u,v) from the seed: a polyline (an iso-line's two
// points, or a guide's projection), walked by its (u,v) arc length t.
struct GeneratorPath {
  std::vector<Vec2> pts;    // pts[0]: the seed
  std::vector<Vec2> unit;   // unit direction of each segment
  std::vector<double> cum;  // (u,v) length up to each point
  Vec2 heading;             // the way out where the path has no length (unit)
  // The largest step a rod may take along u and along v (a third of a
  // closed direction, half of one between two poles; seam_sides.h).
  Vec2 widest;

  GeneratorPath(std::vector<Vec2> points, const Vec2& way_out, const Vec2& widest_step)
      : heading(way_out), widest(widest_step) {
    for (const Vec2& p : points)
      if (pts.empty() || (p - pts.back()).norm() > 0) pts.push_back(p);
    cum.assign(1, 0.0);
    for (std::size_t k = 1; k < pts.size(); ++k) {
      const double l = (pts[k] - pts[k - 1]).norm();
      unit.push_back((pts[k] - pts[k - 1]) / l);
      cum.push_back(cum.back() + l);
    }
  }
  double room() const { return cum.back(); }
  std::size_t segment(double t) const {
    const std::size_t k = std::size_t(std::upper_bound(cum.begin(), cum.end(), t) - cum.begin());
    return std::min(k == 0 ? 0 : k - 1, unit.size() - 1);
  }
  Vec2 at(double t) const {
    const std::size_t k = segment(t);
    return pts[k] + (t - cum[k]) * unit[k];
  }
  Vec2 direction(double t) const { return unit[segment(t)]; }
  bool too_wide(const Vec2& step) const {
    return std::abs(step.x()) > widest.x() || std::abs(step.y()) > widest.y();
  }
  // The longest step along unit direction `dir` that is not too wide.
  double longest_along(const Vec2& dir) const {
    double t = std::numeric_limits<double>::infinity();
    if (dir.x() != 0) t = std::min(t, widest.x() / std::abs(dir.x()));
    if (dir.y() != 0) t = std::min(t, widest.y() / std::abs(dir.y()));
    return t;
  }
};

// The next generator node from t_from: the first point of the path at
// chord `length` from it, or nothing when the path ends first. Marching in
// quarter steps finds the first crossing of the chord length (a wavy curve
// may cross it again later); bisection with secant steps then refines it.
std::optional<double> chord_step(const SurfaceFace& face, const GeneratorPath& path, double t_from,
                                 double length) {
  const double room = path.room() - t_from;
  if (path.unit.empty() || !(room > 0)) return std::nullopt;
  const Vec2 from = path.at(t_from), dir = path.direction(t_from);
  const Vec3 p0 = face.point(from.x(), from.y());
  const SurfacePoint d = face.derivatives(from.x(), from.y());
  const double speed = (d.du * dir.x() + d.dv * dir.y()).norm();
  const double dt = speed > 0 ? std::min(0.25 * length / speed, room / 8) : room / 64;
  auto gap = [&](double t) {
    const Vec2 q = path.at(t_from + t);
    return (face.point(q.x(), q.y()) - p0).norm() - length;
  };
  double t0 = 0, g0 = -length, t1 = 0, g1 = -length;
  for (int k = 1;; ++k) {
    t1 = std::min(k * dt, room);
    g1 = gap(t1);
    if (g1 >= 0) break;
    if (t1 >= room || k > 100000) return std::nullopt;
    t0 = t1, g0 = g1;
  }
  for (int it = 0; it < 200 && std::abs(g1) > 1e-13 * length; ++it) {
    double t = t0 - g0 * (t1 - t0) / (g1 - g0);
    if (!(t > t0 && t < t1) || it % 3 == 2) t = 0.5 * (t0 + t1);  // keep bisecting too
    if (!(t > t0 && t < t1)) break;  // the bracket is down to the last bit
    const double g = gap(t);
    if (g >= 0)
      t1 = t, g1 = g;
    else
      t0 = t, g0 = g;
  }
  return t_from + t1;
}

// The fishnet rule: the point of the surface at `length` from both a and b,
// by Newton in (u,v) from `guess`; nothing when it does not converge inside
// the bounds.
std::optional<Vec2> fishnet_node(const SurfaceFace& face, const UvBounds& b, const Vec3& a,
                                 const Vec3& bb, const Vec2& guess, double length) {
  const double l2 = length * length;
  Vec2 uv = guess;
  for (int it = 0; it < 40; ++it) {
    if (!in_bounds(b, uv)) return std::nullopt;
    const SurfacePoint s = face.derivatives(uv.x(), uv.y());
    const Vec3 da = s.point - a, db = s.point - bb;
    const double fa = da.dot(da) - l2, fb = db.dot(db) - l2;
    if (std::max(std::abs(fa), std::abs(fb)) <= 1e-13 * l2) return uv;
    const double j00 = 2 * da.dot(s.du), j01 = 2 * da.dot(s.dv);
    const double j10 = 2 * db.dot(s.du), j11 = 2 * db.dot(s.dv);
    const double det = j00 * j11 - j01 * j10;
    const double scale = std::abs(j00 * j11) + std::abs(j01 * j10);
    if (!(std::abs(det) > 1e-12 * scale)) return std::nullopt;
    Vec2 step((-fa * j11 + fb * j01) / det, (-fb * j00 + fa * j10) / det);
    // At most half a rod a step (3D), so a poor guess does not jump sheets.
    const double move = (s.du * step.x() + s.dv * step.y()).norm();
    if (move > 0.5 * length) step *= 0.5 * length / move;
    uv += step;
    if (it >= 30 && std::max(std::abs(fa), std::abs(fb)) <= 1e-9 * l2) {
      return in_bounds(b, uv) ? std::optional<Vec2>(uv) : std::nullopt;
    }
  }
  return std::nullopt;
}

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// A cell (corners in lattice order) turns counter-clockwise and is convex.
bool convex_ccw(const Vec2& p0, const Vec2& p1, const Vec2& p2, const Vec2& p3) {
  const Vec2 q[4] = {p0, p1, p2, p3};
  for (int k = 0; k < 4; ++k) {
    if (!(cross(q[(k + 1) % 4] - q[k], q[(k + 2) % 4] - q[(k + 1) % 4]) > 0)) return false;
  }
  return true;
}

// Whether segment pq meets the closed box.
bool segment_meets_box(const Vec2& p, const Vec2& q, const UvBounds& b) {
  double t0 = 0, t1 = 1;
  const double d[2] = {q.x() - p.x(), q.y() - p.y()};
  const double s[2] = {p.x(), p.y()};
  const double lo[2] = {b.u_min, b.v_min}, hi[2] = {b.u_max, b.v_max};
  for (int a = 0; a < 2; ++a) {
    if (d[a] == 0) {
      if (s[a] < lo[a] || s[a] > hi[a]) return false;
      continue;
    }
    double e0 = (lo[a] - s[a]) / d[a], e1 = (hi[a] - s[a]) / d[a];
    if (e0 > e1) std::swap(e0, e1);
    t0 = std::max(t0, e0), t1 = std::min(t1, e1);
    if (t0 > t1) return false;
  }
  return true;
}

struct Lattice {
  int i_lo = 0, i_hi = 0, j_lo = 0, j_hi = 0;  // node index range (seed at 0, 0)
  std::vector<Vec2> uv;
  std::vector<char> on_net;
  int nu() const { return i_hi - i_lo + 1; }
  int nv() const { return j_hi - j_lo + 1; }
  std::size_t at(int i, int j) const {
    return std::size_t(j - j_lo) * std::size_t(nu()) + std::size_t(i - i_lo);
  }
};

// A generator from the seed along its path: its net nodes (at chord
// `length`), then `margin` steps past the bounds by the last (u,v) step.
std::vector<std::pair<Vec2, bool>> generator(const SurfaceFace& face, const UvBounds& b,
                                             const GeneratorPath& path, double length, int margin) {
  const Vec2 seed = path.pts[0];
  std::vector<std::pair<Vec2, bool>> nodes;
  Vec2 cur = seed;
  for (double t = 0;;) {
    const std::optional<double> next = chord_step(face, path, t, length);
    if (!next || path.too_wide(path.at(*next) - cur)) break;
    t = *next;
    cur = path.at(t);
    nodes.push_back({cur, true});
  }
  Vec2 step = Vec2::Zero();
  if (!nodes.empty())
    step = nodes.back().first - (nodes.size() > 1 ? nodes[nodes.size() - 2].first : seed);
  if (!(step.norm() > 0)) {
    // No rod fits (a face smaller than the size): a step of one rod by the
    // seed's speed, at most the widest (one cell over the face, not dozens).
    const Vec2 dir = path.unit.empty() ? path.heading : path.unit[0];
    const SurfacePoint d = face.derivatives(seed.x(), seed.y());
    const double speed = (d.du * dir.x() + d.dv * dir.y()).norm();
    const double widest = path.longest_along(dir);
    step = dir * (speed > 0 ? std::min(length / speed, widest) : widest);
  }
  int past = 0;
  while (past < margin) {
    cur = cur + step;
    nodes.push_back({cur, false});
    if (!in_bounds(b, cur)) ++past;
  }
  return nodes;
}

// paths[axis][s]: the generators from the seed, i (axis 0) and j (axis 1),
// backwards (s = 0) and forwards; forwards i then forwards j turn
// counter-clockwise in (u,v).
Lattice build_lattice(const SurfaceFace& face, const UvBounds& b,
                      const std::vector<GeneratorPath>& paths, double length, int margin,
                      std::size_t max_nodes) {
  const Vec2 seed = paths[0].pts[0];
  std::vector<std::pair<Vec2, bool>> gen[2][2];  // [axis][forwards]
  for (int axis = 0; axis < 2; ++axis)
    for (int s = 0; s < 2; ++s)
      gen[axis][s] = generator(face, b, paths[std::size_t(2 * axis + s)], length, margin);
  Lattice L;
  L.i_lo = -int(gen[0][0].size()), L.i_hi = int(gen[0][1].size());
  L.j_lo = -int(gen[1][0].size()), L.j_hi = int(gen[1][1].size());
  const double nodes = double(L.nu()) * double(L.nv());
  if (nodes > double(max_nodes)) {
    throw LimitExceeded("the Chebyshev net's lattice would have " +
                        std::to_string(static_cast<long long>(nodes)) +
                        " nodes: choose a larger size or raise max_panels");
  }
  L.uv.assign(std::size_t(L.nu()) * L.nv(), Vec2::Zero());
  L.on_net.assign(L.uv.size(), 0);
  L.uv[L.at(0, 0)] = seed;
  L.on_net[L.at(0, 0)] = in_bounds(b, seed);
  for (int s = 0; s < 2; ++s) {
    for (std::size_t k = 0; k < gen[0][s].size(); ++k) {
      const int i = s ? int(k) + 1 : -int(k) - 1;
      L.uv[L.at(i, 0)] = gen[0][s][k].first, L.on_net[L.at(i, 0)] = gen[0][s][k].second;
    }
    for (std::size_t k = 0; k < gen[1][s].size(); ++k) {
      const int j = s ? int(k) + 1 : -int(k) - 1;
      L.uv[L.at(0, j)] = gen[1][s][k].first, L.on_net[L.at(0, j)] = gen[1][s][k].second;
    }
  }
  std::vector<Vec3> xyz(L.uv.size(), Vec3::Zero());
  std::vector<char> known(L.uv.size(), 0);
  auto point_of = [&](std::size_t k) -> const Vec3& {
    if (!known[k]) xyz[k] = face.point(L.uv[k].x(), L.uv[k].y()), known[k] = 1;
    return xyz[k];
  };
  // Quadrant by quadrant, away from the generators: node (i, j) from its
  // neighbours towards the seed a = (i - si, j), b = (i, j - sj) and the
  // opposite corner c = (i - si, j - sj).
  for (const int si : {1, -1}) {
    for (const int sj : {1, -1}) {
      const int i_end = si > 0 ? L.i_hi : -L.i_lo, j_end = sj > 0 ? L.j_hi : -L.j_lo;
      for (int jj = 1; jj <= j_end; ++jj) {
        for (int ii = 1; ii <= i_end; ++ii) {
          const int i = si * ii, j = sj * jj;
          const std::size_t ka = L.at(i - si, j), kb = L.at(i, j - sj), kc = L.at(i - si, j - sj);
          const std::size_t k = L.at(i, j);
          const Vec2 guess = L.uv[ka] + L.uv[kb] - L.uv[kc];
          L.uv[k] = guess;
          // A guess of the net's own (a node where it failed) is a surface
          // point too: the rule goes on from it, so a failure stays local.
          if (!(in_bounds(b, L.uv[ka]) && in_bounds(b, L.uv[kb]) && in_bounds(b, L.uv[kc])))
            continue;
          const std::optional<Vec2> node =
              fishnet_node(face, b, point_of(ka), point_of(kb), guess, length);
          if (!node) continue;
          // The cell in lattice order: corners (i0,j0), (i0+1,j0), (i0+1,j0+1), (i0,j0+1).
          const int i0 = std::min(i, i - si), j0 = std::min(j, j - sj);
          auto uv_at = [&](int ci, int cj) {
            return ci == i && cj == j ? *node : L.uv[L.at(ci, cj)];
          };
          if (!convex_ccw(uv_at(i0, j0), uv_at(i0 + 1, j0), uv_at(i0 + 1, j0 + 1),
                          uv_at(i0, j0 + 1)))
            continue;
          const Vec3 p = face.point(node->x(), node->y());
          const Vec3 &pa = point_of(ka), &pb = point_of(kb), &pc = point_of(kc);
          if (!shear_ok(angle_deg(pa - pc, pb - pc)) || !shear_ok(angle_deg(pa - p, pb - p)))
            continue;
          L.uv[k] = *node;
          L.on_net[k] = 1;
          xyz[k] = p, known[k] = 1;
        }
      }
    }
  }
  return L;
}

// The lattice covers the bounds once: its border ring stays off the bounds
// box and winds once round it. (Every cell over the bounds turning
// counter-clockwise, checked apart, then makes the cells over the face a
// tiling: the count of cells over a point is the border's winding number.)
bool covers_bounds(const Lattice& L, const UvBounds& b) {
  std::vector<Vec2> ring;
  for (int i = L.i_lo; i < L.i_hi; ++i) ring.push_back(L.uv[L.at(i, L.j_lo)]);
  for (int j = L.j_lo; j < L.j_hi; ++j) ring.push_back(L.uv[L.at(L.i_hi, j)]);
  for (int i = L.i_hi; i > L.i_lo; --i) ring.push_back(L.uv[L.at(i, L.j_hi)]);
  for (int j = L.j_hi; j > L.j_lo; --j) ring.push_back(L.uv[L.at(L.i_lo, j)]);
  const Vec2 centre(0.5 * (b.u_min + b.u_max), 0.5 * (b.v_min + b.v_max));
  int winding = 0;
  for (std::size_t k = 0; k < ring.size(); ++k) {
    const Vec2 &p = ring[k], &q = ring[(k + 1) % ring.size()];
    if (segment_meets_box(p, q, b)) return false;
    if (p.y() <= centre.y()) {
      if (q.y() > centre.y() && cross(q - p, centre - p) > 0) ++winding;
    } else if (q.y() <= centre.y() && cross(q - p, centre - p) < 0) {
      --winding;
    }
  }
  return winding == 1;
}

// The cells over the bounds that are turned over or not convex, by their
// first corner's lattice index.
std::vector<std::pair<int, int>> folded_cells(const Lattice& L, const UvBounds& b) {
  std::vector<std::pair<int, int>> out;
  for (int j = L.j_lo; j < L.j_hi; ++j) {
    for (int i = L.i_lo; i < L.i_hi; ++i) {
      const Vec2 q[4] = {L.uv[L.at(i, j)], L.uv[L.at(i + 1, j)], L.uv[L.at(i + 1, j + 1)],
                         L.uv[L.at(i, j + 1)]};
      UvBounds box{q[0].x(), q[0].x(), q[0].y(), q[0].y()};
      for (const Vec2& p : q) {
        box.u_min = std::min(box.u_min, p.x()), box.u_max = std::max(box.u_max, p.x());
        box.v_min = std::min(box.v_min, p.y()), box.v_max = std::max(box.v_max, p.y());
      }
      if (box.u_max < b.u_min || box.u_min > b.u_max || box.v_max < b.v_min || box.v_min > b.v_max)
        continue;
      if (!convex_ccw(q[0], q[1], q[2], q[3])) out.push_back({i, j});
    }
  }
  return out;
}

// Where the guesses fold (beyond a net that sheared to its limit, the
// parallelograms of turned edges overlap), they are laid out again as a
// Tutte embedding: the lattice's border ring spread round a box about
// everything, the net's nodes fixed, every other node at the mean of its
// four neighbours. With a convex border such a layout turns no cell over
// but where the fixed net forces it (checked again by the caller, which
// then frees the net's nodes round the folds).
void relax_guesses(Lattice& L, const UvBounds& b) {
  UvBounds box = b;
  for (const Vec2& p : L.uv) {
    box.u_min = std::min(box.u_min, p.x()), box.u_max = std::max(box.u_max, p.x());
    box.v_min = std::min(box.v_min, p.y()), box.v_max = std::max(box.v_max, p.y());
  }
  const double mu = 0.01 * (box.u_max - box.u_min), mv = 0.01 * (box.v_max - box.v_min);
  box = {box.u_min - mu, box.u_max + mu, box.v_min - mv, box.v_max + mv};
  const int nu = L.nu(), nv = L.nv();
  std::vector<char> fixed(L.uv.size(), 0);
  for (int j = L.j_lo; j <= L.j_hi; ++j) {
    for (int i = L.i_lo; i <= L.i_hi; ++i) {
      const std::size_t k = L.at(i, j);
      const double s = double(i - L.i_lo) / (nu - 1), t = double(j - L.j_lo) / (nv - 1);
      if (i == L.i_lo || i == L.i_hi || j == L.j_lo || j == L.j_hi) {
        L.uv[k] = {box.u_min + s * (box.u_max - box.u_min),
                   box.v_min + t * (box.v_max - box.v_min)};
        fixed[k] = 1;
      } else {
        fixed[k] = L.on_net[k];
      }
    }
  }
  std::vector<int> index(L.uv.size(), -1);
  int n = 0;
  for (std::size_t k = 0; k < L.uv.size(); ++k)
    if (!fixed[k]) index[k] = n++;
  if (n == 0) return;
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 2);
  for (int j = L.j_lo + 1; j < L.j_hi; ++j) {
    for (int i = L.i_lo + 1; i < L.i_hi; ++i) {
      const std::size_t k = L.at(i, j);
      if (fixed[k]) continue;
      entries.emplace_back(index[k], index[k], 4.0);
      for (const std::size_t m : {L.at(i - 1, j), L.at(i + 1, j), L.at(i, j - 1), L.at(i, j + 1)}) {
        if (fixed[m]) {
          rhs(index[k], 0) += L.uv[m].x(), rhs(index[k], 1) += L.uv[m].y();
        } else {
          entries.emplace_back(index[k], index[m], -1.0);
        }
      }
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(A);
  if (solver.info() != Eigen::Success) return;
  const Eigen::MatrixXd x = solver.solve(rhs);
  for (std::size_t k = 0; k < L.uv.size(); ++k)
    if (index[k] >= 0) L.uv[k] = {x(index[k], 0), x(index[k], 1)};
}

// The largest step along u and v: fewer cells round a closed direction give
// panels that coincide (two halves of a cylinder as one flat panel twice).
Vec2 widest_steps(const SurfaceFace& face, const UvBounds& b) {
  return {(b.u_max - b.u_min) / fewest_cells_along(face, true),
          (b.v_max - b.v_min) / fewest_cells_along(face, false)};
}

// The generators along the face's u and v iso-lines through the seed, each
// way to the bounds.
std::vector<GeneratorPath> iso_paths(const SurfaceFace& face, const UvBounds& b, const Vec2& seed) {
  std::vector<GeneratorPath> out;
  const Vec2 widest = widest_steps(face, b);
  for (int axis = 0; axis < 2; ++axis) {
    for (const int sign : {-1, 1}) {
      const Vec2 e = axis == 0 ? Vec2(sign, 0) : Vec2(0, sign);
      const double start = axis == 0 ? seed.x() : seed.y();
      const double lo = axis == 0 ? b.u_min : b.v_min, hi = axis == 0 ? b.u_max : b.v_max;
      const double room = std::max(0.0, sign > 0 ? hi - start : start - lo);
      GeneratorPath path(std::vector<Vec2>{seed, seed + room * e}, e, widest);
      if (!path.unit.empty()) path.unit[0] = e, path.cum[1] = room;  // exactly along the axis
      out.push_back(std::move(path));
    }
  }
  return out;
}

// The guides projected onto the surface, in (u,v); InvalidParameter where a
// guide lies farther than 5% of the model from it.
std::vector<Vec2> guide_on_surface(const SurfaceFace& face, const std::vector<Vec3>& guide,
                                   int index) {
  if (guide.size() < 2)
    throw InvalidParameter("guides: guide " + std::to_string(index + 1) + " has no length");
  const double tolerance = 0.05 * face.model_size();
  std::vector<Vec2> uv;
  for (const Vec3& p : guide) {
    const Projection f = uv.empty() ? face.project(p) : face.project(p, uv.back());
    if (!(f.distance <= tolerance)) {
      throw InvalidParameter("guides: guide " + std::to_string(index + 1) + " lies " +
                             std::to_string(f.distance) + " mm from the face (at most " +
                             std::to_string(tolerance) + ": 5% of the model)");
    }
    Vec2 q = f.uv;
    // Round a closed direction the projection may land on the seam's other
    // side: read it on the previous point's side (the path then leaves the
    // bounds there, and the lattice goes on by guesses).
    if (!uv.empty() && closed_along(face, 0))
      q.x() += seam_shift(uv.back().x(), q.x(), face.u_period());
    if (!uv.empty() && closed_along(face, 1))
      q.y() += seam_shift(uv.back().y(), q.y(), face.v_period());
    uv.push_back(q);
  }
  return uv;
}

// The part of a (u,v) polyline from its first point up to where it leaves
// the bounds (that point moved onto them).
std::vector<Vec2> within_bounds(const std::vector<Vec2>& pts, const UvBounds& b) {
  std::vector<Vec2> out{pts[0]};
  for (std::size_t k = 1; k < pts.size(); ++k) {
    if (in_bounds(b, pts[k])) {
      out.push_back(pts[k]);
      continue;
    }
    // The exit of segment k-1..k from the box: bisection on the segment.
    Vec2 in = pts[k - 1], out_p = pts[k];
    for (int it = 0; it < 60; ++it) {
      const Vec2 mid = 0.5 * (in + out_p);
      (in_bounds(b, mid) ? in : out_p) = mid;
    }
    out.push_back(in);
    break;
  }
  return out;
}

// The generators along two crossing guides: their first crossing in (u,v)
// is the seed; guide 1 gives i, guide 2 j (its direction turned so that the
// cells run counter-clockwise).
std::vector<GeneratorPath> guide_paths(const SurfaceFace& face, const UvBounds& b,
                                       const Polylines& guides,
                                       const std::vector<std::vector<Vec2>>& cuts, double size) {
  const std::vector<Vec2> a =
      path_along_cuts(face, guide_on_surface(face, guides[0], 0), cuts, size);
  const std::vector<Vec2> c0 =
      path_along_cuts(face, guide_on_surface(face, guides[1], 1), cuts, size);
  // Round a closed direction the second guide may lie a period off the
  // first: its copies a period either way are tried too.
  std::vector<Vec2> shifts{Vec2::Zero()};
  for (const double su : {-1.0, 1.0})
    if (closed_along(face, 0)) shifts.push_back(Vec2(su * face.u_period(), 0));
  for (const double sv : {-1.0, 1.0})
    if (closed_along(face, 1)) shifts.push_back(Vec2(0, sv * face.v_period()));
  for (const Vec2& shift : shifts) {
    std::vector<Vec2> c = c0;
    for (Vec2& p : c) p += shift;
    for (std::size_t i = 0; i + 1 < a.size(); ++i) {
      for (std::size_t j = 0; j + 1 < c.size(); ++j) {
        const Vec2 r = a[i + 1] - a[i], q = c[j + 1] - c[j];
        const double den = cross(r, q);
        if (den == 0) continue;
        const double t = cross(c[j] - a[i], q) / den, u = cross(c[j] - a[i], r) / den;
        if (t < 0 || t >= 1 || u < 0 || u >= 1) continue;
        const Vec2 x = a[i] + t * r;
        if (!in_bounds(b, x))
          throw InvalidParameter("guides: the two guides cross outside the face's (u,v) bounds");
        // The crossing angle on the surface, not in (u,v).
        const SurfacePoint d = face.derivatives(x.x(), x.y());
        const double angle = angle_deg(d.du * r.x() + d.dv * r.y(), d.du * q.x() + d.dv * q.y());
        if (!shear_ok(angle)) {
          throw InvalidParameter("guides: the two guides cross at " + std::to_string(angle) +
                                 " degrees; a net needs them to cross between " +
                                 std::to_string(int(kChebyshevMinShearDeg)) + " and " +
                                 std::to_string(int(180 - kChebyshevMinShearDeg)));
        }
        auto way = [&](const std::vector<Vec2>& g, std::size_t k, bool forwards) {
          std::vector<Vec2> pts{x};
          if (forwards)
            for (std::size_t m = k + 1; m < g.size(); ++m) pts.push_back(g[m]);
          else
            for (std::size_t m = k + 1; m-- > 0;) pts.push_back(g[m]);
          return within_bounds(pts, b);
        };
        const Vec2 widest = widest_steps(face, b);
        // Guide 2 turned so that forwards i then forwards j run counter-clockwise.
        const bool flip = den < 0;
        const Vec2 ra = r.normalized(), rq = (flip ? -1.0 : 1.0) * q.normalized();
        return {GeneratorPath(way(a, i, false), -ra, widest),
                GeneratorPath(way(a, i, true), ra, widest),
                GeneratorPath(way(c, j, flip), -rq, widest),
                GeneratorPath(way(c, j, !flip), rq, widest)};
      }
    }
  }
  throw InvalidParameter("guides: the two guides do not cross on the face's surface");
}

}  // namespace

ChebyshevLattice chebyshev_lattice(const SurfaceFace& face, const ChebyshevNetParams& params,
                                   const std::vector<std::vector<Vec2>>& cuts) {
  if (params.size == 0.0) throw InvalidParameter("size (mm) is required for chebyshev_net");
  require_in_range("size (mm)", params.size, 1e-3, 1e9);
  require_in_range("seed_u", params.seed_u, 0.0, 1.0);
  require_in_range("seed_v", params.seed_v, 0.0, 1.0);
  require_in_range("max_panels", params.clip.max_panels, 1, 1e8);
  const double estimate = face.area() / (params.size * params.size);
  if (estimate > params.clip.max_panels) {
    throw LimitExceeded(
        "the net would have about " + std::to_string(static_cast<long long>(estimate)) +
        " panels, more than max_panels = " + std::to_string(params.clip.max_panels) +
        ": choose a larger size or raise max_panels");
  }
  if (!params.guides.empty() && params.guides.size() != 2)
    throw InvalidParameter("guides: give two crossing guide curves, or none (the iso-lines)");
  const UvBounds b = face.bounds();
  const Vec2 seed(b.u_min + params.seed_u * (b.u_max - b.u_min),
                  b.v_min + params.seed_v * (b.v_max - b.v_min));
  const std::vector<GeneratorPath> paths =
      params.guides.empty() ? iso_paths(face, b, seed)
                            : guide_paths(face, b, params.guides, cuts, params.size);
  // The lattice may hold many cells off the face (a face far from its
  // bounds' rectangle): room for 16 times the panels, and more on small runs.
  const std::size_t max_nodes = 16 * std::size_t(params.clip.max_panels) + 100000;
  for (int margin = 1; margin <= 64; margin *= 2) {
    Lattice L = build_lattice(face, b, paths, params.size, margin, max_nodes);
    if (!covers_bounds(L, b)) continue;
    // Folds: the guesses relaxed, then the net's nodes round the folds
    // freed in widening rings until none is left (at last the whole
    // lattice is a Tutte embedding, which cannot fold).
    std::vector<std::pair<int, int>> folds = folded_cells(L, b);
    for (int ring = 0; !folds.empty(); ring = std::max(ring + 1, 3 * ring / 2)) {
      if (ring > L.nu() + L.nv()) {
        throw InvalidGeometry("the Chebyshev net folds over this face near (u,v) = (" +
                              std::to_string(L.uv[L.at(folds[0].first, folds[0].second)].x()) +
                              ", " +
                              std::to_string(L.uv[L.at(folds[0].first, folds[0].second)].y()) +
                              "); try a smaller size or another seed (seed_u, seed_v)");
      }
      for (const auto& [fi, fj] : folds)
        for (int j = std::max(L.j_lo, fj - ring); j <= std::min(L.j_hi, fj + 1 + ring); ++j)
          for (int i = std::max(L.i_lo, fi - ring); i <= std::min(L.i_hi, fi + 1 + ring); ++i)
            L.on_net[L.at(i, j)] = 0;
      relax_guesses(L, b);
      folds = folded_cells(L, b);
    }
    return {std::move(L.uv), std::move(L.on_net), L.nu(), L.nv()};
  }
  throw InvalidGeometry(
      "the Chebyshev net does not cover this face's (u,v) bounds once (its border folds back "
      "into them): try another seed (seed_u, seed_v) or a smaller size");
}

PanelMesh chebyshev_net(const SurfaceFace& face, const ChebyshevNetParams& params,
                        ChebyshevNetReport* report) {
  const ChebyshevLattice lattice = chebyshev_lattice(face, params);
  if (report) {
    const UvTrimClassifier inside(face.trim_loops(steering_trim_deflection(face)));
    *report = {};
    report->lattice_u = lattice.nu, report->lattice_v = lattice.nv;
    for (std::size_t k = 0; k < lattice.uv.size(); ++k) {
      if (!inside.contains(lattice.uv[k])) continue;
      ++(lattice.on_net[k] ? report->net_nodes : report->extrapolated_nodes);
    }
  }
  return chebyshev_net_on_lattice(face, lattice, params.clip);
}

PanelMesh chebyshev_net_on_lattice(const SurfaceFace& face, const ChebyshevLattice& lattice,
                                   const GridClipParams& clip) {
  // The lattice's cells off the face go in the cut; only the panels count.
  GridClipParams cut = clip;
  cut.max_panels = std::max<int>(clip.max_panels, (lattice.nu - 1) * (lattice.nv - 1));
  PanelMesh mesh = clip_cells(face, lattice.uv, lattice.nu, lattice.nv, cut);
  if (mesh.panels.size() > std::size_t(clip.max_panels)) {
    throw LimitExceeded("the net has " + std::to_string(mesh.panels.size()) +
                        " panels, more than max_panels = " + std::to_string(clip.max_panels) +
                        ": choose a larger size or raise max_panels");
  }
  return mesh;
}

}  // namespace tessella
