// Boundary-driven meshing, stage 1 (seed 001 section 2, "feature selection"):
// the curves the direction field is interpolated from. By default every trim
// loop of the face (outer and inner wires); or a chosen subset of loops; plus
// extra curves lying on the surface, given as (u,v) polylines (paper Figure 20).
#pragma once

#include <vector>

#include "tessella/boundary_driven.h"
#include "tessella/surface_face.h"
#include "tessella/vec.h"

namespace tessella {

struct BdSources {
  std::vector<BdPolyline> boundary;  // every trim loop (for clipping and nodes)
  std::vector<BdPolyline> sources;   // the selected ones (+ extra curves)
};

// `loops` = face.trim_loops(deflection). Throws InvalidParameter for a loop index
// out of range or an unusable extra curve, InvalidGeometry for a face with a
// degenerate (zero-length) trim loop.
// Each loop starts where its geometry says, not where the B-rep lists its
// wire: at its B-rep vertex of least (u, v), or (start_shift k > 0) at the
// k-th in that order (a loop without vertices: a third of the way round
// per step), for a second try of a layout that failed.
BdSources select_bd_sources(const SurfaceFace& face, const std::vector<TrimLoop>& loops,
                            const BdSourceParams& params, int start_shift = 0);

}  // namespace tessella

namespace tessella {

// Arc lengths of the corners of a polyline: vertices where the 3D direction
// turns by more than `angle_deg` (sorted). Open polylines: the end points too.
std::vector<double> bd_corners(const BdPolyline& line, double angle_deg);

// Unit 3D tangent (chord direction) and (u,v) direction of the segment holding s.
void bd_tangent_at(const BdPolyline& line, double s, Vec3& tangent3, Vec2& tangent_uv);

}  // namespace tessella
