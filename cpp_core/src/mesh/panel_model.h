// The panel a workshop builds, as every measurement and export models it:
// triangle -> flat triangle; quad -> bilinear patch of its corners;
// n-gon -> flat triangles of an ear-clipping triangulation of its (u,v) outline
// (valid for non-convex boundary panels, unlike a fan).
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

// Area of the panel model: bilinear for quads, triangulated otherwise.
double panel_model_area(const std::vector<Vec3>& xyz, const std::vector<Vec2>& uv);
// The same for panel p of a mesh.
double panel_area(const PanelMesh& mesh, std::size_t p);

}  // namespace tessella
