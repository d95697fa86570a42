// Boundary-driven meshing, stage 3: BDCurves (seed 001 section 2.2), streamlines
// of the BDTensor traced in (u,v) with steps measured in 3D (midpoint RK2), each
// following whichever of the four field directions is closest to its previous
// step. Seeding keeps neighbouring parallel curves about `spacing` apart
// (evenly spaced streamlines in the manner of Jobard and Lefer):
//  1. a seed on every boundary span between corners, every `spacing` of arc
//     length, traced inward along the field direction closest to the inward
//     normal (the curves that meet the trims);
//  2. then, for every line in turn (boundary loops, then traced curves), seeds
//     offset by `spacing` across it, traced both ways along the direction
//     parallel to it.
// A seed closer than 0.75 * spacing to a parallel line is dropped; a curve stops
// at the trim boundary (the exact crossing with the trim polyline), or when it
// comes closer than stop_fraction * spacing to a parallel line (that dangling
// end is pruned by the network stage), or when it closes on itself.
#pragma once

#include <vector>

#include "methods/boundary_driven/bd_tensor.h"

namespace tessella {

// Seeds a caller dictates along the trims: on the boundary segments flagged
// in `dictated` (per boundary polyline, per segment) no seeds are spaced;
// curves start at `seeds` instead (faces traced as a group,
// trace_bd_curves_across: the group's seeds along its free boundary).
// `order` (if given): each seed's place in one sequence over all charts, in
// which they are traced (a group's seeds in order along its boundary, as
// one face traces its seeds loop by loop).
struct BdSeedPlan {
  std::vector<std::vector<char>> dictated;
  std::vector<BdCurveEnd> seeds;  // boundary polyline index and arc length
  std::vector<int> order;
};

struct BdCurveParams {
  double spacing = 0.0;          // mm between neighbouring parallel curves, > 0
  double step_fraction = 0.1;    // RK2 step in 3D = spacing * step_fraction, [0.01, 0.5]
  double stop_fraction = 0.5;    // [0.1, 0.9]
  double corner_angle_deg = 30;  // boundary corners: no seed on them
  int max_curves = 20000;
  // The field to follow, sampled on a grid (curvature_lines' principal
  // directions); null: the tensor's, sampled on bd_field_grid_size's grid.
  const BdTensorGrid* field = nullptr;
};

// The field grid's size: nodes about spacing / 3 apart in 3D (from the
// lengths of the iso-lines through the middle), 16 to 400 per direction.
void bd_field_grid_size(const SurfaceFace& face, double spacing, int& nu, int& nv);

std::vector<BdCurve> trace_bd_curves(const SurfaceFace& face, const BdTensor& tensor,
                                     const std::vector<BdPolyline>& boundary,
                                     const BdCurveParams& params);

// One face of a group of faces traced together (faces on different surfaces
// joined by smooth edges, issue 14).
struct BdChart {
  const SurfaceFace* face = nullptr;
  const std::vector<BdPolyline>* boundary = nullptr;  // its trims
  // Per boundary polyline, per segment: the chart across it where the segment
  // runs along a smooth edge to another face of the group, -1 elsewhere.
  std::vector<std::vector<int>> across;
  BdSeedPlan plan;  // its seeds along its trims
};

// The curves traced on the charts as on one face, except that a curve
// reaching a smooth edge goes on into the face across it (from the nearest
// point of that face's trim along the edge, in the field direction nearest
// to its own): per chart, the pieces of the curves on it, each ending where
// its curve crosses a trim (loop and arc length, as one face's curves end).
// The smooth edges are no trims to the seeding: no curve starts on them or
// beside them, and a curve does not join them. Each chart samples `tensor`
// on its own grid; params.field must be null. On one chart with no smooth
// edge and a plan dictating nothing, trace_bd_curves' curves.
std::vector<std::vector<BdCurve>> trace_bd_curves_across(const std::vector<BdChart>& charts,
                                                         const BdTensor& tensor,
                                                         const BdCurveParams& params);

}  // namespace tessella
