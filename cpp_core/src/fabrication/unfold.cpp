#include "tessella/unfold.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <map>
#include <tuple>
#include <utility>

#include "tessella/errors.h"
#include "mesh/panel_model.h"

namespace tessella {

namespace {

constexpr double kPi = 3.14159265358979323846;

using Tri = std::array<int, 3>;

double signed_area(const std::vector<Vec2>& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2& q = p[i];
    const Vec2& r = p[(i + 1) % p.size()];
    a += q.x() * r.y() - r.x() * q.y();
  }
  return 0.5 * a;
}

// Triangles of the panel, each in the cyclic orientation of the panel's corner
// order (so counter-clockwise seen from the panel's front).
std::vector<Tri> panel_triangles(const std::vector<Vec3>& xyz, const std::vector<Vec2>& uv) {
  const int n = static_cast<int>(xyz.size());
  if (n == 3) return {Tri{0, 1, 2}};
  if (n == 4) {
    // The diagonal with the smaller fold.
    const double f02 = std::abs(fold_angle_deg(xyz[0], xyz[2], xyz[3], xyz[1]));
    const double f13 = std::abs(fold_angle_deg(xyz[1], xyz[3], xyz[0], xyz[2]));
    if (f13 < f02) return {Tri{1, 2, 3}, Tri{1, 3, 0}};
    return {Tri{0, 1, 2}, Tri{0, 2, 3}};
  }
  if (signed_area(uv) >= 0) {
    std::vector<Tri> out;
    for (const auto& t : triangulate_polygon(uv)) out.push_back({t[0], t[1], t[2]});
    return out;
  }
  // Clockwise in (u,v) (a reversed face): triangulate the reversed outline,
  // map back and keep the panel's orientation.
  std::vector<Vec2> rev(uv.rbegin(), uv.rend());
  std::vector<Tri> out;
  for (const auto& t : triangulate_polygon(rev))
    out.push_back({n - 1 - t[0], n - 1 - t[2], n - 1 - t[1]});
  return out;
}

// Third corner r of the counter-clockwise triangle (p, q, r) with p, q placed.
Vec2 place_apex(const Vec2& p, const Vec2& q, double d_pr, double d_qr) {
  const double d_pq = (q - p).norm();
  const Vec2 e = (q - p) / d_pq;
  const Vec2 left(-e.y(), e.x());
  const double x = (d_pr * d_pr - d_qr * d_qr + d_pq * d_pq) / (2.0 * d_pq);
  const double h = std::sqrt(std::max(0.0, d_pr * d_pr - x * x));
  return p + x * e + h * left;
}

// Rotates t so that its first two corners are a, b (in either order as given
// by the triangle's own cycle); returns false if the triangle lacks edge a-b.
bool rotate_to_edge(Tri& t, int a, int b) {
  for (int k = 0; k < 3; ++k) {
    if (t[0] == a && t[1] == b) return true;
    std::rotate(t.begin(), t.begin() + 1, t.end());
  }
  return false;
}

double orient(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// True if two non-adjacent edges of the closed polygon cross or touch.
bool crosses_itself(const std::vector<Vec2>& p) {
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 &a = p[i], &b = p[(i + 1) % n];
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing edge
      const Vec2 &c = p[j], &d = p[(j + 1) % n];
      if (std::max(a.x(), b.x()) < std::min(c.x(), d.x()) ||
          std::max(c.x(), d.x()) < std::min(a.x(), b.x()) ||
          std::max(a.y(), b.y()) < std::min(c.y(), d.y()) ||
          std::max(c.y(), d.y()) < std::min(a.y(), b.y()))
        continue;
      const double o1 = orient(a, b, c), o2 = orient(a, b, d);
      const double o3 = orient(c, d, a), o4 = orient(c, d, b);
      if (((o1 > 0) != (o2 > 0) || o1 == 0 || o2 == 0) &&
          ((o3 > 0) != (o4 > 0) || o3 == 0 || o4 == 0))
        return true;
    }
  }
  return false;
}

}  // namespace

double fold_angle_deg(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 n1 = (b - a).cross(c - a);
  const Vec3 n2 = (d - a).cross(b - a);
  const double l1 = n1.norm(), l2 = n2.norm();
  if (l1 == 0.0 || l2 == 0.0) return 0.0;
  const double s = n1.cross(n2).norm() / (l1 * l2);
  const double c_ = n1.dot(n2) / (l1 * l2);
  const double angle = std::atan2(s, c_) * 180.0 / kPi;
  return (d - a).dot(n1) >= 0.0 ? angle : -angle;
}

FlatPanel unfold_panel(const std::vector<Vec3>& xyz, const std::vector<Vec2>& uv,
                       const UnfoldParams& params) {
  if (xyz.size() < 3) throw InvalidGeometry("a panel needs at least three corners");
  return unfold_triangles(xyz, uv, panel_triangles(xyz, uv), params);
}

