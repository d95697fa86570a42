// Guide-line grids for free-form grid shells (seed 004, sections 4-5): the
// Guide Line Scaling Method (GSM) and its building blocks (chord division with
// the left-over rule, the 90-degree connection rule), each usable on its own.
#pragma once

#include <array>
#include <vector>

#include "tessella/panel_mesh.h"
#include "tessella/vec.h"

namespace tessella {

class SurfaceFace;

// A curve lying on the surface: a dense polyline in (u,v) and the surface
// points it maps to (xyz[i] == face.point(uv[i])).
struct SurfaceCurve {
  std::vector<Vec2> uv;
  std::vector<Vec3> xyz;
};

// Equal-chord division of a polyline (seed 004 section 5.1 step 7). Returns the
// node positions as polyline parameters t (integer part = segment index,
// fraction = position on that segment); the first is 0 and the last is the end
// (points.size() - 1). Chords of `chord` (L1) are laid from the start; when the
// left-over chord L2 at the end is under merge_fraction * L1 it is merged into
// the last chord (the paper's rule), otherwise it is spread: the chord length is
// iterated (bisection) so that n equal chords end exactly at the end, with n the
// count (full chords, or one more) whose chord is closest to L1.
struct ChordDivisionParams {
  double chord = 0.0;           // L1 (mm), > 0
  double merge_fraction = 0.2;  // delta / L1
};
std::vector<double> divide_by_chords(const std::vector<Vec3>& points,
                                     const ChordDivisionParams& params);
// Chords of exactly `chord` laid from the start (at most max_count), as
// polyline parameters; the first is 0, the rest of the curve is left over.
std::vector<double> lay_chords(const std::vector<Vec3>& points, double chord, int max_count);
// Point of the polyline at parameter t (linear on each segment).
Vec3 polyline_point(const std::vector<Vec3>& points, double t);

// Connects two neighbouring node rows P (curve i) and Q (curve i+1) into
// triangles by the 90-degree rule of seed 004 section 5.1 step 8: starting from
// the rod P0-Q0, Q_j is connected to the next point P_{k+1} while the angle
// Q_j P_k P_{k+1} is at most 90 degrees (Q_j is not behind P_k), else the rule
// moves on to Q_{j+1}; residual points at the end are connected to the last
// point of the other row. Triangle corners index P as 0..n-1 and Q as n..n+m-1.
std::vector<std::array<int, 3>> connect_rows_right_angle(const std::vector<Vec3>& p,
                                                         const std::vector<Vec3>& q);

// The Guide Line Scaling Method (seed 004 section 5). The guide is a 3D polyline
// on or near the face (the console API discretizes the user's edge).
struct GuideLineScalingParams {
  std::vector<Vec3> guide;      // >= 2 points, within guide_tolerance of the face
  double rod_length = 0.0;      // L1 (mm): target chord of the rods along the curves
  double advance = 0.0;         // L (mm): step between curves; 0 = rod_length * sqrt(3)/2
  double merge_fraction = 0.2;  // left-over rule: merge the rest under this * L1
  // Largest allowed distance of a guide point from the surface (mm);
  // 0 = 5% of the model size.
  double guide_tolerance = 0.0;
  int max_curves = 2000;  // refuse to advance more curves than this
  // After the GSM step stalls (the ends reached the far corners), offset the
  // curve point by point until it has left the face (covers the strip the
  // paper's sweep leaves open); false = the paper's sweep only.
  bool finish_sweep = true;
  // Nodes of each curve at the feet of the midpoints of the neighbouring
  // curve's rods (staggered rows, near-equal rods between the curves); false =
  // the paper's equal chords on every curve.
  bool stagger = true;
  double trim_deflection = 0.0;  // chord deflection of the trim polylines; 0 = automatic
  int max_panels = 200000;
};

// What the method produced besides the mesh: the advanced curves in sweep order
// (for plots and checks).
struct GuideLineResult {
  PanelMesh mesh;
  std::vector<SurfaceCurve> curves;
  std::size_t guide_index = 0;  // curves[guide_index] is the guide, projected and extended
};

// The Two Guide Lines with Two End Vertices Method (seed 004 section 6): the
// outer boundary is split at corners into boundary curves; from each end of a
// guide the boundary curve is divided into chords of rod_length (both ways;
// past a corner, or past the half-way point to the other end, along the
// tangent: the paper's boundary extension where a vertex has no twin); the
// guide is moved through the k-th vertex pairs (steps 4-6 of section 5.1);
// the cells between the two families, closed by the trim along the outline and
// around holes, are the panels (curve_family_mesh.h): quads inside, boundary
// cells with nodes where the curves meet the trim (`triangulate`: triangles).
struct TwoGuideLinesParams {
  std::vector<Vec3> guide_a, guide_b;
  double rod_length = 0.0;  // chord of the boundary vertices (mm)
  // > 0: every boundary curve at a guide end is divided into this many equal
  // chords instead (the paper's "divided in 48 segments"; each boundary curve
  // gets its own chord); 0 = chords of rod_length.
  int boundary_divisions = 0;
  bool triangulate = false;  // one diagonal per quad (the shorter)
  // Each curve is the guide moved through a vertex pair: by a similarity of
  // the (u,v) plane (true), or by the paper's 3D scale / rotate / nearest-point
  // projection (false; bows the curves on domes, see two_guide_lines.cpp).
  bool map_in_uv = true;
  double corner_angle = 30.0;    // deg: a sharper turn of the outline splits boundary curves
  double guide_tolerance = 0.0;  // as for GSM; 0 = 5% of the model size
  int max_curves = 2000;
  double trim_deflection = 0.0;
  int max_panels = 200000;
};
struct TwoGuideLinesResult {
  PanelMesh mesh;
  std::vector<SurfaceCurve> curves_a, curves_b;
};
TwoGuideLinesResult two_guide_lines_curves(const SurfaceFace& face,
                                           const TwoGuideLinesParams& params);
PanelMesh two_guide_lines(const SurfaceFace& face, const TwoGuideLinesParams& params);

GuideLineResult guide_line_scaling_curves(const SurfaceFace& face,
                                          const GuideLineScalingParams& params);
// The triangle mesh only (rods built).
PanelMesh guide_line_scaling(const SurfaceFace& face, const GuideLineScalingParams& params);

}  // namespace tessella
