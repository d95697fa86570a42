// Builds OCCT compounds of the result and returns them as BRep strings, so a
// host (FreeCAD) can import them in one call.
#pragma once

#include <string>
#include <vector>

#include "tessella/panel_mesh.h"

namespace tessella {

// One sub-shape per panel, in panel order: planar polygon faces where the panel
// is planar within `planar_tolerance` (mm), a bilinear face for a bent quad, and
// a shell of flat fan triangles for a bent n-gon.
std::string panels_to_brep(const PanelMesh& mesh, double planar_tolerance);
// The faces panels_to_brep builds, as data, for a host that builds the same
// shapes itself (cheaper than writing and reading BRep text): panel k is a
// compound of its faces (compound[k] = 1: flat pieces or a fan of triangles)
// or its one face. A face is the bilinear patch of its 4 corners (poles in
// corner order) or a flat face on the plane (origin, unit normal) bounded by
// the polygon of its corners, whose edges need `tolerance` (mm) when above
// 1e-7 (corners off the plane by up to that).
struct PanelFaceList {
  std::vector<int> panel_offsets;    // faces of panel k: [panel_offsets[k], panel_offsets[k+1])
  std::vector<char> compound;        // per panel
  std::vector<int> corner_offsets;   // corners of face f: [corner_offsets[f], corner_offsets[f+1])
  std::vector<int> corners;          // mesh vertex indices, counter-clockwise
  std::vector<char> bilinear;        // per face
  std::vector<Vec3> origin, normal;  // per face (flat faces; zero for bilinear ones)
  std::vector<double> tolerance;     // per face
};
PanelFaceList panel_faces(const PanelMesh& mesh, double planar_tolerance);

// One edge per rod, in rod order.
std::string rods_to_brep(const PanelMesh& mesh);
// One vertex per node (see PanelMesh::is_node), in vertex order.
std::string nodes_to_brep(const PanelMesh& mesh);

}  // namespace tessella
