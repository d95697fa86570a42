#include "mesh/fixed_vertices.h"

#include <algorithm>
#include <array>

namespace tessella {

MeshBoundary mesh_boundary(const PanelMesh& mesh) {
  const std::size_t nv = mesh.vertex_count();
  MeshBoundary out{std::vector<std::vector<int>>(nv), std::vector<char>(nv, 0)};
  std::vector<std::array<int, 2>> sides;
  for (const auto& p : mesh.panels) {
    bool piece = false;
    for (int v : p) piece = piece || !is_node(mesh, v);
    for (std::size_t i = 0; i < p.size(); ++i) {
      const int a = p[i], b = p[(i + 1) % p.size()];
      sides.push_back({std::min(a, b), std::max(a, b)});
      if (piece) out.in_piece[static_cast<std::size_t>(a)] = 1;
    }
  }
  // A side of one panel is on the boundary.
  std::sort(sides.begin(), sides.end());
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j] == sides[i]) ++j;
    if (j - i == 1) {
      out.along[static_cast<std::size_t>(sides[i][0])].push_back(sides[i][1]);
      out.along[static_cast<std::size_t>(sides[i][1])].push_back(sides[i][0]);
    }
    i = j;
  }
  return out;
}

std::vector<char> fixed_vertices(const PanelMesh& mesh) {
  const MeshBoundary b = mesh_boundary(mesh);
  std::vector<char> fixed(mesh.vertex_count(), 0);
  for (std::size_t v = 0; v < fixed.size(); ++v)
    fixed[v] = b.in_piece[v] || !b.along[v].empty() ? 1 : 0;
  return fixed;
}

}  // namespace tessella
