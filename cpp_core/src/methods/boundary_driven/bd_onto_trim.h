// Boundary-driven meshing, after the refinement: an interior node left beside
// a trim with an edge across it becomes a node of that trim.
//
// The curves' chords and the quadrangulation's new nodes can put an interior
// node in a strip narrower than a panel, between the trim and another one
// (cone_facade at 900 mm: a node 4 mm from a hole's rim, 83 mm from the
// face's edge). No move clears its edge across the rim
// (untangle_trim_crossings); the panel that follows the rim past it is
// pinched there, and its outline crosses itself. Such a node is moved onto
// the trim (its nearest point, within `reach`, mm in 3D) and the panel is
// split there: the piece between the node and the trim on the far side is a
// sliver of no width, and goes (its rods then follow the trim). Only a node
// of the panel whose trim side runs past that point moves, so no other panel
// is pinched; shared-edge nodes of a face set stay. Returns the nodes moved.
#pragma once

#include <vector>

#include "tessella/boundary_driven.h"
#include "tessella/surface_face.h"

namespace tessella {

int move_crossing_nodes_onto_trims(const SurfaceFace& face, const std::vector<BdPolyline>& boundary,
                                   BdNetwork& net, double reach);

}  // namespace tessella
