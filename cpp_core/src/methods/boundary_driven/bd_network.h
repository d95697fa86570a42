// Boundary-driven meshing, stage 4 (seed 001 sections 2.2-2.3): the curve
// network and its faces.
//
// Nodes are the curve-curve intersections, the curve ends on the trim and the
// trim corners. Along each curve and each trim loop the nodes are sorted by
// parameter and consecutive ones joined (the paper's Figure 7). Dangling curve
// ends (curves stopped next to a parallel one) are pruned.
//
// Faces: the paper fits each mesh face by a shortest-path search around a node
// between two consecutive neighbours (section 2.3.1, Figure 9). For a planar
// embedding - the network lives in the (u,v) plane and no two of its edges
// cross, every crossing being a node - the smallest cycle through two
// consecutive edges of a node is exactly the face of the embedding between
// them, so we traverse the faces of the planar graph directly: from half-edge
// a->b continue with the edge of b that comes next clockwise from b->a (edges
// sorted by angle in (u,v); an orientation-preserving linear map keeps that
// order, so (u,v) angles give the same faces as angles in the tangent plane).
// Faces that run against a trim loop's orientation (the outside, the holes) are
// dropped.
#pragma once

#include <array>
#include <vector>

#include "methods/boundary_driven/bd_curves.h"

namespace tessella {

struct BdNetworkParams {
  double corner_angle_deg = 30.0;  // trim vertices turning more than this are nodes
};

BdNetwork build_bd_network(const SurfaceFace& face, const std::vector<BdPolyline>& boundary,
                           const std::vector<BdCurve>& curves, const BdNetworkParams& params);

}  // namespace tessella
