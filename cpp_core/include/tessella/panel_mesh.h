// PanelMesh: the panelization result shared by every method - vertices in uv
// and 3D, polygon panels, unique edges (the rods) and nodes.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "tessella/vec.h"

namespace tessella {

class SurfaceFace;

// The default cap on the panel count of every method (one place: a larger
// request is refused with a clear message instead of exhausting memory).
constexpr int kDefaultMaxPanels = 200000;

struct PanelMesh {
  std::vector<Vec2> uv;
  std::vector<Vec3> xyz;
  // Vertex indices, counter-clockwise seen from the face normal.
  std::vector<std::vector<int>> panels;
  // Which vertices are nodes (rod ends): grid nodes, grid/trim crossings and
  // trim corners. Other vertices are outline points where a boundary panel
  // follows a curved trim; a rod runs straight from node to node past them.
  // Empty: every vertex is a node.
  std::vector<char> is_node;
  // Unique undirected rods (a < b, vertex indices), sorted; filled by
  // build_rods(): consecutive nodes along each panel's outline.
  std::vector<std::array<int, 2>> rods;
  // (u,v) of each panel corner as seen from that panel, parallel to `panels`.
  // Differs from uv[vertex] only where welding merged vertices (a periodic
  // seam, a pole); empty until weld_coincident_vertices() fills it.
  std::vector<std::vector<Vec2>> corner_uv;

  // Folds: quads a method split into two flat triangles along a diagonal
  // (vertex pair, a < b). The fold angle follows from the two triangles.
  std::vector<std::array<int, 2>> folds;

  // Bend lines of the panels modelled as flat pieces (see mesh/panel_model.h):
  // per panel, node-to-node diagonals (panel-local corner indices, a < b) along
  // which the sheet is bent. Parallel to `panels` once the boundary-piece stage
  // ran (empty lists for unbent panels); empty before.
  std::vector<std::vector<std::array<int, 2>>> bends;

  // What the method reports about its own run.
  int merged_slivers = 0;     // slivers merged into a neighbour
  int merged_spikes = 0;      // panels with a knife-edge corner merged (mesh/sliver_merge.h)
  double nominal_area = 0.0;  // area of a full panel (mm^2), for irregularity
  int regular_corners = 4;    // corners of a regular panel (3 in a triangular layout)

  std::size_t vertex_count() const { return xyz.size(); }
};

// Recomputes mesh.rods from mesh.panels and mesh.is_node.
void build_rods(PanelMesh& mesh);

// Whether vertex v is a node (see PanelMesh::is_node).
inline bool is_node(const PanelMesh& mesh, int v) {
  return mesh.is_node.empty() || mesh.is_node[static_cast<std::size_t>(v)];
}

// Per-node data: how many rods meet there, and the face normal.
struct NodeData {
  std::vector<int> valence;
  std::vector<Vec3> normal;
};
NodeData node_data(const SurfaceFace& face, const PanelMesh& mesh);

// Removes vertices no panel uses and renumbers panels (keeps order otherwise).
void remove_unused_vertices(PanelMesh& mesh);

// Merges vertices closer than `tolerance` in 3D (a periodic seam, a pole), then
// drops repeated corners and panels left with fewer than three. Fills
// mesh.corner_uv from the (u,v) the corners had before welding. With `only`
// (a flag per vertex), only flagged vertices are merged.
void weld_coincident_vertices(PanelMesh& mesh, double tolerance,
                              const std::vector<char>& only = {});

// Corner (u,v)s of panel p (mesh.corner_uv if filled, else the vertices' uv).
std::vector<Vec2> panel_corner_uv(const PanelMesh& mesh, std::size_t p);

// Reverses every panel's corner order (and corner_uv with it).
void reverse_panels(PanelMesh& mesh);

}  // namespace tessella
