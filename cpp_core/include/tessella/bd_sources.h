// Boundary-driven meshing, stage 1 (seed 001 section 2, "feature selection"):
// the curves the direction field is interpolated from. By default every trim
// loop of the face (outer and inner wires); or a chosen subset of loops; plus
// extra curves lying on the surface, given as (u,v) polylines (paper Figure 20).
#pragma once

#include <vector>

#include "tessella/surface_face.h"
#include "tessella/vec.h"

namespace tessella {

// A polyline on the surface with its 3D arc length, parameterized by that
// length s (mm). Closed polylines do not repeat their first point.
struct BdPolyline {
  std::vector<Vec2> uv;
  std::vector<Vec3> xyz;
  std::vector<double> arc;  // cumulative 3D length at each vertex (+ closing one)
  bool closed = false;
  int loop = -1;  // index of the trim loop it came from, -1 for an extra curve
  bool outer = false;

  double length() const { return arc.empty() ? 0.0 : arc.back(); }
  int segment_count() const { return static_cast<int>(arc.size()) - 1; }
  // Segment i runs from vertex i to vertex (i + 1) % n.
  const Vec2& seg_end_uv(int i) const { return uv[(i + 1) % uv.size()]; }
  // (u,v) at arc length s (wrapped when closed, clamped otherwise).
  Vec2 uv_at(double s) const;
  // Arc length of the point at fraction t of segment i.
  double s_at(int i, double t) const { return arc[i] + t * (arc[i + 1] - arc[i]); }
  // Segment holding arc length s (wrapped / clamped like uv_at) and s itself.
  int segment_at(double& s) const;
};

// Builds the arc lengths of a polyline (uv and xyz must be filled).
void finish_polyline(BdPolyline& line);

struct BdSourceParams {
  // Indices into the face's trim loops (SurfaceFace::trim_loops order) to use
  // as sources; empty = all loops.
  std::vector<int> loops;
  // Extra source curves on the surface as (u,v) polylines (open, >= 2 points,
  // every point inside the face).
  std::vector<std::vector<Vec2>> extra_curves;
};

struct BdSources {
  std::vector<BdPolyline> boundary;  // every trim loop (for clipping and nodes)
  std::vector<BdPolyline> sources;   // the selected ones (+ extra curves)
};

// `loops` = face.trim_loops(deflection). Throws InvalidParameter for a loop index
// out of range or an unusable extra curve, InvalidGeometry for a face with a
// degenerate (zero-length) trim loop.
BdSources select_bd_sources(const SurfaceFace& face, const std::vector<TrimLoop>& loops,
                            const BdSourceParams& params);

}  // namespace tessella

namespace tessella {

// Arc lengths of the corners of a polyline: vertices where the 3D direction
// turns by more than `angle_deg` (sorted). Open polylines: the end points too.
std::vector<double> bd_corners(const BdPolyline& line, double angle_deg);

// Unit 3D tangent (chord direction) and (u,v) direction of the segment holding s.
void bd_tangent_at(const BdPolyline& line, double s, Vec3& tangent3, Vec2& tangent_uv);

}  // namespace tessella
