// The panel a workshop builds, as every measurement and export models it:
// triangle -> flat triangle; quad of four nodes -> bilinear patch of its corners
// (unless it is dented: then flat pieces, as below);
// any other panel (a boundary panel whose outline follows a trim, a polygon of
// more than four nodes) -> flat pieces: its outline cut along its bend lines
// (PanelMesh::bends), each piece flat (mesh/boundary_pieces.h puts the outline
// points on the piece planes) and triangulated on its plane.
#pragma once

#include <array>
#include <vector>

#include "tessella/panel_mesh.h"
#include "tessella/vec.h"

namespace tessella {

// Triangles (corner indices) covering a simple polygon given by its (u,v)
// corners, n-2 for n corners, each turning the same way as the outline
// (counter-clockwise outline: counter-clockwise triangles; clockwise: clockwise).
std::vector<std::array<int, 3>> triangulate_polygon(const std::vector<Vec2>& uv);

// Whether panel k is modelled as flat pieces (see above) rather than as a flat
// triangle or a bilinear quad of four nodes.
bool modelled_as_pieces(const PanelMesh& mesh, std::size_t k);

// The bend lines of panel k (empty if none).
const std::vector<std::array<int, 2>>& panel_bends(const PanelMesh& mesh, std::size_t k);

// The outline of a polygon cut along non-crossing diagonals (corner pairs):
// the corner lists of the pieces, each in the outline's own order.
std::vector<std::vector<int>> split_polygon(int corners,
                                            const std::vector<std::array<int, 2>>& diagonals);

// Triangles of a polygon of pieces cut along `bends`, each piece triangulated
// on its own plane if it is flat, else on its (u,v) outline, so that no
// triangle spans a bend (corner indices, turning like the corner order).
std::vector<std::array<int, 3>> triangulate_pieces(const std::vector<Vec3>& xyz,
                                                   const std::vector<Vec2>& uv,
                                                   const std::vector<std::array<int, 2>>& bends);

// The flat triangles panel k is built of (corner indices, the panel's
// orientation); empty for a quad of four nodes (its bilinear patch).
std::vector<std::array<int, 3>> panel_model_triangles(const PanelMesh& mesh, std::size_t k);

// Area of the panel model: bilinear for quads, triangulated otherwise.
double panel_model_area(const std::vector<Vec3>& xyz, const std::vector<Vec2>& uv);
// The same for panel p of a mesh.
double panel_area(const PanelMesh& mesh, std::size_t p);

}  // namespace tessella
