// Boundary-driven meshing across faces (issue 14): the curves traced once on a
// surface that several faces of a set lie on, cut to one of those faces.
//
// Faces split from one surface (seed 004's roof in four sub-surfaces, a
// façade cut into fabrication zones) share its (u,v). Tracing on their union
// lets the curves run on across the edges between them, as if the faces were
// one; each face then builds its network from the pieces of the curves inside
// it and its own trims, so the shared edges become lines of nodes where the
// curves cross them (the same crossing, at the same (u,v), on both sides).
#pragma once

#include <vector>

#include "methods/boundary_driven/bd_curves.h"
#include "tessella/boundary_driven.h"
#include "tessella/panel_mesh.h"

namespace tessella {

// The pieces of `curves` (in the (u,v) of `face`'s surface) inside `face`,
// whose trim polylines are `boundary` (select_bd_sources' boundary). A piece
// ends where its curve crosses a trim loop (that loop and arc length), or at
// its curve's own end: on the trim of the union (found on `boundary` within
// `on_trim` in (u,v)) or inside (a dangling end, loop -1). Pieces shorter
// than `on_trim` in (u,v) are dropped (a curve grazing a trim).
std::vector<BdCurve> clip_bd_curves(const SurfaceFace& face, const std::vector<BdCurve>& curves,
                                    const std::vector<BdPolyline>& boundary, double on_trim);

// The curves of boundary_driven traced on `union_face` (the faces' union on
// their one surface), with the spacing they were traced at and the union's
// trim polylines.
struct BdSurfaceCurves {
  std::vector<BdCurve> curves;
  std::vector<BdPolyline> boundary;
  double spacing = 0;
  double on_trim = 0;  // (u,v) distance under which a point lies on the union's trim
};
BdSurfaceCurves trace_bd_surface_curves(const SurfaceFace& union_face,
                                        const BoundaryDrivenParams& params);

// boundary_driven on `member` (a face on the same surface, inside the union)
// from the pieces of `traced`'s curves inside it: its network, refinement and
// panels as for one face. Nodes on its trim where it is not the union's (the
// edges it shares with the other faces) stay where the curves cross it.
PanelMesh boundary_driven_on_curves(const SurfaceFace& member, const BoundaryDrivenParams& params,
                                    const BdSurfaceCurves& traced);

}  // namespace tessella