FlatPanel unfold_triangles(const std::vector<Vec3>& xyz, const std::vector<Vec2>& uv,
                           const std::vector<std::array<int, 3>>& tris,
                           const UnfoldParams& params) {
  require_in_range("fold_tolerance_deg", params.fold_tolerance_deg, 0.0, 180.0);
  const int n = static_cast<int>(xyz.size());
  if (n < 3) throw InvalidGeometry("a panel needs at least three corners");
  if (uv.size() != xyz.size())
    throw InvalidGeometry("panel corners and their (u,v) differ in count");
  for (int i = 0; i < n; ++i)
    if ((xyz[(i + 1) % n] - xyz[i]).norm() == 0.0)
      throw InvalidGeometry("a panel has two coincident corners");

  if (tris.empty()) throw InvalidGeometry("unfold: a panel without triangles");
  auto dist = [&](int i, int j) { return (xyz[i] - xyz[j]).norm(); };

  // Triangles sharing a diagonal, by the diagonal's (min, max) corners.
  std::map<std::pair<int, int>, std::vector<int>> by_edge;
  for (std::size_t t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = tris[t][k], b = tris[t][(k + 1) % 3];
      by_edge[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(t));
    }

  FlatPanel out;
  out.triangles = tris;
  std::vector<Vec2> flat(n, Vec2::Zero());
  std::vector<bool> placed_corner(n, false), placed_tri(tris.size(), false);
  {
    const Tri& t = tris[0];
    flat[t[0]] = Vec2(0, 0);
    flat[t[1]] = Vec2(dist(t[0], t[1]), 0);
    flat[t[2]] = place_apex(flat[t[0]], flat[t[1]], dist(t[0], t[2]), dist(t[1], t[2]));
    for (int c : t) placed_corner[c] = true;
    placed_tri[0] = true;
  }
  // Breadth-first across shared diagonals: the triangles of a polygon
  // triangulation form a tree, so every triangle is placed exactly once.
  std::deque<int> queue{0};
  while (!queue.empty()) {
    const int t = queue.front();
    queue.pop_front();
    for (int k = 0; k < 3; ++k) {
      const int a = tris[t][k], b = tris[t][(k + 1) % 3];
      for (int s : by_edge[{std::min(a, b), std::max(a, b)}]) {
        if (placed_tri[s]) continue;
        Tri other = tris[s];
        if (!rotate_to_edge(other, b, a)) continue;  // opposite orientation: not a mesh neighbour
        const int r = other[2];
        flat[r] = place_apex(flat[b], flat[a], dist(b, r), dist(a, r));
        placed_corner[r] = true;
        placed_tri[s] = true;
        queue.push_back(s);
        // The fold along a-b: triangle t = (a, b, c), neighbour (b, a, r).
        const int c = tris[t][(k + 2) % 3];
        const double angle = fold_angle_deg(xyz[a], xyz[b], xyz[c], xyz[r]);
        out.max_fold_deg = std::max(out.max_fold_deg, std::abs(angle));
        if (std::abs(angle) > params.fold_tolerance_deg)
          out.folds.push_back({std::min(a, b), std::max(a, b), angle});
      }
    }
  }
  for (int i = 0; i < n; ++i)
    if (!placed_corner[i]) throw GeometryFailure("unfold: a panel corner is in no triangle");

  // Corner 0 at the origin, edge 0->1 along +x.
  const Vec2 e = (flat[1] - flat[0]).normalized();
  const Vec2 origin = flat[0];
  out.outline.resize(n);
  for (int i = 0; i < n; ++i) {
    const Vec2 d = flat[i] - origin;
    out.outline[i] = Vec2(d.dot(e), -e.y() * d.x() + e.x() * d.y());
  }
  out.self_intersecting = n > 3 && crosses_itself(out.outline);
  std::sort(out.folds.begin(), out.folds.end(),
            [](const Fold& x, const Fold& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });

  // Orientation mark: flat = A (u,v) + t by least squares; u maps along A's first column.
  Eigen::MatrixXd m(n, 3), rhs(n, 2);
  for (int i = 0; i < n; ++i) {
    m.row(i) << uv[i].x(), uv[i].y(), 1.0;
    rhs.row(i) << out.outline[i].x(), out.outline[i].y();
  }
  const Eigen::MatrixXd x = m.colPivHouseholderQr().solve(rhs);
  const Vec2 du(x(0, 0), x(0, 1));
  if (du.allFinite() && du.norm() > 0.0) out.u_direction = du.normalized();
  return out;
}

std::vector<FlatPanel> unfold_panels(const PanelMesh& mesh, const UnfoldParams& params) {
  require_in_range("fold_tolerance_deg", params.fold_tolerance_deg, 0.0, 180.0);
  std::vector<FlatPanel> out;
  out.reserve(mesh.panels.size());
  for (std::size_t p = 0; p < mesh.panels.size(); ++p) {
    std::vector<Vec3> xyz;
    for (int v : mesh.panels[p]) xyz.push_back(mesh.xyz[v]);
    const std::vector<Vec2> uv = panel_corner_uv(mesh, p);
    // A panel modelled as flat pieces unfolds by its pieces' triangles: only
    // its bend lines can fold. Others as unfold_panel does.
    if (modelled_as_pieces(mesh, p))
      out.push_back(unfold_triangles(xyz, uv, panel_model_triangles(mesh, p), params));
    else
      out.push_back(unfold_panel(xyz, uv, params));
  }
  return out;
}

}  // namespace tessella
