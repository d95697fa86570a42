// Builds OCCT compounds of the result and returns them as BRep strings, so a
// host (FreeCAD) can import them in one call.
#pragma once

#include <string>

#include "tessella/panel_mesh.h"

namespace tessella {

// One sub-shape per panel, in panel order: planar polygon faces where the panel
// is planar within `planar_tolerance` (mm), a bilinear face for a bent quad, and
// a shell of flat fan triangles for a bent n-gon.
std::string panels_to_brep(const PanelMesh& mesh, double planar_tolerance);
// One edge per rod, in rod order.
std::string rods_to_brep(const PanelMesh& mesh);
// One vertex per node (see PanelMesh::is_node), in vertex order.
std::string nodes_to_brep(const PanelMesh& mesh);

}  // namespace tessella
