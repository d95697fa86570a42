// Boundary-driven quad-dominant meshing of a trimmed face (seed 001, Wang,
// Krishnamurti, Shimada 2014): the stages of bd_sources.h, bd_tensor.h,
// bd_curves.h, bd_network.h and bd_refine.h in a row.
#pragma once

#include <array>
#include <vector>

#include "tessella/methods.h"
#include "tessella/panel_mesh.h"
#include "tessella/surface_face.h"
#include "tessella/vec.h"

namespace tessella {

// The data the stages pass on (their functions are private, next to their
// sources in src/methods/boundary_driven/).

// A polyline on the surface with its 3D arc length, parameterized by that
// length s (mm). Closed polylines do not repeat their first point.
struct BdPolyline {
  std::vector<Vec2> uv;
  std::vector<Vec3> xyz;
  // Cumulative 3D length at each vertex (+ closing one); a collapsed segment
  // along (u,v) (a pole) gets a tiny length so that arc stays increasing.
  std::vector<double> arc;
  // 1 where the point is a vertex of the B-rep wire (TrimLoop::corner); empty
  // for a polyline that is no trim loop.
  std::vector<char> corner;
  bool closed = false;
  int loop = -1;  // index of the trim loop it came from, -1 for an extra curve
  bool outer = false;

  double length() const { return arc.empty() ? 0.0 : arc.back(); }
  int segment_count() const { return static_cast<int>(arc.size()) - 1; }
  // Segment i runs from vertex i to vertex (i + 1) % n.
  const Vec2& seg_end_uv(int i) const { return uv[(i + 1) % uv.size()]; }
  bool is_corner(std::size_t i) const { return i < corner.size() && corner[i]; }
  // Whether segment i has no length in 3D (within 1e-12 of the polyline's):
  // a repeated point, or a stretch of a pole.
  bool collapsed(int i) const {
    return (xyz[(i + 1) % xyz.size()] - xyz[i]).norm() <= 1e-12 * length();
  }
  // (u,v) at arc length s (wrapped when closed, clamped otherwise).
  Vec2 uv_at(double s) const;
  // Arc length of the point at fraction t of segment i.
  double s_at(int i, double t) const { return arc[i] + t * (arc[i + 1] - arc[i]); }
  // Segment holding arc length s (wrapped / clamped like uv_at) and s itself.
  int segment_at(double& s) const;
};

struct BdSourceParams {
  // Indices into the face's trim loops (SurfaceFace::trim_loops order) to use
  // as sources; empty = all loops.
  std::vector<int> loops;
  // Extra source curves on the surface as (u,v) polylines (open, >= 2 points,
  // every point inside the face).
  std::vector<std::vector<Vec2>> extra_curves;
};

// Builds the arc lengths of a polyline (uv and xyz must be filled).
void finish_polyline(BdPolyline& line);

// Where a curve ends on the trim boundary: index into the boundary vector
// (-1 = it does not end there) and the arc length along that loop.
struct BdCurveEnd {
  int loop = -1;
  double s = 0.0;
};

struct BdCurve {
  std::vector<Vec2> uv;
  std::vector<Vec3> xyz;
  bool closed = false;  // a loop (around a hole): last point joins the first
  BdCurveEnd start, end;
};

struct BdNode {
  Vec2 uv = Vec2::Zero();
  Vec3 xyz = Vec3::Zero();
  int loop = -1;        // trim loop (index into boundary) the node lies on, -1 inside
  double s = 0.0;       // arc length along that loop
  bool corner = false;  // a trim corner: never moved or removed
  bool shared = false;  // on an edge this face shares with another of a face set
};

struct BdNetwork {
  std::vector<BdNode> nodes;
  std::vector<std::array<int, 2>> edges;  // after pruning
  std::vector<std::vector<int>> panels;   // node cycles, counter-clockwise in (u,v)
  std::vector<double> loop_lengths;       // 3D length of each trim loop (for BdNode::s)
};

struct BoundaryDrivenParams {
  double size = 0.0;        // target panel edge length, mm (required)
  double rho = 2.0;         // IDW power of the BDTensor (eq. 2)
  double skew_ratio = 0.3;  // min/max corner angle under which a triangle is removed
  int smoothing_iterations = 10;
  // Split every panel by centre + edge midpoints (section 3.2). The curves are
  // then traced 2 * size apart so the final panels come out near `size`.
  bool quadrangulate = true;
  BdSourceParams sources;
  double trim_deflection = 0.0;  // mm; 0 = automatic (the one rule of every method)
  double step_fraction = 0.1;    // tracing step / curve spacing
  double corner_angle_deg = 30.0;
  // Network edges shorter than this fraction of the curve spacing are collapsed.
  double min_edge_fraction = 0.35;
  // After smoothing, nodes of panels with a corner under this angle (deg) are
  // relocated to open it (improve_bd_angles); 0 switches the step off.
  double angle_target_deg = 30.0;
  int angle_passes = 30;
  int max_panels = kDefaultMaxPanels;
  // curvature_lines (issue 16): the curves follow the principal curvature
  // directions instead of the trims' field, which takes over within
  // `boundary_blend` curve spacings of the trim (methods/boundary_driven/
  // principal_field.h); `field_smoothness` weighs equal neighbours in the
  // field's fit.
  bool principal_directions = false;
  double boundary_blend = 0.25;
  double field_smoothness = 0.25;
  // Where `size` is too coarse for the face's openings and notches: return
  // the mesh at the first smaller size that works (its nominal_area is that
  // size squared) instead of an error naming that size. A face set takes it
  // for each face, so that one small face of a part does not refuse the set.
  bool take_a_smaller_size = false;
};

// curvature_lines' parameters: boundary_driven's, along the principal
// directions, with defaults that keep the lines on them: no quadrangulation
// (its centres lie off the lines), no Laplacian smoothing and no angle moves
// (both pull nodes off them); a line's node moves off its curvature line turn
// planar quads warped.
struct CurvatureLinesParams : BoundaryDrivenParams {
  CurvatureLinesParams() {
    principal_directions = true;
    quadrangulate = false;
    smoothing_iterations = 0;
    angle_target_deg = 0.0;
  }
};

// Everything the stages produced (the curve network for display, the mesh).
struct BoundaryDrivenResult {
  std::vector<BdPolyline> boundary;
  std::vector<BdCurve> curves;
  BdNetwork network;  // the preliminary mesh (before refinement)
  int removed_triangles = 0;
  int collapsed_edges = 0;
  int angle_moves = 0;  // node moves made by improve_bd_angles
  PanelMesh mesh;
};

// The params struct from checked declaration values (tessella/methods.h), for
// boundary_driven_stages called with the console's keywords.
BoundaryDrivenParams boundary_driven_params(const ParamValues& values);

BoundaryDrivenResult boundary_driven_stages(const SurfaceFace& face,
                                            const BoundaryDrivenParams& params);

// The final mesh: panels counter-clockwise about the face normal, rods built,
// nominal_area = size^2.
PanelMesh boundary_driven(const SurfaceFace& face, const BoundaryDrivenParams& params);

// The same along the principal curvature lines (params.principal_directions
// set whatever it was): a layout planarize() can make planar close to the
// surface.
PanelMesh curvature_lines(const SurfaceFace& face, const BoundaryDrivenParams& params);

}  // namespace tessella
