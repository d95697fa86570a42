#include "tessella/panel_model.h"

#include <cmath>
#include <numeric>

namespace tessella {

namespace {

double cross2(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

bool inside_triangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  return cross2(a, b, p) >= 0 && cross2(b, c, p) >= 0 && cross2(c, a, p) >= 0;
}

// Area of the bilinear patch by 4x4 Gauss-Legendre quadrature.
double bilinear_area(const std::vector<Vec3>& p) {
  static const double x[4] = {0.0694318442029737, 0.3300094782075719, 0.6699905217924281,
                              0.9305681557970263};
  static const double w[4] = {0.1739274225687269, 0.3260725774312731, 0.3260725774312731,
                              0.1739274225687269};
  double area = 0;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const double s = x[i], t = x[j];
      const Vec3 ds = (1 - t) * (p[1] - p[0]) + t * (p[2] - p[3]);
      const Vec3 dt = (1 - s) * (p[3] - p[0]) + s * (p[2] - p[1]);
      area += w[i] * w[j] * ds.cross(dt).norm();
    }
  }
  return area;
}

}  // namespace

std::vector<std::array<int, 3>> triangulate_polygon(const std::vector<Vec2>& uv) {
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> ring(uv.size());
  std::iota(ring.begin(), ring.end(), 0);
  // Ear clipping; the first convex corner whose triangle holds no other corner
  // is cut. If rounding leaves no clean ear, the most convex corner is cut so
  // the result always has n-2 triangles.
  while (ring.size() > 3) {
    const std::size_t n = ring.size();
    std::size_t ear = n, best = 0;
    double best_turn = -INFINITY;
    for (std::size_t k = 0; k < n && ear == n; ++k) {
      const Vec2& a = uv[ring[(k + n - 1) % n]];
      const Vec2& b = uv[ring[k]];
      const Vec2& c = uv[ring[(k + 1) % n]];
      const double turn = cross2(a, b, c);
      if (turn > best_turn) best_turn = turn, best = k;
      if (turn <= 0) continue;
      bool empty = true;
      for (std::size_t m = 0; m < n && empty; ++m) {
        const int q = ring[m];
        if (q == ring[(k + n - 1) % n] || q == ring[k] || q == ring[(k + 1) % n]) continue;
        if (uv[q] == a || uv[q] == b || uv[q] == c) continue;
        if (inside_triangle(uv[q], a, b, c)) empty = false;
      }
      if (empty) ear = k;
    }
    if (ear == n) ear = best;
    triangles.push_back({ring[(ear + n - 1) % n], ring[ear], ring[(ear + 1) % n]});
    ring.erase(ring.begin() + static_cast<long>(ear));
  }
  if (ring.size() == 3) triangles.push_back({ring[0], ring[1], ring[2]});
  return triangles;
}

double panel_model_area(const std::vector<Vec3>& xyz, const std::vector<Vec2>& uv) {
  if (xyz.size() == 4) return bilinear_area(xyz);
  double area = 0;
  for (const auto& t : triangulate_polygon(uv)) {
    area += 0.5 * (xyz[t[1]] - xyz[t[0]]).cross(xyz[t[2]] - xyz[t[0]]).norm();
  }
  return area;
}

double panel_area(const PanelMesh& mesh, std::size_t p) {
  std::vector<Vec3> xyz;
  for (int v : mesh.panels[p]) xyz.push_back(mesh.xyz[v]);
  return panel_model_area(xyz, panel_corner_uv(mesh, p));
}

}  // namespace tessella
