// weld_coincident_vertices (tessella/panel_mesh.h) against the rule it
// implements, written the plain way: each vertex in index order goes onto
// the first kept vertex within the tolerance, the 27 neighbouring cells of
// a grid of cell `tolerance` looked at in (dx, dy, dz) order, each cell's
// kept vertices in the order they were kept.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <tuple>
#include <vector>

#include "tessella/panel_mesh.h"

using namespace tessella;

namespace {

std::vector<int> targets_by_the_rule(const std::vector<Vec3>& xyz, double tolerance) {
  std::map<std::tuple<long long, long long, long long>, std::vector<int>> cells;
  auto cell = [&](double c) { return std::llround(std::floor(c / tolerance)); };
  std::vector<int> target(xyz.size());
  for (std::size_t v = 0; v < xyz.size(); ++v) {
    target[v] = int(v);
    const long long x = cell(xyz[v].x()), y = cell(xyz[v].y()), z = cell(xyz[v].z());
    bool found = false;
    for (long long dx = -1; dx <= 1 && !found; ++dx)
      for (long long dy = -1; dy <= 1 && !found; ++dy)
        for (long long dz = -1; dz <= 1 && !found; ++dz) {
          const auto it = cells.find({x + dx, y + dy, z + dz});
          if (it == cells.end()) continue;
          for (int w : it->second)
            if ((xyz[std::size_t(w)] - xyz[v]).norm() <= tolerance) {
              target[v] = w;
              found = true;
              break;
            }
        }
    if (!found) cells[{x, y, z}].push_back(int(v));
  }
  return target;
}

}  // namespace

TEST(WeldCoincidentVertices, FollowsTheRuleOnClustersAcrossCellBorders) {
  // Clusters of points within 0.4-1.6 tolerances of a centre (some weld,
  // some do not; several candidates at once), centres on cell borders too;
  // triangles over consecutive points.
  const double tol = 1e-3;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.8 * tol, 0.8 * tol);
  std::uniform_int_distribution<int> grid(0, 40);
  PanelMesh mesh;
  for (int c = 0; c < 600; ++c) {
    const Vec3 centre(grid(rng) * tol * 0.5, grid(rng) * tol * 0.5, grid(rng) * tol);
    for (int k = 0; k < 5; ++k) {
      mesh.xyz.push_back(centre + Vec3(jitter(rng), jitter(rng), jitter(rng)));
      mesh.uv.push_back(Vec2(double(mesh.uv.size()), 0.0));
    }
  }
  for (std::size_t v = 0; v + 2 < mesh.xyz.size(); v += 3)
    mesh.panels.push_back({int(v), int(v + 1), int(v + 2)});
  const std::vector<int> target = targets_by_the_rule(mesh.xyz, tol);
  int moved = 0;
  for (std::size_t v = 0; v < target.size(); ++v) moved += target[v] != int(v) ? 1 : 0;
  ASSERT_GT(moved, 500);  // the case is one of many welds

  // The panels the rule gives: corners renamed, repeats and panels under
  // three corners dropped.
  std::vector<std::vector<int>> expected;
  for (const auto& p : mesh.panels) {
    std::vector<int> ids;
    for (int v : p) {
      const int t = target[std::size_t(v)];
      if (ids.empty() || ids.back() != t) ids.push_back(t);
    }
    while (ids.size() > 1 && ids.front() == ids.back()) ids.pop_back();
    if (ids.size() >= 3) expected.push_back(ids);
  }
  PanelMesh welded = mesh;
  weld_coincident_vertices(welded, tol);
  EXPECT_EQ(welded.panels, expected);
  ASSERT_EQ(welded.corner_uv.size(), welded.panels.size());
}
