// The vertices a step that moves nodes after the fact (family regularization,
// planarization) keeps where they are: those on the mesh's boundary (a side
// of one panel: on a trim) and every vertex of a boundary piece (a panel with
// trim points, modelled on its trim).
#pragma once

#include <vector>

#include "tessella/panel_mesh.h"

namespace tessella {

// Where the mesh's boundary runs: per vertex, its neighbours along the
// boundary (the other ends of its sides used by one panel) and whether it is
// a vertex of a boundary piece.
struct MeshBoundary {
  std::vector<std::vector<int>> along;
  std::vector<char> in_piece;
};
MeshBoundary mesh_boundary(const PanelMesh& mesh);

std::vector<char> fixed_vertices(const PanelMesh& mesh);

}  // namespace tessella
