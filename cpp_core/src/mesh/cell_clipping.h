// Cuts a structured grid of general quad cells (relaxed_grid's relaxed layout:
// a nu x nv lattice of (u,v) nodes whose cells are not axis-aligned) by the
// trimmed face: cells wholly inside stay quads, cells crossing a trim become
// polygons that follow the trim loops, cells outside go, and a cell holding a
// whole opening is split so that every panel is a simple polygon.
//
// The cells must not overlap; where their union covers the face's (u,v)
// region (relaxed_grid: the whole bounds rectangle), the panels tile the face.
// A node within a thousandth of its shortest cell edge of a trim goes onto
// the trim first (rows laid along a face set's cuts meet them node to node,
// not in knife-edge slivers).
#pragma once

#include <vector>

#include "tessella/grid_methods.h"
#include "tessella/panel_mesh.h"
#include "tessella/vec.h"

namespace tessella {

class SurfaceFace;

// nodes: nu x nv (u,v) points, row by row (node (i,j) at j * nu + i), i along
// u and j along v, so cell (i,j) = nodes (i,j), (i+1,j), (i+1,j+1), (i,j+1)
// is counter-clockwise. Vertices: the nodes kept, the trim polyline points
// (outline points, not nodes, except the trim corners) and the crossings of
// cell edges with the trims (nodes, on the true trim curves); neighbouring
// panels share every vertex along their common edge (no T-junctions).
PanelMesh clip_cells(const SurfaceFace& face, const std::vector<Vec2>& nodes, int nu, int nv,
                     const GridClipParams& params);

}  // namespace tessella
