#include "tessella/panel_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <unordered_map>

#include "tessella/surface_face.h"

namespace tessella {

void build_rods(PanelMesh& mesh) {
  std::vector<std::array<int, 2>> rods;
  std::vector<int> nodes;
  for (const auto& panel : mesh.panels) {
    nodes.clear();
    for (int v : panel)
      if (is_node(mesh, v)) nodes.push_back(v);
    if (nodes.size() < 2) continue;
    for (std::size_t k = 0; k < nodes.size(); ++k) {
      const int a = nodes[k], b = nodes[(k + 1) % nodes.size()];
      if (a != b) rods.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(rods.begin(), rods.end());
  rods.erase(std::unique(rods.begin(), rods.end()), rods.end());
  mesh.rods = std::move(rods);
}

NodeData node_data(const SurfaceFace& face, const PanelMesh& mesh) {
  NodeData nodes;
  nodes.valence.assign(mesh.vertex_count(), 0);
  for (const auto& rod : mesh.rods) {
    ++nodes.valence[rod[0]];
    ++nodes.valence[rod[1]];
  }
  nodes.normal.reserve(mesh.vertex_count());
  for (const Vec2& q : mesh.uv) nodes.normal.push_back(face.normal(q.x(), q.y()));
  return nodes;
}

void remove_unused_vertices(PanelMesh& mesh) {
  std::vector<int> new_index(mesh.vertex_count(), -1);
  for (const auto& panel : mesh.panels)
    for (int v : panel) new_index[v] = 0;
  int next = 0;
  for (std::size_t v = 0; v < new_index.size(); ++v) {
    if (new_index[v] < 0) continue;
    new_index[v] = next;
    mesh.uv[next] = mesh.uv[v];
    mesh.xyz[next] = mesh.xyz[v];
    if (!mesh.is_node.empty()) mesh.is_node[next] = mesh.is_node[v];
    ++next;
  }
  mesh.uv.resize(next);
  mesh.xyz.resize(next);
  if (!mesh.is_node.empty()) mesh.is_node.resize(next);
  for (auto& panel : mesh.panels)
    for (int& v : panel) v = new_index[v];
  for (auto& rod : mesh.rods) rod = {new_index[rod[0]], new_index[rod[1]]};
  for (auto& fold : mesh.folds) {
    fold = {new_index[fold[0]], new_index[fold[1]]};
    if (fold[0] > fold[1]) std::swap(fold[0], fold[1]);
  }
}

void weld_coincident_vertices(PanelMesh& mesh, double tolerance, const std::vector<char>& only) {
  // Bucket by a grid of cell `tolerance`; compare with the 27 neighbours,
  // each bucket's vertices in the order they were kept: a vertex goes onto
  // the first kept one within the tolerance. The buckets are lists threaded
  // through one array in an open-addressing table (a map of vectors
  // allocated one vector per vertex: 3.6 ms of the dome's 83).
  const std::size_t n = mesh.vertex_count();
  struct Cell {
    long long x = 0, y = 0, z = 0;
    int head = -1, tail = -1;  // first and last kept vertex, -1: empty slot
  };
  std::size_t slots = 16;
  while (slots < 2 * n + 16) slots *= 2;
  std::vector<Cell> table(slots);
  std::vector<int> next(n, -1);
  auto slot_of = [&](long long x, long long y, long long z) {
    std::uint64_t h = static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ULL ^
                      static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4FULL ^
                      static_cast<std::uint64_t>(z) * 0x165667B19E3779F9ULL;
    h ^= h >> 29;
    std::size_t k = static_cast<std::size_t>(h) & (slots - 1);
    while (table[k].head >= 0 && !(table[k].x == x && table[k].y == y && table[k].z == z))
      k = (k + 1) & (slots - 1);
    return k;
  };
  auto cell = [&](double c) { return std::llround(std::floor(c / tolerance)); };
  std::vector<int> target(n);
  for (std::size_t v = 0; v < n; ++v) {
    target[v] = int(v);
    if (!only.empty() && !only[v]) continue;
    const Vec3& p = mesh.xyz[v];
    const long long kx = cell(p.x()), ky = cell(p.y()), kz = cell(p.z());
    bool found = false;
    for (long long dx = -1; dx <= 1 && !found; ++dx)
      for (long long dy = -1; dy <= 1 && !found; ++dy)
        for (long long dz = -1; dz <= 1 && !found; ++dz) {
          const Cell& c = table[slot_of(kx + dx, ky + dy, kz + dz)];
          for (int w = c.head; w >= 0; w = next[static_cast<std::size_t>(w)]) {
            if ((mesh.xyz[static_cast<std::size_t>(w)] - p).norm() <= tolerance) {
              target[v] = w;
              found = true;
              break;
            }
          }
        }
    if (found) continue;
    Cell& c = table[slot_of(kx, ky, kz)];
    if (c.head < 0) {
      c.x = kx, c.y = ky, c.z = kz, c.head = int(v);
    } else {
      next[static_cast<std::size_t>(c.tail)] = int(v);
    }
    c.tail = int(v);
  }
  if (!mesh.is_node.empty()) {
    for (std::size_t v = 0; v < target.size(); ++v)
      if (mesh.is_node[v]) mesh.is_node[target[v]] = 1;
  }
  std::vector<std::vector<int>> kept;
  std::vector<std::vector<Vec2>> kept_uv;
  for (std::size_t p = 0; p < mesh.panels.size(); ++p) {
    const std::vector<Vec2> before = panel_corner_uv(mesh, p);
    std::vector<int> ids;
    std::vector<Vec2> uv;
    for (std::size_t k = 0; k < mesh.panels[p].size(); ++k) {
      const int t = target[mesh.panels[p][k]];
      if (!ids.empty() && ids.back() == t) continue;
      ids.push_back(t);
      uv.push_back(before[k]);
    }
    while (ids.size() > 1 && ids.front() == ids.back()) ids.pop_back(), uv.pop_back();
    if (ids.size() < 3) continue;
    kept.push_back(std::move(ids));
    kept_uv.push_back(std::move(uv));
  }
  mesh.panels = std::move(kept);
  mesh.corner_uv = std::move(kept_uv);
}

std::vector<Vec2> panel_corner_uv(const PanelMesh& mesh, std::size_t p) {
  if (p < mesh.corner_uv.size()) return mesh.corner_uv[p];
  std::vector<Vec2> uv;
  for (int v : mesh.panels[p]) uv.push_back(mesh.uv[v]);
  return uv;
}

void reverse_panels(PanelMesh& mesh) {
  for (auto& panel : mesh.panels) std::reverse(panel.begin(), panel.end());
  for (auto& uv : mesh.corner_uv) std::reverse(uv.begin(), uv.end());
}

}  // namespace tessella
