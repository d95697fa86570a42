// Cuts a tensor grid of (u,v) lines by the trimmed face: full cells stay quads,
// boundary cells become polygons that follow the trim loops; holes stay open.
#pragma once

#include <vector>

#include "mesh/sliver_merge.h"
#include "tessella/grid_methods.h"
#include "tessella/panel_mesh.h"

namespace tessella {

class SurfaceFace;

// u_lines and v_lines: strictly increasing, covering the face's uv bounds.
PanelMesh clip_grid(const SurfaceFace& face, const std::vector<double>& u_lines,
                    const std::vector<double>& v_lines, const GridClipParams& params);

// Points of the trim polylines clip_grid cuts with (same deflection) where the
// trim turns in (u,v) away from a B-rep corner. Any clipped grid whose lines
// miss such a point keeps it as a vertex of one boundary panel only, a vertex
// that is no node: a caller that wants only node-cornered panels (the walking
// agent's iso fallback) rejects such a grid without cutting it.
std::vector<Vec2> trim_turning_points(const SurfaceFace& face, const GridClipParams& params);

}  // namespace tessella
