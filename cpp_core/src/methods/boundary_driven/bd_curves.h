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

}  // namespace tessella
